//! Progress of long work on stderr: a bar on a terminal, else a line per tenth of the
//! work when there is more than a little of it.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicU64, Ordering};

use indicatif::{ProgressBar, ProgressStyle};

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
            } => {
                let done = done.fetch_add(1, Ordering::Relaxed) + 1;
                if done * 10 / total != (done - 1) * 10 / total {
                    eprintln!("{task}: {done}/{total} {unit}");
                }
            }
            Progress::Quiet => {}
        }
    }

    pub fn finish(&self) {
        if let Progress::Bar(bar) = self {
            bar.finish();
        }
    }
}
