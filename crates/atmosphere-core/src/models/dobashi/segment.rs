//! The pre-integrated values of one view segment (Dobashi, Yamamoto and Nishita 2002, Eq. 12 and appendix A.2,
//! Eq. A.5-A.6): for a segment that starts at radius r with direction cosine mu,
//!
//! dI_r = ∫_0^L K_r ρ_r(t) exp(-τ(0 → t)) dt,  dI_m = ∫_0^L K_m ρ_m(t) exp(-τ(0 → t)) dt,
//! dg_v = exp(-τ(0 → L)),
//!
//! at each wavelength, where τ counts every species (ozone included). The segment stops
//! where it leaves the atmosphere: at the ground or the top, whichever comes first (the
//! caller gives that distance), so that the last segment of a ray ends exactly there.
//! The integrals are converged f64 quadrature: 8-point Gauss-Legendre on the panels of
//! [`crate::optics::column::panels`] at the reference's view-ray fineness, the column to each
//! node by a nested 8-point rule.

use crate::atmosphere::Atmosphere;
use crate::atmosphere::spectra::Spectra;
use crate::numerics::quadrature::{GAUSS_LEGENDRE_8, mapped};
use crate::optics::column::{Fineness, densities, optical_depth, panels};
use crate::optics::geometry::radius_at;

/// dI_r, dI_m and dg_v of one segment, per wavelength.
#[derive(Clone, Debug, PartialEq)]
pub struct SegmentValues {
    pub scatter_r: Vec<f64>,
    pub scatter_m: Vec<f64>,
    pub transmittance: Vec<f64>,
}

/// The values of the segments from (r, mu) of lengths `lengths` (ascending, m), each cut
/// at `clip_m`, the distance to where the ray leaves the atmosphere. With `with_mie` false
/// dI_m is left at zero (no Mie scattering to integrate: `ModelSettings::prune`).
pub fn integrate(
    atmosphere: &Atmosphere,
    spectra: &Spectra,
    r: f64,
    mu: f64,
    clip_m: f64,
    lengths: &[f64],
    with_mie: bool,
) -> Vec<SegmentValues> {
    let n_w = spectra.wavelengths_nm.len();
    let bottom = atmosphere.bottom_radius_m;
    let r = r.clamp(bottom, atmosphere.top_radius_m);
    let end = lengths.last().copied().unwrap_or(0.0).min(clip_m).max(0.0);
    let cuts: Vec<f64> = lengths.iter().copied().filter(|l| *l < end).collect();
    let density_at = |t: f64| densities(atmosphere, radius_at(r, mu, t) - bottom);
    let column_over = |a: f64, b: f64| {
        let mut c = [0.0; 3];
        for (t, w) in mapped(&GAUSS_LEGENDRE_8, a, b) {
            let rho = density_at(t);
            for k in 0..3 {
                c[k] += w * rho[k];
            }
        }
        c
    };

    let mut out = Vec::with_capacity(lengths.len());
    let mut current = SegmentValues {
        scatter_r: vec![0.0; n_w],
        scatter_m: vec![0.0; n_w],
        transmittance: vec![1.0; n_w],
    };
    let mut column = [0.0; 3];
    let mut next = 0;
    // Panels as the reference cuts view rays (at most 20 km): the integrand decays as the
    // view's own transmittance, which the density scales alone (`Fineness::REFERENCE`, up
    // to 100 km panels) do not bound: one 8-point panel over a 93 km near-horizontal
    // segment from the ground in `hazy` (optical depth 30) was 4.4e-3 low.
    for (a, b) in panels(atmosphere, r, mu, end, Fineness::VIEW, &cuts) {
        for (t, weight) in mapped(&GAUSS_LEGENDRE_8, a, b) {
            let partial = column_over(a, t);
            let rho = density_at(t);
            let to_node = [
                column[0] + partial[0],
                column[1] + partial[1],
                column[2] + partial[2],
            ];
            for w in 0..n_w {
                let attenuation = weight * (-optical_depth(to_node, spectra.extinction[w])).exp();
                current.scatter_r[w] += attenuation * spectra.rayleigh_scattering[w] * rho[0];
                if with_mie {
                    current.scatter_m[w] += attenuation * spectra.mie_scattering[w] * rho[1];
                }
            }
        }
        let panel = column_over(a, b);
        for k in 0..3 {
            column[k] += panel[k];
        }
        while next < lengths.len() && lengths[next] <= b {
            out.push(finish(&current, column, spectra));
            next += 1;
        }
    }
    while out.len() < lengths.len() {
        out.push(finish(&current, column, spectra));
    }
    out
}

fn finish(current: &SegmentValues, column: [f64; 3], spectra: &Spectra) -> SegmentValues {
    SegmentValues {
        transmittance: spectra
            .extinction
            .iter()
            .map(|e| (-optical_depth(column, *e)).exp())
            .collect(),
        ..current.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::density::{DensityLayer, DensityProfile};
    use crate::atmosphere::spectral::Spectral;

    /// A uniform layer (constant densities, no ozone): dI = K / β (1 - exp(-β L)) and
    /// dg_v = exp(-β L) in closed form, for each checkpoint length.
    #[test]
    fn uniform_layer_is_closed_form() {
        let mut a = crate::atmosphere::presets::earth();
        let uniform = DensityProfile {
            layers: vec![DensityLayer {
                constant_term: 1.0,
                ..DensityLayer::default()
            }],
        };
        a.rayleigh.density = uniform.clone();
        a.mie.density = uniform;
        a.ozone.absorption_per_m = Spectral::Constant { value: 0.0 };
        let spectra = Spectra::new(&a, &[440.0, 680.0]);
        let r = a.bottom_radius_m + 1_000.0;
        let lengths = [500.0, 3_000.0, 9_000.0];
        let values = integrate(&a, &spectra, r, 0.3, 1e9, &lengths, true);
        for (l, v) in lengths.iter().zip(&values) {
            for w in 0..2 {
                let beta = spectra.extinction[w][0] + spectra.extinction[w][1];
                let t = (-beta * l).exp();
                let k_r = spectra.rayleigh_scattering[w] / beta * (1.0 - t);
                let k_m = spectra.mie_scattering[w] / beta * (1.0 - t);
                assert!((v.transmittance[w] / t - 1.0).abs() < 1e-12);
                assert!((v.scatter_r[w] / k_r - 1.0).abs() < 1e-10, "{l}");
                assert!((v.scatter_m[w] / k_m - 1.0).abs() < 1e-10, "{l}");
            }
        }
        // Cut at the clip distance; without Mie, dI_m stays zero.
        let clipped = integrate(&a, &spectra, r, 0.3, 2_000.0, &lengths, false);
        assert_eq!(clipped[1], clipped[2]);
        assert!(clipped[0].scatter_r[0] < clipped[1].scatter_r[0]);
        assert!(
            clipped
                .iter()
                .all(|v| v.scatter_m.iter().all(|m| *m == 0.0))
        );
    }
}
