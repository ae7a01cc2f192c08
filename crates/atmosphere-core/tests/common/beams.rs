//! Scenes and independent evaluations shared by the beams tests.

use std::path::Path;

use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::{BeamMethod, BeamSettings};
use atmosphere_core::beams::methods::qtable2002::Qtable2002;
use atmosphere_core::beams::methods::registry::prepare;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::numerics::quadrature::{GAUSS_LEGENDRE_8, mapped};
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;

pub const CAMERA: &str = "[camera]\nposition_m = [0, 2, 20]\nlook_at_m = [0, 2, 0]\n\
                      vertical_fov_deg = 45\nwidth_px = 32\nheight_px = 24\n";

pub fn scene(medium: &str, rest: &str) -> BeamScene {
    let text = format!("[medium]\n{medium}\n{CAMERA}\n{rest}");
    BeamScene::from_toml(&text, "test.toml", Path::new(".")).unwrap()
}

/// The shipped sphere under a spotlight (Dobashi et al. 2002's Fig. 4 scene).
pub fn sphere_scene() -> BeamScene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenes/beams/sphere_spotlight.toml");
    BeamScene::load(&path).unwrap()
}

/// qtable2002 prepared for `scene` with the settings `options` ("key=value").
pub fn qtable(scene: &BeamScene, options: &[&str]) -> Qtable2002 {
    let settings = BeamSettings {
        options: ModelOptions::parse(options).unwrap(),
        ..BeamSettings::default()
    };
    Qtable2002::new(scene, &settings).unwrap()
}

/// The mean |L_550 - L_ref| of `method` against `truth` over the mean L_ref (Dobashi
/// et al. 2002's "average error in intensities") on a `columns` x `rows` grid of the
/// scene camera's pixels, each ray `offset` of a cell across and down from the cell's
/// corner (0.5: its centre).
pub fn grid_mean_error(
    scene: &BeamScene,
    method: &dyn BeamMethod,
    truth: &dyn BeamMethod,
    (columns, rows): (u32, u32),
    offset: f64,
) -> f64 {
    let cell = (
        f64::from(scene.camera.width_px) / f64::from(columns),
        f64::from(scene.camera.height_px) / f64::from(rows),
    );
    let (mut diff, mut total) = (0.0, 0.0);
    for j in 0..rows {
        for i in 0..columns {
            let ray = scene.camera.ray(
                (f64::from(i) + offset) * cell.0,
                (f64::from(j) + offset) * cell.1,
            );
            let expected = truth.radiance(&ray).unwrap()[1];
            diff += (method.radiance(&ray).unwrap()[1] - expected).abs();
            total += expected;
        }
    }
    diff / total
}

/// Method `id` prepared for `scene` with the settings `options` ("key=value").
pub fn method(id: BeamMethodId, scene: &BeamScene, options: &[&str]) -> Box<dyn BeamMethod> {
    let settings = BeamSettings {
        options: ModelOptions::parse(options).unwrap(),
        ..BeamSettings::default()
    };
    prepare(id, scene, &settings).unwrap()
}

pub fn medium(scattering: f64, absorption: f64, phase: &str) -> String {
    format!(
        "scattering_per_m = {{ kind = \"constant\", value = {scattering} }}\n\
         absorption_per_m = {{ kind = \"constant\", value = {absorption} }}\n\
         phase = {phase}\n"
    )
}

pub const ISOTROPIC: &str = "{ kind = \"henyey_greenstein\", g = 0.0 }";

/// Single scattering of an unshadowed point light of intensity `intensity` over
/// [ta, tb] of the ray, by the substitution t - t0 = h tan(theta) (Sun et al. 2005,
/// section 3): dt / s^2 = d(theta) / h and s = h sec(theta), so the integrand
/// exp(-sigma_t (t + s)) p(-sin(theta)) is smooth; 4000 panels of the 8-point rule.
#[allow(clippy::too_many_arguments)]
pub fn point_light_airlight(
    o: DVec3,
    d: DVec3,
    light: DVec3,
    intensity: f64,
    sigma_s: f64,
    sigma_t: f64,
    phase: &PhaseFunction,
    (ta, tb): (f64, f64),
) -> f64 {
    let t0 = (light - o).dot(d);
    let h = (o + d * t0 - light).length();
    let (a, b) = (((ta - t0) / h).atan(), ((tb - t0) / h).atan());
    let panels = 4000;
    let step = (b - a) / panels as f64;
    let mut sum = 0.0;
    for k in 0..panels {
        let lo = a + step * k as f64;
        for (theta, w) in mapped(&GAUSS_LEGENDRE_8, lo, lo + step) {
            let t = t0 + h * theta.tan();
            let s = h / theta.cos();
            sum += w * (-sigma_t * (t + s)).exp() * phase.eval(-theta.sin());
        }
    }
    sigma_s * intensity * sum / h
}

pub fn point_light(position: [f64; 3], intensity: f64) -> String {
    format!(
        "[[lights]]\nkind = \"point\"\nposition_m = {position:?}\nradius_m = 0.001\n\
         intensity_w_sr_nm = {{ kind = \"constant\", value = {intensity} }}\n"
    )
}

pub fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}
