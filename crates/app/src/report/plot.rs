//! The report's plots: daytime error against the time of a 1280 x 720 frame (on the CPU,
//! and on the GPU), one point per model setting, log axes, with the Pareto front (no
//! faster setting is more accurate).

use std::path::{Path, PathBuf};

use anyhow::{Context, anyhow};
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::clouds::layer::settings::LayerMethod;
use atmosphere_core::models::id::ModelId;

use crate::report::measure::VariantResult;
use crate::report::optics_rows::RowKind;

const FONT: &[u8] = include_bytes!("../../../../assets/fonts/DejaVuSans.ttf");

/// What a plot's time axis measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeAxis {
    pub caption: &'static str,
    pub description: &'static str,
    /// The unit after a time in the Pareto list.
    pub unit: &'static str,
}

/// A frame on one CPU thread, seconds.
pub const CPU_AXIS: TimeAxis = TimeAxis {
    caption: "Daytime luminance error against frame time (CPU, one thread)",
    description: "time of a 1280 x 720 frame on one CPU thread, s",
    unit: "s",
};

/// A frame on the report's GPU adapter as a multiple of the baseline's frame of the same
/// views, measured interleaved with it: the machine's load cancels, as it does not in
/// milliseconds on a busy machine.
pub const GPU_AXIS: TimeAxis = TimeAxis {
    caption: "Daytime luminance error against frame time (GPU, relative to nishita-16)",
    description: "time of a 1280 x 720 GPU frame / the same of nishita samples=16",
    unit: "x baseline",
};

/// What a point's colour tells: a sky model, a beam method, a cloud method (`None`:
/// the cloud spheres), or what an optics row changes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Series {
    Sky(ModelId),
    Beam(BeamMethodId),
    Cloud(Option<LayerMethod>),
    /// An optics row, by the setting it changes from the shipped scenes'.
    Optics(RowKind),
}

/// One point of the plot.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub label: String,
    pub series: Series,
    /// Frame time in the axis's unit.
    pub frame_time: f64,
    pub error_percent: f64,
}

impl Point {
    /// The setting's CPU frame time, s.
    pub fn cpu(result: &VariantResult) -> Point {
        Point {
            label: result.variant.label(),
            series: Series::Sky(result.variant.model),
            frame_time: result.frame_seconds(),
            error_percent: 100.0 * result.daytime.rms,
        }
    }

    /// The setting's GPU frame time relative to the baseline's, where it was measured.
    pub fn gpu(result: &VariantResult) -> Option<Point> {
        result.gpu.as_ref().map(|gpu| Point {
            frame_time: gpu.ratio(),
            ..Point::cpu(result)
        })
    }
}

/// One setting's points from its rows on several scenes, `(CPU frame s, relative RMS
/// error, GPU time)` each: the means of its CPU time and error, and of its GPU time
/// where every scene has one.
pub fn mean_points(
    label: &str,
    series: Series,
    scenes: &[(f64, f64, Option<f64>)],
) -> (Point, Option<Point>) {
    let n = scenes.len().max(1) as f64;
    let point = Point {
        label: label.to_string(),
        series,
        frame_time: scenes.iter().map(|s| s.0).sum::<f64>() / n,
        error_percent: 100.0 * scenes.iter().map(|s| s.1).sum::<f64>() / n,
    };
    let gpu_times: Option<Vec<f64>> = scenes.iter().map(|s| s.2).collect();
    let gpu = gpu_times.map(|times| Point {
        frame_time: times.iter().sum::<f64>() / n,
        ..point.clone()
    });
    (point, gpu)
}

/// The points on the Pareto front, fastest first: each more accurate than every faster
/// point.
pub fn pareto_front(points: &[Point]) -> Vec<Point> {
    let mut sorted: Vec<&Point> = points.iter().collect();
    sorted.sort_by(|a, b| {
        a.frame_time
            .total_cmp(&b.frame_time)
            .then(a.error_percent.total_cmp(&b.error_percent))
    });
    let mut front: Vec<Point> = Vec::new();
    for p in sorted {
        if front
            .last()
            .is_none_or(|best| p.error_percent < best.error_percent)
        {
            front.push(p.clone());
        }
    }
    front
}

/// The front as a staircase: the best error so far holds until a faster-to-slower step
/// improves it, and the last holds to `x_end` (a one-point front is a line too).
fn staircase(front: &[Point], x_end: f64) -> Vec<(f64, f64)> {
    let mut line = Vec::with_capacity(2 * front.len() + 1);
    for (i, p) in front.iter().enumerate() {
        if i > 0 {
            line.push((p.frame_time, front[i - 1].error_percent));
        }
        line.push((p.frame_time, p.error_percent));
    }
    if let Some(last) = front.last() {
        line.push((x_end, last.error_percent));
    }
    line
}

/// The colour of a series' points.
fn series_color(series: Series) -> RGBColor {
    let model = match series {
        Series::Sky(model) => model,
        Series::Cloud(method) => {
            return match method {
                Some(LayerMethod::Riley) => RGBColor(214, 39, 40),
                Some(LayerMethod::Octaves) => RGBColor(31, 119, 180),
                Some(LayerMethod::Eddington) => RGBColor(148, 103, 189),
                Some(LayerMethod::FourStream) => RGBColor(255, 127, 14),
                None => RGBColor(44, 160, 44),
            };
        }
        Series::Optics(kind) => {
            return match kind {
                RowKind::Shipped => RGBColor(90, 90, 90),
                RowKind::Wavelengths => RGBColor(31, 119, 180),
                RowKind::PointSun => RGBColor(255, 127, 14),
                RowKind::Steps => RGBColor(44, 160, 44),
                RowKind::PeakExtinction => RGBColor(214, 39, 40),
                RowKind::SkyHorizontal => RGBColor(148, 103, 189),
                RowKind::OrdersNone => RGBColor(140, 86, 75),
            };
        }
        Series::Beam(method) => {
            return match method {
                BeamMethodId::March => RGBColor(31, 119, 180),
                BeamMethodId::Planes2000 => RGBColor(255, 127, 14),
                BeamMethodId::Qtable2002 => RGBColor(44, 160, 44),
                BeamMethodId::Reference => RGBColor(90, 90, 90),
            };
        }
    };
    match model {
        ModelId::Nishita => RGBColor(31, 119, 180),
        ModelId::Oneil => RGBColor(255, 127, 14),
        ModelId::Dobashi => RGBColor(44, 160, 44),
        ModelId::Riley => RGBColor(214, 39, 40),
        ModelId::Bruneton => RGBColor(148, 103, 189),
        ModelId::Hillaire => RGBColor(140, 86, 75),
        ModelId::Reference => RGBColor(90, 90, 90),
    }
}

/// Log-axis range from the power of ten below the smallest positive value to the one
/// above the largest.
fn log_range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values
        .filter(|v| *v > 0.0 && v.is_finite())
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo > hi {
        return 0.1..10.0;
    }
    10f64.powf(lo.log10().floor())..10f64.powf((hi.log10() + 1e-9).ceil())
}

/// Tick labels without trailing zeros: 0.1, 1, 20.
fn tick(v: &f64) -> String {
    let text = format!("{v:.3}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// Pixel boxes of the labels drawn so far; a new label moves down until it overlaps none.
#[derive(Debug, Default)]
struct LabelPlacer {
    boxes: Vec<(i32, i32, i32, i32)>,
}

impl LabelPlacer {
    const LINE: i32 = 17;

    /// The offset from the point (x, y) at which a label of `chars` characters fits:
    /// right of the point, then above or below it, then left of it; the first place that
    /// overlaps no label drawn so far (the last one tried if none is free).
    fn place(&mut self, (x, y): (i32, i32), chars: usize) -> (i32, i32) {
        let width = 8 * chars as i32;
        let line = Self::LINE;
        let candidates = [
            (9, -8),
            (9, -8 - line),
            (9, -8 + line),
            (-9 - width, -8),
            (-9 - width, -8 - line),
            (-9 - width, -8 + line),
            (9, -8 - 2 * line),
            (9, -8 + 2 * line),
        ];
        let mut chosen = candidates[0];
        for (dx, dy) in candidates {
            chosen = (dx, dy);
            let b = (x + dx, y + dy, x + dx + width, y + dy + line);
            let overlaps = self
                .boxes
                .iter()
                .any(|o| b.0 < o.2 && o.0 < b.2 && b.1 < o.3 && o.1 < b.3);
            if !overlaps {
                break;
            }
        }
        let (dx, dy) = chosen;
        self.boxes
            .push((x + dx, y + dy, x + dx + width, y + dy + line));
        chosen
    }
}

/// Makes the shipped DejaVu Sans plotters' "sans-serif" font; registering it again is
/// harmless.
pub fn register_sans_serif() -> anyhow::Result<()> {
    register_font("sans-serif", FontStyle::Normal, FONT)
        .map_err(|_| anyhow!("the plot font assets/fonts/DejaVuSans.ttf is not a font"))
}

/// Draws the plot to `path` (PNG), through a partial file renamed into place.
pub fn draw(path: &Path, axis: &TimeAxis, points: &[Point]) -> anyhow::Result<()> {
    register_sans_serif()?;
    let mut partial = path.as_os_str().to_owned();
    partial.push(".partial.png");
    let partial = PathBuf::from(partial);
    draw_to(&partial, axis, points)
        .map_err(|e| anyhow!("{e}"))
        .and_then(|()| std::fs::rename(&partial, path).map_err(Into::into))
        .with_context(|| format!("cannot draw {}", path.display()))
        .inspect_err(|_| {
            let _ = std::fs::remove_file(&partial);
        })
}

fn draw_to(
    path: &Path,
    axis: &TimeAxis,
    points: &[Point],
) -> Result<(), Box<dyn std::error::Error>> {
    let root = BitMapBackend::new(path, (1200, 800)).into_drawing_area();
    root.fill(&WHITE)?;
    let x_range = log_range(points.iter().map(|p| p.frame_time));
    let x_end = x_range.end;
    let y_range = log_range(points.iter().map(|p| p.error_percent));
    let mut chart = ChartBuilder::on(&root)
        .caption(axis.caption, ("sans-serif", 26))
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(80)
        .build_cartesian_2d(x_range.log_scale(), y_range.log_scale())?;
    chart
        .configure_mesh()
        .x_desc(axis.description)
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .y_desc("relative RMS luminance error, %")
        .axis_desc_style(("sans-serif", 20))
        .label_style(("sans-serif", 16))
        .draw()?;
    let front = staircase(&pareto_front(points), x_end);
    chart
        .draw_series(LineSeries::new(front, BLACK.stroke_width(2)))?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
    let mut placer = LabelPlacer::default();
    for p in points {
        let color = series_color(p.series);
        let at = (p.frame_time, p.error_percent);
        let offset = placer.place(chart.backend_coord(&at), p.label.chars().count());
        chart.draw_series(std::iter::once(
            EmptyElement::at(at)
                + Circle::new((0, 0), 6, color.filled())
                + Text::new(p.label.clone(), offset, ("sans-serif", 15)),
        ))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font(("sans-serif", 16))
        .draw()?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(label: &str, t: f64, e: f64) -> Point {
        Point {
            label: label.into(),
            series: Series::Sky(ModelId::Nishita),
            frame_time: t,
            error_percent: e,
        }
    }

    #[test]
    fn the_front_keeps_only_settings_no_faster_one_beats() {
        let points = [
            point("a", 1.0, 10.0),
            point("b", 2.0, 12.0),
            point("c", 3.0, 5.0),
            point("d", 0.5, 20.0),
            point("e", 4.0, 5.0),
        ];
        let front: Vec<String> = pareto_front(&points).into_iter().map(|p| p.label).collect();
        assert_eq!(front, ["d", "a", "c"]);
        let steps = staircase(&pareto_front(&points), 10.0);
        assert_eq!(
            steps,
            [
                (0.5, 20.0),
                (1.0, 20.0),
                (1.0, 10.0),
                (3.0, 10.0),
                (3.0, 5.0),
                (10.0, 5.0)
            ]
        );
    }

    #[test]
    fn draws_a_png() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("plot.png");
        let points = [point("a", 1.0, 10.0), point("b", 3.0, 2.0)];
        draw(&path, &GPU_AXIS, &points).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        assert!(!dir.path().join("plot.png.partial.png").exists());
    }
}
