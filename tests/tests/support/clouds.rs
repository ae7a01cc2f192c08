//! What the cloud tests share: multiple-scattering tables, the CPU's sun map of a
//! renderer frame and the CPU's march of a pixel's segment.

use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::march::{CloudLight, MarchRay, march, march_in_sun_map};
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::settings::SunLight;
use atmosphere_core::clouds::layer::sun_map::{CloudSunMap, SunMapResolution};
use atmosphere_core::optics::legendre_series::LegendreSeries;
use glam::DVec3;
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
/// the default resolution, or `SunMapResolution::LIT` when the layer is lit by it), on
/// the CPU.
pub fn frame_sun_map(layer: &CloudLayer, frame: &Frame) -> CloudSunMap {
    let resolution = match layer.settings().sun_light {
        SunLight::March => SunMapResolution::default(),
        SunLight::Map => SunMapResolution::LIT,
    };
    let grid = CloudSunMap::grid_for(layer.shell(), frame.camera_position_m, &resolution);
    let sun = frame.sun_direction.normalize();
    CloudSunMap::new(layer, grid.unwrap(), sun, &resolution).unwrap()
}

/// The CPU march of `segment` of the ray from `o` along `d`, lit through `map` where the
/// layer's settings say `sun_light = map`: [radiance x 3, transmittance].
pub fn cpu_march(
    layer: &CloudLayer,
    orders: &ScatteringOrders,
    (light, map): (&CloudLight, &CloudSunMap),
    (o, d): (DVec3, DVec3),
    (t0, t1): (f64, f64),
) -> [f64; 4] {
    let light = CloudLight {
        up: (o + d * t0).normalize(),
        ..light.clone()
    };
    let ray = MarchRay {
        origin: o,
        direction: d,
        t0,
        t1,
    };
    let s = layer.settings();
    let c = match s.sun_light {
        SunLight::March => march(layer, &ray, &light, orders, s),
        SunLight::Map => march_in_sun_map(layer, &ray, &light, orders, s, map),
    };
    [
        c.radiance[0],
        c.radiance[1],
        c.radiance[2],
        c.transmittance[0],
    ]
}
