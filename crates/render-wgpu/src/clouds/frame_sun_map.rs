//! The cloud layer's sun map in a renderer frame: the planner's rule for it
//! ([`why_no_sun_map`]), its grid under the frame's camera, and its fill before the
//! cloud's march, which reads it with `sun_light = map`, and the model's passes, which
//! multiply the surface's sun by its transmittance (the clouds' shadows on the terrain;
//! docs/clouds.md, "Cloud shadows") and, after the fill, the cloud's shadow in the air
//! below the layer's base (`air_shadow_pass.rs`, planned by `frame_cloud_shafts.rs`),
//! which every model's pixel pass subtracts.

use atmosphere_core::clouds::layer::settings::SunLight;
use atmosphere_core::clouds::layer::shell::Shell;
use atmosphere_core::clouds::layer::sun_map::{CloudSunMap, SunMapResolution, half_width_m};

use crate::clouds::air_shadow_pass::AirShadowPass;
use crate::clouds::frame_cloud_shafts::{CLOUD_SHAFTS, NO_CLOUD_STEPS, why_no_cloud_shafts};
use crate::clouds::frame_clouds::FrameClouds;
use crate::clouds::frame_pass::frame_camera;
use crate::clouds::layer_inputs::LayerInputs;
use crate::clouds::layer_uniform::LayerUniform;
use crate::clouds::sun_map_pass::{PixelInputs, SunMapPass};
use crate::clouds::sun_map_texture::{SunMapTexture, SunMapUniform};
use crate::frame::Frame;
use crate::frame::plan::{FramePlan, StepKind};
use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::timer::GpuTimer;

/// Why the planner leaves the sun map out of a frame whose rays end on no surface and
/// whose air the cloud does not shade.
pub const NO_SURFACE: &str = "no surface or air in view to shade";
/// Why it leaves the map out when the sun is below the horizon all over the map.
pub const SUN_DOWN: &str = "the sun is below the horizon over the map";

/// Why `frame` needs no sun map when its cloud steps run: no surface and no air
/// (`shades`) takes the shadow, or the sun is more than the map's angular half width (and 2 degrees for the
/// relief) below the camera's horizon, where no point of the map's region sees it.
pub fn why_no_sun_map(frame: &Frame, shades: bool, shell: &Shell) -> Option<&'static str> {
    if !shades {
        return Some(NO_SURFACE);
    }
    let up = frame.camera_position_m.normalize();
    let altitude = frame.camera_position_m.length() - shell.ground_radius_m;
    let half = half_width_m(shell.ground_radius_m, altitude);
    let below = half / shell.ground_radius_m + 2f64.to_radians();
    let elevation = frame
        .sun_direction
        .normalize()
        .dot(up)
        .clamp(-1.0, 1.0)
        .asin();
    (elevation < -below).then_some(SUN_DOWN)
}

/// The frame's sun map: its texture (bound by every pixel pass), its fill pass and the
/// pass of the cloud's shadow in the air (each made on first use), the steps they run as
/// in this frame and whether a surface reads the map.
#[derive(Debug)]
pub struct FrameSunMap {
    texture: SunMapTexture,
    pass: Option<SunMapPass>,
    air: Option<AirShadowPass>,
    step: Option<u32>,
    air_step: Option<u32>,
    shades_surface: bool,
}

impl FrameSunMap {
    pub fn new(gpu: &GpuContext) -> FrameSunMap {
        FrameSunMap {
            texture: SunMapTexture::new(gpu),
            pass: None,
            air: None,
            step: None,
            air_step: None,
            shades_surface: false,
        }
    }

    /// The texture and parameters the pixel passes bind.
    pub fn texture(&self) -> &SunMapTexture {
        &self.texture
    }

    /// Plans the map of `frame`, whose cloud steps run when `clouds_run`, into `plan`
    /// (`cloud_shadow`, or skipped with why by [`why_no_sun_map`] when the clouds
    /// prune; never skipped when the layer is lit by it, whose resolution is then
    /// [`SunMapResolution::LIT`]), with the cloud's shadow in the air where
    /// [`why_no_cloud_shafts`] finds none missing (the step `cloud_shafts` after the
    /// fill, else skipped with why), and sets the parameters the pixel passes read.
    pub fn plan(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
        clouds: Option<(&FrameClouds, bool)>,
        has_surface: bool,
        plan: &mut FramePlan,
    ) -> Result<(), RenderError> {
        self.step = None;
        self.air_step = None;
        self.shades_surface = has_surface;
        let pixels = (frame.width, frame.height);
        let clouds = match clouds {
            Some((clouds, true)) => clouds,
            Some((clouds, false)) => {
                if clouds.shafts {
                    plan.skip(CLOUD_SHAFTS, NO_CLOUD_STEPS);
                }
                return self.texture.set(gpu, None, pixels);
            }
            None => return self.texture.set(gpu, None, pixels),
        };
        let air = match why_no_cloud_shafts(frame, clouds) {
            Some(why) => {
                plan.skip(CLOUD_SHAFTS, why);
                false
            }
            None => true,
        };
        let ground = frame.atmosphere.bottom_radius_m;
        let (base, top) = clouds.settings.radii_m(ground);
        let shell = Shell {
            ground_radius_m: ground,
            base_radius_m: base,
            top_radius_m: top,
        };
        let lit = clouds.settings.sun_light == SunLight::Map;
        let shades = has_surface || air;
        let skip = why_no_sun_map(frame, shades, &shell).filter(|_| clouds.prune && !lit);
        if let Some(why) = skip {
            plan.skip("cloud_shadow", why);
            return self.texture.set(gpu, None, pixels);
        }
        // The air below the base reads level 0 alone: without a surface, one level.
        let resolution = match (lit, has_surface) {
            (true, _) => SunMapResolution::LIT,
            (false, true) => SunMapResolution::default(),
            (false, false) => SunMapResolution {
                levels: 1,
                ..SunMapResolution::default()
            },
        };
        let to_error =
            |e: atmosphere_core::clouds::error::CloudError| RenderError::Frame(e.to_string());
        let grid = CloudSunMap::grid_for(&shell, frame.camera_position_m, &resolution)
            .map_err(to_error)?;
        let sun = frame
            .sun_direction
            .try_normalize()
            .ok_or_else(|| RenderError::Frame("sun direction must be non-zero".into()))?;
        let params = SunMapUniform::new(&grid, sun, top, &resolution).shading_air(air);
        self.texture.set(gpu, Some(&params), pixels)?;
        if self.pass.is_none() {
            self.pass = Some(SunMapPass::new(gpu)?);
        }
        plan.cloud_shafts = air;
        plan.run("cloud_shadow", StepKind::Pass);
        self.step = Some(plan.steps.len() as u32 - 1);
        if air {
            if self.air.is_none() {
                self.air = Some(AirShadowPass::new(gpu)?);
            }
            if let Some(pass) = self.air.as_mut() {
                pass.plan(&frame.atmosphere);
            }
            plan.run(CLOUD_SHAFTS, StepKind::Pass);
            self.air_step = Some(plan.steps.len() as u32 - 1);
        }
        Ok(())
    }

    /// The planned step's index, if the map runs in this frame.
    pub fn step(&self) -> Option<u32> {
        self.step
    }

    /// Records the fill of the planned map of `frame` with `clouds` over `inputs`' cover,
    /// then the cloud's shadow in the air where it is planned, else the map's read at
    /// each pixel's surface where the frame has one; `timer`, when the frame is timed,
    /// times the fill's and the air's steps.
    pub fn encode(
        &mut self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        scene: (&Frame, &FrameClouds, &LayerInputs),
        pixels: PixelInputs<'_>,
        timer: Option<&GpuTimer>,
    ) -> Result<(), RenderError> {
        let (frame, clouds, inputs) = scene;
        let (Some(_), Some(pass)) = (self.step, &self.pass) else {
            return Ok(());
        };
        let layer = LayerUniform::new(
            &frame_camera(frame),
            &clouds.light,
            &clouds.settings,
            frame.atmosphere.bottom_radius_m,
            inputs.cover_size,
        )?;
        let [fill, air] = [self.step, self.air_step]
            .map(|step| timer.zip(step).map(|(t, s)| t.compute_writes(s)));
        pass.encode(gpu, encoder, &layer, &inputs.cover, &self.texture, fill);
        if let (Some(_), Some(air_pass)) = (self.air_step, self.air.as_mut()) {
            if self.shades_surface {
                let size = (frame.width, frame.height);
                let target = air_pass.surface_sun_target(gpu, size);
                pass.encode_pixels_into(gpu, encoder, pixels, &self.texture, target);
            }
            let divisor = clouds.settings.air_shadow_divisor;
            air_pass.encode(gpu, encoder, pixels, (&self.texture, divisor), air)?;
        } else if self.shades_surface {
            pass.encode_pixels(gpu, encoder, pixels, &self.texture);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use atmosphere_core::atmosphere::Atmosphere;
    use atmosphere_core::models::id::ModelId;
    use glam::DVec3;

    use super::*;
    use crate::frame::look_orientation;

    /// A frame 1 km up on the x axis, the sun `elevation_deg` above its horizon.
    fn frame(elevation_deg: f64) -> Frame {
        let atmosphere = Atmosphere::preset("earth").unwrap();
        let e = elevation_deg.to_radians();
        Frame {
            camera_position_m: DVec3::X * (atmosphere.bottom_radius_m + 1_000.0),
            orientation: look_orientation(DVec3::Y, DVec3::X).unwrap(),
            vertical_fov_deg: 50.0,
            sun_direction: DVec3::new(e.sin(), e.cos(), 0.0),
            atmosphere,
            model: ModelId::Nishita,
            settings: Default::default(),
            exposure_ev100: 14.0,
            width: 64,
            height: 36,
            terrain: None,
        }
    }

    #[test]
    fn the_map_is_left_out_without_a_surface_or_a_sun_over_it() {
        let f = frame(30.0);
        let ground = f.atmosphere.bottom_radius_m;
        let shell = Shell {
            ground_radius_m: ground,
            base_radius_m: ground + 1_500.0,
            top_radius_m: ground + 3_000.0,
        };
        assert_eq!(why_no_sun_map(&f, true, &shell), None);
        assert_eq!(why_no_sun_map(&f, false, &shell), Some(NO_SURFACE));
        // The map reaches 133 km, 1.2 degrees of arc, out: a sun 1 degree down still
        // lights its far side; 10 degrees down lights none of it.
        assert_eq!(why_no_sun_map(&frame(-1.0), true, &shell), None);
        assert_eq!(why_no_sun_map(&frame(-10.0), true, &shell), Some(SUN_DOWN));
    }
}
