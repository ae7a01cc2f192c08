//! Shadow maps of a beams scene's lights: for each light, the distance from the light to
//! the first occluder along the ray through each texel (Williams 1978; the shadow maps
//! of Dobashi et al. 2000 section 5.2). A spot has one perspective map over its cone, a
//! point light six (a cube), a parallel light one orthographic map over its beam or the
//! occluders' footprint. A point is lit where it is no farther from the light than the
//! stored depth plus a bias; four texels are compared and blended bilinearly
//! (percentage-closer filtering). The CPU casts a ray per texel where a GPU rasterises.

use glam::DVec3;
use rayon::prelude::*;

use crate::beams::light::{Light, LightPath, LightShape};
use crate::beams::light_frame::LightFrame;
use crate::beams::occluders::Occluders;

/// How a map's texels are laid out from the light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// From `apex` through the square of tangents [-tan_half, tan_half]^2 about
    /// `frame.z`; depth is the distance from the apex.
    Perspective {
        apex: DVec3,
        frame: LightFrame,
        tan_half: f64,
    },
    /// Along `frame.z` from the rectangle of half-sides `half` about `center` in the
    /// plane through it; depth is the distance from that plane.
    Orthographic {
        center: DVec3,
        frame: LightFrame,
        half: [f64; 2],
    },
}

/// One square depth image: `size` x `size` distances from the light, m, row by row
/// from the top (infinite where no occluder is met).
#[derive(Clone, Debug, PartialEq)]
pub struct View {
    pub projection: Projection,
    pub size: usize,
    pub depth_m: Vec<f32>,
}

/// A light's shadow map; no views when nothing can shadow the light.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowMap {
    views: Vec<View>,
}

impl ShadowMap {
    /// The shadow map of `light` among `occluders`, `size` texels a side.
    pub fn new(light: &Light, occluders: &Occluders, size: usize) -> ShadowMap {
        if occluders.is_empty() {
            return ShadowMap { views: Vec::new() };
        }
        let projections: Vec<Projection> = match &light.shape {
            LightShape::Spot {
                position_m,
                frame,
                tan_cone,
                ..
            } => vec![Projection::Perspective {
                apex: *position_m,
                frame: *frame,
                tan_half: *tan_cone,
            }],
            LightShape::Point { position_m, .. } => CUBE_AXES
                .iter()
                .filter_map(|&axis| LightFrame::new(axis, None))
                .map(|frame| Projection::Perspective {
                    apex: *position_m,
                    frame,
                    tan_half: 1.0,
                })
                .collect(),
            LightShape::Parallel {
                position_m,
                frame,
                half_size_m,
            } => footprint(*position_m, *frame, *half_size_m, occluders)
                .into_iter()
                .collect(),
        };
        let views = projections
            .into_iter()
            .map(|projection| View::render(projection, occluders, size))
            .collect();
        ShadowMap { views }
    }

    /// The depth images, looked up in this order (what a GPU pass uploads).
    pub fn views(&self) -> &[View] {
        &self.views
    }

    /// The lit fraction, in [0, 1], of `point` on `path` to the light. Points outside
    /// every view are lit, but for infinite planes, tested exactly.
    pub fn visibility(&self, occluders: &Occluders, point: DVec3, path: &LightPath) -> f64 {
        if self.views.is_empty() {
            return 1.0;
        }
        for view in &self.views {
            if let Some(lit) = view.lookup(point) {
                return lit;
            }
        }
        if occluders.planes_block(point, path.to_light, path.distance_m) {
            0.0
        } else {
            1.0
        }
    }
}

const CUBE_AXES: [DVec3; 6] = [
    DVec3::X,
    DVec3::NEG_X,
    DVec3::Y,
    DVec3::NEG_Y,
    DVec3::Z,
    DVec3::NEG_Z,
];

/// The orthographic view of a parallel light: its beam, or the occluders' footprint on
/// its plane (none when every occluder is an infinite plane).
fn footprint(
    position: DVec3,
    frame: LightFrame,
    half_size: Option<[f64; 2]>,
    occluders: &Occluders,
) -> Option<Projection> {
    if let Some(half) = half_size {
        return Some(Projection::Orthographic {
            center: position,
            frame,
            half,
        });
    }
    let (lo, hi) = occluders.finite_bounds()?;
    let corners = (0..8).map(|i| {
        DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    });
    let (mut min, mut max) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for c in corners {
        let l = frame.local(c - position);
        for (k, v) in [l.x, l.y].into_iter().enumerate() {
            min[k] = min[k].min(v);
            max[k] = max[k].max(v);
        }
    }
    let mid = [0.5 * (min[0] + max[0]), 0.5 * (min[1] + max[1])];
    // A margin of 1 % keeps the occluders' silhouettes off the map's edge.
    let half = [0.505 * (max[0] - min[0]), 0.505 * (max[1] - min[1])];
    Some(Projection::Orthographic {
        center: position + frame.x * mid[0] + frame.y * mid[1],
        frame,
        half,
    })
}

impl View {
    fn render(projection: Projection, occluders: &Occluders, size: usize) -> View {
        let depth_m = (0..size * size)
            .into_par_iter()
            .map(|i| {
                let (u, v) = (
                    ((i % size) as f64 + 0.5) / size as f64,
                    ((i / size) as f64 + 0.5) / size as f64,
                );
                let (origin, direction) = projection.texel_ray(u, v);
                occluders
                    .nearest(origin, direction, f64::INFINITY)
                    .map_or(f32::INFINITY, |t| t as f32)
            })
            .collect();
        View {
            projection,
            size,
            depth_m,
        }
    }

    /// The lit fraction of `point`, or `None` when it is outside this view.
    fn lookup(&self, point: DVec3) -> Option<f64> {
        let (u, v, depth, texel_m) = self.projection.project(point, self.size)?;
        if !(0.0..=1.0).contains(&u) || !(0.0..=1.0).contains(&v) {
            return None;
        }
        let n = self.size as f64;
        let (x, y) = (u * n - 0.5, v * n - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let bias = 2.0 * texel_m;
        let lit = |i: f64, j: f64| -> f64 {
            let (i, j) = (
                i.clamp(0.0, n - 1.0) as usize,
                j.clamp(0.0, n - 1.0) as usize,
            );
            let stored = f64::from(self.depth_m[j * self.size + i]);
            if depth <= stored + bias { 1.0 } else { 0.0 }
        };
        let top = lit(x0, y0) * (1.0 - fx) + lit(x0 + 1.0, y0) * fx;
        let bottom = lit(x0, y0 + 1.0) * (1.0 - fx) + lit(x0 + 1.0, y0 + 1.0) * fx;
        Some(top * (1.0 - fy) + bottom * fy)
    }
}

impl Projection {
    /// The ray through the texel at (u, v) (u across, v down, in [0, 1]).
    fn texel_ray(&self, u: f64, v: f64) -> (DVec3, DVec3) {
        let (x, y) = (2.0 * u - 1.0, 1.0 - 2.0 * v);
        match *self {
            Projection::Perspective {
                apex,
                frame,
                tan_half,
            } => {
                let d = frame.z + (frame.x * x + frame.y * y) * tan_half;
                (apex, d.normalize())
            }
            Projection::Orthographic {
                center,
                frame,
                half,
            } => (
                center + frame.x * (x * half[0]) + frame.y * (y * half[1]),
                frame.z,
            ),
        }
    }

    /// Where `point` falls: (u, v), its depth, and the size of a texel there, m; `None`
    /// behind a perspective view's apex.
    fn project(&self, point: DVec3, size: usize) -> Option<(f64, f64, f64, f64)> {
        match *self {
            Projection::Perspective {
                apex,
                frame,
                tan_half,
            } => {
                let l = frame.local(point - apex);
                if l.z <= 0.0 {
                    return None;
                }
                let (x, y) = (l.x / (l.z * tan_half), l.y / (l.z * tan_half));
                let distance = l.length();
                let texel = distance * 2.0 * tan_half / size as f64;
                Some((0.5 + 0.5 * x, 0.5 - 0.5 * y, distance, texel))
            }
            Projection::Orthographic {
                center,
                frame,
                half,
            } => {
                let l = frame.local(point - center);
                let texel = 2.0 * half[0].max(half[1]) / size as f64;
                Some((
                    0.5 + 0.5 * l.x / half[0],
                    0.5 - 0.5 * l.y / half[1],
                    l.z,
                    texel,
                ))
            }
        }
    }
}
