//! The cloud's shadow in the air (`air_shadow.rs`) at a reduced resolution, brought to
//! full size without smearing it across the edge of the frame's surface: one view ray per
//! block of `divisor` x `divisor` pixels on `upsample.rs`'s grid (ended on the surface its
//! nearest full pixel shows), each keeping the far end t1 of the span below the layer's
//! base it marched. A full pixel whose ray has no such span loses nothing; otherwise it
//! takes the bilinear taps whose span ends as far as its own, to within
//! [`SPAN_TOLERANCE`] of it,
//!     |t1_tap - t1| <= SPAN_TOLERANCE t1,
//! their bilinear weights renormalised; where those weights sum to less than
//! [`MIN_SAME_WEIGHT`] (a mountain's edge, the rim where rays stop dipping below the
//! base) the pixel is marched itself. The beams vary slowly across the screen (their
//! edges are the sun map's cells, seen from afar), and the loss grows smoothly with the
//! span's end, so the taps of the same span stand for the pixel.

use super::upsample::bilinear_taps;

/// How far the span's end of a tap may lie from a pixel's, relative to the pixel's.
pub const SPAN_TOLERANCE: f64 = 0.25;
/// The least bilinear weight of matching taps for a pixel to be interpolated: half, so
/// that no pixel takes its loss from a single tap of a lesser weight (at a quarter those
/// pixels, a dotted row along the base's rim, carried most of the upsample's error:
/// docs/clouds.md, "At a reduced resolution").
pub const MIN_SAME_WEIGHT: f64 = 0.5;

/// The far end of a ray's span below the base, m (distance from its segment's start);
/// `None`: the ray does not dip below the base within the map.
pub type SpanEnd = Option<f64>;

/// The reduced march: the single scattering lost per unit solar irradiance at three
/// wavelengths and the span's end of each reduced pixel, row-major, of `size`.
#[derive(Clone, Copy, Debug)]
pub struct ReducedAirShadow<'a> {
    pub loss: &'a [[f64; 3]],
    pub span_ends: &'a [SpanEnd],
    pub size: (u32, u32),
}

/// Whether a tap whose span ends at `tap` may stand for a pixel whose span ends at `end`.
pub fn same_span(end: f64, tap: SpanEnd) -> bool {
    tap.is_some_and(|t| (t - end).abs() <= SPAN_TOLERANCE * end)
}

/// What full pixel (x, y) of a `width` x `height` frame, whose span ends at `end`, takes
/// from `reduced`: the interpolated loss, or `None` when it is to be marched itself.
pub fn interpolate(
    reduced: &ReducedAirShadow<'_>,
    (width, height): (u32, u32),
    (x, y): (u32, u32),
    end: f64,
) -> Option<[f64; 3]> {
    let mut sum = [0.0; 3];
    let mut weight = 0.0;
    for (k, w) in bilinear_taps((width, height), reduced.size, (x, y)) {
        if w > 0.0 && same_span(end, reduced.span_ends[k]) {
            weight += w;
            for (s, v) in sum.iter_mut().zip(reduced.loss[k]) {
                *s += w * v;
            }
        }
    }
    (weight >= MIN_SAME_WEIGHT).then(|| sum.map(|s| s / weight))
}

/// The full pixel's loss: nothing where its `span_end` is `None`, interpolated from
/// `reduced` where taps match, else `march()`.
pub fn upsampled_loss(
    reduced: &ReducedAirShadow<'_>,
    size: (u32, u32),
    pixel: (u32, u32),
    span_end: SpanEnd,
    march: impl FnOnce() -> [f64; 3],
) -> [f64; 3] {
    match span_end {
        None => [0.0; 3],
        Some(end) => interpolate(reduced, size, pixel, end).unwrap_or_else(march),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pixel_takes_only_taps_of_its_own_span_and_is_marched_without_any() {
        // Reduced 2 x 1 image for a 6 x 1 frame: the left ray ended 2 km away on a
        // mountain, the right one ran below the base to 40 km.
        let loss = [[1.0; 3], [3.0; 3]];
        let span_ends = [Some(2_000.0), Some(40_000.0)];
        let reduced = ReducedAirShadow {
            loss: &loss,
            span_ends: &span_ends,
            size: (2, 1),
        };
        let marched = [9.0; 3];
        let at = |x: u32, end: SpanEnd| upsampled_loss(&reduced, (6, 1), (x, 0), end, || marched);
        let close = |a: [f64; 3], b: f64| a.iter().all(|v| (v - b).abs() < 1e-12);
        // Between the two taps (x = 2: weights 2/3 and 1/3), a pixel on the mountain
        // takes the left tap alone, one seeing far (x = 3) the right tap alone.
        assert!(close(at(2, Some(2_100.0)), 1.0));
        assert!(close(at(3, Some(38_000.0)), 3.0));
        // Both taps' spans match a pixel between them: the bilinear mean.
        let both = ReducedAirShadow {
            span_ends: &[Some(30_000.0), Some(34_000.0)],
            ..reduced
        };
        let mean = upsampled_loss(&both, (6, 1), (2, 0), Some(32_000.0), || marched);
        assert!(close(mean, 2.0 / 3.0 + 3.0 / 3.0), "{mean:?}");
        // No tap of its span (a pixel at 10 km): marched; no span: nothing lost.
        assert_eq!(at(2, Some(10_000.0)), marched);
        assert_eq!(at(2, None), [0.0; 3]);
        // The only matching tap without weight (the right one at x = 1): marched.
        assert_eq!(at(1, Some(40_000.0)), marched);
    }
}
