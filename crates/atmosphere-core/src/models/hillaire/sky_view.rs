//! The sky-view LUT of Hillaire 2020 (section 5.3): for one camera altitude and sun
//! elevation, the light scattered towards the camera along every direction, 192 x 108
//! texels in the [`LatLong`] mapping, each ray marched with 30 samples to where it leaves
//! the atmosphere or meets the ground (the ground's own light is not in the table: the
//! model adds it where a ray ends on the ground). Per unit solar irradiance, f32.

use crate::models::hillaire::directions::{LatLong, view_sun_cosine};
use crate::models::hillaire::march::ViewMarch;
use crate::models::hillaire::medium::{Medium, ground_distance};
use crate::models::hillaire::multiple_scattering::MultipleScattering;
use crate::models::hillaire::rows::rows_in_parallel;
use crate::optics::geometry::distance_to_exit;

/// The sky-view LUT of one view.
#[derive(Clone, Debug, PartialEq)]
pub struct SkyView {
    pub grid: LatLong,
    /// Camera radius and sun zenith cosine the table was built for.
    pub r: f64,
    pub mu_s: f64,
    wavelengths: usize,
    bottom_m: f64,
    pub values: Vec<f32>,
}

impl SkyView {
    /// Marches every texel's ray with `samples` segments (rows on scoped threads: see
    /// `view_cache`).
    pub fn build(
        medium: &Medium,
        multiple: Option<&MultipleScattering>,
        grid: LatLong,
        r: f64,
        mu_s: f64,
        samples: usize,
    ) -> SkyView {
        let n = medium.wavelengths();
        let a = medium.atmosphere;
        let bottom = a.bottom_radius_m;
        let values = rows_in_parallel(grid.height, |j| {
            let mut row = Vec::with_capacity(grid.width * n);
            for i in 0..grid.width {
                let (mu, phi, ground) = grid.texel_direction(r, bottom, i, j);
                let length = if ground {
                    ground_distance(r, mu, bottom)
                } else {
                    distance_to_exit(r, mu, a.top_radius_m)
                };
                let nu = view_sun_cosine(mu, phi, mu_s);
                let mut march = ViewMarch::new(*medium, multiple, r, mu, mu_s, nu);
                march.run(length, samples);
                row.extend(march.radiance.iter().map(|v| *v as f32));
            }
            row
        });
        SkyView {
            grid,
            r,
            mu_s,
            wavelengths: n,
            bottom_m: bottom,
            values,
        }
    }

    /// Radiance per unit solar irradiance towards the camera from direction cosine `mu`
    /// and azimuth `phi` from the sun, on the ground side of the horizon or not.
    pub fn lookup(&self, mu: f64, phi: f64, ground: bool, out: &mut [f64]) {
        let p = self.grid.position(self.r, self.bottom_m, mu, phi, ground);
        self.grid
            .interpolate(&self.values, self.wavelengths, 0, &p, ground, out);
    }

    /// Bytes held by a table of `grid` at `wavelengths` wavelengths.
    pub fn bytes_for(grid: LatLong, wavelengths: usize) -> usize {
        grid.width * grid.height * wavelengths * std::mem::size_of::<f32>()
    }
}
