//! `atmos record`: a camera path's frames, headless, to numbered image files
//! (docs/recording.md). One renderer serves the whole run, so tables are built once and
//! rebuilt only when their inputs change; every file is written atomically; a frame
//! whose files are already whole and from the same inputs is skipped, so a run that was
//! stopped at any moment resumes where it stopped.

pub mod exr_order;
pub mod fingerprint;
pub mod frame_files;
pub mod frame_range;
pub mod naming;
pub mod out_folder;
pub mod shard;
pub mod verify;
pub mod video;

use std::ops::Range;
use std::time::Instant;

use anyhow::{Context, bail};
use render_wgpu::Renderer;
use render_wgpu::frame::MAX_SIDE_PX;

use crate::camera_path::CameraPath;
use crate::cli::RecordArgs;
use crate::exposure_meter::metered_ev100;
use crate::files::write_atomically;
use crate::progress::Progress;
use fingerprint::FrameInputs;
use frame_range::FrameRange;
use naming::{FileKind, frame_path};
use shard::Shard;
use verify::{Verdict, verify};

/// Frame rates, frames per second: above zero, and no more than a high-speed camera's.
const FPS: (f64, f64) = (0.0, 1000.0);

/// The most frames a path may have at the chosen rate.
const MAX_FRAMES: u64 = 10_000_000;

/// A frame to render, with the kinds of file it lacks and whether any was there before.
#[derive(Debug)]
struct Job {
    index: u64,
    kinds: Vec<FileKind>,
    redone: bool,
}

/// Records the frames of `args`; prints progress and a closing summary on stderr.
pub fn run(args: &RecordArgs) -> anyhow::Result<()> {
    let path = CameraPath::load(&args.path)?;
    let fps = args.fps.unwrap_or_else(|| path.fps());
    if !(fps > FPS.0 && fps <= FPS.1) {
        bail!("--fps {fps} must lie in (0, 1000] frames per second");
    }
    let (path_width, path_height) = path.size_px();
    let (width, height) = (
        args.width.unwrap_or(path_width),
        args.height.unwrap_or(path_height),
    );
    for (side, flag) in [(width, "width"), (height, "height")] {
        if !(1..=MAX_SIDE_PX).contains(&side) {
            bail!("--{flag} {side} must be 1 to {MAX_SIDE_PX} px");
        }
    }
    let count = path.frame_count(fps) as u64;
    if count > MAX_FRAMES {
        bail!(
            "{}: {count} frames at {fps} fps is over the limit of {MAX_FRAMES}; lower --fps",
            args.path.display()
        );
    }
    let selected = match &args.frames {
        Some(text) => FrameRange::parse(text)?.resolve(count)?,
        None => 0..count,
    };
    let flag = args.shard.as_deref().map(Shard::parse).transpose()?;
    let shard = Shard::choose(flag, args.shard_count, |name| std::env::var(name).ok())?;
    let frames = shard.part(selected.clone());
    let kinds = args.format.kinds();
    if let Some(video) = &args.video {
        video::check(video, args.format)?;
    }
    out_folder::prepare(&args.out, &frame_path(&args.out, frames.start, kinds[0]))?;
    let path_toml = path.to_toml();
    let inputs = |index| FrameInputs {
        path_toml: &path_toml,
        index,
        fps,
        width,
        height,
    };
    // Every frame of this run is checked before the GPU opens.
    for index in frames.clone() {
        path.frame_at(index as f64 / fps, width, height)
            .with_context(|| frame_name(index, fps))?;
    }
    let jobs = jobs(&args.out, frames.clone(), kinds, &inputs);
    let earth_data = args.earth_data.source()?;
    let skipped = (frames.end - frames.start) as usize - jobs.len();
    let start = Instant::now();
    if !jobs.is_empty() {
        let mut renderer = Renderer::headless()?;
        renderer.set_earth_data(earth_data);
        let progress = Progress::new("record", "frames", jobs.len() as u64);
        for job in &jobs {
            render_job(&mut renderer, &path, job, &args.out, &inputs(job.index))?;
            progress.inc();
        }
        progress.finish();
    }
    let video = match &args.video {
        Some(video) => Some(make_video(&args.out, count, &inputs, video)?),
        None => None,
    };
    eprintln!(
        "{}",
        summary(
            &jobs,
            skipped,
            start.elapsed().as_secs_f64(),
            &selected,
            frames,
            shard
        ) + &format!("; the path has {count}; into {}", args.out.display())
    );
    if let Some(line) = video {
        eprintln!("{line}");
    }
    Ok(())
}

/// Assembles `video` when all `count` PNG frames of the path are whole in `dir`; says
/// what it wrote, or which frames it still waits for (another shard's, say).
fn make_video<'a>(
    dir: &std::path::Path,
    count: u64,
    inputs: &impl Fn(u64) -> FrameInputs<'a>,
    video: &std::path::Path,
) -> anyhow::Result<String> {
    let (width, height) = (inputs(0).width, inputs(0).height);
    let missing: Vec<u64> = (0..count)
        .filter(|&index| {
            let print = inputs(index).fingerprint(FileKind::Png);
            let file = frame_path(dir, index, FileKind::Png);
            verify(&file, FileKind::Png, width, height, &print) != Verdict::Complete
        })
        .collect();
    if let Some(first) = missing.first() {
        return Ok(format!(
            "video: not made yet, {} of {count} frames are not whole (the first is {first}); \
             run again with --video once every shard is done",
            missing.len()
        ));
    }
    video::assemble(dir, inputs(0).fps, video)?;
    Ok(format!("video: wrote {}", video.display()))
}

/// The frames of `frames` whose files in `dir` are not all complete, with the kinds to
/// write.
fn jobs<'a>(
    dir: &std::path::Path,
    frames: Range<u64>,
    kinds: &[FileKind],
    inputs: &impl Fn(u64) -> FrameInputs<'a>,
) -> Vec<Job> {
    let (width, height) = (inputs(0).width, inputs(0).height);
    frames
        .filter_map(|index| {
            let mut job = Job {
                index,
                kinds: Vec::new(),
                redone: false,
            };
            for &kind in kinds {
                let print = inputs(index).fingerprint(kind);
                match verify(&frame_path(dir, index, kind), kind, width, height, &print) {
                    Verdict::Complete => {}
                    Verdict::Missing => job.kinds.push(kind),
                    Verdict::Redo(_) => {
                        job.kinds.push(kind);
                        job.redone = true;
                    }
                }
            }
            (!job.kinds.is_empty()).then_some(job)
        })
        .collect()
}

/// Renders one frame and writes its missing files.
fn render_job(
    renderer: &mut Renderer,
    path: &CameraPath,
    job: &Job,
    dir: &std::path::Path,
    inputs: &FrameInputs,
) -> anyhow::Result<()> {
    let name = frame_name(job.index, inputs.fps);
    let time_s = job.index as f64 / inputs.fps;
    let mut frame = path
        .frame_at(time_s, inputs.width, inputs.height)
        .with_context(|| name.clone())?;
    let mut plan = renderer.render(&frame).with_context(|| name.clone())?;
    // Metered from this frame alone, so that shards and resumed runs agree.
    if path.auto_exposure_at(time_s) {
        let luminance = renderer.average_luminance().with_context(|| name.clone())?;
        frame.exposure_ev100 = metered_ev100(luminance);
        plan = renderer.render(&frame).with_context(|| name.clone())?;
    }
    // Progressive builds are off in a headless renderer: every table is whole.
    if let Some(building) = &plan.building {
        bail!("{name}: the tables were still building ({building})");
    }
    for &kind in &job.kinds {
        let bytes = match kind {
            FileKind::Png => frame_files::png_file(&frame, &renderer.read_ldr()?, inputs, time_s),
            FileKind::Exr => frame_files::exr_file(&frame, &renderer.read_hdr()?, inputs, time_s),
        }
        .with_context(|| name.clone())?;
        write_atomically(&frame_path(dir, job.index, kind), &bytes)
            .with_context(|| name.clone())?;
    }
    Ok(())
}

/// A frame as errors name it.
fn frame_name(index: u64, fps: f64) -> String {
    format!("frame {index} (t = {:.3} s)", index as f64 / fps)
}

/// The closing line: what was rendered, redone and skipped, and the time per frame.
fn summary(
    jobs: &[Job],
    skipped: usize,
    seconds: f64,
    selected: &Range<u64>,
    frames: Range<u64>,
    shard: Shard,
) -> String {
    let redone = jobs.iter().filter(|j| j.redone).count();
    let per_frame = if jobs.is_empty() {
        String::new()
    } else {
        format!(", {:.3} s per frame", seconds / jobs.len() as f64)
    };
    format!(
        "record: {} rendered ({redone} redone: incomplete or from other inputs), {skipped} skipped as complete{per_frame}; frames {}..{} of {}..{} (shard {shard})",
        jobs.len(),
        frames.start,
        frames.end,
        selected.start,
        selected.end
    )
}
