//! The exact answer: a march from the point towards the sun through the relief itself,
//! with steps no longer than the gap to the relief allows (sphere tracing, Hart 1996,
//! section 2, with the relief's slope bound as the Lipschitz constant).

use glam::DVec3;

use super::relief::Relief;
use super::sun_visibility::SunVisibility;

/// Marches at most this many steps; a point whose march has not ended counts as lit
/// (only reachable by a relief steeper than its stated slope bound).
const MAX_STEPS: usize = 1 << 20;

/// The relief's shadow by marching the relief from each point.
#[derive(Clone, Debug)]
pub struct HeightFieldShadow<R> {
    pub relief: R,
    /// Radius of the reference sphere, m.
    pub radius_m: f64,
    /// Bound on the relief's slope, |dh/ds| (rise over horizontal run): a step may be
    /// the gap to the relief over this.
    pub slope_bound: f64,
    /// Shortest step, m: the resolution of the shadow's boundary.
    pub min_step_m: f64,
}

impl<R: Relief> HeightFieldShadow<R> {
    /// The march of `relief` on a sphere of `radius_m`, with a slope bound of 1 and
    /// steps of at least 5 m.
    pub fn new(relief: R, radius_m: f64) -> HeightFieldShadow<R> {
        HeightFieldShadow {
            relief,
            radius_m,
            slope_bound: 1.0,
            min_step_m: 5.0,
        }
    }
}

impl<R: Relief> HeightFieldShadow<R> {
    /// The distance from `origin_m` along the unit `direction` to where the straight ray
    /// first meets the relief, m (past it by less than the shortest step); `None` where
    /// it rises above the relief's top first.
    pub fn first_hit_m(&self, origin_m: DVec3, direction: DVec3) -> Option<f64> {
        let top = self.relief.elevation_bound_m();
        let mut t = 0.0;
        for _ in 0..MAX_STEPS {
            let q = origin_m + t * direction;
            let r = q.length();
            let altitude = r - self.radius_m;
            if altitude > top && q.dot(direction) >= 0.0 {
                return None;
            }
            let gap = altitude - self.relief.elevation_m(q / r);
            if gap < 0.0 {
                return Some(t);
            }
            t += (gap / self.slope_bound).max(self.min_step_m);
        }
        None
    }
}

impl<R: Relief> SunVisibility for HeightFieldShadow<R> {
    /// 0 where the straight ray to the sun's centre meets the relief, else 1.
    fn sun_visible(&self, point_m: DVec3, sun: DVec3) -> f64 {
        if self.first_hit_m(point_m, sun).is_some() {
            0.0
        } else {
            1.0
        }
    }
}
