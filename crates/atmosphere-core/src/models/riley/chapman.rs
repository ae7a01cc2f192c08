//! Columns of an exponential species on the sphere in closed form: the Chapman function in
//! its parabolic (large r / H) form, for the spherical geometry of the riley model
//! ([`super::settings::RileySettings::sphere`]).
//!
//! Along a ray from radius r with direction cosine mu, the height above the ground is
//! h + mu s + s^2 / (2 r) to second order in s / r, so the column of exp(-h / H) to infinity
//! is sqrt(pi r H / 2) exp(-h / H) erfcx(mu sqrt(r / (2 H))) (Chapman 1931; the
//! approximation's error is about H / r relative, 1.3e-3 for air at H = 8 km). A ray going
//! down (mu < 0) passes its perigee at radius r sqrt(1 - mu^2): twice the level column from
//! there, less the column from the point the other way.

use std::f64::consts::PI;

/// erfcx(z) = exp(z^2) erfc(z) for z >= 0, without overflow: the Chebyshev fit of
/// Press et al., Numerical Recipes (2nd ed., section 6.2, `erfcc`), whose fractional error
/// is below 1.2e-7 everywhere.
pub fn erfcx(z: f64) -> f64 {
    let t = 1.0 / (1.0 + 0.5 * z.max(0.0));
    let poly = -1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    t * poly.exp()
}

/// Column (m) of the relative density exp(-h / H) from height `height_m` (radius
/// `bottom_m + height_m`) to infinity along a direction of cosine `mu >= 0` to the zenith.
pub fn column_upwards(height_m: f64, mu: f64, scale_height_m: f64, bottom_m: f64) -> f64 {
    let r = bottom_m + height_m;
    let x = r / scale_height_m;
    scale_height_m
        * (0.5 * PI * x).sqrt()
        * (-height_m / scale_height_m).exp()
        * erfcx(mu.max(0.0) * (0.5 * x).sqrt())
}

/// Height (m) of the perigee of a ray from height `height_m` with direction cosine `mu`,
/// r sqrt(1 - mu^2) - bottom written without the difference of two radii.
pub fn perigee_height_m(height_m: f64, mu: f64, bottom_m: f64) -> f64 {
    let r = bottom_m + height_m;
    // r sqrt(1 - mu^2) - R = (r^2 (1 - mu^2) - R^2) / (r sqrt(1 - mu^2) + R).
    let r_perigee = r * ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
    (height_m * (r + bottom_m) - (r * mu) * (r * mu)) / (r_perigee + bottom_m)
}

/// Column (m) of exp(-h / H) from height `height_m` to infinity along direction cosine `mu`
/// (any sign). A ray whose perigee lies below the ground is taken as grazing it (the
/// callers only ask for rays that miss the ground, up to rounding).
pub fn column_to_space(height_m: f64, mu: f64, scale_height_m: f64, bottom_m: f64) -> f64 {
    if mu >= 0.0 {
        return column_upwards(height_m, mu, scale_height_m, bottom_m);
    }
    let perigee = perigee_height_m(height_m, mu, bottom_m).max(0.0);
    2.0 * column_upwards(perigee, 0.0, scale_height_m, bottom_m)
        - column_upwards(height_m, -mu, scale_height_m, bottom_m)
}

/// Column (m) of exp(-h / H) from height `height_m` along direction cosine `mu` to where
/// the ray leaves the atmosphere's top at height `top_m` (the ray must miss the ground):
/// [`column_to_space`] less the column beyond the top, so that a layer fitted by an
/// exponential (ozone) has none above it. The ray leaves the top with cosine
/// sqrt(r_top^2 - r_p^2) / r_top, r_p its perigee's radius.
pub fn column_to_top(
    height_m: f64,
    mu: f64,
    scale_height_m: f64,
    bottom_m: f64,
    top_m: f64,
) -> f64 {
    let r = bottom_m + height_m;
    let r_top = bottom_m + top_m;
    // r_p^2 - R^2 and r_top^2 - R^2, without differences of squared radii.
    let q_perigee = height_m * (r + bottom_m) - (r * mu) * (r * mu);
    let q_top = top_m * (r_top + bottom_m);
    let mu_exit = (q_top - q_perigee).max(0.0).sqrt() / r_top;
    let beyond = column_upwards(top_m, mu_exit, scale_height_m, bottom_m);
    (column_to_space(height_m, mu, scale_height_m, bottom_m) - beyond).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The column by a midpoint sum along the straight ray.
    fn column_by_quadrature(height_m: f64, mu: f64, scale_height_m: f64, bottom_m: f64) -> f64 {
        let r = bottom_m + height_m;
        let length = 4.0e6;
        let n = 400_000;
        let ds = length / n as f64;
        (0..n)
            .map(|i| {
                let s = (i as f64 + 0.5) * ds;
                let radius = (r * r + 2.0 * r * mu * s + s * s).sqrt();
                (-(radius - bottom_m) / scale_height_m).exp() * ds
            })
            .sum()
    }

    #[test]
    fn erfcx_matches_its_values_and_asymptote() {
        // erfc(0) = 1, erfc(1) = 0.157299207050285, erfcx(z) ~ 1 / (z sqrt(pi)).
        assert!((erfcx(0.0) - 1.0).abs() < 2e-7);
        assert!((erfcx(1.0) / (0.157_299_207_050_285 * 1f64.exp()) - 1.0).abs() < 2e-7);
        let z = 1e4;
        assert!((erfcx(z) * z * PI.sqrt() - 1.0).abs() < 2e-7);
    }

    /// Against quadrature within H / r (the parabolic form's error), up, level and down
    /// past the perigee, for air, aerosol and the ozone fit's scale heights.
    #[test]
    fn columns_match_quadrature_within_the_scale_height_over_the_radius() {
        let bottom = 6.36e6;
        for h_scale in [1200.0, 8000.0, 25_000.0] {
            for height in [0.0, 20_000.0, 60_000.0] {
                for mu in [1.0, 0.5, 0.1, 0.0, -0.05] {
                    if perigee_height_m(height, mu, bottom) < 0.0 {
                        continue;
                    }
                    let want = column_by_quadrature(height, mu, h_scale, bottom);
                    let got = column_to_space(height, mu, h_scale, bottom);
                    let bound = 1.1 * h_scale / bottom;
                    assert!(
                        (got / want - 1.0).abs() < bound,
                        "H {h_scale} h {height} mu {mu}: {got} vs {want}"
                    );
                }
            }
        }
    }

    /// Up to the top: quadrature truncated there, and nothing from the top itself.
    #[test]
    fn columns_to_the_top_leave_out_what_lies_above_it() {
        let (bottom, top) = (6.36e6, 60_000.0);
        let h_scale = 25_000.0;
        for (height, mu) in [(0.0, 1.0), (20_000.0, 0.3), (30_000.0, -0.05)] {
            let r = bottom + height;
            let n = 400_000;
            let ds = 4.0e6 / n as f64;
            let want: f64 = (0..n)
                .map(|i| {
                    let s = (i as f64 + 0.5) * ds;
                    let radius = (r * r + 2.0 * r * mu * s + s * s).sqrt();
                    if radius - bottom < top {
                        (-(radius - bottom) / h_scale).exp() * ds
                    } else {
                        0.0
                    }
                })
                .sum();
            let got = column_to_top(height, mu, h_scale, bottom, top);
            assert!(
                (got / want - 1.0).abs() < 5e-3,
                "{height} {mu}: {got} vs {want}"
            );
        }
        assert_eq!(column_to_top(top, 0.5, h_scale, bottom, top), 0.0);
    }

    #[test]
    fn perigee_height_is_exact_for_a_level_ray_and_continuous_below() {
        let bottom = 6.36e6;
        assert_eq!(perigee_height_m(1000.0, 0.0, bottom), 1000.0);
        let mu: f64 = -0.01;
        let r = bottom + 1000.0;
        let direct = r * (1.0 - mu * mu).sqrt() - bottom;
        assert!((perigee_height_m(1000.0, mu, bottom) - direct).abs() < 1e-6);
    }
}
