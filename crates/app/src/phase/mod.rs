//! `atmos phase`: phase functions of particles as CSV (docs/particles.md), at each
//! wavelength, with Q_ext, Q_sca and g in the header: water drops by Lorenz-Mie, of one
//! radius or averaged over a size distribution (`water.rs`); rain, Lorenz-Mie over the
//! Marshall-Palmer drop sizes of a rain rate (`rain.rs`); hexagonal ice columns and
//! plates by ray tracing with diffraction (`ice.rs`).

pub mod flags;
pub mod ice;
pub mod rain;
pub mod table;
pub mod water;

use std::io::Write;

use anyhow::bail;

use crate::cli::PhaseArgs;
use crate::files::{check_writable, write_atomically};
use flags::{MAX_WAVELENGTHS, Particle};
use table::write_csv;

/// Runs `atmos phase`.
pub fn run(args: &PhaseArgs) -> anyhow::Result<()> {
    if let Some(path) = &args.output {
        check_writable(path)?;
    }
    if args.wavelengths.len() > MAX_WAVELENGTHS {
        bail!(
            "--wavelengths: {} wavelengths; at most {MAX_WAVELENGTHS}",
            args.wavelengths.len()
        );
    }
    for w in &args.wavelengths {
        if !(w.nm.is_finite() && w.nm > 0.0) {
            bail!("--wavelengths: {} nm is not a positive wavelength", w.label);
        }
    }
    check_flags_apply(args)?;
    let (description, results) = match args.particle {
        Particle::Water => water::compute(args)?,
        Particle::Rain => rain::compute(args)?,
        Particle::IceColumn | Particle::IcePlate => ice::compute(args)?,
    };
    let text = write_csv(&description, &args.angles_deg, &results);
    match &args.output {
        Some(path) => write_atomically(path, text.as_bytes()),
        None => Ok(std::io::stdout().lock().write_all(text.as_bytes())?),
    }
}

/// Refuses a flag the particle does not take, and a missing one it needs, by name.
fn check_flags_apply(args: &PhaseArgs) -> anyhow::Result<()> {
    let particle = args.particle;
    let ice = matches!(particle, Particle::IceColumn | Particle::IcePlate);
    // Each flag: its name, whether it was given, and whether this particle takes it.
    let flags = [
        (
            "--radius-um",
            args.radius_um.is_some(),
            particle != Particle::Rain,
        ),
        (
            "--distribution",
            args.distribution.is_some(),
            particle == Particle::Water,
        ),
        (
            "--rain-rate-mm-h",
            args.rain_rate_mm_h.is_some(),
            particle == Particle::Rain,
        ),
        ("--length-um", args.length_um.is_some(), ice),
        (
            "--horizontal",
            args.horizontal,
            particle == Particle::IcePlate,
        ),
        (
            "--sun-elevation-deg",
            args.sun_elevation_deg.is_some(),
            args.horizontal,
        ),
    ];
    for (name, given, takes) in flags {
        if given && !takes {
            bail!(
                "{name} does not apply to --particle {}: it is for {}",
                particle.name(),
                takers(name)
            );
        }
    }
    let needed = [
        (
            "--radius-um",
            args.radius_um.is_none() && particle != Particle::Rain,
        ),
        (
            "--rain-rate-mm-h",
            args.rain_rate_mm_h.is_none() && particle == Particle::Rain,
        ),
        ("--length-um", args.length_um.is_none() && ice),
        (
            "--sun-elevation-deg",
            args.sun_elevation_deg.is_none() && args.horizontal,
        ),
    ];
    for (name, missing) in needed {
        if missing {
            bail!("{name} is required for --particle {}", particle.name());
        }
    }
    Ok(())
}

/// Which particles take a flag, for the message that refuses it elsewhere.
fn takers(flag: &str) -> &'static str {
    match flag {
        "--radius-um" => "water, ice-column and ice-plate only",
        "--distribution" => "water only",
        "--rain-rate-mm-h" => "rain only",
        "--length-um" => "ice-column and ice-plate only",
        "--horizontal" => "ice-plate only",
        _ => "ice-plate with --horizontal only",
    }
}
