//! Bruneton scattering tables filled with a known function of each texel's direction,
//! for the tests of the table's axes.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::bruneton::parameterization::{
    Radii, ScatteringSize, texel_parameters,
};
use atmosphere_core::models::bruneton::tables::Table4;

/// The Earth preset's radii.
pub fn earth_radii() -> Radii {
    let a = Atmosphere::preset("earth").unwrap();
    Radii {
        bottom_m: a.bottom_radius_m,
        top_m: a.top_radius_m,
    }
}

/// A table of `size` whose every texel holds `value(mu, nu)` of the view and view-sun
/// cosines it stands for (`texel_parameters`).
pub fn table_of(radii: &Radii, size: ScatteringSize, value: impl Fn(f64, f64) -> f64) -> Table4 {
    let mut table = Table4::zeros(size);
    for (i, v) in table.data.iter_mut().enumerate() {
        let (ir, imu, imus, inu) = size.coords(i);
        let (_, mu, _, nu, _) = texel_parameters(radii, &size, ir, imu, imus, inu);
        *v = [value(mu, nu) as f32; 3];
    }
    table
}
