//! `atmos phase --particle rain`: Lorenz-Mie drops of 0.1 to 3 mm averaged over the
//! Marshall-Palmer (1948) distribution of a rain rate.

use anyhow::{Context, bail};
use atmosphere_core::optics::mie::coefficients::wiscombe_terms;
use atmosphere_core::optics::mie::marshall_palmer::{MarshallPalmer, RADIUS_RANGE_M};
use atmosphere_core::optics::mie::rain::rain_optics_converged;
use atmosphere_core::optics::refractive_index::water::water_refractive_index;

use super::table::WavelengthResult;
use super::water::MAX_WORK;
use crate::cli::PhaseArgs;

/// How closely the rain average must settle: cross-sections and g to 3e-3, the phase
/// function to 3e-2 (relative to the larger of it and 1 / (4 pi)).
pub const RAIN_TOLERANCE: f64 = 3e-3;

/// The radii a settled rain average is expected to take, all rules together: about
/// twice the last rule's (docs/particles.md).
const EXPECTED_RADII: f64 = 4100.0;

/// The description and the per-wavelength results of rain.
pub fn compute(args: &PhaseArgs) -> anyhow::Result<(String, Vec<WavelengthResult>)> {
    let Some(rate) = args.rain_rate_mm_h else {
        bail!("--rain-rate-mm-h is required for --particle rain");
    };
    let rain = MarshallPalmer::new(rate).context("--rain-rate-mm-h")?;
    let indices = args
        .wavelengths
        .iter()
        .map(|w| match args.refractive_index {
            Some(m) => Ok(m),
            None => Ok(water_refractive_index(w.nm)?),
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let angles = args.angles_deg.count as f64;
    let work: f64 = args
        .wavelengths
        .iter()
        .map(|w| {
            let x = 2.0 * std::f64::consts::PI * RADIUS_RANGE_M[1] / (w.nm * 1e-9);
            wiscombe_terms(x.min(1e6)) as f64 * angles * EXPECTED_RADII
        })
        .sum();
    if work > MAX_WORK {
        bail!(
            "rain asks for about {work:.1e} term evaluations (Mie terms x angles x about \
             {EXPECTED_RADII} radii), more than {MAX_WORK:.0e}: use fewer --angles-deg or \
             --wavelengths"
        );
    }
    let cosines = args.angles_deg.cosines();
    // The radii run in parallel within each wavelength.
    let results = args
        .wavelengths
        .iter()
        .zip(&indices)
        .map(|(w, &m)| {
            let optics = rain_optics_converged(m, w.nm * 1e-9, &rain, &cosines, RAIN_TOLERANCE)
                .with_context(|| format!("at {} nm", w.label))?;
            Ok(WavelengthResult {
                label: w.label.clone(),
                refractive_index: m,
                optics,
                samples: "radii",
            })
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let index = match args.refractive_index {
        Some(m) => format!("refractive index {}{:+e}i", m.re, m.im),
        None => "refractive index of Hale and Querry 1973".to_string(),
    };
    let description = format!(
        "particle rain, rain rate {rate} mm/h, Marshall-Palmer 1948 drops of radius 0.1 to \
         3 mm ({:.1} per m^3), {index}",
        rain.number_density_m3()
    );
    Ok((description, results))
}
