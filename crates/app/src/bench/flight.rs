//! `atmos bench --flight PATH.toml`: a camera path flown as the viewer flies it, the
//! terrain's chunk meshes built off the render thread (`TerrainOptions::wait_for_chunks`
//! off), timing every frame from `render` to the GPU's end; it reports the median and the
//! longest frame and their ratio (docs/terrain.md, "No popping"). The first frame, which
//! compiles the shaders, builds the tables and loads the maps, is reported apart.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::bail;
use render_wgpu::Renderer;
use render_wgpu::frame::Frame;

use crate::camera_path::CameraPath;
use crate::progress::Progress;

use super::timing::{median, timed};

/// One timed frame of the flight.
#[derive(Clone, Debug, PartialEq)]
pub struct FlightFrame {
    pub time_s: f64,
    pub altitude_m: f64,
    pub wall_ms: f64,
    /// Chosen chunks drawn as a cover, and meshes being built, after the frame.
    pub covered: usize,
    pub building: usize,
    /// Whether a choice of chunks was being made off the render thread after the frame.
    pub selecting: bool,
    /// The render thread's time preparing the terrain (choosing what to draw, uploading
    /// finished meshes), ms.
    pub prepare_ms: f64,
    /// The frame's passes with their GPU times, ms (indicative on a software adapter).
    pub passes: String,
}

/// The path's frames at `fps` frames per second of its time (the path's own fps when
/// `None`) at `width` x `height`, checked before any GPU work: at least 3, each with
/// terrain. `file` names the path in errors.
pub fn frames(
    camera_path: &CameraPath,
    file: &Path,
    fps: Option<u32>,
    (width, height): (u32, u32),
) -> anyhow::Result<Vec<(f64, Frame)>> {
    let fps = fps.map_or(camera_path.fps(), f64::from);
    let count = camera_path.frame_count(fps);
    if count < 3 {
        bail!(
            "--flight {}: {count} frames at {fps} fps; at least 3 are needed",
            file.display()
        );
    }
    (0..count)
        .map(|k| {
            let time_s = k as f64 / fps;
            let mut frame = camera_path.frame_at(time_s, width, height)?;
            let Some(terrain) = frame.terrain.as_mut() else {
                bail!(
                    "--flight {}: no terrain at {time_s} s; the flight measures terrain work",
                    file.display()
                );
            };
            terrain.wait_for_chunks = false;
            Ok((time_s, frame))
        })
        .collect()
}

/// Renders the flight's `frames` in order, timing each.
pub fn measure(
    renderer: &mut Renderer,
    frames: &[(f64, Frame)],
) -> anyhow::Result<Vec<FlightFrame>> {
    let progress = Progress::new("flight", "frames", frames.len() as u64);
    let mut timed_frames = Vec::with_capacity(frames.len());
    for (time_s, frame) in frames {
        let (plan, wall_ms) = timed(renderer, frame)?;
        let passes = plan
            .steps
            .iter()
            .map(|step| match step.gpu_ms {
                Some(ms) => format!("{} {ms:.0}", step.name),
                None => step.name.to_string(),
            })
            .collect::<Vec<_>>()
            .join(", ");
        let stand = renderer.terrain_progress().unwrap_or_default();
        timed_frames.push(FlightFrame {
            time_s: *time_s,
            altitude_m: frame.camera_position_m.length() - frame.atmosphere.bottom_radius_m,
            wall_ms,
            covered: stand.covered,
            building: stand.building,
            selecting: stand.selecting,
            prepare_ms: stand.prepare_us as f64 / 1e3,
            passes,
        });
        progress.inc();
    }
    progress.finish();
    Ok(timed_frames)
}

/// The report: the first frame, the median and the longest of the others and their
/// ratio, and the five longest frames with one of median length.
pub fn markdown(path: &Path, adapter: &str, size: (u32, u32), frames: &[FlightFrame]) -> String {
    let (first, rest) = frames
        .split_first()
        .expect("measure returns 3 frames or more");
    let times: Vec<f64> = rest.iter().map(|f| f.wall_ms).collect();
    let mid = median(&times).expect("frames after the first");
    let mut longest: Vec<&FlightFrame> = rest.iter().collect();
    longest.sort_by(|a, b| b.wall_ms.total_cmp(&a.wall_ms));
    let mut text = String::new();
    let _ = writeln!(
        text,
        "Flight {} on {adapter}, {} x {}, {} frames; chunk meshes built off the render thread.\n",
        path.display(),
        size.0,
        size.1,
        frames.len()
    );
    let _ = writeln!(
        text,
        "first frame (shaders, tables, maps): {:.1} ms",
        first.wall_ms
    );
    let _ = writeln!(text, "median frame: {mid:.1} ms");
    let top = longest[0];
    let _ = writeln!(
        text,
        "longest frame: {:.1} ms at {:.2} s ({:.0} m), {:.2} x the median\n",
        top.wall_ms,
        top.time_s,
        top.altitude_m,
        top.wall_ms / mid
    );
    let _ = writeln!(
        text,
        "| time, s | altitude, m | frame, ms | terrain prepare, ms | selecting | covered | building | passes, GPU ms |"
    );
    let _ = writeln!(text, "|---|---|---|---|---|---|---|---|");
    // The five longest, then one of median length.
    let typical = longest.iter().find(|f| f.wall_ms <= mid);
    for f in longest.iter().take(5).chain(typical) {
        let _ = writeln!(
            text,
            "| {:.2} | {:.0} | {:.1} | {:.1} | {} | {} | {} | {} |",
            f.time_s,
            f.altitude_m,
            f.wall_ms,
            f.prepare_ms,
            if f.selecting { "yes" } else { "no" },
            f.covered,
            f.building,
            f.passes
        );
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(time_s: f64, wall_ms: f64) -> FlightFrame {
        FlightFrame {
            time_s,
            altitude_m: 2.0,
            wall_ms,
            covered: 0,
            building: 0,
            selecting: false,
            prepare_ms: 1.5,
            passes: "terrain 5".to_string(),
        }
    }

    #[test]
    fn the_report_leaves_out_the_first_frame_and_finds_the_longest() {
        let frames = [at(0.0, 900.0), at(0.1, 10.0), at(0.2, 30.0), at(0.3, 12.0)];
        let text = markdown(Path::new("f.toml"), "lavapipe", (64, 36), &frames);
        assert!(
            text.contains("first frame (shaders, tables, maps): 900.0 ms"),
            "{text}"
        );
        assert!(text.contains("median frame: 12.0 ms"), "{text}");
        assert!(
            text.contains("longest frame: 30.0 ms at 0.20 s (2 m), 2.50 x the median"),
            "{text}"
        );
        // The table: the longest first, the one of median length last.
        let rows: Vec<&str> = text.lines().filter(|l| l.starts_with("| 0.")).collect();
        assert_eq!(
            rows.first(),
            Some(&"| 0.20 | 2 | 30.0 | 1.5 | no | 0 | 0 | terrain 5 |")
        );
        assert_eq!(
            rows.last(),
            Some(&"| 0.30 | 2 | 12.0 | 1.5 | no | 0 | 0 | terrain 5 |")
        );
        assert_eq!(rows.len(), 4);
    }
}
