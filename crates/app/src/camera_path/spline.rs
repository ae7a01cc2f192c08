//! Monotone cubic interpolation (Fritsch and Carlson 1980, "Monotone piecewise cubic
//! interpolation", SIAM J. Numer. Anal. 17(2), with the weighted harmonic mean of
//! Fritsch and Butland 1984 for the slopes): a C1 curve through every knot that never
//! overshoots between two knots, so an altitude that only rises never dips.

/// The slopes at the knots `(times[i], values[i])`; times strictly increasing.
pub fn slopes(times: &[f64], values: &[f64]) -> Vec<f64> {
    let n = times.len();
    if n < 2 {
        return vec![0.0; n];
    }
    let h: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
    let delta: Vec<f64> = (0..n - 1)
        .map(|i| (values[i + 1] - values[i]) / h[i])
        .collect();
    let mut m = vec![0.0; n];
    m[0] = delta[0];
    m[n - 1] = delta[n - 2];
    for i in 1..n - 1 {
        let (a, b) = (delta[i - 1], delta[i]);
        if a * b > 0.0 {
            let (w1, w2) = (2.0 * h[i] + h[i - 1], h[i] + 2.0 * h[i - 1]);
            m[i] = (w1 + w2) / (w1 / a + w2 / b);
        }
    }
    m
}

/// The cubic Hermite curve between `(t0, y0)` with slope `m0` and `(t1, y1)` with slope
/// `m1` at fraction `h` in [0, 1]: exactly `y0` at 0 and `y1` at 1.
pub fn hermite(y0: f64, y1: f64, m0: f64, m1: f64, dt: f64, h: f64) -> f64 {
    if h <= 0.0 {
        return y0;
    }
    if h >= 1.0 {
        return y1;
    }
    let (h2, h3) = (h * h, h * h * h);
    (2.0 * h3 - 3.0 * h2 + 1.0) * y0
        + (h3 - 2.0 * h2 + h) * dt * m0
        + (3.0 * h2 - 2.0 * h3) * y1
        + (h3 - h2) * dt * m1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn monotone_data_stay_monotone_and_knots_are_hit() {
        let t = [0.0, 1.0, 3.0, 3.5, 10.0];
        let y = [0.0, 0.1, 5.0, 5.0, 9.0];
        let m = slopes(&t, &y);
        let mut last = f64::NEG_INFINITY;
        for i in 0..t.len() - 1 {
            for k in 0..=100 {
                let h = k as f64 / 100.0;
                let v = hermite(y[i], y[i + 1], m[i], m[i + 1], t[i + 1] - t[i], h);
                assert!(v >= last - 1e-12, "{i} {h}");
                assert!(v >= y[i].min(y[i + 1]) - 1e-12 && v <= y[i].max(y[i + 1]) + 1e-12);
                last = v;
            }
            assert_eq!(hermite(y[i], y[i + 1], m[i], m[i + 1], 1.0, 0.0), y[i]);
            assert_eq!(hermite(y[i], y[i + 1], m[i], m[i + 1], 1.0, 1.0), y[i + 1]);
        }
    }
}
