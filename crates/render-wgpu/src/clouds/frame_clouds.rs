//! The cloud layer of a renderer frame: its settings and light ([`FrameClouds`]), the
//! planner's rule for when the frame can do without it ([`why_no_clouds`]), its rule for
//! the form the cloud takes by the camera's altitude, the layer's march, the spheres or
//! both blended ([`plan_clouds`], atmosphere-core's `clouds/spheres/handover.rs`), and
//! the light from the frame's CPU sky model ([`frame_light`]). The compositing is
//! atmosphere-core's `clouds/layer/composite.rs`; the GPU passes are
//! [`crate::clouds::frame_pass`].

use atmosphere_core::clouds::layer::composite::light_at;
use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::spheres::handover::{CloudForm, sphere_weight};
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::models::sky_model::SkyModel;

use crate::clouds::sun_map_texture::SunMapTexture;
use crate::frame::Frame;
use crate::frame::plan::{FramePlan, StepKind};
use crate::gpu::error::RenderError;

/// Why the planner leaves a frame's cloud steps out when the cover holds no cloud.
pub const NO_CLOUD_IN_COVER: &str = "no cloud in the cover";
/// Why the planner leaves a frame's cloud steps out when no pixel's ray meets the layer.
pub const LAYER_NOT_IN_VIEW: &str = "the cloud layer is not in view";

/// Why the planner leaves out the model's second run (`cloud_front`) when the camera is
/// inside the layer: every ray enters the cloud at the camera, with no air in front.
pub const CAMERA_IN_LAYER: &str = "the camera is inside the cloud layer";

/// Why the composite is no step of its own when the camera is inside the layer at a
/// reduced resolution: with no air in front of the cloud, the upsample composites each
/// pixel over the model's as it finds it (`frame_pass.rs`).
pub const COMPOSITE_IN_UPSAMPLE: &str =
    "the camera is inside the cloud layer: the upsample composites each pixel";

/// Why the composite is no step of its own from above the layer with the spheres and the
/// model's run in front of them at reduced resolutions: the spheres' upsample composites
/// each pixel, reading the reduced run (`spheres/frame_spheres.rs`).
pub const COMPOSITE_IN_SPHERES: &str =
    "the spheres' upsample composites each pixel with the reduced run in front";

/// Why the planner leaves out the spheres under the hand-over band (`CloudForm::Auto`).
pub const BELOW_HANDOVER: &str = "the camera is below the hand-over to the cloud spheres (50 km)";
/// Why the planner leaves out the layer's march above the hand-over band.
pub const ABOVE_HANDOVER: &str = "the camera is above the hand-over to the cloud spheres (100 km)";
/// Why the planner leaves out the spheres when the form is forced to the layer.
pub const FORCED_LAYER: &str = "the cloud form is set to the layer";
/// Why the planner leaves out the layer's march when the form is forced to the spheres.
pub const FORCED_SPHERES: &str = "the cloud form is set to the spheres";

/// The cloud layer a frame shows: the layer's settings and the light on it (one value
/// for the image, as the layer pass takes it). The cover and the multiple-scattering
/// tables are uploaded once ([`crate::Renderer::set_cloud_inputs`]).
#[derive(Clone, Debug, PartialEq)]
pub struct FrameClouds {
    pub settings: LayerSettings,
    /// The sun and sky light on the layer at the frame's three wavelengths.
    pub light: CloudLight,
    /// The layer's march, the cloud spheres, or a choice by the camera's altitude.
    pub form: CloudForm,
    /// The spheres' count and attenuation textures.
    pub spheres: SphereSettings,
    /// Whether the planner may leave the cloud steps out when they cannot change the
    /// image ([`why_no_clouds`]); off only to check that pruning changes nothing.
    pub prune: bool,
    /// Whether the cloud shadows the air below its base (crepuscular rays; hillaire's
    /// shafts, `frame_cloud_shafts.rs`).
    pub shafts: bool,
}

/// Why `frame` needs no cloud steps, if it does not: the cover, scaled by the settings'
/// `coverage_scale`, is 0 everywhere (its largest value is `max_cover`) or the layer is
/// empty; or the camera is above the layer's top and the cone around the view that holds
/// every pixel's ray misses the sphere of the top. Both are conservative: a frame they
/// prune has no pixel whose ray meets a cloud.
pub fn why_no_clouds(
    frame: &Frame,
    settings: &LayerSettings,
    max_cover: f64,
) -> Option<&'static str> {
    if max_cover * settings.coverage_scale <= 0.0 || settings.extinction_per_m <= 0.0 {
        return Some(NO_CLOUD_IN_COVER);
    }
    let (_, top_m) = settings.radii_m(frame.atmosphere.bottom_radius_m);
    let r = frame.camera_position_m.length();
    if r <= top_m {
        return None;
    }
    let [_, _, forward] = frame.axes();
    let (half_w, half_h) = frame.half_extent();
    let cone = half_w.hypot(half_h).atan();
    let to_centre = -frame.camera_position_m / r;
    let off_centre = forward.normalize().dot(to_centre).clamp(-1.0, 1.0).acos();
    // A margin of 1e-6 rad keeps rays that graze the top in.
    let sphere = (top_m / r).asin();
    (off_centre - cone > sphere + 1e-6).then_some(LAYER_NOT_IN_VIEW)
}

/// Why `frame` needs no second run of its model in front of the cloud, if it does not:
/// the camera lies between the layer's base and top, so every pixel's cloud starts at
/// the camera (`frame_march.wgsl` writes an entry distance of 0 there, which the
/// composite reads as no air in front).
pub fn why_nothing_in_front(frame: &Frame, settings: &LayerSettings) -> Option<&'static str> {
    let (base_m, top_m) = settings.radii_m(frame.atmosphere.bottom_radius_m);
    let r = frame.camera_position_m.length();
    (base_m <= r && r <= top_m).then_some(CAMERA_IN_LAYER)
}

/// The sun map the model's second run in front of the cloud binds: the frame's `map`
/// with the camera below the layer's base, where the cloud's shadow in the air lies in
/// front of the cloud; above it the same without that shadow, which then lies behind
/// the cloud ([`SunMapTexture::without_air_shadow`]).
pub fn front_sun_map(
    map: &SunMapTexture,
    frame: &Frame,
    settings: &LayerSettings,
) -> SunMapTexture {
    let (base_m, _) = settings.radii_m(frame.atmosphere.bottom_radius_m);
    if frame.camera_position_m.length() < base_m {
        map.clone()
    } else {
        map.without_air_shadow()
    }
}

/// The light of `model` (the frame's model on the CPU, at the GPU's three wavelengths)
/// on the layer of `settings`, at the middle of the layer on the camera's vertical:
/// Riley et al. 2004's cloud lit by the sky model's transmitted sun and its sky
/// (`composite.rs`, `light_at`).
pub fn frame_light(
    model: &dyn SkyModel,
    frame: &Frame,
    settings: &LayerSettings,
) -> Result<CloudLight, RenderError> {
    settings
        .check()
        .map_err(|e| RenderError::Frame(e.to_string()))?;
    let (base_m, top_m) = settings.radii_m(frame.atmosphere.bottom_radius_m);
    let vertical = frame
        .camera_position_m
        .try_normalize()
        .ok_or_else(|| RenderError::Frame("camera at the planet's centre".into()))?;
    let sun = frame
        .sun_direction
        .try_normalize()
        .ok_or_else(|| RenderError::Frame("sun direction must be non-zero".into()))?;
    Ok(light_at(model, vertical * (0.5 * (base_m + top_m)), sun)?)
}

/// The cloud steps a frame runs: the layer's march, the spheres (blended with the
/// march by `weight` when both run) and their indices in the frame's plan.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CloudSteps {
    pub march: Option<u32>,
    pub spheres: Option<u32>,
    /// The spheres' share of the cloud, in [0, 1] (`handover.rs`'s `sphere_weight`).
    pub weight: f64,
    /// Whether the march's upsample composites each pixel over the model's, so that the
    /// composite is no step of its own ([`COMPOSITE_IN_UPSAMPLE`]).
    pub composite_in_upsample: bool,
    /// Whether the spheres' upsample composites each pixel, so that the composite is no
    /// step of its own ([`COMPOSITE_IN_SPHERES`]): the spheres run at a reduced
    /// resolution and the model's run in front is reduced, which needs nothing the
    /// spheres write and so runs before them.
    pub composite_in_spheres: bool,
    /// 1 when the model's second run takes every pixel, else the divisor of its reduced
    /// run ([`front_divisor`]).
    pub front_divisor: u32,
}

/// How much coarser than the cloud's reduced image the model's reduced run in front of
/// it is, per axis: the air in front changes across the image with the planet's
/// geometry, not the cloud's.
pub const FRONT_GRID_SCALE: u32 = 2;

/// The divisor of the model's second run in front of the cloud (`clouds/frame_front.rs`)
/// with the camera above the layer's top, where every ray's cloud starts on the sphere
/// of the top: [`FRONT_GRID_SCALE`] times the resolution divisor of the cloud the frame
/// shows (the spheres' where they run, else the layer's march's) where that is above 1;
/// else 1, every pixel.
pub fn front_divisor(frame: &Frame, clouds: &FrameClouds, spheres_run: bool) -> u32 {
    let (_, top_m) = clouds.settings.radii_m(frame.atmosphere.bottom_radius_m);
    let cloud_divisor = match spheres_run {
        true => clouds.spheres.resolution_divisor,
        false => clouds.settings.resolution_divisor,
    };
    match frame.camera_position_m.length() > top_m && cloud_divisor > 1 {
        true => FRONT_GRID_SCALE * cloud_divisor,
        false => 1,
    }
}

/// The cloud steps of `frame` in `plan` (`None`: no clouds, or pruned with the reason
/// recorded when `clouds.prune`), and whether the model's second run in front of the
/// cloud is needed ([`why_nothing_in_front`]). The spheres' weight of the camera's
/// altitude chooses the steps: the march alone at 0, the spheres alone at 1, both in
/// between; the plan names the one left out and why. `max_cover` is the cover's largest
/// value, `None` when no cover was given.
pub fn plan_clouds(
    frame: &Frame,
    clouds: Option<&FrameClouds>,
    max_cover: Option<f64>,
    plan: &mut FramePlan,
) -> Result<(Option<CloudSteps>, bool), RenderError> {
    let Some(clouds) = clouds else {
        return Ok((None, false));
    };
    let Some(max_cover) = max_cover else {
        return Err(RenderError::Frame(
            "clouds are on but no cloud cover was given (set_cloud_inputs)".into(),
        ));
    };
    clouds
        .spheres
        .check()
        .map_err(|e| RenderError::Frame(e.to_string()))?;
    if let Some(why) = why_no_clouds(frame, &clouds.settings, max_cover).filter(|_| clouds.prune) {
        plan.skip("clouds", why);
        return Ok((None, false));
    }
    let altitude_m = frame.camera_position_m.length() - frame.atmosphere.bottom_radius_m;
    let weight = sphere_weight(clouds.form, altitude_m);
    let (why_no_march, why_no_spheres) = match clouds.form {
        CloudForm::Layer => (FORCED_LAYER, FORCED_LAYER),
        CloudForm::Spheres => (FORCED_SPHERES, FORCED_SPHERES),
        CloudForm::Auto => (ABOVE_HANDOVER, BELOW_HANDOVER),
    };
    let mut step = |name, runs: bool, why| {
        if runs {
            plan.run(name, StepKind::Pass);
            Some(plan.steps.len() as u32 - 1)
        } else {
            plan.skip(name, why);
            None
        }
    };
    let march = step("clouds", weight < 1.0, why_no_march);
    let spheres = step("cloud_spheres", weight > 0.0, why_no_spheres);
    let front = why_nothing_in_front(frame, &clouds.settings);
    if let Some(why) = front {
        plan.skip("cloud_front", why);
    }
    let front_divisor = front_divisor(frame, clouds, spheres.is_some());
    let steps = CloudSteps {
        march,
        spheres,
        weight,
        composite_in_upsample: march.is_some()
            && spheres.is_none()
            && clouds.settings.resolution_divisor > 1
            && front.is_some(),
        // The run in front is reduced only with the spheres' divisor above 1.
        composite_in_spheres: spheres.is_some() && front_divisor > 1,
        front_divisor,
    };
    Ok((Some(steps), front.is_none()))
}

/// The cloud steps that follow the model's pixel passes in `plan`: the model's second
/// run in front of the cloud when `front_needed`, and the composite unless the upsample
/// does it; `steps` with their indices in the plan.
pub fn plan_after_model(
    steps: CloudSteps,
    front_needed: bool,
    plan: &mut FramePlan,
) -> (CloudSteps, Option<u32>, Option<u32>) {
    let mut run = |name| {
        plan.run(name, StepKind::Pass);
        Some(plan.steps.len() as u32 - 1)
    };
    let front = if front_needed {
        run("cloud_front")
    } else {
        None
    };
    let composite = match (steps.composite_in_upsample, steps.composite_in_spheres) {
        (true, _) => {
            plan.skip("cloud_composite", COMPOSITE_IN_UPSAMPLE);
            None
        }
        (_, true) => {
            plan.skip("cloud_composite", COMPOSITE_IN_SPHERES);
            None
        }
        _ => run("cloud_composite"),
    };
    (steps, front, composite)
}

#[cfg(test)]
mod tests {
    use super::*;
    use atmosphere_core::atmosphere::Atmosphere;
    use atmosphere_core::models::id::ModelId;
    use glam::DVec3;

    use crate::frame::look_orientation;

    fn frame(altitude_m: f64, forward: DVec3) -> Frame {
        let atmosphere = Atmosphere::preset("earth").unwrap();
        Frame {
            camera_position_m: DVec3::Z * (atmosphere.bottom_radius_m + altitude_m),
            orientation: look_orientation(forward, DVec3::X)
                .or_else(|| look_orientation(forward, DVec3::Z))
                .unwrap(),
            vertical_fov_deg: 50.0,
            sun_direction: DVec3::Z,
            atmosphere,
            model: ModelId::Nishita,
            settings: Default::default(),
            exposure_ev100: 14.0,
            width: 64,
            height: 36,
            terrain: None,
        }
    }

    /// Whether the ray through any of a grid of points over the image (its edges
    /// included) meets the sphere of the layer's top.
    fn any_ray_meets_the_top(frame: &Frame, settings: &LayerSettings) -> bool {
        let (_, top_m) = settings.radii_m(frame.atmosphere.bottom_radius_m);
        let o = frame.camera_position_m;
        (0..=32).any(|i| {
            (0..=18).any(|j| {
                let x = f64::from(frame.width) * f64::from(i) / 32.0;
                let y = f64::from(frame.height) * f64::from(j) / 18.0;
                let d = frame.direction_through(x, y).normalize();
                let b = o.dot(d);
                b < 0.0 && b * b - o.length_squared() + top_m * top_m >= 0.0
            })
        })
    }

    #[test]
    fn a_pruned_frame_has_no_ray_that_meets_the_layer() {
        let settings = LayerSettings::default();
        let (mut pruned, mut kept) = (0, 0);
        for altitude_m in [3_500.0, 1e5, 4e5, 3.6e7] {
            for k in 0..72 {
                let angle = f64::from(k) * 5f64.to_radians();
                let forward = DVec3::new(angle.sin(), 0.3 * angle.cos(), angle.cos());
                let f = frame(altitude_m, forward.normalize());
                match why_no_clouds(&f, &settings, 1.0) {
                    Some(why) => {
                        assert_eq!(why, LAYER_NOT_IN_VIEW);
                        assert!(!any_ray_meets_the_top(&f, &settings), "{altitude_m} {k}");
                        pruned += 1;
                    }
                    None => kept += 1,
                }
            }
        }
        assert!(pruned > 20 && kept > 20, "{pruned} pruned, {kept} kept");
        // Below the top and with no cloud in the cover.
        let f = frame(1_000.0, DVec3::Z);
        assert_eq!(why_no_clouds(&f, &settings, 1.0), None);
        assert_eq!(why_no_clouds(&f, &settings, 0.0), Some(NO_CLOUD_IN_COVER));
        let empty = LayerSettings {
            coverage_scale: 0.0,
            ..settings
        };
        assert_eq!(why_no_clouds(&f, &empty, 1.0), Some(NO_CLOUD_IN_COVER));
    }

    /// The default cloud in `form`, the sun overhead.
    fn clouds(form: CloudForm) -> FrameClouds {
        FrameClouds {
            settings: LayerSettings::default(),
            light: CloudLight {
                sun_direction: DVec3::Z,
                sun_irradiance: vec![1.5; 3],
                sky_irradiance: vec![0.1; 3],
                up: DVec3::Z,
            },
            form,
            spheres: SphereSettings::default(),
            prune: true,
            shafts: true,
        }
    }

    fn planned(altitude_m: f64, form: CloudForm) -> (FramePlan, Option<CloudSteps>) {
        let f = frame(altitude_m, -DVec3::Z);
        let clouds = clouds(form);
        let mut plan = FramePlan::default();
        let (steps, _) = plan_clouds(&f, Some(&clouds), Some(1.0), &mut plan).unwrap();
        (plan, steps)
    }

    fn skipped_why(plan: &FramePlan, name: &str) -> Option<&'static str> {
        plan.skipped
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, why)| *why)
    }

    #[test]
    fn the_spheres_composite_only_where_they_and_the_run_in_front_are_reduced() {
        let plan_with = |altitude_m: f64, form: CloudForm, divisor: u32| {
            let f = frame(altitude_m, -DVec3::Z);
            let mut c = clouds(form);
            c.spheres.resolution_divisor = divisor;
            c.settings.resolution_divisor = divisor;
            let mut plan = FramePlan::default();
            let (steps, front_needed) = plan_clouds(&f, Some(&c), Some(1.0), &mut plan).unwrap();
            let (steps, _, composite) = plan_after_model(steps.unwrap(), front_needed, &mut plan);
            (plan, steps, composite)
        };
        // From orbit and in the hand-over band the reduced spheres composite.
        for altitude_m in [4e5, 75e3] {
            let (plan, steps, composite) = plan_with(altitude_m, CloudForm::Auto, 3);
            assert!(steps.composite_in_spheres && steps.front_divisor > 1);
            assert!(composite.is_none());
            assert_eq!(
                skipped_why(&plan, "cloud_composite"),
                Some(COMPOSITE_IN_SPHERES)
            );
        }
        // Every pixel shaded (the offline quality): the composite is a pass of its own.
        let (plan, steps, composite) = plan_with(4e5, CloudForm::Auto, 1);
        assert!(!steps.composite_in_spheres && composite.is_some());
        assert!(plan.runs("cloud_composite"));
        // The spheres forced below the layer's top: the run in front takes every pixel
        // and ends on the spheres' entries, so it runs after them and the composite too.
        let (_, steps, composite) = plan_with(500.0, CloudForm::Spheres, 3);
        assert!(!steps.composite_in_spheres && steps.front_divisor == 1);
        assert!(composite.is_some());
        // The march above the deck: its composite is a pass of its own.
        let (_, steps, composite) = plan_with(5e3, CloudForm::Auto, 3);
        assert!(!steps.composite_in_spheres && !steps.composite_in_upsample);
        assert!(steps.front_divisor > 1 && composite.is_some());
    }

    #[test]
    fn the_run_in_front_is_reduced_only_above_the_layer_with_a_reduced_cloud() {
        let clouds = |layer: u32, spheres: u32| {
            let mut c = clouds(CloudForm::Auto);
            c.settings.resolution_divisor = layer;
            c.spheres.resolution_divisor = spheres;
            c
        };
        // The default layer lies between 1.5 and 3 km.
        let (below, inside, above) = (
            frame(500.0, -DVec3::Z),
            frame(2e3, -DVec3::Z),
            frame(4e5, -DVec3::Z),
        );
        assert_eq!(
            front_divisor(&above, &clouds(1, 3), true),
            3 * FRONT_GRID_SCALE
        );
        assert_eq!(
            front_divisor(&above, &clouds(2, 1), false),
            2 * FRONT_GRID_SCALE
        );
        assert_eq!(front_divisor(&above, &clouds(2, 1), true), 1);
        for f in [&below, &inside] {
            assert_eq!(front_divisor(f, &clouds(3, 3), true), 1);
            assert_eq!(front_divisor(f, &clouds(3, 3), false), 1);
        }
    }

    #[test]
    fn the_planner_chooses_the_form_by_altitude_and_says_why() {
        use atmosphere_core::clouds::spheres::handover::{HANDOVER_END_M, HANDOVER_START_M};
        assert!(BELOW_HANDOVER.contains(&format!("({} km)", HANDOVER_START_M / 1e3)));
        assert!(ABOVE_HANDOVER.contains(&format!("({} km)", HANDOVER_END_M / 1e3)));
        // 1 km: the layer's march alone.
        let (plan, steps) = planned(1e3, CloudForm::Auto);
        let steps = steps.unwrap();
        assert!(steps.march.is_some() && steps.spheres.is_none() && steps.weight == 0.0);
        assert!(plan.runs("clouds") && !plan.runs("cloud_spheres"));
        assert_eq!(skipped_why(&plan, "cloud_spheres"), Some(BELOW_HANDOVER));
        // 100 km and 1000 km: the spheres alone.
        for altitude_m in [1e5, 1e6] {
            let (plan, steps) = planned(altitude_m, CloudForm::Auto);
            let steps = steps.unwrap();
            assert!(steps.march.is_none() && steps.spheres.is_some() && steps.weight == 1.0);
            assert!(
                !plan.runs("clouds") && plan.runs("cloud_spheres"),
                "{altitude_m}"
            );
            assert_eq!(skipped_why(&plan, "clouds"), Some(ABOVE_HANDOVER));
        }
        // In the band both run, blended.
        let (plan, steps) = planned(75e3, CloudForm::Auto);
        assert!(plan.runs("clouds") && plan.runs("cloud_spheres"));
        assert_eq!(steps.unwrap().weight, 0.5);
        // Forced forms hold at every altitude, with their reason.
        for altitude_m in [1e3, 1e5, 1e6] {
            let (plan, _) = planned(altitude_m, CloudForm::Layer);
            assert!(plan.runs("clouds"));
            assert_eq!(skipped_why(&plan, "cloud_spheres"), Some(FORCED_LAYER));
            let (plan, _) = planned(altitude_m, CloudForm::Spheres);
            assert!(plan.runs("cloud_spheres"));
            assert_eq!(skipped_why(&plan, "clouds"), Some(FORCED_SPHERES));
        }
    }
}
