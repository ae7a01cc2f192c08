//! `atmos phase --particle water`: Lorenz-Mie spheres of one radius or averaged over a
//! size distribution.

use anyhow::{Context, bail};
use atmosphere_core::optics::mie::coefficients::wiscombe_terms;
use atmosphere_core::optics::mie::polydisperse::particle_optics;
use atmosphere_core::optics::mie::size_distribution::SizeDistribution;
use atmosphere_core::optics::refractive_index::water::water_refractive_index;
use rayon::prelude::*;

use super::table::WavelengthResult;
use crate::cli::PhaseArgs;

/// How closely a size-distribution average must settle: cross-sections and g to 1e-3,
/// the phase function to 1e-2 (relative to the larger of it and 1 / (4 pi)).
pub const DISTRIBUTION_TOLERANCE: f64 = 1e-3;

/// The most work one run takes on, in Mie terms times angles times radii (about a
/// minute on two cores): more is refused before it starts rather than left to run.
pub const MAX_WORK: f64 = 2e11;

/// The description and the per-wavelength results of water drops.
pub fn compute(args: &PhaseArgs) -> anyhow::Result<(String, Vec<WavelengthResult>)> {
    let Some(radius_um) = args.radius_um else {
        bail!("--radius-um is required for --particle water");
    };
    let radius_m = radius_um * 1e-6;
    let distribution = match &args.distribution {
        None => SizeDistribution::Monodisperse { radius_m },
        Some(flag) => flag
            .with_effective_radius(radius_m)
            .context("--distribution")?,
    };
    let indices = args
        .wavelengths
        .iter()
        .map(|w| match args.refractive_index {
            Some(m) => Ok(m),
            None => Ok(water_refractive_index(w.nm)?),
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    check_work(args, &distribution)?;

    let cosines = args.angles_deg.cosines();
    let results = args
        .wavelengths
        .par_iter()
        .zip(&indices)
        .map(|(w, &m)| {
            let optics = particle_optics(
                m,
                w.nm * 1e-9,
                &distribution,
                &cosines,
                DISTRIBUTION_TOLERANCE,
            )
            .with_context(|| format!("at {} nm", w.label))?;
            Ok(WavelengthResult {
                label: w.label.clone(),
                refractive_index: m,
                optics,
                samples: "radii",
            })
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    Ok((describe(args, radius_um), results))
}

/// The first header line: what was computed.
fn describe(args: &PhaseArgs, radius_um: f64) -> String {
    let particle = "water";
    let index = match args.refractive_index {
        Some(m) => format!("refractive index {}{:+e}i", m.re, m.im),
        None => "refractive index of Hale and Querry 1973".to_string(),
    };
    match &args.distribution {
        None => format!("particle {particle}, radius {radius_um} um, {index}"),
        Some(d) => format!(
            "particle {particle}, effective radius {radius_um} um, distribution {}, {index}",
            d.describe()
        ),
    }
}

/// Refuses a run whose estimated work (terms at the largest radius, times angles, times
/// radii: about one per half unit of size parameter across a distribution) is past
/// [`MAX_WORK`].
fn check_work(args: &PhaseArgs, distribution: &SizeDistribution) -> anyhow::Result<()> {
    let [lo, hi] = distribution.log_radius_range();
    let angles = args.angles_deg.count as f64;
    let work: f64 = args
        .wavelengths
        .iter()
        .map(|w| {
            let k = 2.0 * std::f64::consts::PI / (w.nm * 1e-9);
            let (x_lo, x_hi) = (k * lo.exp(), k * hi.exp());
            let radii = if lo == hi {
                1.0
            } else {
                (2.0 * (x_hi - x_lo)).max(64.0)
            };
            wiscombe_terms(x_hi.min(1e6)) as f64 * angles * radii
        })
        .sum();
    if work > MAX_WORK {
        bail!(
            "this asks for about {work:.1e} term evaluations (Mie terms x angles x radii), \
             more than {MAX_WORK:.0e}: use fewer angles, wavelengths, a smaller radius or a \
             narrower distribution"
        );
    }
    Ok(())
}
