//! The air in front of a cloud (L_front of `composite.rs`) from a run of the sky model at
//! a reduced resolution: from above the layer the cloud's entry is where each ray meets
//! the sphere of the layer's top, a smooth function of the pixel. The model's run at the
//! reduced rays of `upsample.rs` (ended where each enters the layer) is divided by each
//! ray's opacity 1 - T_front to its entry, the mean source of the air in front
//! (L_front = the integral of J e^-tau dtau, the mean J times 1 - e^-tau), which changes
//! across the image more slowly than the radiance where rays graze the layer's top and
//! the air before the cloud grows fast from pixel to pixel. A full pixel takes (1 -
//! T_front) at its own ray times the mean source of its four bilinear taps, kept where
//! the tap's ray enters the layer; where none does (a pixel on the rim of the layer's
//! top as seen from the camera) that of the nearest reduced ray within [`FRONT_SEARCH`]
//! of the pixel's nearest one that enters it; where there is none, no air. The GPU's
//! `clouds/frame_composite.wgsl` (`reduced_front`) follows this.

use crate::clouds::layer::upsample::bilinear_taps;

/// How far, in reduced pixels each way, the search for an entering ray looks.
pub const FRONT_SEARCH: i64 = 2;

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

impl ReducedFront<'_> {
    /// The mean source in front of reduced ray `i`.
    fn source(&self, i: usize) -> [f64; 3] {
        std::array::from_fn(|c| {
            self.radiance[i][c] / (1.0 - self.transmittance[i][c]).max(MIN_OPACITY)
        })
    }
}

/// L_front at full pixel `(x, y)` of a `full`-sized image, whose transmittance to its
/// entry is `t_front`, from `reduced`; `None` where no reduced ray near it enters the
/// layer.
pub fn front_at(
    reduced: &ReducedFront<'_>,
    full: (u32, u32),
    (x, y): (u32, u32),
    t_front: [f64; 3],
) -> Option<[f64; 3]> {
    let enters = |i: usize| reduced.entry_m[i] > 0.0;
    let in_front = |source: [f64; 3]| std::array::from_fn(|c| (1.0 - t_front[c]) * source[c]);
    let mut sum = [0.0; 3];
    let mut weight = 0.0;
    for (i, w) in bilinear_taps(full, reduced.size, (x, y)) {
        if w > 0.0 && enters(i) {
            for (s, j) in sum.iter_mut().zip(reduced.source(i)) {
                *s += w * j;
            }
            weight += w;
        }
    }
    if weight > 0.0 {
        return Some(in_front(sum.map(|s| s / weight)));
    }
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
            if enters(index) && best.is_none_or(|(d, _)| distance2 < d) {
                best = Some((distance2, index));
            }
        }
    }
    best.map(|(_, index)| in_front(reduced.source(index)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::clouds::layer::upsample::{marched_coordinate, reduced_size};

    const FULL: (u32, u32) = (40, 22);
    const DIVISOR: u32 = 3;

    /// The opacity of the air in front at the full image's fractional pixel (x, y): a
    /// ray that grazes more air towards the right.
    fn opacity(x: f64, _: f64) -> f64 {
        0.02 * (0.1 * x).exp()
    }

    /// A reduced run whose mean source is the field `f` of the full image's fractional
    /// pixel, entering the layer where `enters` says: radiance, transmittance, entry.
    fn reduced(
        f: impl Fn(f64, f64) -> f64,
        enters: impl Fn(f64, f64) -> bool,
    ) -> Vec<([f64; 3], [f64; 3], f64)> {
        let size = reduced_size(FULL.0, FULL.1, DIVISOR);
        (0..size.1)
            .flat_map(|j| (0..size.0).map(move |i| (i, j)))
            .map(|(i, j)| {
                let x = marched_coordinate(i, size.0, FULL.0);
                let y = marched_coordinate(j, size.1, FULL.1);
                let l = f(x, y) * opacity(x, y);
                let t = 1.0 - opacity(x, y);
                let entry = if enters(x, y) { 1e5 } else { 0.0 };
                ([l, 2.0 * l, 3.0 * l], [t; 3], entry)
            })
            .collect()
    }

    /// The transmittance in front of full pixel (x, y).
    fn t_front(x: u32, y: u32) -> [f64; 3] {
        [1.0 - opacity(f64::from(x), f64::from(y)); 3]
    }

    fn unzip3(rays: &[([f64; 3], [f64; 3], f64)]) -> (Vec<[f64; 3]>, Vec<[f64; 3]>, Vec<f64>) {
        (
            rays.iter().map(|r| r.0).collect(),
            rays.iter().map(|r| r.1).collect(),
            rays.iter().map(|r| r.2).collect(),
        )
    }

    /// The source is read bilinearly, the opacity at the pixel's own ray: a field whose
    /// radiance grows exponentially across the image but whose source is linear is read
    /// exactly.
    #[test]
    fn a_linear_source_is_read_exactly_where_every_ray_enters() {
        let f = |x: f64, y: f64| 1.0 + 0.05 * x - 0.02 * y;
        let rays = reduced(f, |_, _| true);
        let (radiance, transmittance, entry_m) = unzip3(&rays);
        let front = ReducedFront {
            size: reduced_size(FULL.0, FULL.1, DIVISOR),
            radiance: &radiance,
            transmittance: &transmittance,
            entry_m: &entry_m,
        };
        // Away from the edges, where the taps' clamp holds the value.
        for y in 2..FULL.1 - 2 {
            for x in 2..FULL.0 - 2 {
                let l = front_at(&front, FULL, (x, y), t_front(x, y)).unwrap();
                let want = f(f64::from(x), f64::from(y)) * opacity(f64::from(x), f64::from(y));
                assert!((l[0] - want).abs() < 1e-12, "({x}, {y}): {} {want}", l[0]);
                assert!((l[2] - 3.0 * want).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn rays_that_do_not_enter_are_left_out_and_the_nearest_entering_one_stands_in() {
        // Rays left of x = 20 enter with radiance 1, the others do not (radiance 100,
        // which must never be read).
        let f = |x: f64, _: f64| if x < 20.0 { 1.0 } else { 100.0 };
        let enters = |x: f64, _: f64| x < 20.0;
        let rays = reduced(f, enters);
        let (radiance, transmittance, entry_m) = unzip3(&rays);
        let front = ReducedFront {
            size: reduced_size(FULL.0, FULL.1, DIVISOR),
            radiance: &radiance,
            transmittance: &transmittance,
            entry_m: &entry_m,
        };
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
                match front_at(&front, FULL, (x, y), t_front(x, y)) {
                    Some(l) => {
                        let want = opacity(f64::from(x), f64::from(y));
                        assert!((l[0] - want).abs() < 1e-12 * want, "({x}, {y})");
                        assert!(nearest <= last_entering + 2, "({x}, {y})");
                    }
                    None => assert!(nearest > last_entering + 2, "({x}, {y})"),
                }
            }
        }
        // A pixel between the last entering column and the next takes the entering one
        // alone.
        let between = (marched_coordinate(last_entering, size.0, FULL.0) + 1.0) as u32;
        let l = front_at(&front, FULL, (between, 5), [0.5; 3]).unwrap();
        assert!((l[1] - 0.5 * 2.0).abs() < 1e-12, "{l:?}");
    }
}
