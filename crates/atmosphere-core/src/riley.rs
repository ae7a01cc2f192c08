//! Riley et al. 2004, section 4.1: single scattering in a flat, exponentially stratified
//! atmosphere of one scattering species, in closed form.
//!
//! With density exp(-gamma y), sea-level scattering beta (extinction = scattering),
//! camera at height y0 looking along a direction of vertical component p_y, sun at
//! vertical component l_y > 0, Eq. (11) gives the transmittance between two points and
//! Eq. (12) the sunlight reaching a point. Substituting both in Eq. (14) and integrating
//! over the ray gives Eq. (15). Writing u = exp(-gamma y) and a = beta / gamma:
//!
//! L = I P(nu) l_y / (p_y - l_y) exp(-a u0 / p_y) [exp(-c u1) - exp(-c u0)],
//! c = a (1/l_y - 1/p_y),
//!
//! with u0 at the camera and u1 at the end of the ray. The printed Eq. (15) lacks the
//! factor exp(-a u0 / p_y), the transmittance from the camera to infinity along the ray;
//! re-deriving from Eq. (11)-(14) restores it, and the reference agrees with the restored
//! form (tests/reference_physics.rs).

/// A flat atmosphere of one exponentially stratified, non-absorbing species.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatExponential {
    /// Scattering (= extinction) coefficient at height 0, m^-1.
    pub beta_sea_level_per_m: f64,
    /// 1 / gamma, m.
    pub scale_height_m: f64,
    /// The sun's irradiance at infinity.
    pub irradiance: f64,
}

impl FlatExponential {
    /// Single-scattered radiance (Riley et al. 2004 Eq. 15, restored as above) of a ray
    /// from height `camera_height_m` with vertical direction component `view_up` (not 0,
    /// not equal to `sun_up`) running `length_m` (infinite allowed when `view_up > 0`),
    /// sun at vertical component `sun_up > 0`, phase function value `phase` (sr^-1).
    pub fn single_scattering(
        &self,
        camera_height_m: f64,
        view_up: f64,
        sun_up: f64,
        length_m: f64,
        phase: f64,
    ) -> f64 {
        let a = self.beta_sea_level_per_m * self.scale_height_m;
        let u0 = (-camera_height_m / self.scale_height_m).exp();
        let end_height = camera_height_m + view_up * length_m;
        let u1 = if end_height.is_finite() {
            (-end_height / self.scale_height_m).exp()
        } else {
            0.0
        };
        let c = a * (1.0 / sun_up - 1.0 / view_up);
        self.irradiance * phase * sun_up / (view_up - sun_up)
            * (-a * u0 / view_up).exp()
            * ((-c * u1).exp() - (-c * u0).exp())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form against a brute-force midpoint sum of Eq. (14).
    #[test]
    fn closed_form_matches_direct_integration() {
        let atm = FlatExponential {
            beta_sea_level_per_m: 1.35e-5,
            scale_height_m: 8000.0,
            irradiance: 1.8,
        };
        let (y0, p_y, l_y, length, phase) = (500.0, 0.4, 0.7, 150_000.0, 0.05);
        let n = 200_000;
        let ds = length / n as f64;
        let mut sum = 0.0;
        for i in 0..n {
            let s = (i as f64 + 0.5) * ds;
            let y = y0 + p_y * s;
            let beta_y = atm.beta_sea_level_per_m * (-y / 8000.0).exp();
            let view_t = (-atm.beta_sea_level_per_m * 8000.0 / p_y
                * ((-y0 / 8000.0).exp() - (-y / 8000.0).exp()))
            .exp();
            let sun_t = (-atm.beta_sea_level_per_m * 8000.0 / l_y * (-y / 8000.0).exp()).exp();
            sum += view_t * beta_y * phase * atm.irradiance * sun_t * ds;
        }
        let closed = atm.single_scattering(y0, p_y, l_y, length, phase);
        assert!((closed / sum - 1.0).abs() < 1e-8, "{closed} vs {sum}");
    }
}
