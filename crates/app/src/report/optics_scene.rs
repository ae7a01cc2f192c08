//! One view of the optics section made ready to answer: its shipped scene's frame (at
//! [`FRAME_SIZE`]), the sky model's CPU twin, the line of rays, the volume lit for a
//! row's settings, the CPU composite of a row (`hydrometeors/render.rs`) and the path
//! tracer's answers (`hydrometeors/reference/`).

use std::path::Path;

use anyhow::{Context, bail};
use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::clouds::reference::settings::PathSettings;
use atmosphere_core::clouds::reference::sun_light::SunThroughAtmosphere;
use atmosphere_core::hydrometeors::forward_peak::ForwardPeak;
use atmosphere_core::hydrometeors::reference::path::{VolumePaths, environment_around};
use atmosphere_core::hydrometeors::reference::phase::ChannelSampler;
use atmosphere_core::hydrometeors::reference::ray::{VolumeTracedRay, radiance_path_traced};
use atmosphere_core::hydrometeors::render::{LitVolume, composite_in_steps};
use atmosphere_core::hydrometeors::scene::{VolumeOptics, lit_volume};
use atmosphere_core::hydrometeors::sky_light::SkyLight;
use atmosphere_core::hydrometeors::sun_orders::MultipleScattering;
use atmosphere_core::hydrometeors::volumes::Volume;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{RayRadiance, SkyModel, ViewRay};
use rayon::prelude::*;
use render_wgpu::Frame;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;

use crate::cloud_rays::CloudAnswer;
use crate::progress::Progress;
use crate::render::scene::Scene;
use crate::report::optics_views::{FRAME_SIZE, OpticsView};
use crate::table_cache_dir::table_cache;

/// A volume's tables: wavelengths across 380-720 nm, and whether they hold the sun's
/// disc (a point sun otherwise).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tables {
    pub wavelengths: usize,
    pub sun_disc: bool,
}

/// A view, its frame, rays and sky.
pub struct OpticsScene {
    pub view: OpticsView,
    /// The scene file's text (the reference's fingerprint holds it).
    pub scene_text: String,
    pub frame: Frame,
    pub rays: Vec<ViewRay>,
    volume: Volume,
    air: Box<dyn SkyModel>,
    extinction: [[f64; 3]; 3],
}

impl std::fmt::Debug for OpticsScene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OpticsScene")
            .field("view", &self.view)
            .field("rays", &self.rays.len())
            .finish_non_exhaustive()
    }
}

impl OpticsScene {
    /// `view` with its scene read from `folder`.
    pub fn new(view: OpticsView, folder: &Path) -> anyhow::Result<OpticsScene> {
        let path = folder.join(view.scene);
        let scene_text = std::fs::read_to_string(&path)
            .with_context(|| format!("optics view {}: {}", view.id, path.display()))?;
        let scene = Scene::parse(&scene_text, &path)?
            .overridden_by(Scene {
                width: Some(FRAME_SIZE.0),
                height: Some(FRAME_SIZE.1),
                ..Scene::default()
            })
            .resolved()?;
        let frame = scene.frame()?;
        let volumes = scene.volumes.volumes(&frame)?;
        let [(_, volume)] = volumes[..] else {
            bail!(
                "optics view {}: {} holds {} volumes, the view one",
                view.id,
                path.display(),
                volumes.len()
            );
        };
        let air = prepare(frame.model, &frame.atmosphere, &frame.settings)?;
        let spectra = Spectra::new(&frame.atmosphere, &RGB_WAVELENGTHS_NM);
        let extinction = std::array::from_fn(|c| spectra.extinction[c]);
        let rays = view
            .directions(frame.camera_position_m, frame.sun_direction)
            .into_iter()
            .map(|direction| ViewRay {
                origin_m: frame.camera_position_m,
                direction,
                sun_direction: frame.sun_direction,
                max_distance_m: None,
            })
            .collect();
        Ok(OpticsScene {
            view,
            scene_text,
            frame,
            rays,
            volume,
            air,
            extinction,
        })
    }

    pub fn air(&self) -> &dyn SkyModel {
        self.air.as_ref()
    }

    /// The scene's volume with `tables` (from the table cache, or built) and its
    /// forward peak counted as `forward_peak` says, lit by the sky model as the renderer
    /// lights it, the sky's light as `sky_light` says, the sun's higher orders as
    /// `multiple_scattering` says.
    pub fn lit(
        &self,
        tables: Tables,
        (forward_peak, sky_light, multiple_scattering): (ForwardPeak, SkyLight, MultipleScattering),
    ) -> anyhow::Result<LitVolume> {
        let sun_radius = if tables.sun_disc {
            self.frame.atmosphere.sun.angular_radius_rad
        } else {
            0.0
        };
        lit_volume(
            self.air(),
            self.volume,
            (self.frame.camera_position_m, self.frame.sun_direction),
            VolumeOptics {
                wavelengths: tables.wavelengths,
                sun_radius_rad: sun_radius,
                forward_peak,
                sky_light,
                multiple_scattering,
            },
            RGB_WAVELENGTHS_NM,
            &table_cache(),
        )
        .with_context(|| format!("optics view {}: the volume's tables", self.view.id))
    }

    /// The renderer's CPU twin for `ray`: the model's pixel with `lit` composited over
    /// it, marched in `steps` steps.
    pub fn composite(
        &self,
        lit: &LitVolume,
        ray: &ViewRay,
        steps: usize,
    ) -> anyhow::Result<CloudAnswer> {
        let full = self.air.radiance(ray)?;
        let pixel = std::array::from_fn(|c| full.radiance[c]);
        let radiance = self.composite_over(lit, ray, steps, pixel);
        Ok(CloudAnswer {
            radiance: RayRadiance {
                radiance: radiance.to_vec(),
                ..full
            },
            cloud_transmittance: 1.0,
            paths: None,
        })
    }

    /// `lit` composited over the model's `pixel` for `ray`, marched in `steps` steps.
    pub fn composite_over(
        &self,
        lit: &LitVolume,
        ray: &ViewRay,
        steps: usize,
        pixel: [f64; 3],
    ) -> [f64; 3] {
        composite_in_steps(
            &self.frame.atmosphere,
            &self.extinction,
            std::slice::from_ref(lit),
            (ray.origin_m, ray.direction.normalize(), f64::INFINITY),
            pixel,
            steps,
        )
    }

    /// The path tracer's answers for every ray, in parallel, through `lit` (the
    /// reference's tables, their forward peak whole: the path tracer truncates it
    /// itself), to `paths`' stopping rule.
    pub fn reference(
        &self,
        lit: &LitVolume,
        paths: &PathSettings,
        progress: &Progress,
    ) -> anyhow::Result<Vec<VolumeTracedRay>> {
        if lit.peak_fraction != [0.0; 3] {
            bail!(
                "optics view {}: the reference takes the whole table and truncates its \
                 forward peak itself",
                self.view.id
            );
        }
        let atmosphere = &self.frame.atmosphere;
        let sun =
            SunThroughAtmosphere::new(atmosphere, &Spectra::new(atmosphere, &RGB_WAVELENGTHS_NM));
        let sampler = ChannelSampler::new(&lit.phase)?;
        let sun_direction = self.frame.sun_direction.normalize();
        let environment = environment_around(
            &lit.volume,
            self.air(),
            self.frame.camera_position_m,
            sun_direction,
        )?;
        let scene = VolumePaths {
            volume: &lit.volume,
            phase: &sampler,
            sun: &sun,
            environment: Some(&environment),
            sun_direction,
        };
        self.rays
            .par_iter()
            .map(|ray| {
                let answer = radiance_path_traced(&scene, self.air(), ray, paths);
                progress.inc();
                Ok(answer?)
            })
            .collect()
    }
}
