//! What the cloud tests share: multiple-scattering tables and the CPU's sun map of a
//! renderer frame.

use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::sun_map::{CloudSunMap, SunMapResolution};
use atmosphere_core::optics::legendre_series::LegendreSeries;
use render_wgpu::frame::Frame;

/// Henyey-Greenstein tables, another g at each wavelength so that a swapped channel
/// shows.
pub fn orders() -> ScatteringOrders {
    let series: Vec<LegendreSeries> = [0.84, 0.85, 0.86]
        .iter()
        .map(|&g| LegendreSeries::henyey_greenstein(g, 300))
        .collect();
    ScatteringOrders::new(&series).unwrap()
}

/// The sun map the renderer makes for `layer` in `frame` (its grid under the camera,
/// the default resolution), on the CPU.
pub fn frame_sun_map(layer: &CloudLayer, frame: &Frame) -> CloudSunMap {
    let resolution = SunMapResolution::default();
    let grid = CloudSunMap::grid_for(layer.shell(), frame.camera_position_m, &resolution);
    let sun = frame.sun_direction.normalize();
    CloudSunMap::new(layer, grid.unwrap(), sun, &resolution).unwrap()
}
