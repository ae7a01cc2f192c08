//! Equirectangular grids addressed by latitude and longitude, and the planet-fixed frame's
//! directions.
//!
//! A grid of `width x height` texels covers the sphere north up, its first column starting
//! at 180 deg west: texel (i, j) is centred on longitude `-180 + (i + 0.5) 360 / width`
//! and latitude `90 - (j + 0.5) 180 / height` (degrees). Bilinear sampling wraps in
//! longitude and clamps in latitude (the rows nearest the poles are held constant beyond
//! their centres), as a GPU sampler with repeat in u and clamp-to-edge in v does.
//!
//! Frame: x towards latitude 0 longitude 0, y towards latitude 0 longitude 90 deg east,
//! z towards the north pole (the terrain's cube sphere and [`crate::sun_position`] use it).

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use glam::DVec3;

/// Latitude and longitude (radians, longitude east positive in (-pi, pi]) of a direction
/// (need not be unit).
pub fn lat_lon(direction: DVec3) -> (f64, f64) {
    let horizontal = direction.x.hypot(direction.y);
    (
        direction.z.atan2(horizontal),
        direction.y.atan2(direction.x),
    )
}

/// The unit direction of a latitude and longitude (radians).
pub fn direction(lat_rad: f64, lon_rad: f64) -> DVec3 {
    let (sin_lat, cos_lat) = lat_rad.sin_cos();
    let (sin_lon, cos_lon) = lon_rad.sin_cos();
    DVec3::new(cos_lat * cos_lon, cos_lat * sin_lon, sin_lat)
}

/// Latitude and longitude (radians) of the centre of texel (i, j).
pub fn texel_centre(width: usize, height: usize, i: usize, j: usize) -> (f64, f64) {
    (
        FRAC_PI_2 - (j as f64 + 0.5) / height as f64 * PI,
        -PI + (i as f64 + 0.5) / width as f64 * TAU,
    )
}

/// The four texels around a point and their bilinear weights (summing to 1), as
/// `(index into a row-major texel array, weight)`.
pub fn bilinear_taps(width: usize, height: usize, lat_rad: f64, lon_rad: f64) -> [(usize, f64); 4] {
    // Continuous texel coordinates whose integers are texel centres.
    let x = (lon_rad + PI) / TAU * width as f64 - 0.5;
    let y = (FRAC_PI_2 - lat_rad) / PI * height as f64 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let fx = x - x0;
    let column = |k: f64| (k as i64).rem_euclid(width as i64) as usize;
    let (i0, i1) = (column(x0), column(x0 + 1.0));
    let last_row = height as f64 - 1.0;
    let (j0, j1, fy) = if y <= 0.0 {
        (0, 0, 0.0)
    } else if y >= last_row {
        (height - 1, height - 1, 0.0)
    } else {
        (y0 as usize, y0 as usize + 1, y - y0)
    };
    [
        (j0 * width + i0, (1.0 - fx) * (1.0 - fy)),
        (j0 * width + i1, fx * (1.0 - fy)),
        (j1 * width + i0, (1.0 - fx) * fy),
        (j1 * width + i1, fx * fy),
    ]
}

/// The quadratic B-spline's weights of texels -1, 0 and 1 around offset `t` in
/// [-0.5, 0.5] from texel 0's centre, summing to 1.
pub fn quadratic_bspline_weights(t: f64) -> [f64; 3] {
    [
        (0.5 - t).powi(2) / 2.0,
        0.75 - t * t,
        (0.5 + t).powi(2) / 2.0,
    ]
}

/// The nine texels around a point and their quadratic B-spline weights (summing to 1),
/// as [`bilinear_taps`] gives its four: a read whose value and slope are continuous
/// everywhere, where a bilinear read has creases (its slope jumps) along the lines
/// between texel centres. Columns wrap around the planet; rows past the poles repeat
/// the first and last.
pub fn bspline_taps(width: usize, height: usize, lat_rad: f64, lon_rad: f64) -> [(usize, f64); 9] {
    let x = (lon_rad + PI) / TAU * width as f64 - 0.5;
    let y = (FRAC_PI_2 - lat_rad) / PI * height as f64 - 0.5;
    let (x0, y0) = (x.round(), y.round());
    let (wx, wy) = (
        quadratic_bspline_weights(x - x0),
        quadratic_bspline_weights(y - y0),
    );
    let mut taps = [(0, 0.0); 9];
    for (b, &weight_y) in wy.iter().enumerate() {
        let row = (y0 as i64 - 1 + b as i64).clamp(0, height as i64 - 1) as usize;
        for (a, &weight_x) in wx.iter().enumerate() {
            let column = (x0 as i64 - 1 + a as i64).rem_euclid(width as i64) as usize;
            taps[3 * b + a] = (row * width + column, weight_x * weight_y);
        }
    }
    taps
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A row-major field over a `width` x `height` grid, read at (lat, lon) by `taps`.
    fn read(taps: &[(usize, f64)], field: &[f64]) -> f64 {
        taps.iter().map(|&(n, w)| w * field[n]).sum()
    }

    #[test]
    fn the_bspline_read_keeps_linear_fields_and_has_no_creases() {
        let (width, height) = (64, 32);
        // Linear in the column away from the seam: the spline reproduces it exactly.
        let field: Vec<f64> = (0..width * height)
            .map(|n| 3.0 + 0.5 * (n % width) as f64)
            .collect();
        for t in [0.0f64, 0.1, 0.5, 0.93] {
            let weights = quadratic_bspline_weights(t - t.round());
            assert!((weights.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            let (_, lon) = texel_centre(width, height, 20, 10);
            let lon = lon + t * TAU / width as f64;
            let (lat, _) = texel_centre(width, height, 20, 10);
            let value = read(&bspline_taps(width, height, lat, lon), &field);
            assert!(
                (value - (3.0 + 0.5 * (20.0 + t))).abs() < 1e-12,
                "{t}: {value}"
            );
        }
        // One bright texel: the slope across the line through its centre (where a
        // bilinear read turns sharply) is continuous for the spline, and across the line
        // half-way to the next centre (where the spline's pieces meet).
        let mut spike = vec![0.0; width * height];
        spike[10 * width + 20] = 1.0;
        let (lat, centre) = texel_centre(width, height, 20, 10);
        let h = 1e-4 * TAU / width as f64;
        let slope = |taps: &dyn Fn(f64) -> f64, lon: f64| (taps(lon + h) - taps(lon)) / h;
        let spline = |lon: f64| read(&bspline_taps(width, height, lat, lon), &spike);
        let bilinear = |lon: f64| read(&bilinear_taps(width, height, lat, lon), &spike);
        // The slope just east of the centre less the slope just west of it.
        let jump =
            |f: &dyn Fn(f64) -> f64| (slope(f, centre + h) - slope(f, centre - 2.0 * h)).abs();
        let bilinear_jump = jump(&bilinear);
        assert!(
            bilinear_jump > 1.0,
            "the bilinear read's kink: {bilinear_jump}"
        );
        assert!(jump(&spline) < 1e-3 * bilinear_jump, "{}", jump(&spline));
        let half = 0.5 * TAU / width as f64;
        let jump_at =
            |f: &dyn Fn(f64) -> f64, at: f64| (slope(f, at + h) - slope(f, at - 2.0 * h)).abs();
        assert!(jump_at(&spline, centre + half) < 1e-3 * bilinear_jump);
    }

    #[test]
    fn lat_lon_round_trip_and_frame() {
        assert_eq!(direction(0.0, 0.0), DVec3::X);
        assert!((direction(0.0, FRAC_PI_2) - DVec3::Y).length() < 1e-15);
        assert!((direction(FRAC_PI_2, 0.0) - DVec3::Z).length() < 1e-15);
        for (lat, lon) in [(0.3, -2.0), (-1.2, 3.0), (1.5, 0.1), (0.0, -PI + 1e-9)] {
            let (lat2, lon2) = lat_lon(direction(lat, lon) * 7.0);
            assert!((lat2 - lat).abs() < 1e-14 && (lon2 - lon).abs() < 1e-14);
        }
    }

    #[test]
    fn taps_hit_texel_centres_wrap_and_clamp() {
        let (w, h) = (8, 4);
        // The centre of texel (2, 1): longitude -180 + 2.5 * 45, latitude 90 - 1.5 * 45.
        let taps = bilinear_taps(
            w,
            h,
            (90.0f64 - 67.5).to_radians(),
            (-180.0f64 + 112.5).to_radians(),
        );
        let best = taps.iter().max_by(|a, b| a.1.total_cmp(&b.1)).unwrap();
        assert_eq!(best.0, w + 2);
        assert!((best.1 - 1.0).abs() < 1e-12);
        // Halfway across the antimeridian: the first and last columns, half each.
        let taps = bilinear_taps(w, h, (90.0f64 - 67.5).to_radians(), PI);
        let mut columns: Vec<_> = taps
            .iter()
            .filter(|t| t.1 > 0.0)
            .map(|t| (t.0 % w, t.1))
            .collect();
        columns.sort_by_key(|c| c.0);
        assert_eq!(columns.len(), 2);
        assert_eq!((columns[0].0, columns[1].0), (0, w - 1));
        assert!((columns[0].1 - 0.5).abs() < 1e-12);
        // Beyond the first row's centre (near the pole) the first row is held.
        for t in bilinear_taps(w, h, 1.55, 0.3) {
            assert!(t.0 < w || t.1 == 0.0);
        }
        for lat in [-FRAC_PI_2, -0.7, 0.0, 0.9] {
            let sum: f64 = bilinear_taps(w, h, lat, 1.0).iter().map(|t| t.1).sum();
            assert!((sum - 1.0).abs() < 1e-12);
        }
    }
}
