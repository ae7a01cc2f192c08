//! A Monte Carlo mean with its standard error, from running sums of the per-path scores.

/// Running sums of one score over independent paths.
#[derive(Clone, Copy, Debug, Default)]
pub struct Tally {
    sum: f64,
    sum_sq: f64,
    count: u64,
}

/// A mean and the standard error of the mean, sqrt(sample variance / paths).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    pub mean: f64,
    pub standard_error: f64,
}

impl Tally {
    /// Adds one path's score (0 for paths that do not contribute).
    pub fn add(&mut self, score: f64) {
        self.sum += score;
        self.sum_sq += score * score;
        self.count += 1;
    }

    pub fn estimate(&self) -> Estimate {
        let n = self.count.max(1) as f64;
        let mean = self.sum / n;
        let variance = if self.count > 1 {
            ((self.sum_sq - n * mean * mean) / (n - 1.0)).max(0.0)
        } else {
            0.0
        };
        Estimate {
            mean,
            standard_error: (variance / n).sqrt(),
        }
    }
}
