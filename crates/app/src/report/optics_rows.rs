//! The rows of the optics section: the renderer's settings that change what a rain
//! shaft, cirrus layer or droplet deck looks like (docs/optics-rendering.md, "Settings
//! and their ranges"): the wavelengths its phase tables are computed at, whether they
//! hold the sun's disc, the steps of its march (the GPU pass marches [`MARCH_STEPS`]:
//! other counts are CPU rows), how it counts the forward peak and which sky's light it
//! scatters. Their answers for a
//! view's rays and the CPU time they took.

use std::fmt;
use std::time::Instant;

use anyhow::{Context, bail};
use atmosphere_core::hydrometeors::forward_peak::ForwardPeak;
use atmosphere_core::hydrometeors::render::MARCH_STEPS;
use atmosphere_core::hydrometeors::sky_light::SkyLight;
use atmosphere_core::hydrometeors::spectral_phase::WAVELENGTH_COUNT_RANGE;
use atmosphere_core::hydrometeors::sun_orders::MultipleScattering;

use crate::cloud_rays::CloudAnswer;
use crate::report::optics_scene::{OpticsScene, Tables};

/// Pixels of the 1280 x 720 frame a CPU time per ray is scaled to.
pub const FRAME_PIXELS: f64 = 1280.0 * 720.0;
/// The range of a row's march steps.
pub const STEPS_RANGE: [usize; 2] = [1, 1000];
/// A row's rays are answered again until this much time has passed, s.
const MIN_TIMED_S: f64 = 0.3;

/// What a row changes from the shipped settings (the plots' colours).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RowKind {
    Shipped,
    Wavelengths,
    PointSun,
    Steps,
    PeakExtinction,
    SkyHorizontal,
    OrdersNone,
}

/// One row: the volume's tables and its march.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OpticsRow {
    pub tables: Tables,
    pub steps: usize,
    /// How the march counts the forward peak (`hydrometeors/forward_peak.rs`).
    pub forward_peak: ForwardPeak,
    /// The sky's light the march scatters (`hydrometeors/sky_light.rs`).
    pub sky_light: SkyLight,
    /// The sun's light scattered more than once (`hydrometeors/sun_orders.rs`).
    pub multiple_scattering: MultipleScattering,
}

/// The shipped scenes' settings.
pub const SHIPPED: OpticsRow = OpticsRow {
    tables: Tables {
        wavelengths: 32,
        sun_disc: true,
    },
    steps: MARCH_STEPS,
    forward_peak: ForwardPeak::Unscattered,
    sky_light: SkyLight::Sphere,
    multiple_scattering: MultipleScattering::Probes,
};

impl fmt::Display for OpticsRow {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let sun = if self.tables.sun_disc {
            "disc"
        } else {
            "point"
        };
        write!(
            f,
            "wavelengths={} sun={sun} steps={}",
            self.tables.wavelengths, self.steps
        )?;
        if self.forward_peak != SHIPPED.forward_peak {
            write!(f, " peak={}", self.forward_peak.name())?;
        }
        if self.sky_light != SHIPPED.sky_light {
            write!(f, " sky={}", self.sky_light.name())?;
        }
        if self.multiple_scattering != SHIPPED.multiple_scattering {
            write!(f, " orders={}", self.multiple_scattering.name())?;
        }
        Ok(())
    }
}

impl OpticsRow {
    /// A row as `--variant` writes it: `wavelengths=N` (3 to 128), `sun=disc` or
    /// `sun=point`, `steps=N` (1 to 1000), `peak=unscattered` or `peak=extinction`,
    /// `sky=sphere` or `sky=horizontal`, `orders=probes` or `orders=none`, in any order,
    /// each by default the shipped scenes'. Errors name the word and what it may be.
    pub fn parse(text: &str) -> anyhow::Result<OpticsRow> {
        let mut row = SHIPPED;
        let what = "wavelengths=N, sun=disc, sun=point, steps=N, peak=unscattered, \
                    peak=extinction, sky=sphere, sky=horizontal, orders=probes, orders=none";
        for word in text.split_whitespace() {
            let Some((key, value)) = word.split_once('=') else {
                bail!("optics variant \"{text}\": \"{word}\" is none of {what}");
            };
            match (key, value) {
                ("sun", "disc") => row.tables.sun_disc = true,
                ("sun", "point") => row.tables.sun_disc = false,
                ("peak", "unscattered") => row.forward_peak = ForwardPeak::Unscattered,
                ("peak", "extinction") => row.forward_peak = ForwardPeak::Extinction,
                ("sky", "sphere") => row.sky_light = SkyLight::Sphere,
                ("sky", "horizontal") => row.sky_light = SkyLight::Horizontal,
                ("orders", "probes") => row.multiple_scattering = MultipleScattering::Probes,
                ("orders", "none") => row.multiple_scattering = MultipleScattering::None,
                ("wavelengths", n) => {
                    let [lo, hi] = WAVELENGTH_COUNT_RANGE;
                    row.tables.wavelengths = match n.parse::<usize>() {
                        Ok(n) if (lo..=hi).contains(&(n as f64)) => n,
                        _ => bail!(
                            "optics variant \"{text}\": wavelengths={n} must be a whole number in [{lo}, {hi}]"
                        ),
                    };
                }
                ("steps", n) => {
                    let [lo, hi] = STEPS_RANGE;
                    row.steps = match n.parse::<usize>() {
                        Ok(n) if (lo..=hi).contains(&n) => n,
                        _ => bail!(
                            "optics variant \"{text}\": steps={n} must be a whole number in [{lo}, {hi}]"
                        ),
                    };
                }
                _ => bail!("optics variant \"{text}\": \"{word}\" is none of {what}"),
            }
        }
        Ok(row)
    }

    /// What the row changes from the shipped settings (the first that differs).
    pub fn kind(&self) -> RowKind {
        if self.forward_peak != SHIPPED.forward_peak {
            RowKind::PeakExtinction
        } else if self.sky_light != SHIPPED.sky_light {
            RowKind::SkyHorizontal
        } else if self.multiple_scattering != SHIPPED.multiple_scattering {
            RowKind::OrdersNone
        } else if self.tables.wavelengths != SHIPPED.tables.wavelengths {
            RowKind::Wavelengths
        } else if self.tables.sun_disc != SHIPPED.tables.sun_disc {
            RowKind::PointSun
        } else if self.steps != SHIPPED.steps {
            RowKind::Steps
        } else {
            RowKind::Shipped
        }
    }

    /// How the march lights the volume: the forward peak, the sky's light, the sun's
    /// higher orders.
    pub fn march(&self) -> (ForwardPeak, SkyLight, MultipleScattering) {
        (self.forward_peak, self.sky_light, self.multiple_scattering)
    }

    /// Whether the GPU pass renders this row (it marches [`MARCH_STEPS`]).
    pub fn on_gpu(&self) -> bool {
        self.steps == MARCH_STEPS
    }
}

/// The report's rows: the shipped settings, fewer wavelengths (the viewer's 16, and 8),
/// a point sun, coarser and finer marches, the sun's single scattering alone, the sky's
/// horizontal irradiance too, and the march before all three (the forward peak counted
/// as extinction, the sky's horizontal irradiance, single scattering).
pub fn optics_rows() -> Vec<OpticsRow> {
    let with = |wavelengths, sun_disc, steps| OpticsRow {
        tables: Tables {
            wavelengths,
            sun_disc,
        },
        steps,
        ..SHIPPED
    };
    vec![
        SHIPPED,
        with(16, true, MARCH_STEPS),
        with(8, true, MARCH_STEPS),
        with(32, false, MARCH_STEPS),
        with(32, true, 4),
        with(32, true, 48),
        OpticsRow {
            multiple_scattering: MultipleScattering::None,
            ..SHIPPED
        },
        OpticsRow {
            sky_light: SkyLight::Horizontal,
            multiple_scattering: MultipleScattering::None,
            ..SHIPPED
        },
        OpticsRow {
            forward_peak: ForwardPeak::Extinction,
            sky_light: SkyLight::Horizontal,
            multiple_scattering: MultipleScattering::None,
            ..SHIPPED
        },
    ]
}

/// What a row answered on one view, and what it cost on one CPU thread.
#[derive(Clone, Debug, PartialEq)]
pub struct RowAnswers {
    pub answers: Vec<CloudAnswer>,
    /// The volume's composite per ray (its march and the air in front of it; the sky
    /// model's own answer left out), s.
    pub per_ray_s: f64,
    /// What a frame makes once: the tables read from the cache, reduced to the frame's
    /// wavelengths, and the volume's light, s.
    pub per_frame_s: f64,
}

impl RowAnswers {
    /// A 1280 x 720 frame whose every pixel sees the volume: the per-frame part and a
    /// composite per pixel.
    pub fn frame_s(&self) -> f64 {
        self.per_frame_s + FRAME_PIXELS * self.per_ray_s
    }
}

/// `row` on `scene`.
pub fn answer(row: &OpticsRow, scene: &OpticsScene) -> anyhow::Result<RowAnswers> {
    // The first call may build the tables; the second times what a frame does.
    let march = row.march();
    scene.lit(row.tables, march)?;
    let start = Instant::now();
    let lit = scene.lit(row.tables, march)?;
    let per_frame_s = start.elapsed().as_secs_f64();
    let answers = scene
        .rays
        .iter()
        .map(|ray| scene.composite(&lit, ray, row.steps))
        .collect::<anyhow::Result<Vec<_>>>()
        .with_context(|| format!("{row} on view {}", scene.view.id))?;
    let pixels: Vec<[f64; 3]> = answers
        .iter()
        .map(|a| std::array::from_fn(|c| a.radiance.radiance[c]))
        .collect();
    let start = Instant::now();
    let mut rays = 0usize;
    while start.elapsed().as_secs_f64() < MIN_TIMED_S {
        for (ray, pixel) in scene.rays.iter().zip(&pixels) {
            std::hint::black_box(scene.composite_over(&lit, ray, row.steps, *pixel));
            rays += 1;
        }
    }
    Ok(RowAnswers {
        answers,
        per_ray_s: start.elapsed().as_secs_f64() / rays.max(1) as f64,
        per_frame_s,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_read_back_and_bad_words_are_named() {
        for row in optics_rows() {
            assert_eq!(OpticsRow::parse(&row.to_string()).unwrap(), row);
        }
        assert_eq!(OpticsRow::parse("").unwrap(), SHIPPED);
        assert_eq!(
            OpticsRow::parse("sun=point").unwrap().to_string(),
            "wavelengths=32 sun=point steps=12"
        );
        let e = OpticsRow::parse("sun=square").unwrap_err().to_string();
        assert!(
            e.contains("\"sun=square\"") && e.contains("sun=point"),
            "{e}"
        );
        let e = OpticsRow::parse("wavelengths=200").unwrap_err().to_string();
        assert!(e.contains("[3, 128]"), "{e}");
        assert_eq!(
            OpticsRow::parse("sky=horizontal").unwrap().kind(),
            RowKind::SkyHorizontal
        );
        assert_eq!(OpticsRow::parse("sky=sphere").unwrap(), SHIPPED);
        let paper = OpticsRow::parse("peak=extinction").unwrap();
        assert_eq!(paper.forward_peak, ForwardPeak::Extinction);
        assert_eq!(paper.kind(), RowKind::PeakExtinction);
        assert_eq!(OpticsRow::parse("peak=unscattered").unwrap(), SHIPPED);
        assert_eq!(
            OpticsRow::parse("orders=none").unwrap().kind(),
            RowKind::OrdersNone
        );
        assert_eq!(OpticsRow::parse("orders=probes").unwrap(), SHIPPED);
        assert!(optics_rows().last().unwrap().on_gpu());
        assert!(!OpticsRow::parse("steps=4").unwrap().on_gpu());
        let e = OpticsRow::parse("steps=0").unwrap_err().to_string();
        assert!(e.contains("[1, 1000]"), "{e}");
    }
}
