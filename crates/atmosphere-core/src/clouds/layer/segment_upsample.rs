//! The reduced-resolution march of a frame, brought to full size without smearing a
//! cloud across the edge of the frame's surface. Each marched ray keeps the segment
//! [t0, t1] of the layer it marched (ended on the surface its nearest full pixel shows).
//! A full pixel whose ray meets no cloud segment is clear; otherwise it takes the
//! bilinear taps of `upsample.rs` whose segment is the same as its own, to within
//! [`SEGMENT_TOLERANCE`] of its own end distance or a length whose optical depth at the
//! layer's densest is [`DEPTH_TOLERANCE`] (segments of almost no cloud, such as rays
//! that leave the layer's top at once, all match),
//!     |t0_tap - t0| + |t1_tap - t1| <= SEGMENT_TOLERANCE t1 + DEPTH_TOLERANCE / sigma_max,
//! their bilinear weights renormalised; where those weights sum to less than
//! [`MIN_SAME_WEIGHT`] (a mountain's edge in front of or inside the cloud, the layer's
//! rim) the pixel is marched itself. So the upsample interpolates only between rays that
//! crossed the same stretch of cloud, and a pixel on a mountain in front of a cloud
//! stays as clear as the mountain.

use super::upsample::bilinear_taps;

/// How far the segments of a tap and a pixel may differ, relative to the pixel's end.
pub const SEGMENT_TOLERANCE: f64 = 0.25;
/// The optical depth at the densest below which segments differ by too little cloud to
/// matter.
pub const DEPTH_TOLERANCE: f64 = 0.1;
/// The least bilinear weight of matching taps for a pixel to be interpolated.
pub const MIN_SAME_WEIGHT: f64 = 0.25;

/// A ray's segment of the layer, (t0, t1) in m with t1 > t0 >= 0; `None`: no cloud.
pub type Segment = Option<(f64, f64)>;

/// Whether a tap that marched `tap` may stand for a pixel whose segment is `pixel`, in a
/// layer whose densest extinction is `extinction_per_m`.
pub fn same_segment(pixel: (f64, f64), tap: Segment, extinction_per_m: f64) -> bool {
    let allowed = SEGMENT_TOLERANCE * pixel.1 + DEPTH_TOLERANCE / extinction_per_m;
    tap.is_some_and(|(t0, t1)| (t0 - pixel.0).abs() + (t1 - pixel.1).abs() <= allowed)
}

/// The reduced march: [radiance x 3, transmittance] and the segment of each reduced
/// pixel, row-major, of `size`, through a layer whose densest extinction is
/// `extinction_per_m`.
#[derive(Clone, Copy, Debug)]
pub struct ReducedMarch<'a> {
    pub image: &'a [[f64; 4]],
    pub segments: &'a [Segment],
    pub size: (u32, u32),
    pub extinction_per_m: f64,
}

/// What full pixel (x, y), whose segment is `segment`, takes from `reduced`: the
/// interpolated cloud, or `None` when it is to be marched itself.
pub fn interpolate(
    reduced: &ReducedMarch<'_>,
    (width, height): (u32, u32),
    (x, y): (u32, u32),
    segment: (f64, f64),
) -> Option<[f64; 4]> {
    let mut sum = [0.0; 4];
    let mut weight = 0.0;
    for (k, w) in bilinear_taps((width, height), reduced.size, (x, y)) {
        if w > 0.0 && same_segment(segment, reduced.segments[k], reduced.extinction_per_m) {
            weight += w;
            for (s, v) in sum.iter_mut().zip(reduced.image[k]) {
                *s += w * v;
            }
        }
    }
    (weight >= MIN_SAME_WEIGHT).then(|| sum.map(|s| s / weight))
}

/// The full `width` x `height` image: clear where `segments` (the full pixels', row-major)
/// is `None`, interpolated from `reduced` where taps match, and `march(x, y, segment)`
/// where none do.
pub fn upsample_by_segment(
    reduced: &ReducedMarch<'_>,
    (width, height): (u32, u32),
    segments: &[Segment],
    mut march: impl FnMut(u32, u32, (f64, f64)) -> [f64; 4],
) -> Vec<[f64; 4]> {
    let mut image = Vec::with_capacity(segments.len());
    for y in 0..height {
        for x in 0..width {
            image.push(match segments[(y * width + x) as usize] {
                None => [0.0, 0.0, 0.0, 1.0],
                Some(s) => interpolate(reduced, (width, height), (x, y), s)
                    .unwrap_or_else(|| march(x, y, s)),
            });
        }
    }
    image
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assert_close(a: [f64; 4], b: [f64; 4]) {
        assert!(
            a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12),
            "{a:?} {b:?}"
        );
    }

    #[test]
    fn a_pixel_takes_only_taps_of_its_own_segment_and_is_marched_without_any() {
        // Reduced 2 x 1 image for a 6 x 1 frame: the left ray ended 2 km away on a
        // mountain inside the layer, the right one crossed the layer to 10 km.
        let image = [[1.0, 1.0, 1.0, 0.5], [3.0, 3.0, 3.0, 0.1]];
        let segments = [Some((1_000.0, 2_000.0)), Some((1_000.0, 10_000.0))];
        let reduced = ReducedMarch {
            image: &image,
            segments: &segments,
            size: (2, 1),
            extinction_per_m: 1e-3,
        };
        let full = [
            Some((1_000.0, 2_000.0)),
            Some((1_000.0, 2_000.0)),
            Some((1_000.0, 2_100.0)),
            Some((1_000.0, 10_500.0)),
            None,
            Some((1_000.0, 30_000.0)),
        ];
        let mut marched = Vec::new();
        let out = upsample_by_segment(&reduced, (6, 1), &full, |x, _, _| {
            marched.push(x);
            [9.0, 9.0, 9.0, 0.0]
        });
        // Pixels 0-2 on the mountain keep its ray alone, pixel 3 the far one alone
        // (a plain bilinear read would mix both), pixel 4 is clear, pixel 5's segment
        // matches neither and is marched.
        assert_close(out[0], image[0]);
        assert_close(out[2], image[0]);
        assert_close(out[3], image[1]);
        assert_eq!(out[4], [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(out[5], [9.0, 9.0, 9.0, 0.0]);
        assert_eq!(marched, vec![5]);
        // Rays that leave the layer's top at once: 1 m against 3 m of cloud matches
        // where that is an optical depth below 0.1, not in a cloud 25 times denser.
        assert!(same_segment((0.0, 1.0), Some((0.0, 3.0)), 0.04));
        assert!(!same_segment((0.0, 1.0), Some((0.0, 3.0)), 1.0));
        assert!(!same_segment((0.0, 1.0), None, 0.04));
        // Equal segments everywhere give upsample.rs's bilinear image.
        let same = [Some((1_000.0, 10_000.0)); 6];
        let reduced = ReducedMarch {
            segments: &[Some((1_000.0, 10_000.0)); 2],
            ..reduced
        };
        let out = upsample_by_segment(&reduced, (6, 1), &same, |x, _, _| {
            panic!("pixel {x} marched")
        });
        let bilinear = super::super::upsample::upsample(&image, (2, 1), 6, 1);
        for (a, b) in out.into_iter().zip(bilinear) {
            assert_close(a, b);
        }
    }
}
