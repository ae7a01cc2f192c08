//! Progress of long work on stderr: a bar on a terminal, else a line per tenth of the
//! work, with the time left at the pace so far, when there is more than a little of it.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

/// Less work than this (in items) shows no progress lines when stderr is not a terminal.
const LITTLE_WORK: u64 = 16;

/// Progress of `total` items of one task; safe to advance from many threads.
#[derive(Debug)]
pub enum Progress {
    Bar(ProgressBar),
    Lines {
        task: String,
        unit: &'static str,
        done: AtomicU64,
        total: u64,
        start: Instant,
    },
    Quiet,
}

impl Progress {
    /// `task` names the work in progress lines, `unit` its items ("rays").
    pub fn new(task: &str, unit: &'static str, total: u64) -> Progress {
        if std::io::stderr().is_terminal() {
            let template = format!(
                "{task} {{elapsed_precise}} [{{wide_bar}}] {{pos}}/{{len}} {unit}, {{eta}} left"
            );
            let style = ProgressStyle::with_template(&template)
                .unwrap_or_else(|_| ProgressStyle::default_bar());
            Progress::Bar(ProgressBar::new(total).with_style(style))
        } else if total > LITTLE_WORK {
            Progress::Lines {
                task: task.to_string(),
                unit,
                done: AtomicU64::new(0),
                total,
                start: Instant::now(),
            }
        } else {
            Progress::Quiet
        }
    }

    /// One more item done.
    pub fn inc(&self) {
        match self {
            Progress::Bar(bar) => bar.inc(1),
            Progress::Lines {
                task,
                unit,
                done,
                total,
                start,
            } => {
                let done = done.fetch_add(1, Ordering::Relaxed) + 1;
                if done * 10 / total != (done - 1) * 10 / total {
                    let left = time_left(start.elapsed(), done, *total);
                    eprintln!("{task}: {done}/{total} {unit}, {left:.0?} left");
                }
            }
            Progress::Quiet => {}
        }
    }

    /// Ends the bar (lines need no ending).
    pub fn finish(&self) {
        if let Progress::Bar(bar) = self {
            bar.finish();
        }
    }
}

/// `f` of every item, in parallel (rayon), in the items' order, with progress of `task`
/// counted in `unit`.
pub fn map_with_progress<T: Sync, R: Send>(
    task: &str,
    unit: &'static str,
    items: &[T],
    f: impl Fn(&T) -> R + Sync,
) -> Vec<R> {
    let progress = Progress::new(task, unit, items.len() as u64);
    let results = items
        .par_iter()
        .map(|item| {
            let result = f(item);
            progress.inc();
            result
        })
        .collect();
    progress.finish();
    results
}

/// The time the remaining `total - done` items take at the pace of the first `done`.
fn time_left(elapsed: Duration, done: u64, total: u64) -> Duration {
    let per_item = elapsed.as_secs_f64() / done.max(1) as f64;
    Duration::from_secs_f64(per_item * total.saturating_sub(done) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_time_left_follows_the_pace_so_far() {
        let left = time_left(Duration::from_secs(30), 10, 40);
        assert_eq!(left, Duration::from_secs(90));
        assert_eq!(time_left(Duration::from_secs(5), 4, 4), Duration::ZERO);
    }
}
