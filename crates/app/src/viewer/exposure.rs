//! Exposure: manual (the panel's EV100) or automatic, from the rendered frame.
//!
//! Automatic exposure follows the meter (`exposure_meter`: the EV100 the frame's
//! log-average luminance asks for) exponentially with a time constant of
//! [`TIME_CONSTANT_S`] (`ev += (target - ev)(1 - exp(-dt / tau))`, the same for any frame
//! rate), starting at the first metering without delay, within [`AUTO_EV_RANGE`].

use serde::{Deserialize, Serialize};

pub use crate::exposure_meter::{AUTO_EV_RANGE, metered_ev100};

/// Time constant of the adaptation, seconds.
pub const TIME_CONSTANT_S: f64 = 0.5;

/// Changes of the EV100 smaller than this are not applied (each change re-renders).
pub const SETTLED_EV: f64 = 0.02;

/// How the exposure is chosen.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum ExposureMode {
    /// The panel's EV100.
    Manual,
    /// Metered from the frame.
    #[default]
    Auto,
}

/// The adaptation state; see the module documentation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AutoExposure {
    /// The adapted EV100 (none before the first metering).
    ev100: Option<f64>,
    /// The EV100 of the last metering.
    target: Option<f64>,
}

impl AutoExposure {
    /// Takes the last frame's log-average luminance, cd/m^2.
    pub fn meter(&mut self, luminance_cd_m2: f64) {
        let target = metered_ev100(luminance_cd_m2);
        self.target = Some(target);
        self.ev100.get_or_insert(target);
    }

    /// Adapts over `dt_s` seconds; the adapted EV100 (none before the first metering).
    pub fn step(&mut self, dt_s: f64) -> Option<f64> {
        if let (Some(ev), Some(target)) = (self.ev100.as_mut(), self.target) {
            *ev += (target - *ev) * (1.0 - (-dt_s.max(0.0) / TIME_CONSTANT_S).exp());
        }
        self.ev100
    }

    /// Whether the adapted EV100 is within [`SETTLED_EV`] of the metered one (nothing
    /// left to animate).
    pub fn settled(&self) -> bool {
        match (self.ev100, self.target) {
            (Some(ev), Some(target)) => (target - ev).abs() < SETTLED_EV,
            _ => true,
        }
    }

    /// Adapts over `dt_s` and writes the EV100 into `ev100` when it has moved by
    /// [`SETTLED_EV`] or more since it was last written; true while still adapting (the
    /// app should draw another frame).
    pub fn apply(&mut self, dt_s: f64, ev100: &mut f64) -> bool {
        if let Some(adapted) = self.step(dt_s)
            && (adapted - *ev100).abs() >= SETTLED_EV
        {
            *ev100 = adapted;
        }
        !self.settled()
    }

    /// Forgets the adaptation: the next metering applies at once (a jump of the view).
    pub fn reset(&mut self) {
        *self = AutoExposure::default();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a constant image the EV100 starts at the metered value; after a jump in
    /// brightness it covers 63 % of the way in one time constant, whatever the frame
    /// rate, and settles within a few.
    #[test]
    fn converges_on_a_constant_image() {
        for dt in [1.0 / 144.0, 1.0 / 60.0, 1.0 / 10.0] {
            let mut auto = AutoExposure::default();
            assert_eq!(auto.step(dt), None);
            assert!(auto.settled());
            auto.meter(100.0);
            let start = metered_ev100(100.0);
            assert_eq!(auto.step(dt), Some(start), "no delay at the first metering");
            assert!(auto.settled());
            // The view brightens 64 times: 6 EV.
            let mut t = 0.0;
            let mut ev = start;
            while t < TIME_CONSTANT_S - 1e-9 {
                auto.meter(6400.0);
                ev = auto.step(dt).unwrap();
                t += dt;
            }
            let covered = (ev - start) / 6.0;
            assert!((covered - (1.0 - (-t / TIME_CONSTANT_S).exp())).abs() < 1e-9);
            assert!((covered - 0.632).abs() < 0.1, "dt {dt}: {covered}");
            while t < 10.0 * TIME_CONSTANT_S {
                auto.meter(6400.0);
                ev = auto.step(dt).unwrap();
                t += dt;
            }
            assert!((ev - metered_ev100(6400.0)).abs() < 1e-3, "dt {dt}: {ev}");
            assert!(auto.settled());
        }
        let mut auto = AutoExposure::default();
        auto.meter(1.0);
        auto.reset();
        assert_eq!(auto.step(0.1), None);
    }

    /// The applied EV100 moves in steps of at least SETTLED_EV and ends within it of
    /// the metered one, and the app is asked for frames only until then.
    #[test]
    fn apply_writes_only_visible_changes() {
        let mut auto = AutoExposure::default();
        let mut ev100 = 14.0;
        assert!(!auto.apply(1.0 / 60.0, &mut ev100), "nothing metered yet");
        assert_eq!(ev100, 14.0);
        auto.meter(1000.0);
        let target = metered_ev100(1000.0);
        assert!(!auto.apply(1.0 / 60.0, &mut ev100));
        assert_eq!(ev100, target, "the first metering applies at once");
        auto.meter(10.0);
        let mut written = vec![ev100];
        let mut frames = 0;
        while auto.apply(1.0 / 60.0, &mut ev100) {
            if ev100 != *written.last().unwrap() {
                written.push(ev100);
            }
            frames += 1;
            assert!(frames < 600, "never settles");
        }
        assert!(
            written
                .windows(2)
                .all(|w| (w[1] - w[0]).abs() >= SETTLED_EV)
        );
        assert!(
            (ev100 - metered_ev100(10.0)).abs() < 2.0 * SETTLED_EV,
            "{ev100}"
        );
    }
}
