//! The volumes marched for one pixel in N x N and upsampled, the twin of render-wgpu's
//! reduced volumes pass. The march is most of the pass's work per pixel, and the light
//! a volume adds varies slowly across the frame except where a ray's path through the
//! volumes changes: at a shaft's edges, where the ground or a surface cuts a ray, and
//! at a layer's horizon. So the composite's terms (`render.rs`, [`CompositeTerms`]:
//! L = A L_full + B) are computed for the pixels (N i, N j), the taps (past the frame's
//! last pixel too), and every pixel takes the bilinear mean of the up to four taps
//! around it whose [`Spans`] agree with its own (the nearest entry and the length
//! inside the volumes, each within [`SPAN_TOLERANCE`] of the larger), renormalised
//! over those; a pixel where none agrees is marched itself. Pixels on the taps' grid
//! are their own taps, exact.

use glam::DVec3;

use super::error::HydrometeorError;
use super::render::{CompositeTerms, LitVolume};

/// The divisors the pass takes: 1 marches every pixel.
pub const DIVISOR_RANGE: [u32; 2] = [1, 4];
/// How far a tap's entry and length may be from the pixel's, as a share of the larger.
pub const SPAN_TOLERANCE: f64 = 0.1;

/// Checks a divisor against [`DIVISOR_RANGE`].
pub fn check_divisor(divisor: u32) -> Result<u32, HydrometeorError> {
    let [lo, hi] = DIVISOR_RANGE;
    if (lo..=hi).contains(&divisor) {
        Ok(divisor)
    } else {
        Err(HydrometeorError::Setting {
            what: "volumes resolution divisor",
            value: f64::from(divisor),
            range: "1, 2, 3 or 4",
        })
    }
}

/// Where a ray meets the volumes: its nearest entry and its whole length inside them,
/// m (both 0 where it meets none).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Spans {
    pub entry_m: f64,
    pub length_m: f64,
}

/// The spans of the ray `(origin, direction, max_distance_m)` through `volumes`.
pub fn spans(
    volumes: &[LitVolume],
    (origin, direction, max_distance_m): (DVec3, DVec3, f64),
) -> Spans {
    let mut entry = f64::INFINITY;
    let mut length = 0.0;
    for v in volumes {
        if let Some((t0, t1)) = v.volume.segment(origin, direction, max_distance_m) {
            entry = entry.min(t0);
            length += t1 - t0;
        }
    }
    if length > 0.0 {
        Spans {
            entry_m: entry,
            length_m: length,
        }
    } else {
        Spans::default()
    }
}

impl Spans {
    /// Whether a tap of spans `tap` may stand for a pixel of these: both meet no
    /// volume, or both meet them with entries and lengths within [`SPAN_TOLERANCE`].
    pub fn agree(&self, tap: &Spans) -> bool {
        if self.length_m <= 0.0 || tap.length_m <= 0.0 {
            return self.length_m <= 0.0 && tap.length_m <= 0.0;
        }
        let close = |a: f64, b: f64| (a - b).abs() <= SPAN_TOLERANCE * a.abs().max(b.abs());
        close(self.entry_m, tap.entry_m) && close(self.length_m, tap.length_m)
    }
}

/// The taps of pixel `(x, y)` at `divisor`: the reduced pixels (i, j) around it (the
/// frame's pixels (divisor i, divisor j)) and their bilinear weights, those of weight
/// zero left out.
pub fn taps(x: u32, y: u32, divisor: u32) -> Vec<([u32; 2], f64)> {
    let (i, j) = (x / divisor, y / divisor);
    let fx = f64::from(x % divisor) / f64::from(divisor);
    let fy = f64::from(y % divisor) / f64::from(divisor);
    [
        ([i, j], (1.0 - fx) * (1.0 - fy)),
        ([i + 1, j], fx * (1.0 - fy)),
        ([i, j + 1], (1.0 - fx) * fy),
        ([i + 1, j + 1], fx * fy),
    ]
    .into_iter()
    .filter(|(_, w)| *w > 0.0)
    .collect()
}

/// The weighted mean of the terms of the taps (weight, spans, terms) whose spans agree
/// with the pixel's `own`; `None` where none does.
pub fn upsampled(own: &Spans, taps: &[(f64, Spans, CompositeTerms)]) -> Option<CompositeTerms> {
    let mut sum = CompositeTerms {
        times_full: [0.0; 3],
        added: [0.0; 3],
    };
    let mut weight = 0.0;
    for (w, spans, terms) in taps {
        if own.agree(spans) {
            weight += w;
            for c in 0..3 {
                sum.times_full[c] += w * terms.times_full[c];
                sum.added[c] += w * terms.added[c];
            }
        }
    }
    (weight > 0.0).then(|| CompositeTerms {
        times_full: sum.times_full.map(|v| v / weight),
        added: sum.added.map(|v| v / weight),
    })
}

/// Every pixel's terms of a `width` x `height` frame at `divisor`: `ray(x, y)` gives the
/// ray of pixel (x, y) (for the taps, x and y may reach one tap past the frame) and
/// `terms` marches one.
pub fn frame_terms(
    (width, height): (u32, u32),
    divisor: u32,
    volumes: &[LitVolume],
    ray: impl Fn(u32, u32) -> (DVec3, DVec3, f64),
    terms: impl Fn((DVec3, DVec3, f64)) -> CompositeTerms,
) -> Vec<CompositeTerms> {
    let columns = (width - 1) / divisor + 2;
    let rows = (height - 1) / divisor + 2;
    let reduced: Vec<(Spans, CompositeTerms)> = (0..rows)
        .flat_map(|j| (0..columns).map(move |i| (i, j)))
        .map(|(i, j)| {
            let r = ray(i * divisor, j * divisor);
            (spans(volumes, r), terms(r))
        })
        .collect();
    let mut out = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            let r = ray(x, y);
            if divisor == 1 {
                out.push(terms(r));
                continue;
            }
            let around: Vec<(f64, Spans, CompositeTerms)> = taps(x, y, divisor)
                .into_iter()
                .map(|([i, j], w)| {
                    let (s, t) = reduced[(j * columns + i) as usize];
                    (w, s, t)
                })
                .collect();
            out.push(upsampled(&spans(volumes, r), &around).unwrap_or_else(|| terms(r)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn taps_weigh_like_bilinear_and_the_grid_is_its_own() {
        for divisor in 1..=4 {
            for (x, y) in [(0, 0), (5, 7), (8, 3), (11, 12)] {
                let t = taps(x, y, divisor);
                let total: f64 = t.iter().map(|(_, w)| w).sum();
                assert!((total - 1.0).abs() < 1e-12);
                // The weighted mean of the taps' positions is the pixel's.
                let at: [f64; 2] = std::array::from_fn(|a| {
                    t.iter().map(|(ij, w)| w * f64::from(ij[a] * divisor)).sum()
                });
                assert!((at[0] - f64::from(x)).abs() < 1e-9, "{at:?} {x}");
                assert!((at[1] - f64::from(y)).abs() < 1e-9, "{at:?} {y}");
                if x % divisor == 0 && y % divisor == 0 {
                    assert_eq!(t, vec![([x / divisor, y / divisor], 1.0)]);
                }
            }
        }
        assert!(check_divisor(0).is_err() && check_divisor(5).is_err());
        assert_eq!(check_divisor(3).unwrap(), 3);
    }

    #[test]
    fn only_taps_whose_spans_agree_are_averaged() {
        let meet = |entry_m, length_m| Spans { entry_m, length_m };
        let terms = |v: f64| CompositeTerms {
            times_full: [v; 3],
            added: [2.0 * v; 3],
        };
        let own = meet(3_000.0, 4_000.0);
        let around = [
            (0.25, meet(3_050.0, 3_900.0), terms(1.0)),
            (0.25, meet(3_000.0, 100.0), terms(9.0)),
            (0.5, Spans::default(), terms(7.0)),
        ];
        assert_eq!(upsampled(&own, &around), Some(terms(1.0)));
        assert_eq!(upsampled(&Spans::default(), &around), Some(terms(7.0)));
        assert_eq!(upsampled(&meet(10.0, 1.0), &around), None);
    }
}
