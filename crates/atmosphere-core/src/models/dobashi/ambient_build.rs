//! How the ambient radiance ψ is chosen: it is the mean over all directions of the light arriving at the
//! ground from orders one and up, estimated as in Hillaire 2020 (section 5.5) with the
//! model's own Eq. 12: ψ_1 = (1/4π) ∫ L_1(ω) dω is the mean single-scattered (and
//! sunlit-ground) radiance arriving at a point on the ground, and f = (1/4π) ∫ A(ω) dω the
//! mean transfer of a unit isotropic radiance field (the ambient sums above with ψ = 1);
//! each further order multiplies the mean by f, so with orders up to N,
//! ψ = ψ_1 (1 + f + ... + f^(N-2)), and ψ = ψ_1 / (1 - f) for all orders. ψ is constant in
//! space and direction; it depends on the sun's elevation only, so it is tabulated over
//! the sun's cosine and read at each plane's own sun angle (a night side seen from space
//! stays dark). The sphere integral uses `ambient_directions`^2 directions, equal steps
//! of the zenith cosine (equal solid angles) times equal steps of azimuth.

use std::f64::consts::PI;

use glam::DVec3;
use rayon::prelude::*;

use crate::models::dobashi::ambient::AmbientTable;
use crate::models::dobashi::grid::Grid;
use crate::models::dobashi::trace::{Ambient, Tracer};
use crate::models::error::ModelError;
use crate::models::sky_model::ViewRay;

impl AmbientTable {
    /// Builds ψ for scattering orders up to `max_orders` (`None`: all), at least 2.
    pub fn build(
        tracer: &Tracer<'_>,
        directions: usize,
        sun_angles: usize,
        max_orders: Option<u32>,
    ) -> Result<AmbientTable, ModelError> {
        let bottom = tracer.atmosphere.bottom_radius_m;
        let origin = DVec3::new(0.0, 0.0, bottom);
        let n = directions;
        let weight = 1.0 / (n * n) as f64;
        let rays: Vec<DVec3> = (0..n * n)
            .map(|index| {
                let mu = -1.0 + 2.0 * ((index / n) as f64 + 0.5) / n as f64;
                let phi = 2.0 * PI * ((index % n) as f64 + 0.5) / n as f64;
                let s = (1.0 - mu * mu).max(0.0).sqrt();
                DVec3::new(s * phi.cos(), s * phi.sin(), mu)
            })
            .collect();
        let n_w = tracer.spectra.wavelengths_nm.len();
        let means = (0..sun_angles)
            .into_par_iter()
            .map(|i| {
                let mu_sun = -1.0 + 2.0 * i as f64 / (sun_angles - 1) as f64;
                let sun = DVec3::new((1.0 - mu_sun * mu_sun).max(0.0).sqrt(), 0.0, mu_sun);
                let mut psi_1 = vec![0.0; n_w];
                let mut transfer = vec![0.0; n_w];
                for direction in &rays {
                    let ray = ViewRay {
                        origin_m: origin,
                        direction: *direction,
                        sun_direction: sun,
                        max_distance_m: None,
                    };
                    let terms = tracer.trace(&ray, Ambient::Unit)?;
                    for w in 0..n_w {
                        psi_1[w] += weight * terms.single[w];
                        transfer[w] += weight * terms.ambient[w];
                    }
                }
                Ok((psi_1, transfer))
            })
            .collect::<Result<Vec<_>, ModelError>>()?;
        // f does not depend on the sun: take it from the first node.
        let transfer = means[0].1.clone();
        let series: Vec<f64> = transfer
            .iter()
            .map(|f| {
                let f = f.clamp(0.0, 1.0 - 1e-6);
                match max_orders {
                    None => 1.0 / (1.0 - f),
                    Some(orders) => (0..orders.saturating_sub(1))
                        .map(|i| f.powi(i as i32))
                        .sum(),
                }
            })
            .collect();
        let mut radiance = Grid::filled(sun_angles, 1, n_w, 0.0);
        for (i, (psi_1, _)) in means.iter().enumerate() {
            let psi: Vec<f64> = psi_1.iter().zip(&series).map(|(p, s)| p * s).collect();
            radiance.set(i, 0, &psi);
        }
        Ok(AmbientTable { radiance, transfer })
    }
}
