//! Virtual planes with lattice meshes, projected light maps and shadow maps: Dobashi,
//! Yamamoto and Nishita 2000, section 5, on the CPU.
//!
//! `planes` planes perpendicular to the camera's view direction, evenly spaced out to
//! `far_m`, sample every ray at its crossings (Eq. 5: I_s = sum over k of
//! I(theta_k, phi_k) xi(t_k) dt, dt the ray's spacing between planes). The smooth factor
//! xi = sigma_s F(alpha) exp(-sigma_t (t + r)) / r^2 is computed at the `lattice` x
//! `lattice` points of each plane, which span the camera's frustum, and interpolated
//! linearly over the two triangles of each lattice cell, split along the diagonal from
//! its top-left to its bottom-right corner (the paper's Gouraud shading, as a rasteriser
//! interpolates it: the GPU twin draws these triangles); the sharp factors, the light's intensity
//! distribution with its cone and light map (the projected light-map texture) and the
//! shadow (the shadow map, section 5.2), are evaluated at each sample. The planes belong
//! to the scene's camera: rays must start at its position.

use glam::DVec3;

use crate::beams::camera::Camera;
use crate::beams::error::BeamError;
use crate::beams::in_scattering::{EXTINGUISHED_OPTICAL_DEPTH, InScattering, light_map_rgb};
use crate::beams::light::LightPath;
use crate::beams::methods::method::{BeamMethod, BeamSettings};
use crate::beams::ray::SceneRay;
use crate::beams::scene::BeamScene;
use crate::beams::shadow_map::ShadowMap;
use crate::models::error::ModelError;
use crate::models::options::Setting;

/// Virtual planes (Table 1: 150 for the spotlight scenes, 50 for sunlight).
pub const PLANES: Setting<usize> = Setting {
    model: "planes2000",
    key: "planes",
    range: 1..=4096,
};
/// Lattice points on a side of each plane (Table 1: 20 x 20).
pub const LATTICE: Setting<usize> = Setting {
    model: "planes2000",
    key: "lattice",
    range: 2..=512,
};
/// Texels on a side of each shadow map.
pub const SHADOW_MAP_PX: Setting<usize> = Setting {
    model: "planes2000",
    key: "shadow_map_px",
    range: 16..=8192,
};
/// Depth of the farthest plane along the view direction, m.
pub const FAR_M: Setting<f64> = Setting {
    model: "planes2000",
    key: "far_m",
    range: 1e-3..=1e7,
};
/// The most values of xi stored (planes x lattice points x lights x wavelengths): 2^26,
/// 256 MiB.
pub const MAX_XI_VALUES: usize = 1 << 26;

/// The method's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Planes2000Settings {
    pub planes: usize,
    pub lattice: usize,
    pub shadow_map_px: usize,
    pub far_m: f64,
}

/// The method prepared for a scene: xi on every lattice point, the shadow maps.
#[derive(Debug)]
pub struct Planes2000 {
    scattering: InScattering,
    shadow_maps: Vec<ShadowMap>,
    settings: Planes2000Settings,
    camera: Camera,
    tan_half: [f64; 2],
    /// xi at (plane, row, column, light, wavelength), row-major in that order; f32, as
    /// a GPU's lattice textures hold it.
    xi: Vec<f32>,
}

impl Planes2000 {
    /// The planes for `scene` seen from its camera; `far_m` defaults to the farthest
    /// light or finite occluder along the view direction (at most where the medium
    /// has extinguished the light).
    pub fn new(scene: &BeamScene, settings: &BeamSettings) -> Result<Planes2000, BeamError> {
        let scattering = InScattering::new(scene, &settings.wavelengths_nm);
        let default_far = content_depth(&scattering);
        let mut reader = settings.options.reader("planes2000");
        let own = Planes2000Settings {
            planes: reader.count(&PLANES, 150)?,
            lattice: reader.count(&LATTICE, 20)?,
            shadow_map_px: reader.count(&SHADOW_MAP_PX, 512)?,
            far_m: reader.number(&FAR_M, default_far)?,
        };
        reader.finish()?;
        let values = own.planes * own.lattice * own.lattice;
        let values = values * scene.lights.len() * settings.wavelengths_nm.len();
        if values > MAX_XI_VALUES {
            return Err(ModelError::Settings(format!(
                "planes2000: planes={} and lattice={} store {values} values of xi; at most {MAX_XI_VALUES}",
                own.planes, own.lattice
            ))
            .into());
        }
        let camera = scene.camera.clone();
        let tan_y = (0.5 * camera.vertical_fov_deg.to_radians()).tan();
        let aspect = f64::from(camera.width_px) / f64::from(camera.height_px);
        let mut method = Planes2000 {
            shadow_maps: scene
                .lights
                .iter()
                .map(|l| ShadowMap::new(l, &scene.occluders, own.shadow_map_px))
                .collect(),
            scattering,
            settings: own,
            camera,
            tan_half: [tan_y * aspect, tan_y],
            xi: Vec::new(),
        };
        method.xi = method.lattice_xi();
        Ok(method)
    }

    fn spacing_m(&self) -> f64 {
        self.settings.far_m / self.settings.planes as f64
    }

    /// Step (a) of section 5.3: xi at every lattice point of every plane.
    fn lattice_xi(&self) -> Vec<f32> {
        let (n, lights, wl) = (
            self.settings.lattice,
            self.scattering.scene.lights.len(),
            self.scattering.wavelengths_nm.len(),
        );
        let medium = &self.scattering.medium;
        let phase = &self.scattering.scene.medium.phase;
        let cam = &self.camera;
        let mut xi = Vec::with_capacity(self.settings.planes * n * n * lights * wl);
        for k in 0..self.settings.planes {
            let depth = (k as f64 + 0.5) * self.spacing_m();
            for j in 0..n {
                let y = 1.0 - 2.0 * j as f64 / (n - 1) as f64;
                for i in 0..n {
                    let x = -1.0 + 2.0 * i as f64 / (n - 1) as f64;
                    let offset = cam.forward
                        + cam.right * (x * self.tan_half[0])
                        + cam.up * (y * self.tan_half[1]);
                    let point = cam.position_m + offset * depth;
                    let t = offset.length() * depth;
                    let view = offset.normalize();
                    for light in &self.scattering.scene.lights {
                        let g = light.geometry(point);
                        let f = phase.eval(g.to_light.dot(view)) * g.inverse_square;
                        for w in 0..wl {
                            let attenuation =
                                (-medium.extinction_per_m[w] * (t + g.distance_m)).exp();
                            xi.push((medium.scattering_per_m[w] * f * attenuation) as f32);
                        }
                    }
                }
            }
        }
        xi
    }

    /// The settings read from the options.
    pub fn settings(&self) -> Planes2000Settings {
        self.settings
    }

    /// The scene's lights and medium at the method's wavelengths.
    pub fn scattering(&self) -> &InScattering {
        &self.scattering
    }

    /// Each light's shadow map, in the scene's order.
    pub fn shadow_maps(&self) -> &[ShadowMap] {
        &self.shadow_maps
    }

    /// xi of `light` at wavelength `w` on plane `k` at the lattice coordinates
    /// (fi, fj), linear over the cell's triangle that holds the point: (i0, j0),
    /// (i0 + 1, j0), (i0 + 1, j0 + 1) where fi - i0 >= fj - j0, else (i0, j0),
    /// (i0 + 1, j0 + 1), (i0, j0 + 1).
    fn xi_at(&self, k: usize, fi: f64, fj: f64, light: usize, w: usize) -> f64 {
        let n = self.settings.lattice;
        let (lights, wl) = (
            self.scattering.scene.lights.len(),
            self.scattering.wavelengths_nm.len(),
        );
        let (i0, j0) = (
            (fi.floor() as usize).min(n - 2),
            (fj.floor() as usize).min(n - 2),
        );
        let (a, b) = (fi - i0 as f64, fj - j0 as f64);
        let at = |i: usize, j: usize| {
            f64::from(self.xi[(((k * n + j) * n + i) * lights + light) * wl + w])
        };
        let (corner, diagonal) = (at(i0, j0), at(i0 + 1, j0 + 1));
        if a >= b {
            corner + a * (at(i0 + 1, j0) - corner) + b * (diagonal - at(i0 + 1, j0))
        } else {
            corner + b * (at(i0, j0 + 1) - corner) + a * (diagonal - at(i0, j0 + 1))
        }
    }
}

/// The farthest light position or finite occluder corner along the camera's view, with
/// a margin of 10 %, at most the extinguished distance.
fn content_depth(scattering: &InScattering) -> f64 {
    let scene = &scattering.scene;
    let cam = &scene.camera;
    let mut points: Vec<DVec3> = scene.lights.iter().filter_map(|l| l.position_m()).collect();
    if let Some((lo, hi)) = scene.occluders.finite_bounds() {
        points.extend((0..8).map(|i| {
            DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        }));
    }
    let thinnest = scattering.medium.thinnest_extinction_per_m();
    let extinguished = (EXTINGUISHED_OPTICAL_DEPTH / thinnest).min(FAR_M.range.end().to_owned());
    let farthest = points
        .iter()
        .map(|p| (*p - cam.position_m).dot(cam.forward))
        .fold(0.0, f64::max);
    if farthest > 0.0 {
        (1.1 * farthest).min(extinguished).max(*FAR_M.range.start())
    } else {
        extinguished
    }
}

impl BeamMethod for Planes2000 {
    fn radiance(&self, ray: &SceneRay) -> Result<Vec<f64>, BeamError> {
        let cam = &self.camera;
        let wl = self.scattering.wavelengths_nm.len();
        let mut sum = vec![0.0; wl];
        let Some(cos_forward) = cam.forward_cosine("planes2000", ray)? else {
            return Ok(sum);
        };
        let t_end = self.scattering.ray_end_m(ray);
        let n = (self.settings.lattice - 1) as f64;
        let occluders = &self.scattering.scene.occluders;
        for k in 0..self.settings.planes {
            let depth = (k as f64 + 0.5) * self.spacing_m();
            let t = depth / cos_forward;
            if t >= t_end {
                break;
            }
            let point = ray.at(t);
            let rel = point - cam.position_m;
            let x = rel.dot(cam.right) / (depth * self.tan_half[0]);
            let y = rel.dot(cam.up) / (depth * self.tan_half[1]);
            let fi = (0.5 * (x + 1.0) * n).clamp(0.0, n);
            let fj = (0.5 * (1.0 - y) * n).clamp(0.0, n);
            for (l, light) in self.scattering.scene.lights.iter().enumerate() {
                let g = light.geometry(point);
                let Some((profile, map_uv)) = light.beam(point, &g) else {
                    continue;
                };
                let path = LightPath {
                    to_light: g.to_light,
                    distance_m: g.distance_m,
                    inverse_square: g.inverse_square,
                    profile,
                    map_uv,
                };
                let lit = self.shadow_maps[l].visibility(occluders, point, &path);
                if lit <= 0.0 {
                    continue;
                }
                let rgb = light_map_rgb(light, &path);
                let emission = &self.scattering.emission[l];
                for w in 0..wl {
                    let intensity = emission[w] * profile * self.scattering.filter(rgb, w);
                    sum[w] += intensity * lit * self.xi_at(k, fi, fj, l, w);
                }
            }
        }
        let dt = self.spacing_m() / cos_forward;
        Ok(sum.into_iter().map(|s| s * dt).collect())
    }
}
