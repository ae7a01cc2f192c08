//! `atmos phase --particle ice-column|ice-plate`: hexagonal crystals ray traced with
//! diffraction, in random orientations or, for plates, horizontal with a tilt spread and
//! the sun at an elevation. The table's bins (0.1 degree) are read at the angles asked
//! for, linearly between bin centres.

use anyhow::{Context, bail};
use atmosphere_core::optics::ice::crystal::HexagonalPrism;
use atmosphere_core::optics::ice::orientation::Orientation;
use atmosphere_core::optics::ice::phase_table::{RaySettings, ice_phase_table};
use atmosphere_core::optics::mie::polydisperse::ParticleOptics;
use atmosphere_core::optics::refractive_index::ice::ice_refractive_index;

use super::flags::Particle;
use super::table::WavelengthResult;
use crate::cli::PhaseArgs;

/// The table's bin width, degrees, and the rays' seed.
const BIN_DEG: f64 = 0.1;
const SEED: u64 = 1;

/// The description and the per-wavelength results of ice crystals.
pub fn compute(args: &PhaseArgs) -> anyhow::Result<(String, Vec<WavelengthResult>)> {
    let (Some(radius_um), Some(length_um)) = (args.radius_um, args.length_um) else {
        bail!("--radius-um and --length-um are required for ice crystals");
    };
    let crystal = HexagonalPrism::new(radius_um * 1e-6, length_um * 1e-6)
        .context("--radius-um, --length-um")?;
    let orientation = match (args.horizontal, args.sun_elevation_deg) {
        (true, Some(elevation)) => Orientation::horizontal_plates(args.tilt_deg, elevation)
            .context("--tilt-deg, --sun-elevation-deg")?,
        _ => Orientation::Random,
    };
    let settings = RaySettings {
        rays: args.rays,
        bin_deg: BIN_DEG,
        seed: SEED,
    };
    let results = args
        .wavelengths
        .iter()
        .map(|w| {
            let m = match args.refractive_index {
                Some(m) => m,
                None => ice_refractive_index(w.nm)?,
            };
            let table = ice_phase_table(&crystal, m, w.nm * 1e-9, orientation, settings)
                .with_context(|| format!("--rays, --refractive-index at {} nm", w.label))?;
            let area = table.projected_area_m2;
            let optics = ParticleOptics {
                extinction_cross_section_m2: table.extinction_efficiency() * area,
                scattering_cross_section_m2: table.scattering_efficiency * area,
                geometric_cross_section_m2: area,
                asymmetry: table.asymmetry,
                phase: args
                    .angles_deg
                    .angles_deg()
                    .map(|a| table.value_at(a))
                    .collect(),
                radii: table.hits,
            };
            Ok(WavelengthResult {
                label: w.label.clone(),
                refractive_index: m,
                optics,
                samples: "rays_hit",
            })
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let shape = if args.particle == Particle::IceColumn {
        "column"
    } else {
        "plate"
    };
    let orientation_text = match orientation {
        Orientation::Random => "random orientations".to_string(),
        Orientation::HorizontalPlates {
            tilt_spread_deg,
            sun_elevation_deg,
        } => format!(
            "horizontal, tilt spread {tilt_spread_deg} deg, sun elevation {sun_elevation_deg} \
             deg, averaged over azimuth around the sun"
        ),
    };
    let index = match args.refractive_index {
        Some(m) => format!("refractive index {}{:+e}i", m.re, m.im),
        None => "refractive index of Warren and Brandt 2008".to_string(),
    };
    let description = format!(
        "particle ice-{shape}, hexagonal, radius {radius_um} um, length {length_um} um, \
         {orientation_text}, {} rays, {BIN_DEG} degree bins, {index}",
        args.rays
    );
    Ok((description, results))
}
