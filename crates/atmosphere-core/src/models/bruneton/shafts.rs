//! Light shafts in the bruneton model by the shadow-length approximation of Bruneton and
//! Neyret 2008 (section 5, Eq. 17-18): the total length `l` of the view segment's
//! shadowed parts (here from the frame's shadow map by the midpoint rule of the sun's
//! invisibility along the ray, `shafts::shadowed_length_m`, where the paper counts the
//! shadow volume's faces) is replaced by one segment of that length, at the far end of a
//! ray that ends on the ground or an object (Eq. 17, `x_s = x_o - l v`) or at the
//! camera's end of one that goes to space (Eq. 18, `x_s = x + l v`). The in-scattering
//! of the lit part is then `S|x - T(x, x_s) S|x_s` (Eq. 17) or `T(x, x_s) S|x_s` (Eq. 18):
//! what the shadow takes out of the unshadowed `S|x - T(x, x_o) S|x_o` is, over the
//! shadowed segment `[x_a, x_b]`, `T(x, x_a) S|x_a - T(x, x_b) S|x_b`, with `S|x_b` zero
//! where `x_b` ends the segment on the ground or at the top (its ray has no length).
//!
//! `S` here is the single scattering alone (the tables' single Rayleigh and Mie with
//! their phase functions): orders two and up stay unshadowed, as in the other models'
//! shafts and the reference's ground truth, where the paper takes them out of the
//! shadowed length as well.

use crate::models::bruneton::parameterization::{Radii, table_position};
use crate::models::bruneton::precompute::Tables;
use crate::optics::geometry::radius_at;
use crate::optics::phase::rayleigh;
use crate::optics::transmittance_table::TransmittanceTable;
use crate::optics::view_segment::{SegmentEnd, ViewSegment};

/// The shadowed segment `[a, b]` (distances from the segment's start, m) that stands for
/// a total shadowed length `l`: at the far end of a segment that ends on the ground or
/// an object (Eq. 17), at its start for one that ends in space (Eq. 18).
pub fn shadowed_segment(segment: &ViewSegment, l: f64) -> (f64, f64) {
    let l = l.clamp(0.0, segment.length);
    match segment.end {
        SegmentEnd::Space => (0.0, l),
        SegmentEnd::Ground | SegmentEnd::Object => (segment.length - l, segment.length),
    }
}

/// A view segment as the tables see it.
#[derive(Clone, Copy, Debug)]
pub struct ShaftRay<'a> {
    pub radii: &'a Radii,
    pub transmittance: &'a TransmittanceTable,
    pub segment: &'a ViewSegment,
    /// The sun's zenith cosine at the segment's start, and the view-sun cosine.
    pub mu_s: f64,
    pub nu: f64,
    /// The half of the mu axis of the whole ray.
    pub ground: bool,
    /// The Mie phase function at `nu` (0 when Mie is pruned).
    pub mie_phase: f64,
}

impl ShaftRay<'_> {
    /// `T(x, x_d) S|x_d`, the single scattering per unit solar irradiance of the part of
    /// the segment beyond distance `d` as seen from its start, in the three channels of
    /// `tables`.
    fn single_beyond(&self, tables: &Tables, d: f64) -> [f64; 3] {
        let s = self.segment;
        if d >= s.length && !s.cut {
            return [0.0; 3];
        }
        let (bottom, top) = (self.radii.bottom_m, self.radii.top_m);
        let r_d = radius_at(s.r, s.mu, d).clamp(bottom, top);
        let mu_d = ((s.r * s.mu + d) / r_d).clamp(-1.0, 1.0);
        let mu_s_d = ((s.r * self.mu_s + d * self.nu) / r_d).clamp(-1.0, 1.0);
        let size = &tables.single_rayleigh.size;
        let p = table_position(self.radii, size, r_d, mu_d, mu_s_d, self.nu, self.ground);
        let column = self.transmittance.segment_column(s.r, s.mu, d, self.ground);
        let t = tables.channels.transmittance(column);
        let rayleigh_part = tables.single_rayleigh.at_position(&p);
        let mie_part = tables
            .single_mie
            .as_ref()
            .map_or([0.0; 3], |m| m.at_position(&p));
        let phase_r = rayleigh(self.nu);
        [0, 1, 2].map(|k| t[k] * (phase_r * rayleigh_part[k] + self.mie_phase * mie_part[k]))
    }

    /// The single scattering per unit solar irradiance that the shadowed segment
    /// `[a, b]` takes out: `T(x, x_a) S|x_a - T(x, x_b) S|x_b`.
    pub fn single_taken_out(&self, tables: &Tables, (a, b): (f64, f64)) -> [f64; 3] {
        let (near, far) = (self.single_beyond(tables, a), self.single_beyond(tables, b));
        [0, 1, 2].map(|k| near[k] - far[k])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn segment(end: SegmentEnd) -> ViewSegment {
        ViewSegment {
            start: DVec3::X * 6_361_000.0,
            direction: DVec3::Y,
            sun_direction: DVec3::X,
            t_enter: 0.0,
            r: 6_361_000.0,
            mu: 0.0,
            length: 50_000.0,
            end,
            cut: false,
        }
    }

    #[test]
    fn the_shadowed_length_goes_to_the_ground_end_or_the_camera_end() {
        let ground = segment(SegmentEnd::Ground);
        assert_eq!(shadowed_segment(&ground, 2_000.0), (48_000.0, 50_000.0));
        let space = segment(SegmentEnd::Space);
        assert_eq!(shadowed_segment(&space, 2_000.0), (0.0, 2_000.0));
        // Never longer than the segment.
        assert_eq!(shadowed_segment(&space, 1e6), (0.0, 50_000.0));
        assert_eq!(shadowed_segment(&ground, -1.0), (50_000.0, 50_000.0));
    }
}
