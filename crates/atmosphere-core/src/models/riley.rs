//! Riley et al. 2004, section 4.1: single scattering in a flat, exponentially stratified
//! atmosphere, in closed form, applied per species in the tangent frame at the camera.
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
//!
//! As printed, the form divides by p_y - l_y and by p_y and multiplies exponentials that
//! overflow when p_y < 0. [`FlatExponential::single_scattering`] evaluates the same
//! integral without either division: with tau the optical depth of the ray (Eq. 11,
//! `tau = a (u0 - u1) / p_y = a u0 (K gamma) phi(p_y K gamma)`, phi(x) = (1 - e^-x) / x),
//! the integrand's exponent is linear in u, so
//!
//! L = I P tau exp(f_max) phi(tau |p_y - l_y| / l_y),
//!
//! with f = -(sun optical depth) - (view optical depth from the camera), taken at whichever
//! end of the ray it is larger. Every factor is bounded, phi is evaluated by `expm1` (and
//! a series near 0), and the limits p_y = l_y, p_y = 0 and infinite horizontal rays come
//! out of the same expression. See docs/models/riley.md.

use crate::atmosphere::Atmosphere;
use crate::atmosphere::density::DensityProfile;
use crate::models::error::ModelError;
use crate::models::id::ModelId;
use crate::models::model_base::ModelBase;
use crate::models::settings::ModelSettings;
use crate::models::sky_model::{RayRadiance, SkyModel, SurfacePoint, ViewRay};
use crate::optics::geometry::{distance_to_exit, ray_hits_ground};
use crate::optics::phase::{PhaseFunction, rayleigh};
use crate::optics::surface_lighting::{SurfaceElement, add_ground_light};
use crate::optics::view_segment::{SegmentEnd, ViewSegment};

/// `(1 - exp(-x)) / x`, 1 at x = 0, accurate for every x (0 at +infinity).
pub fn phi(x: f64) -> f64 {
    if x.abs() < 1e-5 {
        // Three terms of the series: the next, x^3 / 24, is below 5e-17.
        1.0 - x / 2.0 + x * x / 6.0
    } else if x == f64::INFINITY {
        0.0
    } else {
        -(-x).exp_m1() / x
    }
}

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
    /// Relative density exp(-y / H) at the end of a ray from `height_m` with vertical
    /// component `view_up` after `length_m` (infinite length: 0 going up, infinite going
    /// down, unchanged for a horizontal ray).
    fn end_density(&self, height_m: f64, view_up: f64, length_m: f64) -> f64 {
        let u0 = (-height_m / self.scale_height_m).exp();
        if length_m.is_infinite() {
            if view_up > 0.0 {
                0.0
            } else if view_up < 0.0 {
                f64::INFINITY
            } else {
                u0
            }
        } else {
            (-(height_m + view_up * length_m) / self.scale_height_m).exp()
        }
    }

    /// Optical depth (Eq. 11) of a ray from height `height_m` with vertical direction
    /// component `view_up` (any sign, 0 included) over `length_m` (infinite allowed).
    pub fn optical_depth(&self, height_m: f64, view_up: f64, length_m: f64) -> f64 {
        let (beta, h) = (self.beta_sea_level_per_m, self.scale_height_m);
        if beta == 0.0 || length_m == 0.0 {
            return 0.0;
        }
        if length_m.is_infinite() && view_up <= 0.0 {
            return f64::INFINITY;
        }
        let u0 = (-height_m / h).exp();
        let x = view_up * length_m / h;
        if x.abs() <= 1.0 {
            // a u0 (u0 - u1) / (u0 p_y) without the cancellation of u0 - u1.
            beta * u0 * length_m * phi(x)
        } else {
            let u1 = self.end_density(height_m, view_up, length_m);
            beta * h * (u0 - u1) / view_up
        }
    }

    /// Single-scattered radiance (Riley et al. 2004 Eq. 15, restored as above) of a ray
    /// from height `camera_height_m` with vertical direction component `view_up` (any
    /// sign; 0 and `sun_up` included) running `length_m` (infinite allowed), sun at
    /// vertical component `sun_up` (no light at `sun_up <= 0`), phase function value
    /// `phase` (sr^-1). Finite and continuous in every argument.
    pub fn single_scattering(
        &self,
        camera_height_m: f64,
        view_up: f64,
        sun_up: f64,
        length_m: f64,
        phase: f64,
    ) -> f64 {
        let (beta, h) = (self.beta_sea_level_per_m, self.scale_height_m);
        if sun_up <= 0.0 || beta == 0.0 || length_m == 0.0 {
            return 0.0;
        }
        let a = beta * h;
        let u0 = (-camera_height_m / h).exp();
        let u1 = self.end_density(camera_height_m, view_up, length_m);
        let tau = self.optical_depth(camera_height_m, view_up, length_m);
        // The exponent of the integrand: sun optical depth plus view optical depth from
        // the camera, at the camera and at the end of the ray.
        let f_camera = -a * u0 / sun_up;
        let f_end = if u1.is_infinite() || tau.is_infinite() {
            f64::NEG_INFINITY
        } else {
            -a * u1 / sun_up - tau
        };
        let f_max = f_camera.max(f_end);
        let spread = (view_up - sun_up).abs() / sun_up;
        // tau phi(tau spread), whose limit at tau = infinity is 1 / spread.
        let tau_phi = if tau.is_infinite() {
            1.0 / spread
        } else {
            tau * phi(tau * spread)
        };
        self.irradiance * phase * tau_phi * f_max.exp()
    }
}

/// The single exponential `rho0 exp(-h / H)` standing for a density profile: returns
/// `(rho0, H)`. A profile of one purely exponential layer gives its own terms; any other
/// is fitted over the atmosphere's thickness by matching its column and its mean height
/// (the first two moments), so the vertical optical depth is kept.
pub fn effective_exponential(profile: &DensityProfile, thickness_m: f64) -> (f64, f64) {
    if let [layer] = profile.layers.as_slice()
        && layer.exp_term > 0.0
        && layer.exp_term <= 1.0
        && layer.exp_scale_per_m < 0.0
        && layer.linear_term_per_m == 0.0
        && layer.constant_term == 0.0
    {
        return (layer.exp_term, -1.0 / layer.exp_scale_per_m);
    }
    let (mut column, mut moment) = (0.0, 0.0);
    let dh = thickness_m / FIT_STEPS as f64;
    for i in 0..FIT_STEPS {
        let h = (i as f64 + 0.5) * dh;
        let rho = profile.density(h);
        column += rho * dh;
        moment += rho * h * dh;
    }
    if column <= 0.0 {
        return (0.0, thickness_m);
    }
    let scale_height = moment / column;
    (column / scale_height, scale_height)
}

/// Midpoint steps of the fit of a non-exponential profile (done once when preparing).
const FIT_STEPS: usize = 100_000;

/// One species as Riley's model sees it: a single exponential over a flat ground.
#[derive(Clone, Debug, PartialEq)]
pub struct Species {
    pub scale_height_m: f64,
    /// Extinction at the ground (density rho0 included), per wavelength, m^-1.
    pub extinction: Vec<f64>,
    /// Scattering / extinction per wavelength.
    pub albedo: Vec<f64>,
}

impl Species {
    fn new(
        profile: &DensityProfile,
        thickness_m: f64,
        scattering: &[f64],
        extinction: &[f64],
    ) -> Species {
        let (rho0, scale_height_m) = effective_exponential(profile, thickness_m);
        Species {
            scale_height_m,
            extinction: extinction.iter().map(|e| e * rho0).collect(),
            albedo: scattering
                .iter()
                .zip(extinction)
                .map(|(s, e)| if *e > 0.0 { (s / e).min(1.0) } else { 0.0 })
                .collect(),
        }
    }

    fn flat(&self, w: usize, irradiance: f64) -> FlatExponential {
        FlatExponential {
            beta_sea_level_per_m: self.extinction[w],
            scale_height_m: self.scale_height_m,
            irradiance,
        }
    }
}

/// One straight piece of the flattened view ray.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Leg {
    height_m: f64,
    view_up: f64,
    length_m: f64,
}

/// Riley et al.'s analytic single-scattering sky, prepared for one atmosphere.
#[derive(Clone, Debug)]
pub struct Riley {
    /// `with_mie` false when pruning at zero aerosol: the Mie terms are skipped.
    base: ModelBase,
    bottom_radius_m: f64,
    top_radius_m: f64,
    ground_albedo: f64,
    rayleigh: Species,
    mie: Species,
    mie_phase: PhaseFunction,
}

impl Riley {
    /// Samples the atmosphere at the settings' wavelengths and fits each species' profile
    /// (Rayleigh, Mie) with one exponential. Ozone is ignored. `max_orders` and the
    /// stochastic settings do not apply: the model is single scattering, in closed form.
    pub fn prepare(atmosphere: &Atmosphere, settings: &ModelSettings) -> Riley {
        let base = ModelBase::new(ModelId::Riley, atmosphere, settings);
        let thickness = atmosphere.thickness_m();
        let spectra = &base.spectra;
        let rayleigh_s = &spectra.rayleigh_scattering;
        let mie_s = &spectra.mie_scattering;
        let mie_e: Vec<f64> = spectra.extinction.iter().map(|e| e[1]).collect();
        Riley {
            bottom_radius_m: atmosphere.bottom_radius_m,
            top_radius_m: atmosphere.top_radius_m,
            ground_albedo: atmosphere.ground_albedo,
            rayleigh: Species::new(
                &atmosphere.rayleigh.density,
                thickness,
                rayleigh_s,
                rayleigh_s,
            ),
            mie: Species::new(&atmosphere.mie.density, thickness, mie_s, &mie_e),
            mie_phase: atmosphere.mie.phase.clone(),
            base,
        }
    }

    /// The scale heights (Rayleigh, Mie) the model uses, m.
    pub fn scale_heights_m(&self) -> (f64, f64) {
        (self.rayleigh.scale_height_m, self.mie.scale_height_m)
    }

    /// The fitted species (Rayleigh, Mie) the closed form is evaluated with; the Mie one
    /// is `None` when its terms are skipped (pruned at zero aerosol). What the GPU twin,
    /// `shaders/sky/riley/pixel.wgsl`, is given.
    pub fn species(&self) -> (&Species, Option<&Species>) {
        (&self.rayleigh, self.base.with_mie.then_some(&self.mie))
    }

    fn answer(&self, radiance: Vec<f64>, transmittance: Vec<f64>) -> RayRadiance {
        let n = radiance.len();
        RayRadiance {
            radiance,
            transmittance,
            radiance_std_error: vec![0.0; n],
        }
    }
}

/// The flattened view ray from the atmosphere entry point at height `y0` (m above the
/// ground), radius `r`, direction cosine `p` to the local zenith: its legs and whether
/// it ends on the ground. Each leg keeps the slope `p` of the real ray at the camera (up
/// to sign), but a ray leaving the atmosphere is no longer than the real ray's chord to
/// the top: a flat ray near the horizon would otherwise run on for ever at the camera's
/// height, where the real one climbs out of the air.
fn flat_legs(y0: f64, r: f64, p: f64, bottom: f64, top: f64) -> (Vec<Leg>, bool) {
    if ray_hits_ground(r, p, bottom) {
        // Down to the flat ground, where the flat ray meets height 0.
        return (
            vec![Leg {
                height_m: y0,
                view_up: p,
                length_m: y0 / -p,
            }],
            true,
        );
    }
    let chord = distance_to_exit(r, p, top);
    if p >= 0.0 {
        (
            vec![Leg {
                height_m: y0,
                view_up: p,
                length_m: chord,
            }],
            false,
        )
    } else {
        // Down past the planet's limb: the real ray descends to its lowest point and
        // climbs back out; flat, it descends to that point's altitude and climbs again
        // at the mirrored slope for the rest of the chord.
        let perigee = (r * ((1.0 - p) * (1.0 + p)).sqrt() - bottom).clamp(0.0, y0);
        let down = ((y0 - perigee) / -p).min(chord);
        (
            vec![
                Leg {
                    height_m: y0,
                    view_up: p,
                    length_m: down,
                },
                Leg {
                    height_m: perigee,
                    view_up: -p,
                    length_m: chord - down,
                },
            ],
            false,
        )
    }
}

impl SkyModel for Riley {
    fn base(&self) -> &ModelBase {
        &self.base
    }

    fn table_bytes(&self) -> usize {
        0
    }

    /// No tables: the fitted coefficients are recomputed, which costs microseconds.
    fn update(&mut self, atmosphere: &Atmosphere) -> Result<Vec<&'static str>, ModelError> {
        atmosphere.validate()?;
        let settings = ModelSettings {
            wavelengths_nm: self.base.spectra.wavelengths_nm.clone(),
            prune: self.base.prune,
            ..ModelSettings::default()
        };
        *self = Riley::prepare(atmosphere, &settings);
        Ok(Vec::new())
    }

    /// The transmitted sun only (single scattering has no sky light), through the flat
    /// atmosphere in the element's own tangent frame: Eq. (12), the sun's optical depth
    /// from height y at vertical component l = mu_s being sum over species of
    /// beta H exp(-y / H) / l; no sun where l <= 0, the flat ground's horizon (the rule
    /// of the view rays' sun, `FlatExponential::single_scattering`).
    fn surface_irradiance(&self, surface: &SurfacePoint) -> Result<Vec<f64>, ModelError> {
        let e = SurfaceElement::new_within(self.bottom_radius_m, self.top_radius_m, surface)?;
        let y = e.r - self.bottom_radius_m;
        let (rayleigh, mie) = self.species();
        Ok(e.sun_irradiances(&self.base.spectra.solar_irradiance, |w| {
            if e.sun_cosine > 0.0 && e.mu_s > 0.0 {
                let tau: f64 = std::iter::once(rayleigh)
                    .chain(mie)
                    .map(|s| {
                        s.extinction[w] * s.scale_height_m * (-y / s.scale_height_m).exp() / e.mu_s
                    })
                    .sum();
                (-tau).exp()
            } else {
                0.0
            }
        }))
    }

    fn radiance(&self, ray: &ViewRay) -> Result<RayRadiance, ModelError> {
        let n = self.base.spectra.wavelengths_nm.len();
        let (bottom, top) = (self.bottom_radius_m, self.top_radius_m);
        let Some(segment) = ViewSegment::new_within(bottom, top, ray)? else {
            return Ok(self.answer(vec![0.0; n], vec![1.0; n]));
        };
        let (direction, sun) = (segment.direction, segment.sun_direction);
        let zenith = segment.start / segment.start.length();
        let (y0, p) = (segment.r - bottom, segment.mu);
        let l = sun.dot(zenith).clamp(-1.0, 1.0);
        let (mut legs, mut ground) = flat_legs(y0, segment.r, p, bottom, top);
        if segment.end == SegmentEnd::Object {
            // Keep the legs up to the object.
            ground = false;
            let mut remaining = segment.length;
            legs.retain_mut(|leg| {
                let keep = remaining > 0.0;
                leg.length_m = leg.length_m.min(remaining);
                remaining -= leg.length_m;
                keep
            });
        }
        let nu = direction.dot(sun);
        let phase_r = rayleigh(nu);
        let phase_m = if self.base.with_mie {
            self.mie_phase.eval(nu)
        } else {
            0.0
        };
        let mut radiance = vec![0.0; n];
        let mut transmittance = vec![1.0; n];
        for w in 0..n {
            let e = self.base.spectra.solar_irradiance[w];
            let both = [
                (self.rayleigh.flat(w, e), self.rayleigh.albedo[w] * phase_r),
                (self.mie.flat(w, e), self.mie.albedo[w] * phase_m),
            ];
            let species = &both[..if self.base.with_mie { 2 } else { 1 }];
            for leg in &legs {
                let mut tau = 0.0;
                for (flat, weighted_phase) in species {
                    radiance[w] += transmittance[w]
                        * flat.single_scattering(
                            leg.height_m,
                            leg.view_up,
                            l,
                            leg.length_m,
                            *weighted_phase,
                        );
                    tau += flat.optical_depth(leg.height_m, leg.view_up, leg.length_m);
                }
                transmittance[w] *= (-tau).exp();
            }
        }
        if ground {
            // The Lambertian ground lit by the transmitted sun, as any surface element
            // facing up at the ray's end.
            let end = segment.end_point();
            let albedo = self.ground_albedo;
            add_ground_light(self, end, sun, albedo, &transmittance, &mut radiance)?;
        }
        Ok(self.answer(radiance, transmittance))
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

    #[test]
    fn phi_is_continuous_across_its_series() {
        for x in [1e-5f64, -1e-5, 1e-5 * (1.0 + 1e-9), 0.0] {
            let exact = if x == 0.0 { 1.0 } else { -(-x).exp_m1() / x };
            assert!((phi(x) - exact).abs() < 1e-15, "{x}");
        }
        assert_eq!(phi(f64::INFINITY), 0.0);
    }

    #[test]
    fn printed_form_and_stable_form_agree_away_from_the_stiff_cases() {
        let atm = FlatExponential {
            beta_sea_level_per_m: 3.31e-5,
            scale_height_m: 8000.0,
            irradiance: 1.9,
        };
        for &(y0, p, l, k) in &[
            (0.0, 0.3, 0.8, f64::INFINITY),
            (2000.0, -0.4, 0.5, 5000.0),
            (100.0, 0.9, 0.1, 20_000.0),
            (30_000.0, -0.2, 0.6, 150_000.0),
        ] {
            let u0 = (-y0 / 8000.0f64).exp();
            let u1 = if k == f64::INFINITY {
                0.0
            } else {
                (-(y0 + p * k) / 8000.0f64).exp()
            };
            let a = 3.31e-5 * 8000.0;
            let c = a * (1.0 / l - 1.0 / p);
            let printed =
                1.9 * 0.1 * l / (p - l) * (-a * u0 / p).exp() * ((-c * u1).exp() - (-c * u0).exp());
            let stable = atm.single_scattering(y0, p, l, k, 0.1);
            assert!(
                (stable / printed - 1.0).abs() < 1e-12,
                "{stable} vs {printed}"
            );
        }
    }

    #[test]
    fn exponential_profiles_are_kept_and_others_fitted_by_moments() {
        assert_eq!(
            effective_exponential(&DensityProfile::exponential(1200.0), 60_000.0),
            (1.0, 1200.0)
        );
        // A tent's mean height is its centre; its column is half its base times 1.
        let (rho0, h) = effective_exponential(
            &DensityProfile::tent(10_000.0, 25_000.0, 40_000.0),
            60_000.0,
        );
        assert!((h - 25_000.0).abs() < 1e-3, "{h}");
        assert!((rho0 * h - 15_000.0).abs() < 1e-2, "{rho0}");
    }
}
