//! The stability sweep: stiff and extreme cases run through a model. Shared by
//! `atmos stability` and the test that fails on any failed case.
//!
//! Every case is a set of view rays on one atmosphere, checked for finite, non-negative
//! radiance and transmittance in [0, 1]; the continuity cases also compare rays that should
//! agree (the same ray from just inside and just outside the top of the atmosphere; rays
//! ever closer to the horizon; views just off Riley's singular directions).

use crate::atmosphere::Atmosphere;
use crate::atmosphere::density::DensityProfile;
use crate::atmosphere::spectral::Spectral;
use crate::models::error::ModelError;
use crate::models::id::ModelId;
use crate::models::registry::prepare;
use crate::models::settings::ModelSettings;
use crate::models::sky_model::{RayRadiance, ViewRay};
use crate::optics::geometry::horizon_mu;

/// How close two rays that should agree must be: relative difference of radiance.
pub const CONTINUITY_TOLERANCE: f64 = 0.01;

/// The outcome of one case for one model.
#[derive(Clone, Debug, PartialEq)]
pub struct CaseResult {
    pub case: &'static str,
    pub passed: bool,
    /// The largest radiance seen, or for continuity cases the largest relative difference.
    pub worst: f64,
    /// What failed first, if anything.
    pub failure: Option<String>,
}

/// A Venus-thick atmosphere: dense CO2 under a thick haze, so that grazing optical depths
/// pass 10^3.
pub fn venus_like() -> Atmosphere {
    let mut a = crate::atmosphere::presets::earth();
    a.name = "venus-like".into();
    a.bottom_radius_m = 6_051_800.0;
    a.top_radius_m = 6_051_800.0 + 150_000.0;
    a.rayleigh.scattering_per_m = Spectral::PowerLaw {
        value_at_1um: 1.2e-4,
        exponent: 4.0,
    };
    a.rayleigh.density = DensityProfile::exponential(15_900.0);
    a.mie.scattering_per_m = Spectral::Constant { value: 1.9e-3 };
    a.mie.extinction_per_m = Spectral::Constant { value: 2.0e-3 };
    a.mie.density = DensityProfile::exponential(5_000.0);
    a.ozone.absorption_per_m = Spectral::Constant { value: 0.0 };
    a
}

/// Settings that keep the sweep quick: the reference's Monte Carlo stops at a loose
/// error and at order two (stability, not accuracy, is checked here; continuity
/// comparisons allow for the reported noise).
pub fn sweep_settings(model_id: ModelId) -> ModelSettings {
    let mut settings = ModelSettings::default();
    if model_id == ModelId::Reference {
        settings.max_orders = Some(2);
        settings.target_relative_error = 0.05;
    }
    settings
}

fn ray(a: &Atmosphere, altitude_m: f64, view_deg: f64, sun_deg: f64, azimuth_deg: f64) -> ViewRay {
    ViewRay::from_angles(
        a.bottom_radius_m,
        altitude_m,
        view_deg,
        sun_deg,
        azimuth_deg,
        None,
    )
    .expect("sweep rays are valid")
}

/// No radiance may exceed this many times the solar irradiance (sr^-1): the strongest
/// forward peak of the presets' aerosols is about 4 sr^-1, and multiple scattering adds
/// less than single scattering's bound again.
pub const RADIANCE_BOUND_PER_SR: f64 = 100.0;

/// Checks of one answer; the message of the first problem.
fn problem(r: &RayRadiance, solar_irradiance: &[f64]) -> Option<String> {
    for w in 0..r.radiance.len() {
        let (l, t) = (r.radiance[w], r.transmittance[w]);
        if !(l.is_finite() && l >= 0.0) {
            return Some(format!("radiance {l}"));
        }
        if l > RADIANCE_BOUND_PER_SR * solar_irradiance[w] {
            return Some(format!(
                "radiance {l} above {RADIANCE_BOUND_PER_SR} x the solar irradiance"
            ));
        }
        if !(t.is_finite() && (0.0..=1.0).contains(&t)) {
            return Some(format!("transmittance {t}"));
        }
        if !r.radiance_std_error[w].is_finite() {
            return Some(format!("standard error {}", r.radiance_std_error[w]));
        }
    }
    None
}

/// Relative difference of two answers' radiances beyond three combined standard errors
/// (stochastic models differ by their noise), with a floor for darkness.
fn relative_difference(a: &RayRadiance, b: &RayRadiance) -> f64 {
    (0..a.radiance.len())
        .map(|w| {
            let (x, y) = (a.radiance[w], b.radiance[w]);
            let noise = 3.0 * a.radiance_std_error[w].hypot(b.radiance_std_error[w]);
            ((x - y).abs() - noise).max(0.0) / x.abs().max(y.abs()).max(1e-9)
        })
        .fold(0.0, f64::max)
}

/// Runs every case of the sweep through the model `model_id`.
pub fn run(model_id: ModelId) -> Result<Vec<CaseResult>, ModelError> {
    run_with(model_id, &sweep_settings(model_id))
}

/// Runs every case of the sweep through the model `model_id` prepared with `settings`
/// (a model's non-default options).
pub fn run_with(
    model_id: ModelId,
    settings: &ModelSettings,
) -> Result<Vec<CaseResult>, ModelError> {
    let earth = crate::atmosphere::presets::earth();
    let mut results = Vec::new();

    // Finite, non-negative, bounded: extreme rays on extreme atmospheres.
    let atmospheres: [(&'static str, Atmosphere); 5] = [
        ("earth: extreme rays", earth.clone()),
        ("aerosol 0", earth.with_aerosol_scale(0.0)),
        ("aerosol x100", earth.with_aerosol_scale(100.0)),
        ("mars", crate::atmosphere::presets::mars()),
        ("venus-like (tau > 1e3)", venus_like()),
    ];
    for (case, atmosphere) in atmospheres {
        let model = prepare(model_id, &atmosphere, settings)?;
        let top = atmosphere.thickness_m();
        let mut worst: f64 = 0.0;
        let mut failure = None;
        'rays: for altitude in [0.0, 1.0, top - 1e-3, top, top + 1.0, 1e8] {
            let r = atmosphere.bottom_radius_m + altitude;
            let horizon = horizon_mu(r, atmosphere.bottom_radius_m)
                .acos()
                .to_degrees();
            for view in [
                0.0,
                60.0,
                89.999,
                90.0,
                horizon - 1e-9,
                horizon + 1e-9,
                135.0,
                180.0,
            ] {
                for sun in [0.0, 60.0, 90.0, 95.0, 110.0] {
                    let answer = model.radiance(&ray(&atmosphere, altitude, view, sun, 30.0))?;
                    worst = answer.radiance.iter().cloned().fold(worst, f64::max);
                    if let Some(p) = problem(&answer, model.solar_irradiance_w_m2_nm()) {
                        failure = Some(format!(
                            "altitude {altitude} m, view {view} deg, sun {sun} deg: {p}"
                        ));
                        break 'rays;
                    }
                }
            }
        }
        results.push(CaseResult {
            case,
            passed: failure.is_none(),
            worst,
            failure,
        });
    }

    let model = prepare(model_id, &earth, settings)?;
    let top = earth.thickness_m();

    // The same ray from just inside and just outside the top.
    let mut worst: f64 = 0.0;
    for (view, sun) in [(120.0, 30.0), (100.0, 80.0), (170.0, 60.0)] {
        let inside = model.radiance(&ray(&earth, top - 1.0, view, sun, 45.0))?;
        let outside = model.radiance(&ray(&earth, top + 1.0, view, sun, 45.0))?;
        worst = worst.max(relative_difference(&inside, &outside));
    }
    results.push(continuity("continuity across the top", worst));

    // Rays ever closer to the horizon, above and below it, converge.
    let mut worst: f64 = 0.0;
    for altitude in [10.0, 10_000.0] {
        let r = earth.bottom_radius_m + altitude;
        let horizon = horizon_mu(r, earth.bottom_radius_m).acos().to_degrees();
        for side in [-1.0, 1.0] {
            let near = model.radiance(&ray(&earth, altitude, horizon + side * 1e-7, 60.0, 0.0))?;
            let nearer =
                model.radiance(&ray(&earth, altitude, horizon + side * 1e-10, 60.0, 0.0))?;
            worst = worst.max(relative_difference(&near, &nearer));
        }
    }
    results.push(continuity("continuity at the horizon", worst));

    // Riley's closed form divides by (p_y - l_y) and p_y: views at the sun's elevation
    // and horizontal views, and just off them.
    let mut worst: f64 = 0.0;
    for (view, sun) in [(60.0, 60.0), (90.0, 45.0), (30.0, 30.0)] {
        let at = model.radiance(&ray(&earth, 100.0, view, sun, 90.0))?;
        let off = model.radiance(&ray(&earth, 100.0, view + 1e-6, sun, 90.0))?;
        if problem(&at, model.solar_irradiance_w_m2_nm()).is_some() {
            worst = f64::INFINITY;
        }
        worst = worst.max(relative_difference(&at, &off));
    }
    results.push(continuity("singular directions", worst));
    Ok(results)
}

fn continuity(case: &'static str, worst: f64) -> CaseResult {
    let passed = worst <= CONTINUITY_TOLERANCE;
    CaseResult {
        case,
        passed,
        worst,
        failure: (!passed)
            .then(|| format!("relative difference {worst:.3e} above {CONTINUITY_TOLERANCE}")),
    }
}
