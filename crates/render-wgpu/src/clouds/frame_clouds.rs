//! The cloud layer of a renderer frame: its settings and light ([`FrameClouds`]), the
//! planner's rule for when the frame can do without it ([`why_no_clouds`]), and the light
//! from the frame's CPU sky model ([`frame_light`]). The compositing is
//! atmosphere-core's `clouds/layer/composite.rs`; the GPU passes are
//! [`crate::clouds::frame_pass`].

use atmosphere_core::clouds::layer::composite::light_at;
use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::models::sky_model::SkyModel;

use crate::frame::Frame;
use crate::gpu::error::RenderError;

/// Why the planner leaves a frame's cloud steps out when the cover holds no cloud.
pub const NO_CLOUD_IN_COVER: &str = "no cloud in the cover";
/// Why the planner leaves a frame's cloud steps out when no pixel's ray meets the layer.
pub const LAYER_NOT_IN_VIEW: &str = "the cloud layer is not in view";

/// The cloud layer a frame shows: the layer's settings and the light on it (one value
/// for the image, as the layer pass takes it). The cover and the multiple-scattering
/// tables are uploaded once ([`crate::Renderer::set_cloud_inputs`]).
#[derive(Clone, Debug, PartialEq)]
pub struct FrameClouds {
    pub settings: LayerSettings,
    /// The sun and sky light on the layer at the frame's three wavelengths.
    pub light: CloudLight,
    /// Whether the planner may leave the cloud steps out when they cannot change the
    /// image ([`why_no_clouds`]); off only to check that pruning changes nothing.
    pub prune: bool,
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
