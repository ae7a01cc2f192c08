//! The camera's orientation between keyframes: squad (Shoemake 1987, "Quaternion calculus
//! and fast animation", SIGGRAPH course notes) through the keyframes' rotations in the
//! local frame of the camera's place, so a camera flying round the planet keeps its
//! horizon; consecutive rotations are put in one hemisphere so it takes the short way.

use glam::DQuat;

/// The squad spline through unit quaternions.
#[derive(Clone, Debug)]
pub struct OrientationSpline {
    keys: Vec<DQuat>,
    inner: Vec<DQuat>,
}

impl OrientationSpline {
    /// The spline through `rotations` (one per keyframe).
    pub fn new(rotations: &[DQuat]) -> OrientationSpline {
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
        let inner = (0..n)
            .map(|i| {
                if i == 0 || i + 1 == n {
                    return keys[i];
                }
                let q = keys[i];
                let to_next = (q.inverse() * keys[i + 1]).to_scaled_axis();
                let to_before = (q.inverse() * keys[i - 1]).to_scaled_axis();
                (q * DQuat::from_scaled_axis(-(to_next + to_before) / 4.0)).normalize()
            })
            .collect();
        OrientationSpline { keys, inner }
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
        let inner = self.inner[i].slerp(self.inner[i + 1], h);
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
        let s = OrientationSpline::new(&keys);
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
    }
}
