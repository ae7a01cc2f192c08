//! The CSV `atmos phase` writes: comment lines naming the particle and, per wavelength,
//! the refractive index, Q_ext, Q_sca, g and the radii averaged (rays that hit, for ice
//! crystals); then `angle_deg` and
//! one column `p_<nm>` per wavelength, the phase function in sr^-1 with unit integral
//! over the sphere.

use std::fmt::Write as _;

use atmosphere_core::optics::mie::polydisperse::ParticleOptics;
use num_complex::Complex64;

use super::flags::AngleRange;

/// One wavelength's result, labelled as the user wrote it.
#[derive(Debug)]
pub struct WavelengthResult {
    pub label: String,
    pub refractive_index: Complex64,
    pub optics: ParticleOptics,
    /// What the last header field counts: `radii` (averaged) or `rays_hit`.
    pub samples: &'static str,
}

/// The CSV text: `description` as the first comment line.
pub fn write_csv(description: &str, angles: &AngleRange, results: &[WavelengthResult]) -> String {
    let mut text = String::new();
    let _ = writeln!(text, "# atmos phase: {description}");
    let _ = writeln!(
        text,
        "# per wavelength (nm): relative refractive index m = m_re + i m_im, efficiencies \
         (cross-sections over pi <r^2>, or over the mean projected area of crystals), \
         asymmetry g, radii averaged or rays that hit"
    );
    for r in results {
        let _ = writeln!(
            text,
            "# wavelength_nm={} m_re={} m_im={:e} Q_ext={:.9} Q_sca={:.9} g={:.9} {}={}",
            r.label,
            r.refractive_index.re,
            r.refractive_index.im,
            r.optics.extinction_efficiency(),
            r.optics.scattering_efficiency(),
            r.optics.asymmetry,
            r.samples,
            r.optics.radii,
        );
    }
    text.push_str("angle_deg");
    for r in results {
        let _ = write!(text, ",p_{}", r.label);
    }
    text.push('\n');
    for (i, angle) in angles.angles_deg().enumerate() {
        let _ = write!(text, "{angle:.*}", angles.decimals);
        for r in results {
            let _ = write!(text, ",{:.9e}", r.optics.phase[i]);
        }
        text.push('\n');
    }
    text
}
