//! The cloud layer of a scene (`atmos render --clouds`, or a scene file's `[clouds]`
//! table): where the cover comes from, where the layer lies, how dense it is, how its
//! light is computed and which form shows it (the layer, the spheres, or by altitude),
//! each checked against its range with errors naming the flag; and
//! what the renderer needs from them (docs/clouds.md, "Clouds in frames").

use std::path::Path;

use anyhow::{Context, bail};
use atmosphere_core::clouds::cover::generated::{CoverParameters, GeneratedCover};
use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::droplets;
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::presets::MarchQuality;
use atmosphere_core::clouds::layer::settings::{
    LayerMethod, LayerSettings, MAX_BASE_M, MAX_EXTINCTION_PER_M, MAX_THICKNESS_M, MIN_BASE_M,
    MIN_THICKNESS_M, SunLight,
};
use atmosphere_core::clouds::spheres::handover::CloudForm;
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::models::registry::prepare;
use clap::Args;
use render_wgpu::clouds::frame_clouds::{FrameClouds, frame_light};
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::{Frame, Renderer};
use serde::{Deserialize, Serialize};

use crate::table_cache_dir::table_cache;

/// The generated cover's grid: 2048 x 1024 texels (20 km at the equator).
pub const GENERATED_GRID: (usize, usize) = (2048, 1024);

/// The cloud flags; every one optional, the layer's defaults
/// (`LayerSettings::default`) filling the rest.
#[derive(Clone, Debug, Default, PartialEq, Args, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CloudFlags {
    /// Composite the planet's cloud layer into the frame, with every model [default:
    /// false].
    #[arg(long = "clouds", value_name = "BOOL", num_args = 0..=1, default_missing_value = "true")]
    pub on: Option<bool>,
    /// The cloud cover: `generated` (a deterministic global cover with the structure of
    /// real weather) or any equirectangular image, north up, the first column at 180 W,
    /// whose channel r, g, b or a (after a colon; default r) gives the cover from 0 to 1
    /// [default: generated].
    #[arg(long = "cloud-cover", value_name = "generated|FILE.png[:r|g|b|a]")]
    pub cover: Option<String>,
    /// Altitude of the layer's base above the ground, m, in [0, 20000] [default: 1500].
    #[arg(long = "cloud-base-m", value_name = "M")]
    pub base_m: Option<f64>,
    /// Thickness of the layer, m, in [10, 15000] [default: 1500].
    #[arg(long = "cloud-thickness-m", value_name = "M")]
    pub thickness_m: Option<f64>,
    /// Extinction where the cloud is densest, m^-1, in [0, 1] [default: 0.04].
    #[arg(long = "cloud-density", value_name = "PER_M")]
    pub density_per_m: Option<f64>,
    /// How light scattered more than once is computed: riley (Riley et al. 2004),
    /// octaves (Wrenninge et al. 2013), eddington (the delta-Eddington slab of Joseph,
    /// Wiscombe and Weinman 1976, for thick layers) or four-stream (a delta-M
    /// four-stream slab, Liou 1974 and Wiscombe 1977: closer, dearer) [default: riley].
    #[arg(
        long = "cloud-method",
        value_name = "riley|octaves|eddington|four-stream"
    )]
    pub method: Option<String>,
    /// The march's quality: interactive (20 steps at a third of the resolution, the
    /// cloud spheres at a third too, the cloud's shadow in the air at a sixth, for
    /// flight) or
    /// offline (128 steps, full resolution, for recordings) [default: offline].
    #[arg(long = "cloud-quality", value_name = "interactive|offline")]
    pub quality: Option<String>,
    /// Where the layer's sun light comes from: march (a shadow march from every sample)
    /// or map (the frame's sun map, made once a frame) [default: march].
    #[arg(long = "cloud-sun-light", value_name = "march|map")]
    pub sun_light: Option<String>,
    /// Which form shows the cloud: layer (the volume's march), spheres (Dobashi et al.
    /// 2002's cloud spheres), or auto (the layer up to 50 km, the spheres from 100 km,
    /// blended between) [default: auto].
    #[arg(long = "cloud-form", value_name = "auto|layer|spheres")]
    pub form: Option<String>,
    /// Shade the cloud spheres for one ray per N x N pixels and bring them to full size
    /// by each ray's span of the layer, N in [1, 4] (from orbit a texel of theirs spans
    /// many pixels) [default: the quality's: 3 at interactive, 1 (every pixel) at
    /// offline].
    #[arg(long = "cloud-sphere-divisor", value_name = "N")]
    pub sphere_divisor: Option<u32>,
    /// The cloud's shadow in the air below its base (crepuscular rays under a deck with
    /// gaps), marched per pixel and taken out by every model (docs/clouds.md)
    /// [default: true].
    #[arg(id = "cloud_shafts", long = "cloud-shafts", value_name = "BOOL")]
    pub shafts: Option<bool>,
}

impl CloudFlags {
    /// Whether no field is set (the scene file then has no `[clouds]` table).
    pub fn is_empty(&self) -> bool {
        *self == CloudFlags::default()
    }

    /// These flags with every field that `flags` sets replaced.
    pub fn overridden_by(self, flags: CloudFlags) -> CloudFlags {
        CloudFlags {
            on: flags.on.or(self.on),
            cover: flags.cover.or(self.cover),
            base_m: flags.base_m.or(self.base_m),
            thickness_m: flags.thickness_m.or(self.thickness_m),
            density_per_m: flags.density_per_m.or(self.density_per_m),
            method: flags.method.or(self.method),
            quality: flags.quality.or(self.quality),
            sun_light: flags.sun_light.or(self.sun_light),
            form: flags.form.or(self.form),
            sphere_divisor: flags.sphere_divisor.or(self.sphere_divisor),
            shafts: flags.shafts.or(self.shafts),
        }
    }

    /// The spheres' settings of `--cloud-sphere-divisor` (by default the quality's,
    /// `MarchQuality::sphere_resolution_divisor`), the rest their defaults; a divisor
    /// out of its range or an unknown quality is an error naming the flag.
    pub fn sphere_settings(&self) -> anyhow::Result<SphereSettings> {
        let spheres = SphereSettings {
            resolution_divisor: match self.sphere_divisor {
                Some(divisor) => divisor,
                None => self.quality()?.sphere_resolution_divisor(),
            },
            ..SphereSettings::default()
        };
        spheres
            .check()
            .map_err(|e| anyhow::anyhow!("--cloud-sphere-divisor: {e}"))?;
        Ok(spheres)
    }

    /// `--cloud-quality`, offline where it is not given; an unknown one is an error
    /// naming the flag.
    fn quality(&self) -> anyhow::Result<MarchQuality> {
        match &self.quality {
            Some(q) => q
                .parse::<MarchQuality>()
                .map_err(|e| anyhow::anyhow!("--cloud-quality: {e}")),
            None => Ok(MarchQuality::Offline),
        }
    }

    /// The layer's settings when the clouds are on, `None` when off; a value out of its
    /// range or an unknown method is an error naming the flag, its value and its range.
    pub fn settings(&self) -> anyhow::Result<Option<LayerSettings>> {
        if self.on != Some(true) {
            return Ok(None);
        }
        let defaults = LayerSettings::default();
        let within = |value: Option<f64>, default: f64, flag: &str, low: f64, high: f64| {
            let v = value.unwrap_or(default);
            if !(v.is_finite() && (low..=high).contains(&v)) {
                bail!("--{flag} {v} must lie in [{low}, {high}]");
            }
            Ok(v)
        };
        let method = match &self.method {
            Some(m) => m
                .parse::<LayerMethod>()
                .map_err(|e| anyhow::anyhow!("--cloud-method: {e}"))?,
            None => defaults.method,
        };
        let quality = self.quality()?;
        let settings = LayerSettings {
            base_m: within(
                self.base_m,
                defaults.base_m,
                "cloud-base-m",
                MIN_BASE_M,
                MAX_BASE_M,
            )?,
            thickness_m: within(
                self.thickness_m,
                defaults.thickness_m,
                "cloud-thickness-m",
                MIN_THICKNESS_M,
                MAX_THICKNESS_M,
            )?,
            extinction_per_m: within(
                self.density_per_m,
                defaults.extinction_per_m,
                "cloud-density",
                0.0,
                MAX_EXTINCTION_PER_M,
            )?,
            method,
            ..quality.apply(defaults)
        };
        let settings = match &self.sun_light {
            Some(s) => LayerSettings {
                sun_light: s
                    .parse::<SunLight>()
                    .map_err(|e| anyhow::anyhow!("--cloud-sun-light: {e}"))?,
                ..settings
            },
            None => settings,
        };
        settings.check()?;
        Ok(Some(settings))
    }

    /// The form of `--cloud-form`; an unknown one is an error naming the flag and the
    /// forms.
    pub fn form(&self) -> anyhow::Result<CloudForm> {
        match &self.form {
            Some(f) => f
                .parse::<CloudForm>()
                .map_err(|e| anyhow::anyhow!("--cloud-form: {e}")),
            None => Ok(CloudForm::default()),
        }
    }

    /// The cover grid of `--cloud-cover`.
    pub fn cover_grid(&self) -> anyhow::Result<CoverGrid> {
        let source = self.cover.as_deref().unwrap_or("generated");
        if source == "generated" {
            let cover = GeneratedCover::new(CoverParameters::default())?;
            let (width, height) = GENERATED_GRID;
            return Ok(CoverGrid::rasterize(width, height, |p| cover.cover(p))?);
        }
        let (path, channel) = match source.rsplit_once(':') {
            Some((path, c)) if ["r", "g", "b", "a"].contains(&c) => (path, c),
            Some((_, c)) if c.len() == 1 => {
                bail!("--cloud-cover {source}: channel {c:?} is not one of r, g, b, a")
            }
            _ => (source, "r"),
        };
        image_cover(Path::new(path), channel).with_context(|| format!("--cloud-cover {source}"))
    }
}

/// The cover in `channel` of the equirectangular image at `path`, 0 to 1.
fn image_cover(path: &Path, channel: &str) -> anyhow::Result<CoverGrid> {
    let image = image::open(path)
        .with_context(|| format!("cannot read {}", path.display()))?
        .to_rgba8();
    let index = ["r", "g", "b", "a"]
        .iter()
        .position(|c| *c == channel)
        .unwrap_or(0);
    let values = image
        .pixels()
        .map(|p| f32::from(p.0[index]) / 255.0)
        .collect();
    let what = format!("{} channel {channel}", path.display());
    Ok(CoverGrid::from_values(
        &what,
        image.width() as usize,
        image.height() as usize,
        values,
    )?)
}

/// The layer's multiple-scattering tables at the renderer's wavelengths (680, 550 and
/// 440 nm): Riley et al. 2004's A_n and F_n of the droplets' Lorenz-Mie phase function
/// (atmosphere-core's `clouds/layer/droplets.rs`), kept in the table cache.
pub fn droplet_orders() -> anyhow::Result<ScatteringOrders> {
    Ok(droplets::droplet_orders_cached(
        &RGB_WAVELENGTHS_NM,
        &table_cache(),
    )?)
}

/// What a frame's clouds need besides the light: the layer's settings, its cover and its
/// tables, made (and checked, errors naming the flag) before the GPU is opened.
#[derive(Debug)]
pub struct CloudInputs {
    pub settings: LayerSettings,
    pub form: CloudForm,
    pub spheres: SphereSettings,
    /// Whether the cloud shadows the air below its base (`--cloud-shafts`).
    pub shafts: bool,
    pub cover: CoverGrid,
    pub orders: ScatteringOrders,
}

impl CloudInputs {
    /// The inputs of `flags`; `None` when the clouds are off.
    pub fn load(flags: &CloudFlags) -> anyhow::Result<Option<CloudInputs>> {
        let Some(settings) = flags.settings()? else {
            return Ok(None);
        };
        Ok(Some(CloudInputs {
            settings,
            form: flags.form()?,
            spheres: flags.sphere_settings()?,
            shafts: flags.shafts.unwrap_or(true),
            cover: flags.cover_grid()?,
            orders: droplet_orders()?,
        }))
    }

    /// Gives `renderer` these clouds for `frame`, lit by the frame's model on the CPU.
    pub fn set_up(&self, renderer: &mut Renderer, frame: &Frame) -> anyhow::Result<()> {
        renderer.set_cloud_inputs(&self.cover, &self.orders)?;
        let model = prepare(frame.model, &frame.atmosphere, &frame.settings)?;
        let light = frame_light(model.as_ref(), frame, &self.settings)?;
        renderer.set_clouds(Some(FrameClouds {
            settings: self.settings,
            light,
            form: self.form,
            spheres: self.spheres,
            prune: true,
            shafts: self.shafts,
        }))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn on() -> CloudFlags {
        CloudFlags {
            on: Some(true),
            ..CloudFlags::default()
        }
    }

    #[test]
    fn off_gives_no_layer_and_on_the_defaults_with_the_flags_set() {
        assert_eq!(CloudFlags::default().settings().unwrap(), None);
        let settings = CloudFlags {
            base_m: Some(800.0),
            method: Some("octaves".into()),
            ..on()
        }
        .settings()
        .unwrap()
        .unwrap();
        assert_eq!(settings.base_m, 800.0);
        assert_eq!(settings.method, LayerMethod::Octaves);
        assert_eq!(settings.thickness_m, LayerSettings::default().thickness_m);
        assert_eq!(
            settings,
            MarchQuality::Offline.apply(LayerSettings {
                base_m: 800.0,
                method: LayerMethod::Octaves,
                ..LayerSettings::default()
            })
        );
        let interactive = CloudFlags {
            quality: Some("interactive".into()),
            ..on()
        };
        assert_eq!(
            interactive.settings().unwrap(),
            Some(MarchQuality::Interactive.apply(LayerSettings::default()))
        );
        let mapped = CloudFlags {
            sun_light: Some("map".into()),
            ..interactive
        };
        assert_eq!(
            mapped.settings().unwrap().map(|s| s.sun_light),
            Some(SunLight::Map)
        );
    }

    #[test]
    fn bad_values_are_refused_naming_the_flag_and_range() {
        let error = |flags: CloudFlags| flags.settings().unwrap_err().to_string();
        let e = error(CloudFlags {
            base_m: Some(-1.0),
            ..on()
        });
        assert!(
            e.contains("--cloud-base-m -1") && e.contains("[0, 20000]"),
            "{e}"
        );
        let e = error(CloudFlags {
            thickness_m: Some(f64::NAN),
            ..on()
        });
        assert!(e.contains("--cloud-thickness-m NaN"), "{e}");
        let e = error(CloudFlags {
            density_per_m: Some(2.0),
            ..on()
        });
        assert!(
            e.contains("--cloud-density 2") && e.contains("[0, 1]"),
            "{e}"
        );
        let e = error(CloudFlags {
            method: Some("slices".into()),
            ..on()
        });
        assert!(
            e.contains("--cloud-method") && e.contains("riley, octaves"),
            "{e}"
        );
        let e = CloudFlags {
            sphere_divisor: Some(5),
            ..on()
        }
        .sphere_settings()
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("--cloud-sphere-divisor") && e.contains("= 5 must lie in [1, 4]"),
            "{e}"
        );
        let spheres = CloudFlags {
            sphere_divisor: Some(3),
            ..on()
        }
        .sphere_settings()
        .unwrap();
        assert_eq!(spheres.resolution_divisor, 3);
        // Without the flag the quality chooses: a third at interactive (the viewer's),
        // every pixel at offline (render's default).
        for (quality, divisor) in [(Some("interactive"), 3), (Some("offline"), 1), (None, 1)] {
            let spheres = CloudFlags {
                quality: quality.map(str::to_string),
                ..on()
            }
            .sphere_settings()
            .unwrap();
            assert_eq!(spheres.resolution_divisor, divisor, "{quality:?}");
        }
        let e = CloudFlags {
            form: Some("volume".into()),
            ..on()
        }
        .form()
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("--cloud-form") && e.contains("auto, layer, spheres"),
            "{e}"
        );
        let e = error(CloudFlags {
            sun_light: Some("rays".into()),
            ..on()
        });
        assert!(
            e.contains("--cloud-sun-light") && e.contains("march, map"),
            "{e}"
        );
        let e = error(CloudFlags {
            quality: Some("best".into()),
            ..on()
        });
        assert!(
            e.contains("--cloud-quality") && e.contains("interactive, offline"),
            "{e}"
        );
        let e = CloudFlags {
            cover: Some("x.png:q".into()),
            ..on()
        }
        .cover_grid()
        .unwrap_err()
        .to_string();
        assert!(e.contains("channel \"q\""), "{e}");
        let e = CloudFlags {
            cover: Some("/nonexistent/cover.png".into()),
            ..on()
        }
        .cover_grid()
        .unwrap_err();
        assert!(
            format!("{e:#}").contains("--cloud-cover /nonexistent/cover.png"),
            "{e:#}"
        );
    }

    #[test]
    fn an_image_channel_is_the_cover() {
        let dir = std::env::temp_dir().join(format!("atmos-cloud-cover-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("cover.png");
        let image = image::RgbaImage::from_fn(4, 2, |x, y| {
            image::Rgba([0, 51 * x as u8, 255, 255 * y as u8])
        });
        image.save(&path).unwrap();
        let flags = |channel: &str| CloudFlags {
            cover: Some(format!("{}:{channel}", path.display())),
            ..on()
        };
        let green = flags("g").cover_grid().unwrap();
        assert_eq!((green.width(), green.height()), (4, 2));
        assert_eq!(&green.values()[..4], &[0.0, 0.2, 0.4, 0.6]);
        let alpha = flags("a").cover_grid().unwrap();
        assert_eq!(&alpha.values()[3..5], &[0.0, 1.0]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_scene_file_takes_a_clouds_table_and_flags_override_it() {
        let file: CloudFlags =
            toml::from_str("on = true\nbase_m = 900.0\nmethod = \"octaves\"\n").unwrap();
        let merged = file.overridden_by(CloudFlags {
            base_m: Some(1200.0),
            ..CloudFlags::default()
        });
        assert_eq!(merged.base_m, Some(1200.0));
        assert_eq!(merged.method.as_deref(), Some("octaves"));
        assert!(toml::from_str::<CloudFlags>("bse_m = 1.0\n").is_err());
        let file: CloudFlags = toml::from_str("on = true\nform = \"spheres\"\n").unwrap();
        assert_eq!(file.form().unwrap(), CloudForm::Spheres);
        let forced = file.overridden_by(CloudFlags {
            form: Some("layer".into()),
            ..CloudFlags::default()
        });
        assert_eq!(forced.form().unwrap(), CloudForm::Layer);
        assert_eq!(CloudFlags::default().form().unwrap(), CloudForm::Auto);
    }
}
