//! Columns of matter along a ray: the integral of each species' relative density over a
//! path, in metres. Optical depth at any wavelength is the sum of columns times the
//! species' coefficients, so columns are computed once per ray for every wavelength.

use crate::atmosphere::Atmosphere;
use crate::numerics::quadrature::{GAUSS_LEGENDRE_8, mapped};
use crate::optics::geometry::{crossings, radius_at};

/// Relative densities (Rayleigh, Mie, ozone) at `altitude_m`.
pub fn densities(atmosphere: &Atmosphere, altitude_m: f64) -> [f64; 3] {
    [
        atmosphere.rayleigh.density.density(altitude_m),
        atmosphere.mie.density.density(altitude_m),
        atmosphere.ozone.density.density(altitude_m),
    ]
}

/// Optical depth of a column at one wavelength: sum of columns times extinctions.
pub fn optical_depth(column: [f64; 3], extinction_per_species: [f64; 3]) -> f64 {
    column[0] * extinction_per_species[0]
        + column[1] * extinction_per_species[1]
        + column[2] * extinction_per_species[2]
}

/// How finely rays are cut for quadrature.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fineness {
    /// Largest change of altitude over one Gauss-Legendre panel, as a fraction of the
    /// shortest density scale of the atmosphere.
    pub altitude_step_fraction: f64,
    /// Longest panel, m.
    pub max_panel_m: f64,
}

impl Fineness {
    /// What the reference uses for columns towards the sun: quartering both changes
    /// columns by less than 1e-9 (tested in `column_quadrature_has_converged`). Two
    /// scale heights per 8-point panel are plenty: the rule's error on exp(-x) over a span
    /// of L scale heights is about L^17 * 2e-23.
    pub const REFERENCE: Fineness = Fineness {
        altitude_step_fraction: 2.0,
        max_panel_m: 100_000.0,
    };

    /// What the reference uses along view rays, where the sun's transmittance also varies
    /// as the local zenith turns (0.18 degrees per 20 km).
    pub const VIEW: Fineness = Fineness {
        altitude_step_fraction: 1.0,
        max_panel_m: 20_000.0,
    };

    /// Twice as fine in both respects.
    pub fn halved(self) -> Fineness {
        Fineness {
            altitude_step_fraction: 0.5 * self.altitude_step_fraction,
            max_panel_m: 0.5 * self.max_panel_m,
        }
    }
}

/// Cuts the ray from (r, mu) over [0, d] into panels on which every density is smooth:
/// cuts at the tangent point, where the ray crosses a profile's breakpoint or the top of
/// the atmosphere, at `extra_cuts` (where the caller's integrand has kinks), and then
/// into pieces over which the altitude changes by at most a
/// fraction of the shortest density scale.
pub fn panels(
    atmosphere: &Atmosphere,
    r: f64,
    mu: f64,
    d: f64,
    fineness: Fineness,
    extra_cuts: &[f64],
) -> Vec<(f64, f64)> {
    let bottom = atmosphere.bottom_radius_m;
    let mut cuts = vec![0.0, d];
    cuts.extend(extra_cuts.iter().filter(|t| **t > 0.0 && **t < d));
    let tangent = -r * mu;
    if tangent > 0.0 && tangent < d {
        cuts.push(tangent);
    }
    let mut levels: Vec<f64> = atmosphere
        .rayleigh
        .density
        .breakpoints_m()
        .into_iter()
        .chain(atmosphere.mie.density.breakpoints_m())
        .chain(atmosphere.ozone.density.breakpoints_m())
        .collect();
    levels.push(atmosphere.thickness_m());
    for h in levels {
        cuts.extend(
            crossings(r, mu, bottom + h)
                .into_iter()
                .filter(|t| *t > 0.0 && *t < d),
        );
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();

    let scale = shortest_scale_m(atmosphere) * fineness.altitude_step_fraction;
    let mut out = Vec::new();
    for pair in cuts.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if b <= a {
            continue;
        }
        let dh = (radius_at(r, mu, b) - radius_at(r, mu, a)).abs();
        let n = ((dh / scale)
            .ceil()
            .max((b - a) / fineness.max_panel_m)
            .ceil() as usize)
            .max(1);
        // Monotone in altitude on [a, b]: cut at equal altitude steps so that steep parts
        // get short panels, then cap their length.
        let ra = radius_at(r, mu, a);
        let rb = radius_at(r, mu, b);
        let ascending = a >= tangent;
        let mut prev = a;
        for k in 1..=n {
            let next = if k == n {
                b
            } else {
                let rk = ra + (rb - ra) * k as f64 / n as f64;
                let disc = (r * mu) * (r * mu) - (r - rk) * (r + rk);
                let root = disc.max(0.0).sqrt();
                let t = if ascending {
                    -r * mu + root
                } else {
                    -r * mu - root
                };
                t.clamp(prev, b)
            };
            if next > prev {
                out.push((prev, next));
            }
            prev = next;
        }
    }
    out
}

/// The shortest density scale of any species that matters (m).
pub fn shortest_scale_m(atmosphere: &Atmosphere) -> f64 {
    atmosphere
        .rayleigh
        .density
        .shortest_scale_m()
        .min(atmosphere.mie.density.shortest_scale_m())
        .min(atmosphere.ozone.density.shortest_scale_m())
        .min(atmosphere.thickness_m())
}

/// Columns (m) along the ray from (r, mu) over [0, d], converged (see [`Fineness`]).
pub fn column(atmosphere: &Atmosphere, r: f64, mu: f64, d: f64) -> [f64; 3] {
    column_with(atmosphere, r, mu, d, Fineness::REFERENCE)
}

/// Columns with a chosen fineness.
pub fn column_with(
    atmosphere: &Atmosphere,
    r: f64,
    mu: f64,
    d: f64,
    fineness: Fineness,
) -> [f64; 3] {
    let bottom = atmosphere.bottom_radius_m;
    let mut sum = [0.0; 3];
    for (a, b) in panels(atmosphere, r, mu, d, fineness, &[]) {
        for (t, w) in mapped(&GAUSS_LEGENDRE_8, a, b) {
            let rho = densities(atmosphere, radius_at(r, mu, t) - bottom);
            for k in 0..3 {
                sum[k] += w * rho[k];
            }
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::geometry::distance_to_exit;

    #[test]
    fn vertical_column_of_an_exponential_layer_is_closed_form() {
        // integral of exp(-h/H) from 0 to Z = H (1 - exp(-Z/H)).
        let earth = Atmosphere::preset("earth").unwrap();
        let z = earth.thickness_m();
        let c = column(&earth, earth.bottom_radius_m, 1.0, z);
        for (k, h) in [(0, 8_000.0), (1, 1_200.0)] {
            let exact = h * (1.0 - (-z / h).exp());
            assert!(
                (c[k] / exact - 1.0).abs() < 1e-12,
                "{k}: {} vs {exact}",
                c[k]
            );
        }
        // The ozone tent's vertical column is its area: 15 km.
        assert!((c[2] / 15_000.0 - 1.0).abs() < 1e-12, "{}", c[2]);
    }

    #[test]
    fn column_quadrature_has_converged() {
        let earth = Atmosphere::preset("earth").unwrap();
        let bottom = earth.bottom_radius_m;
        let top = earth.top_radius_m;
        for &(h, mu) in &[
            (0.0, 0.0),
            (0.0, 0.02),
            (1.0, -0.0001),
            (20_000.0, -0.05),
            (59_000.0, -0.3),
            (0.0, 1.0),
        ] {
            let r = bottom + h;
            let d = if crate::optics::geometry::ray_hits_ground(r, mu, bottom) {
                crate::optics::geometry::distance_to_entry(r, mu, bottom).unwrap()
            } else {
                distance_to_exit(r, mu, top)
            };
            let coarse = column_with(&earth, r, mu, d, Fineness::REFERENCE);
            let fine = column_with(&earth, r, mu, d, Fineness::REFERENCE.halved().halved());
            for k in 0..3 {
                let rel = (coarse[k] - fine[k]).abs() / fine[k].max(1e-30);
                assert!(rel < 1e-9, "h={h} mu={mu} species {k}: {rel:e}");
            }
        }
    }
}
