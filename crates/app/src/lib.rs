//! The `atmos` binary as a library: the command line and its subcommands, so that tests
//! and other tools can run them in-process.

pub mod bench;
pub mod camera_path;
pub mod cli;
pub mod cloud_rays;
pub mod contact_sheet;
pub mod csv_lines;
pub mod earth_data_flag;
pub mod exposure_meter;
pub mod files;
pub mod location_flags;
pub mod phase;
pub mod probe;
pub mod probe_args;
pub mod probe_clouds;
pub mod probe_scene;
pub mod probe_table;
pub mod probe_terrain;
pub mod progress;
pub mod record;
pub mod render;
pub mod report;
pub mod stability;
pub mod table_cache_dir;
pub mod viewer;
pub mod wavelength_flag;

use std::ffi::OsString;

use clap::Parser;

use crate::cli::{Cli, Command};

/// Runs `atmos` with these arguments (the first is the program name). Usage errors come
/// back as a [`clap::Error`] inside the [`anyhow::Error`].
pub fn run(args: impl IntoIterator<Item = OsString>) -> anyhow::Result<()> {
    match Cli::try_parse_from(args)?.command {
        Some(Command::Probe(args)) => match &args.scene {
            Some(scene) => probe_scene::run(&args, scene),
            None => probe::run(&args),
        },
        Some(Command::Stability(args)) => stability::run(&args),
        Some(Command::Report(args)) => report::run(&args),
        Some(Command::Render(args)) => render::run(&args),
        Some(Command::Bench(args)) => bench::run(&args),
        Some(Command::ContactSheet(args)) => contact_sheet::run(&args),
        Some(Command::Record(args)) => record::run(&args),
        Some(Command::View(args)) => viewer::run(&args),
        Some(Command::Phase(args)) => phase::run(&args),
        None => viewer::run(&cli::ViewArgs::default()),
    }
}
