//! The frame planner's rule for beams scenes: no beam work for a light whose light
//! cannot reach the visible air, or in a medium that scatters nothing. A light is
//! skipped when its beam's bounding volume (a spot's pyramid over its cone, a point
//! light's cube, a bounded parallel beam's box, each reaching as far as the medium
//! carries light) lies wholly outside one plane of the camera's view frustum (its four
//! sides, the camera's own plane, or the depth where the medium has extinguished the
//! light): every corner on the outside of that plane. The test is conservative: a
//! volume that crosses a corner of the frustum is kept.

use std::fmt;

use glam::DVec3;

use crate::beams::camera::Camera;
use crate::beams::in_scattering::EXTINGUISHED_OPTICAL_DEPTH;
use crate::beams::light::{Light, LightShape};
use crate::beams::scene::BeamScene;

/// Why a light gets no beam work.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Skip {
    /// The medium scatters nothing at any wavelength.
    NothingScatters,
    /// Its beam's bounding volume lies outside the view frustum.
    OutsideView,
}

impl fmt::Display for Skip {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Skip::NothingScatters => "the medium scatters nothing",
            Skip::OutsideView => "its beam stays outside the view",
        })
    }
}

/// What a frame does with each light of a scene, in the scene's order.
#[derive(Clone, Debug, PartialEq)]
pub struct BeamPlan {
    /// `None`: drawn; otherwise why it is skipped.
    pub lights: Vec<Option<Skip>>,
}

impl BeamPlan {
    /// The plan for `scene` at `wavelengths_nm`.
    pub fn new(scene: &BeamScene, wavelengths_nm: &[f64]) -> BeamPlan {
        let medium = scene.medium.at(wavelengths_nm);
        let scatters = medium.scattering_per_m.iter().any(|&s| s > 0.0);
        let reach = EXTINGUISHED_OPTICAL_DEPTH / medium.thinnest_extinction_per_m();
        let lights = scene
            .lights
            .iter()
            .map(|light| {
                if !scatters {
                    Some(Skip::NothingScatters)
                } else if outside_view(scene, light, reach) {
                    Some(Skip::OutsideView)
                } else {
                    None
                }
            })
            .collect();
        BeamPlan { lights }
    }

    /// The scene with only the lights the plan draws.
    pub fn pruned(&self, scene: &BeamScene) -> BeamScene {
        let mut pruned = scene.clone();
        pruned.lights = scene
            .lights
            .iter()
            .zip(&self.lights)
            .filter(|(_, skip)| skip.is_none())
            .map(|(l, _)| l.clone())
            .collect();
        pruned
    }

    /// The lights drawn.
    pub fn drawn(&self) -> usize {
        self.lights.iter().filter(|s| s.is_none()).count()
    }
}

impl fmt::Display for BeamPlan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let parts: Vec<String> = self
            .lights
            .iter()
            .enumerate()
            .map(|(i, skip)| match skip {
                None => format!("lights[{i}] drawn"),
                Some(why) => format!("lights[{i}] skipped ({why})"),
            })
            .collect();
        f.write_str(&parts.join(", "))
    }
}

/// The corners of `light`'s bounding volume reaching `reach` m from it (Dobashi et al.
/// 2002 section 4.2.1: a spot's pyramid over its cone); `None` where it has none (an
/// unbounded parallel beam, a cone too wide for a pyramid, an infinite reach).
pub fn volume_corners(light: &Light, reach: f64) -> Option<Vec<DVec3>> {
    if !reach.is_finite() {
        return None;
    }
    match &light.shape {
        LightShape::Spot {
            position_m,
            frame,
            tan_cone,
            ..
        } => {
            let side = reach * tan_cone;
            if !side.is_finite() {
                return None;
            }
            let mut corners = vec![*position_m];
            for (sx, sy) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                corners.push(
                    *position_m + frame.z * reach + frame.x * (sx * side) + frame.y * (sy * side),
                );
            }
            Some(corners)
        }
        LightShape::Point { position_m, .. } => Some(
            (0..8)
                .map(|i| {
                    let s = |bit: usize| if i & bit == 0 { -reach } else { reach };
                    *position_m + DVec3::new(s(1), s(2), s(4))
                })
                .collect(),
        ),
        LightShape::Parallel {
            position_m,
            frame,
            half_size_m: Some([hx, hy]),
        } => Some(
            (0..8)
                .map(|i| {
                    let x = if i & 1 == 0 { -hx } else { *hx };
                    let y = if i & 2 == 0 { -hy } else { *hy };
                    let z = if i & 4 == 0 { 0.0 } else { reach };
                    *position_m + frame.x * x + frame.y * y + frame.z * z
                })
                .collect(),
        ),
        LightShape::Parallel {
            half_size_m: None, ..
        } => None,
    }
}

/// The rectangle of the screen of `camera`, in normalised device coordinates
/// [x0, y0, x1, y1] (x right, y up, -1 to 1), that holds the convex hull of `corners`,
/// widened by a pixel on each side; the whole screen where a corner is not in front of
/// the camera.
pub fn screen_bounds(camera: &Camera, corners: &[DVec3]) -> [f64; 4] {
    let tan_y = (0.5 * camera.vertical_fov_deg.to_radians()).tan();
    let tan_x = tan_y * f64::from(camera.width_px) / f64::from(camera.height_px);
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for &p in corners {
        let rel = p - camera.position_m;
        let depth = rel.dot(camera.forward);
        if depth <= 0.0 {
            return [-1.0, -1.0, 1.0, 1.0];
        }
        let x = rel.dot(camera.right) / (depth * tan_x);
        let y = rel.dot(camera.up) / (depth * tan_y);
        b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
    }
    let (px, py) = (
        2.0 / f64::from(camera.width_px),
        2.0 / f64::from(camera.height_px),
    );
    [
        (b[0] - px).clamp(-1.0, 1.0),
        (b[1] - py).clamp(-1.0, 1.0),
        (b[2] + px).clamp(-1.0, 1.0),
        (b[3] + py).clamp(-1.0, 1.0),
    ]
}

/// Whether every corner of `light`'s volume lies outside one plane of the frustum.
fn outside_view(scene: &BeamScene, light: &Light, reach: f64) -> bool {
    let Some(corners) = volume_corners(light, reach) else {
        return false;
    };
    let cam = &scene.camera;
    let tan_y = (0.5 * cam.vertical_fov_deg.to_radians()).tan();
    let tan_x = tan_y * f64::from(cam.width_px) / f64::from(cam.height_px);
    let local: Vec<DVec3> = corners
        .iter()
        .map(|&p| {
            let rel = p - cam.position_m;
            DVec3::new(rel.dot(cam.right), rel.dot(cam.up), rel.dot(cam.forward))
        })
        .collect();
    // Each plane's outside: a corner's signed distance beyond it is positive.
    let planes: [&dyn Fn(DVec3) -> f64; 6] = [
        &|c| c.x - c.z * tan_x,
        &|c| -c.x - c.z * tan_x,
        &|c| c.y - c.z * tan_y,
        &|c| -c.y - c.z * tan_y,
        &|c| -c.z,
        &|c| c.z - reach,
    ];
    planes
        .iter()
        .any(|outside| local.iter().all(|&c| outside(c) > 0.0))
}
