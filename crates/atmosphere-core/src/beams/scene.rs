//! A beams scene, checked and with its files loaded: read from TOML (`scene_file.rs`),
//! every value checked with an error naming its field, light maps decoded, glTF meshes
//! gathered into one BVH. Paths in the file are relative to the file's folder.

use std::path::{Path, PathBuf};

use glam::DVec3;

use crate::atmosphere::spectral::Spectral;
use crate::atmosphere::text_file::{TOML_LIMITS, read_text};
use crate::beams::bvh::Bvh;
use crate::beams::camera::Camera;
use crate::beams::error::BeamError;
use crate::beams::gltf_mesh::load_triangles;
use crate::beams::light::{Light, LightShape};
use crate::beams::light_frame::LightFrame;
use crate::beams::light_map::LightMap;
use crate::beams::medium::Medium;
use crate::beams::occluder::Primitive;
use crate::beams::occluders::Occluders;
use crate::beams::scene_file::{CameraFile, LightFile, MediumFile, OccluderFile, SceneFile};

/// A point light's or spot's radius when none is given, m: a bulb, inside which the
/// inverse-square law stops growing.
pub const DEFAULT_LIGHT_RADIUS_M: f64 = 0.05;

/// The most lights a scene may hold.
pub const MAX_LIGHTS: usize = 64;
/// The largest scattering or absorption coefficient, m^-1 (a light's 1/e distance of a
/// micrometre): beyond it nothing is visible, and the products stay finite.
pub const MAX_COEFFICIENT_PER_M: f64 = 1e6;
/// The largest intensity (W sr^-1 nm^-1) or irradiance (W m^-2 nm^-1) of a light.
pub const MAX_EMISSION: f64 = 1e12;
/// The largest coordinate, size or distance in a scene, m.
pub const MAX_COORDINATE_M: f64 = 1e7;
/// The smallest radius of a point light or spot, m (the inverse square stays finite).
pub const MIN_LIGHT_RADIUS_M: f64 = 1e-4;

/// A checked scene.
#[derive(Clone, Debug, PartialEq)]
pub struct BeamScene {
    pub medium: Medium,
    pub lights: Vec<Light>,
    pub occluders: Occluders,
    pub camera: Camera,
}

impl BeamScene {
    /// Reads the scene file at `path`.
    pub fn load(path: &Path) -> Result<BeamScene, BeamError> {
        let text = read_text(path, TOML_LIMITS)?;
        let folder = path.parent().unwrap_or(Path::new("."));
        BeamScene::from_toml(&text, &path.display().to_string(), folder)
    }

    /// The scene of TOML `text`, named `file` in messages, its paths relative to
    /// `folder`.
    pub fn from_toml(text: &str, file: &str, folder: &Path) -> Result<BeamScene, BeamError> {
        let parsed: SceneFile = toml::from_str(text).map_err(|e| BeamError::Toml {
            file: file.to_string(),
            reason: e.to_string(),
        })?;
        BeamScene::from_file(&parsed, file, folder)
    }

    /// The scene of a parsed (or edited) file, checked as a file's text is, named
    /// `file` in messages, its paths relative to `folder`.
    pub fn from_file(
        parsed: &SceneFile,
        file: &str,
        folder: &Path,
    ) -> Result<BeamScene, BeamError> {
        Check { file, folder }.scene(parsed)
    }
}

/// Checks a parsed file, naming the file in its errors.
struct Check<'a> {
    file: &'a str,
    folder: &'a Path,
}

impl Check<'_> {
    fn error(&self, field: &str, reason: impl Into<String>) -> BeamError {
        BeamError::Field {
            file: self.file.to_string(),
            field: field.to_string(),
            reason: reason.into(),
        }
    }

    fn scene(&self, f: &SceneFile) -> Result<BeamScene, BeamError> {
        if f.lights.len() > MAX_LIGHTS {
            return Err(self.error(
                "lights",
                format!("{} lights; at most {MAX_LIGHTS}", f.lights.len()),
            ));
        }
        let lights = f
            .lights
            .iter()
            .enumerate()
            .map(|(i, l)| self.light(&format!("lights[{i}]"), l))
            .collect::<Result<_, _>>()?;
        let mut occluders = Occluders::default();
        let mut triangles = Vec::new();
        for (i, o) in f.occluders.iter().enumerate() {
            let field = format!("occluders[{i}]");
            match self.occluder(&field, o)? {
                Shape::Primitive(p) => occluders.primitives.push(p),
                Shape::Mesh(t) => triangles.extend(t),
            }
        }
        occluders.triangles = Bvh::new(triangles);
        Ok(BeamScene {
            medium: self.medium(&f.medium)?,
            lights,
            occluders,
            camera: self.camera(&f.camera)?,
        })
    }

    fn medium(&self, m: &MediumFile) -> Result<Medium, BeamError> {
        let max = MAX_COEFFICIENT_PER_M;
        self.spectral("medium.scattering_per_m", &m.scattering_per_m, max)?;
        self.spectral("medium.absorption_per_m", &m.absorption_per_m, max)?;
        if let Some(problem) = m.phase.problem() {
            return Err(self.error("medium.phase", problem));
        }
        Ok(Medium {
            scattering_per_m: m.scattering_per_m.clone(),
            absorption_per_m: m.absorption_per_m.clone(),
            phase: m.phase.clone(),
        })
    }

    /// A spectral quantity, at most `max` over the visible range (checked every 5 nm
    /// from 360 to 830 nm).
    fn spectral(&self, field: &str, s: &Spectral, max: f64) -> Result<(), BeamError> {
        if let Some(problem) = s.problem() {
            return Err(self.error(field, problem));
        }
        let peak = (0..=94)
            .map(|i| s.at(360.0 + 5.0 * f64::from(i)))
            .fold(0.0, f64::max);
        if peak > max {
            return Err(self.error(
                field,
                format!("{peak:e} exceeds the largest allowed, {max:e}"),
            ));
        }
        Ok(())
    }

    fn point(&self, field: &str, p: [f64; 3]) -> Result<DVec3, BeamError> {
        let v = DVec3::from(p);
        if !(v.is_finite() && v.abs().max_element() <= MAX_COORDINATE_M) {
            return Err(self.error(
                field,
                format!(
                    "{p:?} must be finite, each coordinate at most {MAX_COORDINATE_M:e} m in size"
                ),
            ));
        }
        Ok(v)
    }

    fn direction(&self, field: &str, d: [f64; 3]) -> Result<DVec3, BeamError> {
        self.point(field, d)?
            .try_normalize()
            .ok_or_else(|| self.error(field, format!("{d:?} has no length")))
    }

    fn positive(&self, field: &str, x: f64) -> Result<f64, BeamError> {
        if x.is_finite() && x > 0.0 && x <= MAX_COORDINATE_M {
            Ok(x)
        } else {
            Err(self.error(
                field,
                format!("{x} must be > 0 and at most {MAX_COORDINATE_M:e}"),
            ))
        }
    }

    fn frame(
        &self,
        field: &str,
        axis: DVec3,
        up: Option<[f64; 3]>,
    ) -> Result<LightFrame, BeamError> {
        let up = up
            .map(|u| self.point(&format!("{field}.up"), u))
            .transpose()?;
        LightFrame::new(axis, up)
            .ok_or_else(|| self.error(&format!("{field}.up"), "must not be parallel to the axis"))
    }

    fn light_map(&self, field: &str, path: &Option<String>) -> Result<Option<LightMap>, BeamError> {
        let Some(path) = path else { return Ok(None) };
        let full = self.resolve(path);
        LightMap::load(&full)
            .map(Some)
            .map_err(|reason| BeamError::Image {
                file: self.file.to_string(),
                field: format!("{field}.light_map"),
                path: full.display().to_string(),
                reason,
            })
    }

    fn resolve(&self, path: &str) -> PathBuf {
        self.folder.join(path)
    }

    fn radius(&self, field: &str, r: Option<f64>) -> Result<f64, BeamError> {
        let r = r.unwrap_or(DEFAULT_LIGHT_RADIUS_M);
        if r < MIN_LIGHT_RADIUS_M {
            return Err(self.error(
                &format!("{field}.radius_m"),
                format!("{r} must be at least {MIN_LIGHT_RADIUS_M} m"),
            ));
        }
        self.positive(&format!("{field}.radius_m"), r)
    }

    fn light(&self, field: &str, l: &LightFile) -> Result<Light, BeamError> {
        let at = |name: &str| format!("{field}.{name}");
        let (shape, emission, map) = match l {
            LightFile::Point {
                position_m,
                intensity_w_sr_nm,
                radius_m,
                axis,
                up,
                light_map,
            } => {
                let axis = self.direction(&at("axis"), axis.unwrap_or([0.0, -1.0, 0.0]))?;
                let shape = LightShape::Point {
                    position_m: self.point(&at("position_m"), *position_m)?,
                    radius_m: self.radius(field, *radius_m)?,
                    frame: self.frame(field, axis, *up)?,
                };
                (shape, (intensity_w_sr_nm, "intensity_w_sr_nm"), light_map)
            }
            LightFile::Spot {
                position_m,
                direction,
                cone_deg,
                falloff_exponent,
                intensity_w_sr_nm,
                radius_m,
                up,
                light_map,
            } => {
                if !(cone_deg.is_finite() && *cone_deg > 0.0 && *cone_deg < 89.0) {
                    return Err(self.error(
                        &at("cone_deg"),
                        format!("{cone_deg} must be in (0, 89) degrees"),
                    ));
                }
                if !(falloff_exponent.is_finite() && (0.0..=1000.0).contains(falloff_exponent)) {
                    return Err(self.error(
                        &at("falloff_exponent"),
                        format!("{falloff_exponent} must be in [0, 1000]"),
                    ));
                }
                let axis = self.direction(&at("direction"), *direction)?;
                let cone = cone_deg.to_radians();
                let shape = LightShape::Spot {
                    position_m: self.point(&at("position_m"), *position_m)?,
                    radius_m: self.radius(field, *radius_m)?,
                    frame: self.frame(field, axis, *up)?,
                    cos_cone: cone.cos(),
                    tan_cone: cone.tan(),
                    falloff_exponent: *falloff_exponent,
                };
                (shape, (intensity_w_sr_nm, "intensity_w_sr_nm"), light_map)
            }
            LightFile::Parallel {
                position_m,
                direction,
                irradiance_w_m2_nm,
                size_m,
                up,
                light_map,
            } => {
                let half_size_m = match size_m {
                    Some([w, h]) => Some([
                        0.5 * self.positive(&at("size_m[0]"), *w)?,
                        0.5 * self.positive(&at("size_m[1]"), *h)?,
                    ]),
                    None if light_map.is_some() => {
                        return Err(self.error(
                            &at("size_m"),
                            "a parallel light with a light_map needs the size the map covers",
                        ));
                    }
                    None => None,
                };
                let axis = self.direction(&at("direction"), *direction)?;
                let shape = LightShape::Parallel {
                    position_m: self.point(&at("position_m"), *position_m)?,
                    frame: self.frame(field, axis, *up)?,
                    half_size_m,
                };
                (shape, (irradiance_w_m2_nm, "irradiance_w_m2_nm"), light_map)
            }
        };
        let (emission, name) = emission;
        self.spectral(&at(name), emission, MAX_EMISSION)?;
        Ok(Light {
            shape,
            emission: emission.clone(),
            light_map: self.light_map(field, map)?,
        })
    }

    fn occluder(&self, field: &str, o: &OccluderFile) -> Result<Shape, BeamError> {
        let at = |name: &str| format!("{field}.{name}");
        Ok(match o {
            OccluderFile::Sphere { center_m, radius_m } => Shape::Primitive(Primitive::Sphere {
                center: self.point(&at("center_m"), *center_m)?,
                radius: self.positive(&at("radius_m"), *radius_m)?,
            }),
            OccluderFile::Box { min_m, max_m } => {
                let (min, max) = (
                    self.point(&at("min_m"), *min_m)?,
                    self.point(&at("max_m"), *max_m)?,
                );
                if !min.cmplt(max).all() {
                    return Err(self.error(
                        &at("max_m"),
                        format!("{max_m:?} must exceed min_m {min_m:?} on every axis"),
                    ));
                }
                Shape::Primitive(Primitive::Box { min, max })
            }
            OccluderFile::Quad {
                corner_m,
                edge_u_m,
                edge_v_m,
            } => {
                let edge_u = self.point(&at("edge_u_m"), *edge_u_m)?;
                let edge_v = self.point(&at("edge_v_m"), *edge_v_m)?;
                if edge_u.cross(edge_v).length() <= 0.0 {
                    return Err(self.error(
                        &at("edge_v_m"),
                        "the edges must span a parallelogram (not parallel, not zero)",
                    ));
                }
                Shape::Primitive(Primitive::Quad {
                    corner: self.point(&at("corner_m"), *corner_m)?,
                    edge_u,
                    edge_v,
                })
            }
            OccluderFile::Plane { point_m, normal } => Shape::Primitive(Primitive::Plane {
                point: self.point(&at("point_m"), *point_m)?,
                normal: self.direction(&at("normal"), *normal)?,
            }),
            OccluderFile::Gltf {
                file,
                translation_m,
                scale,
            } => {
                let translation = self.point(&at("translation_m"), *translation_m)?;
                let scale = self.positive(&at("scale"), *scale)?;
                let full = self.resolve(file);
                let triangles = load_triangles(&full).map_err(|reason| BeamError::Gltf {
                    file: self.file.to_string(),
                    field: at("file"),
                    path: full.display().to_string(),
                    reason,
                })?;
                let placed = triangles
                    .into_iter()
                    .map(|t| crate::beams::triangle::Triangle(t.0.map(|p| p * scale + translation)))
                    .collect();
                Shape::Mesh(placed)
            }
        })
    }

    fn camera(&self, c: &CameraFile) -> Result<Camera, BeamError> {
        let position_m = self.point("camera.position_m", c.position_m)?;
        let look_at = self.point("camera.look_at_m", c.look_at_m)?;
        let forward = (look_at - position_m)
            .try_normalize()
            .ok_or_else(|| self.error("camera.look_at_m", "must differ from position_m"))?;
        let up_hint = self.direction("camera.up", c.up)?;
        let right = forward
            .cross(up_hint)
            .try_normalize()
            .ok_or_else(|| self.error("camera.up", "must not be parallel to the view direction"))?;
        let fov = c.vertical_fov_deg;
        if !(fov.is_finite() && fov > 0.0 && fov < 179.0) {
            return Err(self.error(
                "camera.vertical_fov_deg",
                format!("{fov} must be in (0, 179) degrees"),
            ));
        }
        for (name, side) in [
            ("camera.width_px", c.width_px),
            ("camera.height_px", c.height_px),
        ] {
            if !(1..=16384).contains(&side) {
                return Err(self.error(name, format!("{side} must be in 1..=16384")));
            }
        }
        Ok(Camera {
            position_m,
            forward,
            right,
            up: right.cross(forward),
            vertical_fov_deg: fov,
            width_px: c.width_px,
            height_px: c.height_px,
        })
    }
}

/// What an occluder entry becomes.
enum Shape {
    Primitive(Primitive),
    Mesh(Vec<crate::beams::triangle::Triangle>),
}
