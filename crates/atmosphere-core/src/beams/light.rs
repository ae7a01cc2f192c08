//! The lights of a beams scene and the path from a point of the medium to each:
//! Dobashi et al. 2000 Eq. 3 (a point light's I(theta, phi) / r^2) and its parallel
//! light (I_p = I_0), with the light map of section 5.1 and a spot's cone.

use glam::DVec3;

use crate::atmosphere::spectral::Spectral;
use crate::beams::light_frame::LightFrame;
use crate::beams::light_map::LightMap;

/// Where a light is and how its beam is shaped.
#[derive(Clone, Debug, PartialEq)]
pub enum LightShape {
    /// Every direction; `frame` lays out the light map about its axis.
    Point {
        position_m: DVec3,
        radius_m: f64,
        frame: LightFrame,
    },
    /// A cone of half-angle `acos(cos_cone)` about `frame.z`.
    Spot {
        position_m: DVec3,
        radius_m: f64,
        frame: LightFrame,
        cos_cone: f64,
        tan_cone: f64,
        falloff_exponent: f64,
    },
    /// Along `frame.z` from the plane through `position_m`, within `half_size_m` of it
    /// across the beam when given.
    Parallel {
        position_m: DVec3,
        frame: LightFrame,
        half_size_m: Option<[f64; 2]>,
    },
}

/// A light: its shape, its emission (intensity in W sr^-1 nm^-1 on the axis, or a
/// parallel light's irradiance in W m^-2 nm^-1) and its light map.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    pub shape: LightShape,
    pub emission: Spectral,
    pub light_map: Option<LightMap>,
}

/// The smooth part of the way from a point of the medium to a light: direction,
/// distance and inverse square, defined everywhere (inside the beam or not).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightGeometry {
    /// Unit vector from the point toward the light (against the light's travel).
    pub to_light: DVec3,
    /// Distance the light travels through the medium to the point, m: to the light's
    /// position, or from a parallel light's plane (0 upstream of it). Shadow rays test
    /// this far.
    pub distance_m: f64,
    /// 1 / r^2, r at least the light's radius; 1 for a parallel light.
    pub inverse_square: f64,
}

/// The way from a point inside a light's beam to the light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightPath {
    pub to_light: DVec3,
    pub distance_m: f64,
    pub inverse_square: f64,
    /// The sharp part before the light map: a spot's cos^n falloff, else 1.
    pub profile: f64,
    /// Where the light map is read: (u, v, whether u wraps).
    pub map_uv: (f64, f64, bool),
}

impl LightPath {
    /// What the emission is multiplied by before the light map.
    pub fn factor(&self) -> f64 {
        self.inverse_square * self.profile
    }
}

impl Light {
    /// The path from `point_m` to the light; `None` where the point is outside the beam.
    pub fn path_from(&self, point_m: DVec3) -> Option<LightPath> {
        let g = self.geometry(point_m);
        let (profile, map_uv) = self.beam(point_m, &g)?;
        Some(LightPath {
            to_light: g.to_light,
            distance_m: g.distance_m,
            inverse_square: g.inverse_square,
            profile,
            map_uv,
        })
    }

    /// The direction, distance and inverse square from `point_m` to the light.
    pub fn geometry(&self, point_m: DVec3) -> LightGeometry {
        match &self.shape {
            LightShape::Point {
                position_m,
                radius_m,
                ..
            }
            | LightShape::Spot {
                position_m,
                radius_m,
                ..
            } => {
                let (to_light, r) = toward(*position_m, point_m);
                LightGeometry {
                    to_light,
                    distance_m: r,
                    inverse_square: 1.0 / r.max(*radius_m).powi(2),
                }
            }
            LightShape::Parallel {
                position_m, frame, ..
            } => LightGeometry {
                to_light: -frame.z,
                distance_m: frame.z.dot(point_m - *position_m).max(0.0),
                inverse_square: 1.0,
            },
        }
    }

    /// Whether `point_m` is inside the beam, and then the spot's falloff there and where
    /// the light map is read (Dobashi et al. 2000 Appendix A for a point light's map).
    pub fn beam(&self, point_m: DVec3, g: &LightGeometry) -> Option<(f64, (f64, f64, bool))> {
        match &self.shape {
            LightShape::Point { frame, .. } => {
                let d = frame.local(-g.to_light);
                let theta = d.z.clamp(-1.0, 1.0).acos();
                let phi = d.y.atan2(d.x).rem_euclid(std::f64::consts::TAU);
                let uv = (
                    phi / std::f64::consts::TAU,
                    theta / std::f64::consts::PI,
                    true,
                );
                Some((1.0, uv))
            }
            LightShape::Spot {
                frame,
                cos_cone,
                tan_cone,
                falloff_exponent,
                ..
            } => {
                let d = frame.local(-g.to_light);
                if d.z < *cos_cone || d.z <= 0.0 {
                    return None;
                }
                let (x, y) = (d.x / (d.z * tan_cone), d.y / (d.z * tan_cone));
                Some((
                    d.z.powf(*falloff_exponent),
                    (0.5 + 0.5 * x, 0.5 - 0.5 * y, false),
                ))
            }
            LightShape::Parallel {
                position_m,
                frame,
                half_size_m,
            } => {
                let local = frame.local(point_m - *position_m);
                if local.z < 0.0 {
                    return None;
                }
                match half_size_m {
                    Some([hx, hy]) => {
                        if local.x.abs() > *hx || local.y.abs() > *hy {
                            return None;
                        }
                        Some((
                            1.0,
                            (0.5 + 0.5 * local.x / hx, 0.5 - 0.5 * local.y / hy, false),
                        ))
                    }
                    None => Some((1.0, (0.5, 0.5, false))),
                }
            }
        }
    }

    /// The light's position, where it has one.
    pub fn position_m(&self) -> Option<DVec3> {
        match &self.shape {
            LightShape::Point { position_m, .. } | LightShape::Spot { position_m, .. } => {
                Some(*position_m)
            }
            LightShape::Parallel { .. } => None,
        }
    }
}

/// The unit vector from `point` toward `light` and the distance between them (any unit
/// vector at zero distance).
fn toward(light: DVec3, point: DVec3) -> (DVec3, f64) {
    let d = light - point;
    let r = d.length();
    (d.try_normalize().unwrap_or(DVec3::Y), r)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spot(cone_deg: f64) -> Light {
        let c = cone_deg.to_radians();
        Light {
            shape: LightShape::Spot {
                position_m: DVec3::new(0.0, 20.0, 0.0),
                radius_m: 0.05,
                frame: LightFrame::new(DVec3::NEG_Y, None).unwrap(),
                cos_cone: c.cos(),
                tan_cone: c.tan(),
                falloff_exponent: 2.0,
            },
            emission: Spectral::Constant { value: 1.0 },
            light_map: None,
        }
    }

    #[test]
    fn spot_lights_only_its_cone_with_inverse_square_and_falloff() {
        let light = spot(30.0);
        let below = light.path_from(DVec3::ZERO).unwrap();
        assert!((below.factor() - 1.0 / 400.0).abs() < 1e-15);
        assert!((below.to_light - DVec3::Y).length() < 1e-15);
        assert_eq!(below.map_uv, (0.5, 0.5, false));
        // 20 degrees off the axis: inside, cos^2 falloff.
        let p = DVec3::new(10.0 * 20f64.to_radians().tan(), 10.0, 0.0);
        let path = light.path_from(p).unwrap();
        let r2 = (p - DVec3::new(0.0, 20.0, 0.0)).length_squared();
        assert!((path.factor() - 20f64.to_radians().cos().powi(2) / r2).abs() < 1e-15);
        // 35 degrees off: outside the cone; above the light: outside.
        let p = DVec3::new(10.0 * 35f64.to_radians().tan(), 10.0, 0.0);
        assert!(light.path_from(p).is_none());
        assert!(light.path_from(DVec3::new(0.0, 30.0, 0.0)).is_none());
    }

    #[test]
    fn light_maps_are_laid_out_as_documented() {
        // A point light's map: theta from the axis down the image, phi across it.
        let frame = LightFrame::new(DVec3::NEG_Y, None).unwrap();
        let point = Light {
            shape: LightShape::Point {
                position_m: DVec3::ZERO,
                radius_m: 0.05,
                frame,
            },
            emission: Spectral::Constant { value: 1.0 },
            light_map: None,
        };
        let uv = |light: &Light, p: DVec3| light.path_from(p).unwrap().map_uv;
        assert!(uv(&point, DVec3::new(0.0, -5.0, 0.0)).1.abs() < 1e-12);
        assert!((uv(&point, DVec3::new(0.0, 5.0, 0.0)).1 - 1.0).abs() < 1e-12);
        let side = uv(&point, frame.x * 3.0);
        assert!((side.1 - 0.5).abs() < 1e-12 && side.0.abs() < 1e-12 && side.2);
        let quarter = uv(&point, frame.y * 3.0);
        assert!((quarter.0 - 0.25).abs() < 1e-12);
        // A spot's map (its axis is -y too, so its frame is `frame`): x to the right of
        // the image, y up.
        let light = spot(30.0);
        let below = DVec3::new(0.0, 10.0, 0.0);
        let (u, v, wrap) = uv(&light, below + frame.x);
        assert!(u > 0.5 && (v - 0.5).abs() < 1e-12 && !wrap);
        let (u, v, _) = uv(&light, below + frame.y);
        assert!((u - 0.5).abs() < 1e-12 && v < 0.5);
        // At the cone's edge along x the map's edge: u = 1.
        let edge = below + frame.x * (10.0 * 30f64.to_radians().tan() * 0.999_999);
        assert!((uv(&light, edge).0 - 1.0).abs() < 1e-5);
    }

    #[test]
    fn parallel_light_lights_its_rectangle_downstream_of_its_plane() {
        let light = Light {
            shape: LightShape::Parallel {
                position_m: DVec3::new(0.0, 5.0, 0.0),
                frame: LightFrame::new(DVec3::NEG_Y, None).unwrap(),
                half_size_m: Some([1.0, 2.0]),
            },
            emission: Spectral::Constant { value: 1.0 },
            light_map: None,
        };
        let path = light.path_from(DVec3::new(0.5, 2.0, 0.0)).unwrap();
        assert!((path.distance_m - 3.0).abs() < 1e-15);
        assert_eq!(path.factor(), 1.0);
        assert!(light.path_from(DVec3::new(1.5, 2.0, 0.0)).is_none());
        assert!(light.path_from(DVec3::new(0.0, 6.0, 0.0)).is_none());
    }
}
