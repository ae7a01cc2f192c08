//! The walk of the planes at reduced resolution, brought to the frame's size where it
//! can be interpolated and walked exactly where it cannot (a setting, off by default:
//! the paper walks, or draws, every pixel). A W x H frame is walked at
//! w x h = ceil(W / divisor) x ceil(H / divisor): the reduced pixel (i, j) walks the
//! frame's ray through the fractional frame coordinate ((i + 0.5) W / w, (j + 0.5) H / h)
//! (pixel x's centre at x + 0.5). A frame pixel at coordinate (X, Y) reads the four
//! reduced pixels about u = X w / W - 0.5, v = Y h / H - 0.5 (clamped to the reduced
//! image), the bilinear taps of the clouds' reduced march (`clouds/layer/upsample.rs`).
//! It takes their bilinear mean only where they agree: their ray ends within
//! [`DEPTH_TOLERANCE`] of the nearest (no silhouette between them) and, at every
//! wavelength, their radiances within `tolerance` of the brightest (no edge of a beam or
//! of a shadow in the air between them); otherwise its own ray is walked. So the beam's
//! edges, the shadows' edges and the occluders' outlines stay as sharp as the walk's, and
//! the smooth glow between them costs a walk per reduced pixel. What lies wholly between
//! four taps is lost: a beam's tip narrower than a reduced pixel between four dark taps
//! stays dark.

use crate::models::options::Setting;

/// The method these settings belong to.
const MODEL: &str = "qtable2002";

/// The side of the block of frame pixels one reduced pixel walks for (1: every pixel
/// walked, the paper's way).
pub const RESOLUTION_DIVISOR: Setting<usize> = Setting {
    model: MODEL,
    key: "resolution_divisor",
    range: 1..=16,
};
/// How far the four taps' radiances may spread, a share of the brightest, for a pixel
/// to be interpolated.
pub const UPSAMPLE_TOLERANCE: Setting<f64> = Setting {
    model: MODEL,
    key: "upsample_tolerance",
    range: 0.0..=1.0,
};
/// How far the four taps' ray ends may spread, a share of the nearest, for a pixel to
/// be interpolated.
pub const DEPTH_TOLERANCE: f64 = 1.0;

/// The reduced walk's size and when its taps may be interpolated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Upsample {
    /// [`RESOLUTION_DIVISOR`], at least 2.
    pub divisor: u32,
    /// [`UPSAMPLE_TOLERANCE`].
    pub tolerance: f64,
}

/// One reduced pixel's walk: its radiance per wavelength and where its ray ends, m.
#[derive(Clone, Debug, PartialEq)]
pub struct Tap {
    pub radiance: Vec<f64>,
    pub end_m: f64,
}

impl Upsample {
    /// The reduced image's size for a `width` x `height` frame.
    pub fn reduced_size(&self, width: u32, height: u32) -> (u32, u32) {
        (width.div_ceil(self.divisor), height.div_ceil(self.divisor))
    }

    /// Whether `taps` may stand for the pixels between them.
    pub fn interpolable(&self, taps: &[Tap; 4]) -> bool {
        let spread = |values: &mut dyn Iterator<Item = f64>| {
            values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            })
        };
        let (near, far) = spread(&mut taps.iter().map(|t| t.end_m));
        if far - near > DEPTH_TOLERANCE * near {
            return false;
        }
        (0..taps[0].radiance.len()).all(|w| {
            let (lo, hi) = spread(&mut taps.iter().map(|t| t.radiance[w]));
            hi - lo <= self.tolerance * hi
        })
    }
}

/// The two reduced pixels about frame coordinate `x` (a pixel's centre at its index
/// plus 0.5) on an axis of `full` frame pixels and `reduced` reduced ones, and the
/// weight of the second.
pub fn axis_taps(x: f64, full: u32, reduced: u32) -> (u32, u32, f64) {
    let u = (x * f64::from(reduced) / f64::from(full) - 0.5).clamp(0.0, f64::from(reduced - 1));
    let i0 = u.floor() as u32;
    (i0, (i0 + 1).min(reduced - 1), u - f64::from(i0))
}

/// The frame coordinate reduced pixel `index` walks on an axis of `reduced` reduced
/// pixels and `full` frame pixels.
pub fn walked_coordinate(index: u32, reduced: u32, full: u32) -> f64 {
    (f64::from(index) + 0.5) * f64::from(full) / f64::from(reduced)
}

/// The pixel at frame coordinate (`x`, `y`) of a `size` frame: the bilinear mean of its
/// four taps where they are interpolable, else `walk` of its own ray. `tap(x, y)` walks
/// the ray through frame coordinate (x, y) and tells where it ends; `walk()` is the
/// pixel's own walk.
pub fn upsampled<E>(
    upsample: &Upsample,
    size: (u32, u32),
    (x, y): (f64, f64),
    tap: impl Fn(f64, f64) -> Result<Tap, E>,
    walk: impl FnOnce() -> Result<Vec<f64>, E>,
) -> Result<Vec<f64>, E> {
    let (width, height) = size;
    let (w, h) = upsample.reduced_size(width, height);
    let (i0, i1, fx) = axis_taps(x, width, w);
    let (j0, j1, fy) = axis_taps(y, height, h);
    let at = |i: u32, j: u32| {
        tap(
            walked_coordinate(i, w, width),
            walked_coordinate(j, h, height),
        )
    };
    let taps = [at(i0, j0)?, at(i1, j0)?, at(i0, j1)?, at(i1, j1)?];
    if !upsample.interpolable(&taps) {
        return walk();
    }
    let weights = [
        (1.0 - fx) * (1.0 - fy),
        fx * (1.0 - fy),
        (1.0 - fx) * fy,
        fx * fy,
    ];
    Ok((0..taps[0].radiance.len())
        .map(|l| {
            taps.iter()
                .zip(weights)
                .map(|(t, k)| k * t.radiance[l])
                .sum()
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tap(radiance: f64, end_m: f64) -> Tap {
        Tap {
            radiance: vec![radiance, 2.0 * radiance],
            end_m,
        }
    }

    #[test]
    fn taps_interpolate_only_within_both_tolerances() {
        let up = Upsample {
            divisor: 4,
            tolerance: 0.1,
        };
        let same = [
            tap(1.0, 10.0),
            tap(0.95, 10.0),
            tap(1.0, 12.0),
            tap(0.92, 11.0),
        ];
        assert!(up.interpolable(&same));
        // A beam's or shadow's edge between the taps: radiance 20 % apart.
        let edge = [
            tap(1.0, 10.0),
            tap(0.8, 10.0),
            tap(1.0, 10.0),
            tap(1.0, 10.0),
        ];
        assert!(!up.interpolable(&edge));
        // An occluder's outline: the same light, the ray ends 2.1 times apart.
        let outline = [
            tap(1.0, 10.0),
            tap(1.0, 21.0),
            tap(1.0, 10.0),
            tap(1.0, 10.0),
        ];
        assert!(!up.interpolable(&outline));
        // Dark taps are all equal; a zero tolerance interpolates only equal taps.
        let dark = [
            tap(0.0, 10.0),
            tap(0.0, 10.0),
            tap(0.0, 10.0),
            tap(0.0, 10.0),
        ];
        assert!(up.interpolable(&dark));
        let exact = Upsample {
            divisor: 4,
            tolerance: 0.0,
        };
        assert!(exact.interpolable(&[
            tap(1.0, 10.0),
            tap(1.0, 10.0),
            tap(1.0, 10.0),
            tap(1.0, 10.0)
        ]));
        assert!(!exact.interpolable(&same));
    }

    #[test]
    fn a_pixel_reads_the_reduced_pixels_about_it_and_lands_on_a_walked_one_exactly() {
        // A 10-pixel axis at divisor 4: 3 reduced pixels walk coordinates 5/3, 5, 25/3.
        assert_eq!(walked_coordinate(1, 3, 10), 5.0);
        for i in 0..3 {
            let (i0, i1, f) = axis_taps(walked_coordinate(i, 3, 10), 10, 3);
            assert_eq!((i0, f), (i, 0.0), "reduced pixel {i}");
            assert_eq!(i1, (i + 1).min(2));
        }
        // Beyond the outer walked pixels the taps are clamped.
        assert_eq!(axis_taps(0.5, 10, 3), (0, 1, 0.0));
        assert_eq!(axis_taps(9.5, 10, 3), (2, 2, 0.0));
        // Interpolated between taps of radiance x (a ramp) gives the ramp; an edge walks.
        let up = Upsample {
            divisor: 4,
            tolerance: 0.5,
        };
        let ramp = |x: f64, _: f64| Ok::<_, ()>(tap(1.0 + x / 10.0, 5.0));
        let got = upsampled(&up, (10, 10), (3.0, 4.0), ramp, || Ok(vec![-1.0])).unwrap();
        assert!((got[0] - 1.3).abs() < 1e-12, "{got:?}");
        let step = |x: f64, _: f64| Ok::<_, ()>(tap(if x < 4.0 { 1.0 } else { 0.1 }, 5.0));
        let got = upsampled(&up, (10, 10), (3.0, 4.0), step, || Ok(vec![-1.0])).unwrap();
        assert_eq!(got, vec![-1.0]);
    }
}
