//! The viewer's recent frame times: the longest of the last frames and its ratio to
//! their median, the hitch a flight would show (docs/terrain.md, "No popping").

use std::collections::VecDeque;

/// Frames kept.
pub const WINDOW: usize = 120;

/// The wall times of the last [`WINDOW`] rendered frames, ms.
#[derive(Clone, Debug, Default)]
pub struct FrameTimes {
    times: VecDeque<f64>,
}

impl FrameTimes {
    /// Adds a frame's wall time, ms.
    pub fn push(&mut self, ms: f64) {
        if self.times.len() == WINDOW {
            self.times.pop_front();
        }
        self.times.push_back(ms);
    }

    /// The longest frame kept and its ratio to the median of those kept; `None` before any.
    pub fn longest(&self) -> Option<(f64, f64)> {
        let mut sorted: Vec<f64> = self.times.iter().copied().collect();
        sorted.sort_by(f64::total_cmp);
        let median = *sorted.get((sorted.len().max(1) - 1) / 2)?;
        let longest = *sorted.last()?;
        Some((longest, longest / median))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_longest_of_the_window_against_its_median() {
        let mut times = FrameTimes::default();
        assert_eq!(times.longest(), None);
        times.push(90.0);
        for _ in 0..WINDOW - 1 {
            times.push(10.0);
        }
        assert_eq!(times.longest(), Some((90.0, 9.0)));
        // The hitch leaves the window.
        times.push(20.0);
        assert_eq!(times.longest(), Some((20.0, 2.0)));
    }
}
