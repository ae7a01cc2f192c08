//! How rough the refined relief is where: an amplitude per data cell from the data's local
//! relief, and its smooth interpolation with the derivatives the refinement needs.
//!
//! A cell's amplitude is `gain` times the root-mean-square difference between its height
//! and its eight neighbours' (large in mountains, small on plains and abyssal plains),
//! with a lower gain below sea level (the sea floor stays smoother), a floor on land (no
//! plain is a mirror) and a cap; 0 in the two rows next to each pole, where the grid's
//! cells meet in a point. Between cells it is the uniform quadratic B-spline of these
//! control values (continuous with continuous first and mixed derivatives), so the detail
//! built from it (`refined_heights.rs`) is continuous.

use super::height_map::HeightMap;

/// The amplitude's gains, floor and cap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AmplitudeSettings {
    /// Amplitude per metre of RMS neighbour difference on land.
    pub land_gain: f64,
    /// The same below sea level.
    pub sea_gain: f64,
    /// The least amplitude on land, m.
    pub land_floor_m: f64,
    /// The largest amplitude, m.
    pub cap_m: f64,
}

/// An amplitude and its derivatives along the grid's columns (`s`) and rows (`t`), in
/// metres per data cell.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Amplitude {
    pub value: f64,
    pub ds: f64,
    pub dt: f64,
    pub dsdt: f64,
}

/// Control values on the data's grid.
#[derive(Clone, Debug)]
pub struct ReliefAmplitude {
    width: usize,
    height: usize,
    control_m: Vec<f32>,
}

impl ReliefAmplitude {
    /// The amplitudes of a height map's cells.
    pub fn new(data: &HeightMap, settings: &AmplitudeSettings) -> ReliefAmplitude {
        let (w, h) = (data.width, data.height);
        let at = |i: isize, j: usize| data.metres[j * w + i.rem_euclid(w as isize) as usize];
        let mut control_m = vec![0.0f32; w * h];
        for j in 2..h.saturating_sub(2) {
            for i in 0..w as isize {
                let centre = at(i, j) as f64;
                let mut sum = 0.0;
                for dj in [-1, 0, 1] {
                    for di in [-1, 0, 1] {
                        let d = at(i + di, j.wrapping_add_signed(dj)) as f64 - centre;
                        sum += d * d;
                    }
                }
                let rms = (sum / 8.0).sqrt();
                let amplitude = if centre >= 0.0 {
                    (settings.land_gain * rms).max(settings.land_floor_m)
                } else {
                    settings.sea_gain * rms
                };
                control_m[j * w + i as usize] = amplitude.min(settings.cap_m) as f32;
            }
        }
        ReliefAmplitude {
            width: w,
            height: h,
            control_m,
        }
    }

    /// The largest control value, m (a bound on the amplitude anywhere).
    pub fn max_m(&self) -> f64 {
        self.control_m.iter().fold(0.0f64, |m, &a| m.max(a as f64))
    }

    /// The control value of cell (i, j), m.
    pub fn control_m(&self, i: usize, j: usize) -> f64 {
        self.control_m[j * self.width + i] as f64
    }

    /// The amplitude at grid coordinates `(s, t)`: `s` in columns from 180 deg west
    /// (cell `i` spans `[i, i + 1]`), `t` in rows from the north pole.
    pub fn at(&self, s: f64, t: f64) -> Amplitude {
        let (w, h) = (self.width as isize, self.height as isize);
        let ci = s.floor();
        let cj = t.floor().clamp(0.0, (h - 1) as f64);
        let (ws, dws) = weights(s - ci);
        let (wt, dwt) = weights(t - cj);
        let (ci, cj) = (ci as isize, cj as isize);
        let mut a = Amplitude::default();
        for (m, (&wy, &dwy)) in wt.iter().zip(&dwt).enumerate() {
            let row = (cj + m as isize - 1).clamp(0, h - 1) as usize;
            for (n, (&wx, &dwx)) in ws.iter().zip(&dws).enumerate() {
                let column = (ci + n as isize - 1).rem_euclid(w) as usize;
                let c = self.control_m[row * self.width + column] as f64;
                a.value += wx * wy * c;
                a.ds += dwx * wy * c;
                a.dt += wx * dwy * c;
                a.dsdt += dwx * dwy * c;
            }
        }
        a
    }
}

/// The uniform quadratic B-spline's weights of the controls `k - 1, k, k + 1` at the
/// fraction `x` of cell `k`, and their derivatives.
fn weights(x: f64) -> ([f64; 3], [f64; 3]) {
    (
        [0.5 * (1.0 - x) * (1.0 - x), 0.5 + x - x * x, 0.5 * x * x],
        [x - 1.0, 1.0 - 2.0 * x, x],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const SETTINGS: AmplitudeSettings = AmplitudeSettings {
        land_gain: 1.0,
        sea_gain: 0.25,
        land_floor_m: 5.0,
        cap_m: 1000.0,
    };

    /// Rough where the heights vary, the floor on flat land, quieter below the sea, zero at
    /// the poles; the spline is continuous with its derivatives across cell borders.
    #[test]
    fn amplitude_follows_the_relief_and_is_smooth() {
        let (w, h) = (16, 8);
        let metres: Vec<f32> = (0..w * h)
            .map(|k| {
                let (i, j) = (k % w, k / w);
                match i {
                    0..4 => 100.0,
                    4..8 => -3000.0 + 100.0 * (i + j) as f32,
                    _ => 200.0 * ((i * 7 + j * 3) % 5) as f32,
                }
            })
            .collect();
        let amplitude = ReliefAmplitude::new(&HeightMap::from_metres(w, h, metres), &SETTINGS);
        assert_eq!(amplitude.control_m(1, 4), 5.0);
        let sea = amplitude.control_m(5, 4);
        assert!((sea - 0.25 * (12e4f64 / 8.0).sqrt()).abs() < 1e-3, "{sea}");
        assert!(amplitude.control_m(11, 4) > 200.0);
        for i in 0..w {
            for j in [0, 1, h - 2, h - 1] {
                assert_eq!(amplitude.control_m(i, j), 0.0);
            }
        }
        let e = 1e-9;
        for (s, t) in [(3.0, 4.5), (9.0, 3.0), (16.0, 5.2), (7.0, 2.0)] {
            let (below, above) = (amplitude.at(s - e, t - e), amplitude.at(s + e, t + e));
            assert!((below.value - above.value).abs() < 1e-5);
            assert!((below.ds - above.ds).abs() < 1e-5);
            assert!((below.dt - above.dt).abs() < 1e-5);
            assert!((below.dsdt - above.dsdt).abs() < 1e-5);
        }
        // Derivatives against differences.
        let h_ = 1e-6;
        let (s, t) = (10.3, 4.7);
        let a = amplitude.at(s, t);
        let ds = (amplitude.at(s + h_, t).value - amplitude.at(s - h_, t).value) / (2.0 * h_);
        let dsdt = (amplitude.at(s, t + h_).ds - amplitude.at(s, t - h_).ds) / (2.0 * h_);
        assert!((ds - a.ds).abs() < 1e-4 && (dsdt - a.dsdt).abs() < 1e-4);
    }
}
