//! Orders two and up in a similarity-scaled medium, a setting (`ms_delta`) beside
//! Hillaire 2020's isotropic Psi_ms (section 5.5; docs/models/hillaire.md,
//! "Similarity-scaled multiple scattering").
//!
//! The paper takes light scattered twice or more as isotropic. Mie's phase function is
//! not: much of what an aerosol particle scatters goes on within a few degrees of where it
//! was going. The delta-M method (Wiscombe 1977; Joseph, Wiscombe and Weinman 1976 for its
//! two-moment form, delta-Eddington) splits the phase function into a forward delta of
//! weight f and the rest, p = f delta(1 - t) / (2 pi) + (1 - f) p'; light scattered into
//! the delta goes on as if it had not been scattered, so the transfer equation is
//! unchanged with
//!   sigma_s' = (1 - f) sigma_s,  sigma_t' = sigma_t - f sigma_s,  phase p'.
//! Only Mie is scaled (Rayleigh's phase function has no forward peak). The paper's
//! isotropic approximation is then applied to p', which is less peaked than p.
//!
//! Used as the truncated multiple-scattering correction of Nakajima and Tanaka 1988:
//! single scattering keeps the true scattering coefficients and phase functions but the
//! scaled transmittances (the sun's and the camera's), and orders two and up are the
//! paper's Psi_ms built in the scaled medium, scattered with sigma_s'. The transmittance a
//! ray reports (to surfaces and to space) stays the true one.
//!
//! f is a setting, since the transport approximation's f = g_1 (p' isotropic)
//! over-corrects; docs/models/hillaire.md gives the errors by f.

use crate::atmosphere::spectra::Spectra;

/// `spectra` with the Mie scattering and extinction of the scaled medium for a delta
/// fraction `f` in [0, 1]: sigma_s' = (1 - f) sigma_s, sigma_t' = sigma_t - f sigma_s
/// (never below the absorption sigma_t - sigma_s).
pub fn scaled(spectra: &Spectra, f: f64) -> Spectra {
    let mut out = spectra.clone();
    for (extinction, scattering) in out.extinction.iter_mut().zip(&mut out.mie_scattering) {
        extinction[1] -= f * *scattering;
        *scattering *= 1.0 - f;
    }
    out
}
