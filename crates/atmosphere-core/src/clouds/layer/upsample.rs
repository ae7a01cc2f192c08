//! The reduced-resolution march: one view ray per block of `divisor` x `divisor` pixels,
//! brought to full size by bilinear interpolation. A W x H image is marched at
//! w x h = ceil(W / divisor) x ceil(H / divisor); the reduced pixel (i, j) marches the
//! full image's ray through the fractional pixel coordinate
//!     x = (i + 0.5) W / w - 0.5,   y = (j + 0.5) H / h - 0.5
//! (pixel x's centre at x), and the full pixel (x, y) reads the reduced image
//! bilinearly at u = (x + 0.5) w / W - 0.5, v = (y + 0.5) h / H - 0.5, clamped to the
//! image: the two maps are each other's inverse, so every marched ray lands where it
//! was marched. Images are row-major, rows from the top, [radiance x 3, transmittance]
//! per pixel.

/// The reduced image's size for a `width` x `height` image marched at `divisor`.
pub fn reduced_size(width: u32, height: u32, divisor: u32) -> (u32, u32) {
    (width.div_ceil(divisor), height.div_ceil(divisor))
}

/// The full image's fractional pixel coordinate marched by reduced pixel `index` of
/// `reduced` along an axis of `full` pixels.
pub fn marched_coordinate(index: u32, reduced: u32, full: u32) -> f64 {
    (f64::from(index) + 0.5) * f64::from(full) / f64::from(reduced) - 0.5
}

/// The two reduced pixels that full pixel `x` of an axis of `full` pixels reads from an
/// axis of `reduced` pixels, and the weight of the second.
pub fn axis_taps(x: u32, full: u32, reduced: u32) -> (u32, u32, f64) {
    let u = ((f64::from(x) + 0.5) * f64::from(reduced) / f64::from(full) - 0.5)
        .clamp(0.0, f64::from(reduced - 1));
    let i0 = u.floor() as u32;
    (i0, (i0 + 1).min(reduced - 1), u - f64::from(i0))
}

/// The four reduced pixels (row-major indices into an image of `reduced` size) that full
/// pixel (x, y) of a `full`-sized image reads, and their bilinear weights.
pub fn bilinear_taps(
    full: (u32, u32),
    reduced: (u32, u32),
    (x, y): (u32, u32),
) -> [(usize, f64); 4] {
    let (i0, i1, fx) = axis_taps(x, full.0, reduced.0);
    let (j0, j1, fy) = axis_taps(y, full.1, reduced.1);
    let at = |i: u32, j: u32| (j * reduced.0 + i) as usize;
    [
        (at(i0, j0), (1.0 - fx) * (1.0 - fy)),
        (at(i1, j0), fx * (1.0 - fy)),
        (at(i0, j1), (1.0 - fx) * fy),
        (at(i1, j1), fx * fy),
    ]
}

/// The full pixel nearest to the fractional pixel coordinate `x` on an axis of `full`
/// pixels: where a reduced ray reads the frame's surface.
pub fn nearest_pixel(x: f64, full: u32) -> u32 {
    (x + 0.5).floor().clamp(0.0, f64::from(full - 1)) as u32
}

/// The full `width` x `height` image from the reduced image `low` of `low_size`.
pub fn upsample(low: &[[f64; 4]], low_size: (u32, u32), width: u32, height: u32) -> Vec<[f64; 4]> {
    let (lw, lh) = low_size;
    let taps = axis_taps;
    let mut image = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        let (j0, j1, fy) = taps(y, height, lh);
        for x in 0..width {
            let (i0, i1, fx) = taps(x, width, lw);
            let at = |i: u32, j: u32| low[(j * lw + i) as usize];
            let (a, b, c, d) = (at(i0, j0), at(i1, j0), at(i0, j1), at(i1, j1));
            image.push(std::array::from_fn(|k| {
                let top = a[k] + (b[k] - a[k]) * fx;
                let bottom = c[k] + (d[k] - c[k]) * fx;
                top + (bottom - top) * fy
            }));
        }
    }
    image
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_marched_coordinates_are_read_back_where_they_were_marched() {
        let (w, h) = reduced_size(65, 36, 2);
        assert_eq!((w, h), (33, 18));
        // A reduced image linear in x and y is reproduced exactly inside the hull of
        // the marched coordinates.
        let low: Vec<[f64; 4]> = (0..h)
            .flat_map(|j| {
                (0..w).map(move |i| {
                    let x = marched_coordinate(i, w, 65);
                    let y = marched_coordinate(j, h, 36);
                    [x, y, 2.0 * x - y, 1.0]
                })
            })
            .collect();
        let full = upsample(&low, (w, h), 65, 36);
        for y in 1..35 {
            for x in 1..63 {
                let p = full[(y * 65 + x) as usize];
                assert!((p[0] - f64::from(x)).abs() < 1e-9, "{x} {y} {p:?}");
                assert!((p[1] - f64::from(y)).abs() < 1e-9, "{x} {y} {p:?}");
                assert_eq!(p[3], 1.0);
            }
        }
        // Divisor 1 is the identity.
        assert_eq!(upsample(&low, (w, h), w, h), low);
    }
}
