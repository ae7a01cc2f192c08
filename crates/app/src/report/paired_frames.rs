//! A section's GPU column as pairs of frames: each row's frame with its feature (clouds,
//! a rain or ice volume) and the same frame without it, interleaved so that both see the
//! same load of a shared machine (`clouds_gpu.rs`, `optics_gpu.rs`).

/// One row's frame of one view and the same frame without the feature, medians, ms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairedFrame {
    pub with_ms: f64,
    pub without_ms: f64,
}

/// Every row's frames: `per_row[row][view]`, `None` where the row is not measured on
/// the view (off the GPU).
#[derive(Clone, Debug, PartialEq)]
pub struct GpuTimes {
    pub adapter: String,
    pub per_row: Vec<Vec<Option<PairedFrame>>>,
}

impl GpuTimes {
    /// The mean over the measured views of row `row`'s frame time, ms, and of its ratio
    /// to the frame without the feature.
    pub fn mean(&self, row: usize) -> Option<(f64, f64)> {
        let frames: Vec<PairedFrame> = self.per_row[row].iter().flatten().copied().collect();
        if frames.is_empty() {
            return None;
        }
        let n = frames.len() as f64;
        Some((
            frames.iter().map(|f| f.with_ms).sum::<f64>() / n,
            frames.iter().map(|f| f.with_ms / f.without_ms).sum::<f64>() / n,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mean_skips_views_not_measured_and_averages_the_ratios() {
        let frame = |with_ms, without_ms| {
            Some(PairedFrame {
                with_ms,
                without_ms,
            })
        };
        let times = GpuTimes {
            adapter: "test".into(),
            per_row: vec![vec![frame(30.0, 10.0), None, frame(10.0, 10.0)], vec![None]],
        };
        assert_eq!(times.mean(0), Some((20.0, 2.0)));
        assert_eq!(times.mean(1), None);
    }
}
