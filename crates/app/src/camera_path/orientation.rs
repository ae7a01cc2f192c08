//! The camera's orientation between keyframes: squad (Shoemake 1987, "Quaternion calculus
//! and fast animation", SIGGRAPH course notes) through the keyframes' rotations in the
//! local frame of the camera's place, so a camera flying round the planet keeps its
//! horizon; consecutive rotations are put in one hemisphere so it takes the short way.
//! The inner points come from an angular velocity at each keyframe, the central difference
//! over the two neighbouring segments' times, so the turn keeps its rate across keyframes
//! however unevenly they are spaced.

use glam::DQuat;

/// The squad spline through unit quaternions.
#[derive(Clone, Debug)]
pub struct OrientationSpline {
    keys: Vec<DQuat>,
    /// The inner point of the segment leaving each keyframe, and of the one arriving.
    leaving: Vec<DQuat>,
    arriving: Vec<DQuat>,
}

impl OrientationSpline {
    /// The spline through `rotations` at `times` (strictly increasing, one per keyframe).
    pub fn new(times: &[f64], rotations: &[DQuat]) -> OrientationSpline {
        let mut keys: Vec<DQuat> = Vec::with_capacity(rotations.len());
        for &q in rotations {
            let q = q.normalize();
            let q = match keys.last() {
                Some(p) if p.dot(q) < 0.0 => -q,
                _ => q,
            };
            keys.push(q);
        }
        let n = keys.len();
        let (mut leaving, mut arriving) = (keys.clone(), keys.clone());
        for i in 1..n.saturating_sub(1) {
            let q = keys[i];
            // Rotation vectors (full angles) to the neighbours, and the segments' lengths.
            let to_next = (q.inverse() * keys[i + 1]).to_scaled_axis();
            let to_before = (q.inverse() * keys[i - 1]).to_scaled_axis();
            let (before_s, after_s) = (times[i] - times[i - 1], times[i + 1] - times[i]);
            let rate = (to_next - to_before) / (before_s + after_s);
            leaving[i] =
                (q * DQuat::from_scaled_axis((rate * after_s - to_next) / 2.0)).normalize();
            arriving[i] =
                (q * DQuat::from_scaled_axis(-(rate * before_s + to_before) / 2.0)).normalize();
        }
        OrientationSpline {
            keys,
            leaving,
            arriving,
        }
    }

    /// The rotation at fraction `h` of segment `i`: exactly the keyframe's at 0 and 1.
    pub fn at(&self, i: usize, h: f64) -> DQuat {
        if h <= 0.0 {
            return self.keys[i];
        }
        if h >= 1.0 {
            return self.keys[i + 1];
        }
        let outer = self.keys[i].slerp(self.keys[i + 1], h);
        let inner = self.leaving[i].slerp(self.arriving[i + 1], h);
        outer.slerp(inner, 2.0 * h * (1.0 - h)).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn keys_are_hit_and_the_curve_is_continuous() {
        let keys: Vec<DQuat> = [0.0, 90.0, 200.0, 210.0]
            .iter()
            .map(|&d: &f64| DQuat::from_axis_angle(DVec3::Z, d.to_radians()))
            .collect();
        let s = OrientationSpline::new(&[0.0, 1.0, 2.0, 5.0], &keys);
        for (i, k) in keys.iter().enumerate().take(3) {
            assert!(s.at(i, 0.0).dot(*k).abs() > 1.0 - 1e-12);
            assert!(s.at(i, 1.0).dot(keys[i + 1]).abs() > 1.0 - 1e-12);
            let mut last = s.at(i, 0.0);
            for step in 1..=200 {
                let q = s.at(i, step as f64 / 200.0);
                assert!(q.angle_between(last) < 0.05, "{i} {step}");
                last = q;
            }
        }
        // A steady turn over uneven keyframes keeps its rate.
        let times = [0.0, 4.0, 20.0, 36.0, 40.0];
        let keys: Vec<DQuat> = times
            .iter()
            .map(|&t: &f64| DQuat::from_axis_angle(DVec3::Z, (5.0 * t).to_radians()))
            .collect();
        let s = OrientationSpline::new(&times, &keys);
        for i in 0..4 {
            for step in 0..=20 {
                let h = step as f64 / 20.0;
                let t = times[i] + h * (times[i + 1] - times[i]);
                let expected = DQuat::from_axis_angle(DVec3::Z, (5.0 * t).to_radians());
                let off = s.at(i, h).angle_between(expected);
                assert!(off < 1e-6, "{t}: {off}");
            }
        }
    }
}
