//! The pre-integrated q(u, v) table with adaptive sub-planes: Dobashi, Yamamoto and
//! Nishita 2002, section 4.2, on the CPU.
//!
//! Each plane interval [t_k, t_k + dt] of a view ray contributes f_h f_l (Eq. 6): f_l,
//! the integral of the smooth g of Eq. 3, read from the table q (Eq. 8-9, `q_table.rs`,
//! `interval.rs`); f_h, the mean of the light's intensity I_l (emission, spot falloff,
//! light map) times its visibility H over the m_k samples of the interval (Eq. 10), H
//! from the shadow maps (`shadow_map.rs`). The planes are perpendicular to the camera's
//! view direction, dt apart, over the depths of each light's bounding volume
//! (`planes.rs`); dt is the largest multiple of `delta_min_m` up to `delta_max_m` whose
//! table stays within `i_max` (section 4.2.1). m_k comes from f_l on the centre ray and
//! epsilon (section 4.2.2; `planes.rs` says how epsilon is scaled). Rays must start at the scene camera's position.
//!
//! Where the paper leaves a choice: an oblique ray crosses the planes dt / cos apart, so
//! its intervals are that long and read the table once per dt of them (the paper keeps
//! dt, leaving gaps off the screen's centre); an interval cut by an occluder counts its
//! share of q and the mean of f_h over the samples in front of the occluder; the m_k
//! samples are dt / m_k apart from the main plane (Eq. 10's dt / (m_k - 1) would put the
//! last on the next main plane, counting it twice). A light's planes cover the part of
//! the screen its bounding volume projects to (widened by a pixel), as the GPU draws
//! them: rays outside it get nothing from that light. With `resolution_divisor` above 1
//! (not the paper's) a ray's answer is its pixel's in the frame of the camera's size
//! walked at reduced resolution and upsampled (`upsample.rs`).

pub mod interval;
pub mod planes;
pub mod q_table;
pub mod sample_weights;
pub mod upsample;

use crate::beams::camera::Camera;
use crate::beams::error::BeamError;
use crate::beams::in_scattering::{EXTINGUISHED_OPTICAL_DEPTH, InScattering, light_map_rgb};
use crate::beams::light::LightShape;
use crate::beams::methods::method::{BeamMethod, BeamSettings};
use crate::beams::plan::{screen_bounds, volume_corners};
use crate::beams::ray::SceneRay;
use crate::beams::scene::{BeamScene, DEFAULT_LIGHT_RADIUS_M};
use crate::beams::shadow_map::ShadowMap;
use crate::models::error::ModelError;
use crate::models::options::{OptionReader, Setting};

use interval::f_l;
use planes::{
    LightPlanes, PlaneContext, SUBPLANES_PER_RAY, SubPlaneRule, default_d0, volume_depths,
};
use q_table::{QExtent, QTable};
use sample_weights::{WEIGHTED_SAMPLES, smooth_factor};
use upsample::{RESOLUTION_DIVISOR, Tap, UPSAMPLE_TOLERANCE, Upsample, upsampled};

const MODEL: &str = "qtable2002";

/// The first plane interval tried, m (the paper starts from a small dt_min and gives no
/// value; 0.1 m makes the 1.2 m of its Fig. 5 a multiple).
pub const DELTA_MIN_M: Setting<f64> = Setting {
    model: MODEL,
    key: "delta_min_m",
    range: 1e-4..=1e4,
};
/// The largest plane interval, m (the paper's dt_max; default the 1.2 m of Fig. 5).
pub const DELTA_MAX_M: Setting<f64> = Setting {
    model: MODEL,
    key: "delta_max_m",
    range: 1e-4..=1e4,
};
/// The largest value the table may hold, m^-2 sr^-1 (the paper's I_max: 1.0).
pub const I_MAX: Setting<f64> = Setting {
    model: MODEL,
    key: "i_max",
    range: 1e-12..=1e12,
};
/// The sub-plane threshold on f_l / m_k as a share of the centre ray's f_l (the paper's
/// epsilon: 0.01).
pub const EPSILON: Setting<f64> = Setting {
    model: MODEL,
    key: "epsilon",
    range: 0.0..=1.0,
};
/// The most sub-planes in one plane interval (the paper sets none; 64).
pub const MAX_SUBPLANES: Setting<usize> = Setting {
    model: MODEL,
    key: "max_subplanes",
    range: 0..=4096,
};
/// Nodes of the table along u (the paper gives no resolution; 256).
pub const TABLE_U: Setting<usize> = Setting {
    model: MODEL,
    key: "table_u",
    range: 2..=4096,
};
/// Nodes of the table along v (256).
pub const TABLE_V: Setting<usize> = Setting {
    model: MODEL,
    key: "table_v",
    range: 2..=4096,
};
/// Texels on a side of each shadow map (512).
pub const SHADOW_MAP_PX: Setting<usize> = Setting {
    model: MODEL,
    key: "shadow_map_px",
    range: 16..=8192,
};
/// The reach of every light's bounding volume, m (the paper's d0, set by the user; by
/// default where a spot's pyramid meets the occluders, else where the medium has
/// extinguished the light).
pub const D0_M: Setting<f64> = Setting {
    model: MODEL,
    key: "d0_m",
    range: 1e-3..=1e7,
};
/// How the GPU draws the planes: `true`, as the paper does, one blended pass per plane
/// and sample over the light's part of the screen; `false` (the default), the same
/// samples walked per pixel in one pass per light, visiting only the intervals where the
/// ray is in the light's beam. The CPU's sum is the same either way.
pub const GPU_RASTER_PLANES: &str = "gpu_raster_planes";
/// The most table entries (nodes x wavelengths): 2^26.
pub const MAX_TABLE_VALUES: usize = 1 << 26;
/// The most planes of one light.
pub const MAX_PLANES: usize = 1 << 16;

/// The method's settings (`d0_m` `None`: each light's default).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Qtable2002Settings {
    pub delta_min_m: f64,
    pub delta_max_m: f64,
    pub i_max: f64,
    pub epsilon: f64,
    pub max_subplanes: usize,
    pub table_u: usize,
    pub table_v: usize,
    pub shadow_map_px: usize,
    pub d0_m: Option<f64>,
    /// [`GPU_RASTER_PLANES`].
    pub gpu_raster_planes: bool,
    /// [`WEIGHTED_SAMPLES`].
    pub weighted_samples: bool,
    /// [`SUBPLANES_PER_RAY`].
    pub subplanes_per_ray: bool,
    /// [`RESOLUTION_DIVISOR`] and [`UPSAMPLE_TOLERANCE`]: `None` at divisor 1.
    pub upsample: Option<Upsample>,
}

impl Qtable2002Settings {
    /// The settings from `r`; `d0_m` is read only when `d0_given`.
    fn read(r: &mut OptionReader<'_>, d0_given: bool) -> Result<Qtable2002Settings, ModelError> {
        let own = Qtable2002Settings {
            delta_min_m: r.number(&DELTA_MIN_M, 0.1)?,
            delta_max_m: r.number(&DELTA_MAX_M, 1.2)?,
            i_max: r.number(&I_MAX, 1.0)?,
            epsilon: r.number(&EPSILON, 0.01)?,
            max_subplanes: r.count(&MAX_SUBPLANES, 64)?,
            table_u: r.count(&TABLE_U, 256)?,
            table_v: r.count(&TABLE_V, 256)?,
            shadow_map_px: r.count(&SHADOW_MAP_PX, 512)?,
            d0_m: if d0_given {
                Some(r.number(&D0_M, 1.0)?)
            } else {
                None
            },
            gpu_raster_planes: r.flag(GPU_RASTER_PLANES, false)?,
            weighted_samples: r.flag(WEIGHTED_SAMPLES, false)?,
            subplanes_per_ray: r.flag(SUBPLANES_PER_RAY, false)?,
            upsample: {
                let divisor = r.count(&RESOLUTION_DIVISOR, 1)?;
                let tolerance = r.number(&UPSAMPLE_TOLERANCE, 0.5)?;
                (divisor > 1).then_some(Upsample {
                    divisor: divisor as u32,
                    tolerance,
                })
            },
        };
        if own.subplanes_per_ray && own.gpu_raster_planes {
            return Err(ModelError::Settings(format!(
                "qtable2002: {SUBPLANES_PER_RAY}=true with {GPU_RASTER_PLANES}=true: drawn \
                 planes give every pixel the centre ray's sub-planes; a ray counts its own \
                 only where the planes are walked per pixel ({GPU_RASTER_PLANES}=false)"
            )));
        }
        if own.delta_min_m > own.delta_max_m {
            return Err(ModelError::Settings(format!(
                "qtable2002: delta_min_m={} exceeds delta_max_m={}",
                own.delta_min_m, own.delta_max_m
            )));
        }
        Ok(own)
    }
}

/// The method prepared for a scene: the table, every light's planes and shadow map.
#[derive(Debug)]
pub struct Qtable2002 {
    scattering: InScattering,
    shadow_maps: Vec<ShadowMap>,
    camera: Camera,
    table: QTable,
    planes: Vec<LightPlanes>,
    /// Each light's part of the screen (`plan::screen_bounds` of its bounding volume).
    bounds: Vec<[f64; 4]>,
    gpu_raster_planes: bool,
    weighted_samples: bool,
    /// The rule each ray counts its own sub-planes by ([`SUBPLANES_PER_RAY`]); `None`:
    /// every ray takes the centre ray's m_k.
    per_ray_rule: Option<SubPlaneRule>,
    upsample: Option<Upsample>,
}

impl Qtable2002 {
    /// The table, planes and shadow maps for `scene` seen from its camera.
    pub fn new(scene: &BeamScene, settings: &BeamSettings) -> Result<Qtable2002, BeamError> {
        let mut reader = settings.options.reader(MODEL);
        let d0_given = settings.options.items().any(|(k, _)| k == D0_M.key);
        let own = Qtable2002Settings::read(&mut reader, d0_given)?;
        reader.finish()?;
        let wavelengths = settings.wavelengths_nm.len();
        let values = own.table_u * own.table_v * wavelengths;
        if values > MAX_TABLE_VALUES {
            return Err(ModelError::Settings(format!(
                "qtable2002: table_u={} and table_v={} store {values} values at {wavelengths} wavelengths; at most {MAX_TABLE_VALUES}",
                own.table_u, own.table_v
            ))
            .into());
        }
        let scattering = InScattering::new(scene, &settings.wavelengths_nm);
        let thinnest = scattering.medium.thinnest_extinction_per_m();
        let extinguished_m = (EXTINGUISHED_OPTICAL_DEPTH / thinnest).min(*D0_M.range.end());
        let camera = scene.camera.clone();
        let d0: Vec<f64> = scene
            .lights
            .iter()
            .map(|light| {
                own.d0_m.unwrap_or_else(|| {
                    default_d0(light, &scene.occluders, extinguished_m).max(*D0_M.range.start())
                })
            })
            .collect();
        let depths: Vec<(f64, f64)> = scene
            .lights
            .iter()
            .zip(&d0)
            .map(|(light, &d0)| volume_depths(light, d0, &camera, extinguished_m))
            .collect();
        let bounds = scene
            .lights
            .iter()
            .zip(&d0)
            .map(|(light, &d0)| match volume_corners(light, d0) {
                Some(corners) => screen_bounds(&camera, &corners),
                None => [-1.0, -1.0, 1.0, 1.0],
            })
            .collect();
        let extent = table_extent(scene, &camera, &depths, own.delta_max_m);
        let nodes = if extent.is_some() {
            [own.table_u, own.table_v]
        } else {
            [2, 2]
        };
        let extent = extent.unwrap_or(QExtent {
            u_min_m: -1.0,
            u_max_m: 1.0,
            v_min_m: DEFAULT_LIGHT_RADIUS_M,
            v_max_m: 1.0,
        });
        let build =
            |dt: f64| QTable::new(&scattering.medium, &scene.medium.phase, extent, nodes, dt);
        let table = choose_interval(&own, build);
        let context = PlaneContext {
            table: &table,
            medium: &scattering.medium,
            phase: &scene.medium.phase,
            camera: &camera,
        };
        let rule = SubPlaneRule {
            epsilon: own.epsilon,
            max_subplanes: own.max_subplanes,
        };
        let mut planes = Vec::with_capacity(scene.lights.len());
        for (l, (light, &(lo, hi))) in scene.lights.iter().zip(&depths).enumerate() {
            let count = (hi - lo) / table.interval_m();
            if count >= MAX_PLANES as f64 {
                return Err(ModelError::Settings(format!(
                    "qtable2002: lights[{l}]'s beam spans {:.6} m of depth, {count:.0} planes {} m apart; at most {MAX_PLANES} (raise delta_min_m or lower d0_m)",
                    hi - lo,
                    table.interval_m()
                ))
                .into());
            }
            planes.push(LightPlanes::new(&context, light, (lo, hi), rule));
        }
        Ok(Qtable2002 {
            shadow_maps: scene
                .lights
                .iter()
                .map(|l| ShadowMap::new(l, &scene.occluders, own.shadow_map_px))
                .collect(),
            scattering,
            camera,
            table,
            planes,
            bounds,
            gpu_raster_planes: own.gpu_raster_planes,
            weighted_samples: own.weighted_samples,
            per_ray_rule: own.subplanes_per_ray.then_some(rule),
            upsample: own.upsample,
        })
    }

    /// The plane interval dt chosen from the table, m.
    pub fn interval_m(&self) -> f64 {
        self.table.interval_m()
    }

    /// The table.
    pub fn table(&self) -> &QTable {
        &self.table
    }

    /// The scene's lights and medium at the method's wavelengths.
    pub fn scattering(&self) -> &InScattering {
        &self.scattering
    }

    /// Each light's shadow map, in the scene's order.
    pub fn shadow_maps(&self) -> &[ShadowMap] {
        &self.shadow_maps
    }

    /// Whether each sample is weighted by g at it ([`WEIGHTED_SAMPLES`]).
    pub fn weighted_samples(&self) -> bool {
        self.weighted_samples
    }

    /// Whether each ray counts its own sub-planes ([`SUBPLANES_PER_RAY`]), and by what
    /// rule.
    pub fn subplanes_per_ray(&self) -> Option<SubPlaneRule> {
        self.per_ray_rule
    }

    /// Each light's part of the screen, normalised device coordinates [x0, y0, x1, y1]:
    /// its planes are drawn there alone.
    pub fn screen_bounds(&self) -> &[[f64; 4]] {
        &self.bounds
    }

    /// Whether the GPU draws the planes one by one ([`GPU_RASTER_PLANES`]).
    pub fn gpu_raster_planes(&self) -> bool {
        self.gpu_raster_planes
    }

    /// The reduced walk and its upsampling, where set ([`RESOLUTION_DIVISOR`] above 1).
    pub fn upsample(&self) -> Option<Upsample> {
        self.upsample
    }

    /// Each light's planes and sub-plane counts.
    pub fn planes(&self) -> &[LightPlanes] {
        &self.planes
    }
}

/// Section 4.2.1's interval: dt grows from `delta_min_m` by `delta_min_m` up to
/// `delta_max_m` while the table's largest value stays within `i_max` (that value grows
/// with dt, since q integrates a positive function over [u, u + dt], so the search
/// halves); at least `delta_min_m`. Returns the table built at that dt.
fn choose_interval(own: &Qtable2002Settings, build: impl Fn(f64) -> QTable) -> QTable {
    let steps = ((own.delta_max_m / own.delta_min_m) * (1.0 + 1e-12)).floor() as usize;
    let at = |n: usize| build(own.delta_min_m * n as f64);
    let widest = at(steps);
    if widest.max_value() <= own.i_max || steps == 1 {
        return widest;
    }
    let (mut good, mut bad) = (1, steps);
    let mut table = at(1);
    if table.max_value() > own.i_max {
        return table;
    }
    while bad - good > 1 {
        let mid = (good + bad) / 2;
        let candidate = at(mid);
        if candidate.max_value() <= own.i_max {
            good = mid;
            table = candidate;
        } else {
            bad = mid;
        }
    }
    table
}

/// The (u, v) region the view rays of the camera's frustum reach for the point lights
/// and spots, `None` when there is none: v from the smallest light radius to the
/// farthest light from the camera, u from before the nearest light to past the farthest
/// plane's end along the frustum's most oblique ray.
fn table_extent(
    scene: &BeamScene,
    camera: &Camera,
    depths: &[(f64, f64)],
    delta_max_m: f64,
) -> Option<QExtent> {
    let tan_y = (0.5 * camera.vertical_fov_deg.to_radians()).tan();
    let aspect = f64::from(camera.width_px) / f64::from(camera.height_px);
    let corner_cos = 1.0 / (1.0 + tan_y * tan_y * (1.0 + aspect * aspect)).sqrt();
    let mut extent: Option<QExtent> = None;
    for (light, &(_, hi)) in scene.lights.iter().zip(depths) {
        let (position, radius) = match &light.shape {
            LightShape::Point {
                position_m,
                radius_m,
                ..
            }
            | LightShape::Spot {
                position_m,
                radius_m,
                ..
            } => (*position_m, *radius_m),
            LightShape::Parallel { .. } => continue,
        };
        let r = position.distance(camera.position_m);
        let reach = (hi.max(0.0) + 2.0 * delta_max_m) / corner_cos;
        let this = QExtent {
            u_min_m: -r - delta_max_m,
            u_max_m: r + reach,
            v_min_m: radius,
            v_max_m: r.max(2.0 * radius),
        };
        extent = Some(match extent {
            None => this,
            Some(e) => QExtent {
                u_min_m: e.u_min_m.min(this.u_min_m),
                u_max_m: e.u_max_m.max(this.u_max_m),
                v_min_m: e.v_min_m.min(this.v_min_m),
                v_max_m: e.v_max_m.max(this.v_max_m),
            },
        });
    }
    extent
}

impl BeamMethod for Qtable2002 {
    fn radiance(&self, ray: &SceneRay) -> Result<Vec<f64>, BeamError> {
        let cam = &self.camera;
        let Some(cos_forward) = cam.forward_cosine("qtable2002", ray)? else {
            return Ok(vec![0.0; self.scattering.wavelengths_nm.len()]);
        };
        // Where the ray meets the screen, normalised device coordinates.
        let (tan_y, aspect) = (
            (0.5 * cam.vertical_fov_deg.to_radians()).tan(),
            f64::from(cam.width_px) / f64::from(cam.height_px),
        );
        let ndc = [
            ray.direction.dot(cam.right) / (cos_forward * tan_y * aspect),
            ray.direction.dot(cam.up) / (cos_forward * tan_y),
        ];
        let Some(upsample) = &self.upsample else {
            return Ok(self.walk(ray, cos_forward, ndc));
        };
        let size = (cam.width_px, cam.height_px);
        let frame = (
            0.5 * (ndc[0] + 1.0) * f64::from(size.0),
            0.5 * (1.0 - ndc[1]) * f64::from(size.1),
        );
        let tap = |x: f64, y: f64| {
            let tap_ray = cam.ray(x, y);
            let cos = tap_ray.direction.dot(cam.forward);
            let ndc = [
                tap_ray.direction.dot(cam.right) / (cos * tan_y * aspect),
                tap_ray.direction.dot(cam.up) / (cos * tan_y),
            ];
            Ok(Tap {
                radiance: self.walk(&tap_ray, cos, ndc),
                end_m: self.scattering.ray_end_m(&tap_ray),
            })
        };
        upsampled(upsample, size, frame, tap, || {
            Ok(self.walk(ray, cos_forward, ndc))
        })
    }
}

impl Qtable2002 {
    /// The walk of the planes along `ray` (from the camera, at `cos_forward` to its
    /// view and meeting the screen at `ndc`): every light's intervals and samples.
    fn walk(&self, ray: &SceneRay, cos_forward: f64, ndc: [f64; 2]) -> Vec<f64> {
        let wl = self.scattering.wavelengths_nm.len();
        let mut sum = vec![0.0; wl];
        let t_end = self.scattering.ray_end_m(ray);
        let dt_ray = self.table.interval_m() / cos_forward;
        let occluders = &self.scattering.scene.occluders;
        let phase = &self.scattering.scene.medium.phase;
        let mut f_h = vec![0.0; wl];
        let mut smooth = vec![0.0; wl];
        let mut weight = vec![1.0; wl];
        let mut weight_sum = vec![0.0; wl];
        for (l, light) in self.scattering.scene.lights.iter().enumerate() {
            let [x0, y0, x1, y1] = self.bounds[l];
            if !(x0..=x1).contains(&ndc[0]) || !(y0..=y1).contains(&ndc[1]) {
                continue;
            }
            let planes = &self.planes[l];
            let emission = &self.scattering.emission[l];
            for (k, &centre_m) in planes.samples.iter().enumerate() {
                let t_k = (planes.first_depth_m + k as f64 * self.table.interval_m()) / cos_forward;
                // A plane within a thousandth of the ray's length of its end meets the
                // occluder's surface at a shadow map's resolution, and the map's bias
                // lights it: that sliver of the ray is left out.
                if t_k >= t_end * (1.0 - 1e-3) {
                    break;
                }
                let length = dt_ray.min(t_end - t_k);
                // f_l of the interval (Eq. 7) at each wavelength: first where the ray
                // counts its own samples from it, else only where a sample is lit.
                let interval_f_l = |w: usize| {
                    f_l(
                        &self.table,
                        &self.scattering.medium,
                        phase,
                        light,
                        ray.origin_m,
                        ray.direction,
                        t_k,
                        length,
                        w,
                    )
                };
                let m = match &self.per_ray_rule {
                    Some(rule) => {
                        for (w, f) in smooth.iter_mut().enumerate() {
                            *f = interval_f_l(w);
                        }
                        planes.samples_for(rule, smooth.iter().copied().fold(0.0, f64::max))
                    }
                    None => centre_m,
                };
                // Eq. 10: the mean of I_l H over the main plane and its sub-planes in
                // front of the ray's end (an occluder hides those behind it, and the
                // sliver by its surface is left out for sub-planes as for planes), each
                // sample weighted alike or by g at it (`sample_weights.rs`).
                let spacing = dt_ray / m as f64;
                let in_front = t_end * (1.0 - 1e-3) - t_k;
                let visible = ((in_front / spacing).ceil() as usize).clamp(1, m);
                f_h.fill(0.0);
                weight_sum.fill(0.0);
                let mut base_m = None;
                for j in 0..visible {
                    let t = t_k + j as f64 * spacing;
                    if self.weighted_samples {
                        let path_m = smooth_factor(
                            light,
                            phase,
                            &self.scattering.medium.extinction_per_m,
                            ray,
                            t,
                            base_m,
                            &mut weight,
                        );
                        base_m.get_or_insert(path_m);
                    }
                    for (total, g) in weight_sum.iter_mut().zip(&weight) {
                        *total += g;
                    }
                    let point = ray.at(t);
                    let Some(path) = light.path_from(point) else {
                        continue;
                    };
                    let lit = self.shadow_maps[l].visibility(occluders, point, &path);
                    if lit <= 0.0 {
                        continue;
                    }
                    let rgb = light_map_rgb(light, &path);
                    for (w, f) in f_h.iter_mut().enumerate() {
                        *f += weight[w]
                            * emission[w]
                            * path.profile
                            * self.scattering.filter(rgb, w)
                            * lit;
                    }
                }
                for (w, s) in sum.iter_mut().enumerate() {
                    if f_h[w] > 0.0 {
                        let f = if self.per_ray_rule.is_some() {
                            smooth[w]
                        } else {
                            interval_f_l(w)
                        };
                        *s += f_h[w] / weight_sum[w] * f;
                    }
                }
            }
        }
        sum
    }
}
