//! The rows of the clouds section: each cloud method and setting (Riley et al. 2004's
//! multiple scattering, Wrenninge et al. 2013's octaves or the delta-Eddington slab of
//! Joseph, Wiscombe and Weinman 1976; the interactive or offline
//! march; the sun's light by a shadow march or from the frame's sun map), and the cloud
//! spheres of Dobashi et al. 2002 section 5.4 on the view from orbit; their answers for
//! a view's rays and the CPU time they took.

use std::fmt;
use std::time::Instant;

use anyhow::{Context, bail};
use atmosphere_core::clouds::layer::presets::MarchQuality;
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings, SunLight};
use atmosphere_core::clouds::spheres::handover::CloudForm;
use atmosphere_core::models::sky_model::ViewRay;

use crate::cloud_rays::{CloudAnswer, RayMaps};
use crate::report::clouds_scene::ViewScene;

/// Pixels of the 1280 x 720 frame a CPU time per ray is scaled to.
pub const FRAME_PIXELS: f64 = 1280.0 * 720.0;
/// A row's rays are answered again until this much time has passed, s, so that the
/// time per ray is not one clock tick.
const MIN_TIMED_S: f64 = 0.3;

/// One row of the section.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CloudRow {
    /// The layer's march with these settings (the cloud itself is the view's).
    Layer {
        method: LayerMethod,
        quality: MarchQuality,
        sun_light: SunLight,
    },
    /// The cloud spheres (frames' settings: 5 spheres) lit as the layer's `method` lights
    /// them (riley: the octaves; eddington, four-stream: their slab), on the views that
    /// measure them.
    Spheres { method: LayerMethod },
}

impl fmt::Display for CloudRow {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CloudRow::Layer {
                method,
                quality,
                sun_light,
            } => write!(f, "{method} {quality} {sun_light}"),
            CloudRow::Spheres {
                method: LayerMethod::Riley,
            } => f.write_str("spheres"),
            CloudRow::Spheres { method } => write!(f, "spheres {method}"),
        }
    }
}

impl CloudRow {
    /// A row as `--variant` writes it: `spheres` (lit as riley lights them) or
    /// `spheres METHOD`, or a method (riley, octaves, eddington, four-stream), a quality
    /// (interactive, offline) and a sun light (march, map) in any order, the method
    /// required, the others by default offline and march. Errors name the word and what
    /// it may be.
    pub fn parse(text: &str) -> anyhow::Result<CloudRow> {
        let words: Vec<&str> = text.split_whitespace().collect();
        match words.as_slice() {
            ["spheres"] => {
                return Ok(CloudRow::Spheres {
                    method: LayerMethod::Riley,
                });
            }
            ["spheres", method] => {
                let method = method
                    .parse::<LayerMethod>()
                    .map_err(|e| anyhow::anyhow!("clouds variant \"{text}\": {e}"))?;
                return Ok(CloudRow::Spheres { method });
            }
            _ => {}
        }
        let (mut method, mut quality, mut sun_light) = (None, None, None);
        for word in &words {
            if let Ok(m) = word.parse::<LayerMethod>() {
                method = Some(m);
            } else if let Ok(q) = word.parse::<MarchQuality>() {
                quality = Some(q);
            } else if let Ok(s) = word.parse::<SunLight>() {
                sun_light = Some(s);
            } else {
                bail!(
                    "clouds variant \"{text}\": \"{word}\" is none of spheres, riley, octaves, \
                     eddington, four-stream, interactive, offline, march, map"
                );
            }
        }
        let Some(method) = method else {
            bail!(
                "clouds variant \"{text}\" names no method: riley, octaves, eddington or four-stream (with interactive \
                 or offline, march or map), or spheres"
            );
        };
        Ok(CloudRow::Layer {
            method,
            quality: quality.unwrap_or(MarchQuality::Offline),
            sun_light: sun_light.unwrap_or(SunLight::March),
        })
    }

    /// The layer's settings a row's clouds take: the march's, or for the spheres the
    /// offline preset with their method.
    pub fn cloud_settings(&self) -> LayerSettings {
        match *self {
            CloudRow::Layer {
                method,
                quality,
                sun_light,
            } => LayerSettings {
                sun_light,
                ..quality.apply(LayerSettings {
                    method,
                    ..LayerSettings::default()
                })
            },
            CloudRow::Spheres { method } => MarchQuality::Offline.apply(LayerSettings {
                method,
                ..LayerSettings::default()
            }),
        }
    }

    /// The form a frame of this row shows.
    pub fn form(&self) -> CloudForm {
        match self {
            CloudRow::Layer { .. } => CloudForm::Layer,
            CloudRow::Spheres { .. } => CloudForm::Spheres,
        }
    }

    /// The method, `None` for the spheres (the plot's colour).
    pub fn method(&self) -> Option<LayerMethod> {
        match self {
            CloudRow::Layer { method, .. } => Some(*method),
            CloudRow::Spheres { .. } => None,
        }
    }
}

/// The report's rows: the four methods, both qualities, both sun lights, and the
/// spheres.
pub fn cloud_rows() -> Vec<CloudRow> {
    let mut rows = Vec::new();
    for method in [
        LayerMethod::Riley,
        LayerMethod::Octaves,
        LayerMethod::Eddington,
        LayerMethod::FourStream,
    ] {
        for quality in [MarchQuality::Interactive, MarchQuality::Offline] {
            for sun_light in [SunLight::March, SunLight::Map] {
                rows.push(CloudRow::Layer {
                    method,
                    quality,
                    sun_light,
                });
            }
        }
    }
    for method in [
        LayerMethod::Riley,
        LayerMethod::Eddington,
        LayerMethod::FourStream,
    ] {
        rows.push(CloudRow::Spheres { method });
    }
    rows
}

/// What a row answered on one view, and what it cost on one CPU thread.
#[derive(Clone, Debug, PartialEq)]
pub struct RowAnswers {
    pub answers: Vec<CloudAnswer>,
    /// The time per ray, s.
    pub per_ray_s: f64,
    /// What a frame makes once (the sun map, or the spheres' attenuation textures), s.
    pub per_frame_s: f64,
}

impl RowAnswers {
    /// A 1280 x 720 frame: the per-frame part and a ray per pixel.
    pub fn frame_s(&self) -> f64 {
        self.per_frame_s + FRAME_PIXELS * self.per_ray_s
    }
}

/// `row` on `scene`; `None` where the row is not measured on the view (the spheres
/// away from orbit).
pub fn answer(row: &CloudRow, scene: &ViewScene) -> anyhow::Result<Option<RowAnswers>> {
    if matches!(row, CloudRow::Spheres { .. }) && !scene.view.spheres {
        return Ok(None);
    }
    let clouds = scene.marched(&row.cloud_settings())?;
    let camera = scene.rays[0].origin_m;
    let sun = scene.rays[0].sun_direction.normalize();
    let start = Instant::now();
    let maps = match row {
        CloudRow::Layer { .. } => clouds.maps(camera, sun)?,
        CloudRow::Spheres { .. } => RayMaps::default(),
    };
    let spheres = match row {
        CloudRow::Spheres { .. } => Some(clouds.spheres(sun)?),
        CloudRow::Layer { .. } => None,
    };
    let per_frame_s = start.elapsed().as_secs_f64();
    let one = |ray: &ViewRay| clouds.in_form(scene.air(), ray, row.form(), &maps, spheres.as_ref());
    let answers = scene
        .rays
        .iter()
        .map(one)
        .collect::<Result<Vec<_>, _>>()
        .with_context(|| format!("{row} on view {}", scene.view.id()))?;
    let start = Instant::now();
    let mut rays = 0usize;
    while start.elapsed().as_secs_f64() < MIN_TIMED_S {
        for ray in &scene.rays {
            std::hint::black_box(one(ray)?);
            rays += 1;
        }
    }
    Ok(Some(RowAnswers {
        answers,
        per_ray_s: start.elapsed().as_secs_f64() / rays.max(1) as f64,
        per_frame_s,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_read_back_and_bad_words_are_named() {
        for row in cloud_rows() {
            assert_eq!(CloudRow::parse(&row.to_string()).unwrap(), row);
            assert!(row.cloud_settings().check().is_ok(), "{row}");
        }
        assert_eq!(
            CloudRow::parse("octaves").unwrap().to_string(),
            "octaves offline march"
        );
        let e = CloudRow::parse("riley fast").unwrap_err().to_string();
        assert!(e.contains("\"fast\"") && e.contains("interactive"), "{e}");
        let e = CloudRow::parse("offline map").unwrap_err().to_string();
        assert!(e.contains("names no method"), "{e}");
        assert_eq!(
            CloudRow::parse("spheres four-stream").unwrap(),
            CloudRow::Spheres {
                method: LayerMethod::FourStream
            }
        );
        let e = CloudRow::parse("spheres fast").unwrap_err().to_string();
        assert!(e.contains("\"fast\"") && e.contains("four-stream"), "{e}");
    }
}
