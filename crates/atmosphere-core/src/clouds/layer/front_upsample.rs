//! The air in front of a cloud (L_front of `composite.rs`) from a run of the sky model at
//! a reduced resolution: from above the layer the cloud's entry is where each ray meets
//! the sphere of the layer's top, a smooth function of the pixel. The model's run at the
//! reduced rays of `upsample.rs` (ended where each enters the layer) and each ray's
//! transmittance T_front to its entry give the optical depth tau in front and the mean
//! source of the air there (L_front = the integral of J e^-tau dtau, the mean J times
//! 1 - e^-tau), which changes across the image more slowly than the radiance where rays
//! graze the layer's top and the air before the cloud grows fast from pixel to pixel. A
//! full pixel takes the mean tau and source of its four bilinear taps, kept where the
//! tap's ray enters the layer; where none does (a pixel on the rim of the layer's top as
//! seen from the camera) those of the nearest reduced ray within [`FRONT_SEARCH`] of the
//! pixel's nearest one that enters it; where there is none, no source. Where that ray,
//! or a kept tap's, enters the layer further than [`FRONT_ENTRY_TOLERANCE`] of the
//! pixel's own entry from it (near the limb of the layer's top, where tau grows fast
//! from pixel to pixel), or none was found, the pixel's tau is its own, integrated along
//! its ray. The GPU's `clouds/frame_composite.wgsl` (`reduced_front`) follows this.

use crate::clouds::layer::upsample::bilinear_taps;

/// How far, in reduced pixels each way, the search for an entering ray looks.
pub const FRONT_SEARCH: i64 = 2;

/// The share of a pixel's entry distance beyond which a tap's entry marks the pixel as
/// one whose depth in front is its own.
pub const FRONT_ENTRY_TOLERANCE: f64 = 0.1;

/// Below this opacity the source divides by it instead (a ray through almost no air).
const MIN_OPACITY: f64 = 1e-6;

/// The model's run at the reduced rays: the image's size, each ray's radiance, its
/// transmittance and where it enters the layer (m; 0 where it does not), row-major.
#[derive(Clone, Copy, Debug)]
pub struct ReducedFront<'a> {
    pub size: (u32, u32),
    pub radiance: &'a [[f64; 3]],
    pub transmittance: &'a [[f64; 3]],
    pub entry_m: &'a [f64],
}

/// The air in front of the cloud at a full pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AirInFront {
    pub transmittance: [f64; 3],
    pub radiance: [f64; 3],
}

impl ReducedFront<'_> {
    /// Reduced ray `i`'s optical depth in front of the cloud and its mean source.
    fn tap(&self, i: usize) -> ([f64; 3], [f64; 3]) {
        let t = self.transmittance[i];
        (
            t.map(|t| -t.max(1e-30).ln()),
            std::array::from_fn(|c| self.radiance[i][c] / (1.0 - t[c]).max(MIN_OPACITY)),
        )
    }
}

/// The air in front of the cloud at full pixel `(x, y)` of a `full`-sized image, whose
/// ray enters the layer at `entry_m`, from `reduced`, read as the module says;
/// `own_transmittance` gives the pixel's own transmittance to its entry where it needs
/// it.
pub fn front_at(
    reduced: &ReducedFront<'_>,
    full: (u32, u32),
    (x, y): (u32, u32),
    entry_m: f64,
    own_transmittance: impl FnOnce() -> [f64; 3],
) -> AirInFront {
    let steep_at =
        |i: usize| (reduced.entry_m[i] - entry_m).abs() > FRONT_ENTRY_TOLERANCE * entry_m;
    let (mut depth, mut source) = ([0.0; 3], [0.0; 3]);
    let mut weight = 0.0;
    let mut steep = false;
    for (i, w) in bilinear_taps(full, reduced.size, (x, y)) {
        if w > 0.0 && reduced.entry_m[i] > 0.0 {
            steep |= steep_at(i);
            let (d, s) = reduced.tap(i);
            for c in 0..3 {
                depth[c] += w * d[c];
                source[c] += w * s[c];
            }
            weight += w;
        }
    }
    if weight > 0.0 {
        depth = depth.map(|d| d / weight);
        source = source.map(|s| s / weight);
    } else {
        steep = true;
        if let Some(i) = nearest_entering(reduced, full, (x, y)) {
            (depth, source) = reduced.tap(i);
        }
    }
    let transmittance = match steep {
        true => own_transmittance(),
        false => depth.map(|d| (-d).exp()),
    };
    AirInFront {
        transmittance,
        radiance: std::array::from_fn(|c| (1.0 - transmittance[c]) * source[c]),
    }
}

/// The reduced ray nearest to full pixel `(x, y)` that enters the layer, within
/// [`FRONT_SEARCH`] of the pixel's nearest reduced ray.
fn nearest_entering(
    reduced: &ReducedFront<'_>,
    full: (u32, u32),
    (x, y): (u32, u32),
) -> Option<usize> {
    let (w, h) = (i64::from(reduced.size.0), i64::from(reduced.size.1));
    let coordinate =
        |x: u32, full: u32, low: i64| (f64::from(x) + 0.5) * low as f64 / f64::from(full) - 0.5;
    let p = (coordinate(x, full.0, w), coordinate(y, full.1, h));
    let nearest = |p: f64, low: i64| (p.clamp(0.0, (low - 1) as f64) + 0.5).floor() as i64;
    let (ni, nj) = (nearest(p.0, w), nearest(p.1, h));
    let mut best: Option<(f64, usize)> = None;
    for j in nj - FRONT_SEARCH..=nj + FRONT_SEARCH {
        for i in ni - FRONT_SEARCH..=ni + FRONT_SEARCH {
            if !(0..w).contains(&i) || !(0..h).contains(&j) {
                continue;
            }
            let index = (j * w + i) as usize;
            let distance2 = (i as f64 - p.0).powi(2) + (j as f64 - p.1).powi(2);
            if reduced.entry_m[index] > 0.0 && best.is_none_or(|(d, _)| distance2 < d) {
                best = Some((distance2, index));
            }
        }
    }
    best.map(|(_, index)| index)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::clouds::layer::upsample::{marched_coordinate, reduced_size};

    const FULL: (u32, u32) = (40, 22);
    const DIVISOR: u32 = 3;

    /// The optical depth in front at the full image's fractional pixel (x, y), growing
    /// towards the right as the rays graze more air.
    fn depth(x: f64, y: f64) -> f64 {
        0.02 + 0.004 * x + 0.001 * y
    }

    /// The reduced rays of the mean source `f` and depth [`depth`] of the full image's
    /// fractional pixel (the channels' sources 1, 2 and 3 times it), entering the layer
    /// where `enters` says.
    struct Rays {
        radiance: Vec<[f64; 3]>,
        transmittance: Vec<[f64; 3]>,
        entry_m: Vec<f64>,
    }

    impl Rays {
        fn new(f: impl Fn(f64, f64) -> f64, enters: impl Fn(f64, f64) -> bool) -> Rays {
            let size = reduced_size(FULL.0, FULL.1, DIVISOR);
            let mut rays = Rays {
                radiance: Vec::new(),
                transmittance: Vec::new(),
                entry_m: Vec::new(),
            };
            for j in 0..size.1 {
                for i in 0..size.0 {
                    let x = marched_coordinate(i, size.0, FULL.0);
                    let y = marched_coordinate(j, size.1, FULL.1);
                    let t = (-depth(x, y)).exp();
                    let l = f(x, y) * (1.0 - t);
                    rays.radiance.push([l, 2.0 * l, 3.0 * l]);
                    rays.transmittance.push([t; 3]);
                    rays.entry_m.push(if enters(x, y) { 1e5 } else { 0.0 });
                }
            }
            rays
        }

        fn front(&self) -> ReducedFront<'_> {
            ReducedFront {
                size: reduced_size(FULL.0, FULL.1, DIVISOR),
                radiance: &self.radiance,
                transmittance: &self.transmittance,
                entry_m: &self.entry_m,
            }
        }
    }

    /// The depth and the source are read bilinearly: where both are linear across the
    /// image they are read exactly, and with them the radiance, which is not.
    #[test]
    fn a_linear_depth_and_source_are_read_exactly_where_every_ray_enters() {
        let f = |x: f64, y: f64| 1.0 + 0.05 * x - 0.02 * y;
        let rays = Rays::new(f, |_, _| true);
        // Away from the edges, where the taps' clamp holds the value.
        for y in 2..FULL.1 - 2 {
            for x in 2..FULL.0 - 2 {
                let own = || unreachable!("({x}, {y}) needs no depth of its own");
                let air = front_at(&rays.front(), FULL, (x, y), 1e5, own);
                let (px, py) = (f64::from(x), f64::from(y));
                let t = (-depth(px, py)).exp();
                let want = f(px, py) * (1.0 - t);
                assert!((air.transmittance[1] - t).abs() < 1e-12, "({x}, {y})");
                let l = air.radiance;
                assert!((l[0] - want).abs() < 1e-12, "({x}, {y}): {} {want}", l[0]);
                assert!((l[2] - 3.0 * want).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn rays_that_do_not_enter_are_left_out_and_the_nearest_entering_one_stands_in() {
        // Rays left of x = 20 enter with source 1, the others do not (source 100, which
        // must never be read: every pixel that finds air has source 1, those between
        // the last entering column and the next included).
        let f = |x: f64, _: f64| if x < 20.0 { 1.0 } else { 100.0 };
        let rays = Rays::new(f, |x, _| x < 20.0);
        let size = reduced_size(FULL.0, FULL.1, DIVISOR);
        let last_entering = (0..size.0)
            .filter(|&i| marched_coordinate(i, size.0, FULL.0) < 20.0)
            .max()
            .unwrap();
        for y in 0..FULL.1 {
            for x in 0..FULL.0 {
                // The pixel's nearest reduced column; within the search's two reduced
                // pixels of it the last entering column is found.
                let u = (f64::from(x) + 0.5) * f64::from(size.0) / f64::from(FULL.0) - 0.5;
                let nearest = (u.clamp(0.0, f64::from(size.0 - 1)) + 0.5).floor() as u32;
                let air = front_at(&rays.front(), FULL, (x, y), 1e5, || [0.5; 3]);
                match nearest <= last_entering + 2 {
                    true => {
                        let source = air.radiance[0] / (1.0 - air.transmittance[0]);
                        assert!((source - 1.0).abs() < 1e-9, "({x}, {y}): {source}");
                    }
                    // None found: the pixel's own depth, and no source.
                    false => assert_eq!((air.radiance[0], air.transmittance[0]), (0.0, 0.5)),
                }
            }
        }
    }

    /// A pixel whose ray enters the layer far from where its taps' rays do takes its own
    /// depth, and the taps' source.
    #[test]
    fn a_pixel_far_from_its_taps_entries_takes_its_own_depth() {
        let rays = Rays::new(|_, _| 2.0, |_, _| true);
        let own = [0.4, 0.5, 0.6];
        for entry_m in [0.85e5, 1.2e5] {
            let air = front_at(&rays.front(), FULL, (20, 10), entry_m, || own);
            assert_eq!(air.transmittance, own);
            for c in 0..3 {
                let want = (1.0 - own[c]) * 2.0 * (c + 1) as f64;
                assert!((air.radiance[c] - want).abs() < 1e-12, "{air:?}");
            }
        }
        // Within the tolerance the taps' depth stands.
        let air = front_at(&rays.front(), FULL, (20, 10), 0.95e5, || own);
        assert_ne!(air.transmittance, own);
    }
}
