//! The sun as a disk where it meets the horizon: the part of a uniform disk of angular
//! radius alpha above the geometric horizon, dimmed along the path of that part's
//! centroid. The paper treats the sun as a point, which switches on and off at the
//! horizon; the reference integrates the disk.

use crate::atmosphere::Atmosphere;
use crate::optics::geometry::horizon_mu;

/// Whether tables built for `old` must be rebuilt for `new` because of the sun: with
/// `sun_disk` the sun's transmittance in single scattering and in the ground's direct
/// light (hence every order and the irradiance) depends on the disk's angular radius; a
/// point sun's tables depend on nothing of the sun.
pub fn disk_changed(sun_disk: bool, old: &Atmosphere, new: &Atmosphere) -> bool {
    sun_disk && old.sun.angular_radius_rad != new.sun.angular_radius_rad
}

/// The visible part of the sun seen from radius r with its centre at zenith cosine mu_s:
/// (fraction of the disk above the horizon, zenith cosine of that part's centroid), or
/// `None` when all of it is below. With the centre a height y (in disk radii) above the
/// horizon, the visible segment above c = -y has area (acos c - c sqrt(1 - c^2)) / pi
/// of the disk and its centroid lies (2/3) (1 - c^2)^(3/2) / (acos c - c sqrt(1 - c^2))
/// radii above the centre.
pub fn visible_sun(
    r: f64,
    mu_s: f64,
    bottom_m: f64,
    angular_radius_rad: f64,
) -> Option<(f64, f64)> {
    let theta_s = mu_s.clamp(-1.0, 1.0).acos();
    let theta_h = horizon_mu(r, bottom_m).acos();
    let height = (theta_h - theta_s) / angular_radius_rad;
    if height >= 1.0 {
        return Some((1.0, mu_s));
    }
    if height <= -1.0 || height.is_nan() {
        return None;
    }
    let c = -height;
    let s = (1.0 - c * c).sqrt();
    let segment = c.acos() - c * s;
    if segment <= 0.0 {
        return None;
    }
    let centroid = 2.0 / 3.0 * s * s * s / segment;
    let mu = (theta_s - centroid * angular_radius_rad).cos();
    Some((segment / std::f64::consts::PI, mu))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Half the disk is visible when its centre is on the horizon, all of it one radius
    /// above, none one radius below; the fraction matches a count of points of the disk.
    #[test]
    fn the_visible_fraction_is_the_area_of_the_disk_above_the_horizon() {
        let (rg, r, a) = (6_360_000.0, 6_370_000.0, 0.004675);
        let theta_h = horizon_mu(r, rg).acos();
        let at = |height: f64| visible_sun(r, (theta_h - height * a).cos(), rg, a);
        let (half, mu_half) = at(0.0).unwrap();
        assert!((half - 0.5).abs() < 1e-9, "{half}");
        assert!(mu_half > horizon_mu(r, rg));
        assert_eq!(at(1.0001).unwrap().0, 1.0);
        assert!(at(-1.0001).is_none());
        for height in [-0.7, -0.2, 0.3, 0.8] {
            let n = 2000;
            let (mut inside, mut visible, mut sum) = (0, 0, 0.0);
            for i in 0..n {
                for j in 0..n {
                    let x = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
                    let y = -1.0 + 2.0 * (j as f64 + 0.5) / n as f64;
                    if x * x + y * y < 1.0 {
                        inside += 1;
                        if y > -height {
                            visible += 1;
                            sum += y;
                        }
                    }
                }
            }
            let (fraction, mu) = at(height).unwrap();
            let expected = visible as f64 / inside as f64;
            assert!(
                (fraction - expected).abs() < 1e-3,
                "{height}: {fraction} {expected}"
            );
            let centroid = (theta_h - height * a - mu.acos()) / a;
            let expected_centroid = sum / visible as f64;
            assert!(
                (centroid - expected_centroid).abs() < 2e-3,
                "{height}: {centroid} {expected_centroid}"
            );
        }
    }
}
