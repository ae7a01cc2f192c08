//! Summaries of a model's error against the reference over many rays: relative RMS, 95th
//! percentile and maximum of the relative error, and the mean of any other per-ray error
//! (the report's CIEDE2000).

/// Statistics of per-ray relative errors |model - reference| / reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RelativeErrorStats {
    /// Rays counted (those with a positive reference value).
    pub count: usize,
    /// sqrt(mean(e^2)).
    pub rms: f64,
    /// Mean of e with its sign: positive when the model is too bright.
    pub bias: f64,
    /// 95th percentile of |e| (nearest rank).
    pub p95: f64,
    pub max: f64,
}

impl RelativeErrorStats {
    /// Statistics over pairs (model, reference). Pairs whose reference is not positive
    /// and finite carry no relative error and are left out; a non-finite model value
    /// gives an infinite error.
    pub fn new(pairs: impl IntoIterator<Item = (f64, f64)>) -> RelativeErrorStats {
        let signed: Vec<f64> = pairs
            .into_iter()
            .filter(|(_, r)| r.is_finite() && *r > 0.0)
            .map(|(m, r)| {
                if m.is_finite() {
                    (m - r) / r
                } else {
                    f64::INFINITY
                }
            })
            .collect();
        let count = signed.len();
        if count == 0 {
            return RelativeErrorStats {
                count,
                rms: 0.0,
                bias: 0.0,
                p95: 0.0,
                max: 0.0,
            };
        }
        let n = count as f64;
        let mut magnitudes: Vec<f64> = signed.iter().map(|e| e.abs()).collect();
        magnitudes.sort_by(f64::total_cmp);
        RelativeErrorStats {
            count,
            rms: (signed.iter().map(|e| e * e).sum::<f64>() / n).sqrt(),
            bias: signed.iter().sum::<f64>() / n,
            p95: percentile_sorted(&magnitudes, 0.95),
            max: magnitudes[count - 1],
        }
    }
}

/// The `q`-quantile of sorted values by the nearest-rank rule (the smallest value with at
/// least a fraction `q` of the values at or below it).
pub fn percentile_sorted(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    let rank = (q * sorted.len() as f64).ceil() as usize;
    sorted[rank.clamp(1, sorted.len()) - 1]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_errors_by_hand() {
        // Errors +10 %, -20 %, 0, and a ray with no reference light (left out).
        let s = RelativeErrorStats::new([(1.1, 1.0), (1.6, 2.0), (3.0, 3.0), (0.5, 0.0)]);
        assert_eq!(s.count, 3);
        assert!((s.rms - ((0.01 + 0.04) / 3.0f64).sqrt()).abs() < 1e-12);
        assert!((s.bias - (-0.1 / 3.0)).abs() < 1e-12);
        assert!((s.max - 0.2).abs() < 1e-12);
        assert!((s.p95 - 0.2).abs() < 1e-12);
        let nan = RelativeErrorStats::new([(f64::NAN, 1.0)]);
        assert!(nan.max.is_infinite());
    }

    #[test]
    fn nearest_rank_percentile() {
        let v: Vec<f64> = (1..=100).map(f64::from).collect();
        assert_eq!(percentile_sorted(&v, 0.95), 95.0);
        assert_eq!(percentile_sorted(&v, 1.0), 100.0);
        assert_eq!(percentile_sorted(&v[..1], 0.95), 1.0);
    }
}
