//! O'Neil 2004, "Real-time atmospheric scattering": single scattering from a
//! few samples per view ray, with every optical depth and density read from one 2D table.
//!
//! The table ([`OpticalDepthTable`]) has height above the ground (0 to the top of the
//! atmosphere) on one axis and the angle of a ray from the local vertical (0 to 180
//! degrees) on the other, and four channels: Rayleigh density, Rayleigh optical length,
//! Mie density, Mie optical length. The density channels are 0 where the ray meets the
//! planet (the point is in the planet's shadow when the ray goes to the sun); the optical
//! lengths of such rays "pretend the ray didn't hit the planet" and run on through it to
//! the top of the atmosphere. "Optical length" here is the column of the species (the
//! integral of its relative density, m); times the atmosphere's extinction coefficient at
//! a wavelength it is the optical depth, so one table serves every wavelength.
//!
//! Along the view ray the model takes `samples` equal sample rays and, at the centre of
//! each, reads the density and the optical length to the sun from the table; the optical
//! length back to the camera is the difference of two lookups (sample point and camera,
//! same direction), with the direction reversed when the camera is above the point; a
//! camera in space stands at the point where the ray enters the atmosphere. With light
//! shafts, each sample's single scattering is multiplied by the sun's visibility past
//! the terrain from the frame's shadow map (`shafts::ShadowMap`), the shadow test at the
//! samples of Dobashi, Yamamoto and Nishita 2002 (Eq. 12) applied to O'Neil's. See
//! docs/models/oneil.md for the equations, the settings' sources and the measured errors.

use std::f64::consts::PI;

use glam::DVec3;

use crate::atmosphere::Atmosphere;
use crate::atmosphere::table_inputs::Inputs;
use crate::models::error::ModelError;
use crate::models::id::ModelId;
use crate::models::model_base::ModelBase;
use crate::models::options::{ModelOptions, Setting};
use crate::models::settings::ModelSettings;
use crate::models::sky_model::{RayRadiance, SkyModel, SurfacePoint, ViewRay};
use crate::optics::geometry::{distance_to_exit, ray_hits_ground};
use crate::optics::surface_lighting::{SurfaceElement, add_ground_light};
use crate::optics::view_segment::{SegmentEnd, ViewSegment};
use crate::shafts::{ShadowMap, SunVisibility};

/// What trades accuracy for time in O'Neil's model. `Default` is the paper's choice.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OneilSettings {
    /// Sample rays per view ray. O'Neil 2004: "3 or 4 samples seems to be sufficient to make
    /// it look good"; the demo's `m_nSamples = 4`.
    pub samples: usize,
    /// Table nodes along the height axis (ground to top). The paper's text gives no size;
    /// the demo's `CPixelBuffer::MakeOpticalDepthBuffer` uses `nSize = 64` on both axes.
    pub table_heights: usize,
    /// Table nodes along the angle axis (0 to 180 degrees from the vertical); 64 as above.
    pub table_angles: usize,
    /// Midpoint samples along each table ray; the demo's `nSamples = 50`.
    pub table_ray_samples: usize,
}

impl Default for OneilSettings {
    fn default() -> Self {
        OneilSettings {
            samples: 4,
            table_heights: 64,
            table_angles: 64,
            table_ray_samples: 50,
        }
    }
}

/// `samples` and `table_ray_samples`: within what every GPU runs in one loop (well under
/// 65535 trips).
pub const SAMPLES: Setting<usize> = Setting {
    model: "oneil",
    key: "samples",
    range: 1..=4096,
};
pub const TABLE_RAY_SAMPLES: Setting<usize> = Setting {
    model: "oneil",
    key: "table_ray_samples",
    range: 1..=4096,
};
/// `table_heights`, `table_angles`: up to 2048 (64 MB of f32 nodes at 2048 x 2048).
pub const TABLE_HEIGHTS: Setting<usize> = Setting {
    model: "oneil",
    key: "table_heights",
    range: 2..=2048,
};
pub const TABLE_ANGLES: Setting<usize> = Setting {
    model: "oneil",
    key: "table_angles",
    range: 2..=2048,
};

impl OneilSettings {
    /// The settings from `key=value` options: `samples`, `table_heights`,
    /// `table_angles`, `table_ray_samples`; the paper's where absent.
    pub fn from_options(options: &ModelOptions) -> Result<OneilSettings, ModelError> {
        options.read_settings("oneil", OneilSettings::validate, |o, d| {
            Ok(OneilSettings {
                samples: o.count(&SAMPLES, d.samples)?,
                table_heights: o.count(&TABLE_HEIGHTS, d.table_heights)?,
                table_angles: o.count(&TABLE_ANGLES, d.table_angles)?,
                table_ray_samples: o.count(&TABLE_RAY_SAMPLES, d.table_ray_samples)?,
            })
        })
    }

    /// Why these settings cannot be used, if they cannot.
    pub fn validate(&self) -> Result<(), ModelError> {
        SAMPLES.check(self.samples)?;
        TABLE_HEIGHTS.check(self.table_heights)?;
        TABLE_ANGLES.check(self.table_angles)?;
        TABLE_RAY_SAMPLES.check(self.table_ray_samples)?;
        Ok(())
    }
}

/// Channels of a table node.
pub const RAYLEIGH_DENSITY: usize = 0;
pub const RAYLEIGH_LENGTH: usize = 1;
pub const MIE_DENSITY: usize = 2;
pub const MIE_LENGTH: usize = 3;

/// The 4-channel optical-depth table of O'Neil 2004, stored as f32 (a GL_FLOAT RGBA texture
/// in the paper's demo), read by bilinear interpolation between nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct OpticalDepthTable {
    heights: usize,
    angles: usize,
    bottom_radius_m: f64,
    thickness_m: f64,
    /// Node (i height, j angle) at `j * heights + i`.
    data: Vec<[f32; 4]>,
}

impl OpticalDepthTable {
    /// What the table depends on: densities only, so the aerosol amount and every
    /// coefficient can change without a rebuild.
    pub const INPUTS: Inputs = Inputs::GEOMETRY
        .union(Inputs::RAYLEIGH_PROFILE)
        .union(Inputs::MIE_PROFILE);

    /// Bytes of the table.
    pub fn bytes(&self) -> usize {
        std::mem::size_of_val(self.data.as_slice())
    }

    /// Builds the table: node i is at height `thickness * i / (heights - 1)`, node j at
    /// angle `180 deg * j / (angles - 1)` from the vertical; each node's optical lengths
    /// are the midpoint rule with `ray_samples` samples along the ray to the top sphere.
    pub fn build(
        atmosphere: &Atmosphere,
        heights: usize,
        angles: usize,
        ray_samples: usize,
    ) -> OpticalDepthTable {
        let bottom = atmosphere.bottom_radius_m;
        let thickness = atmosphere.thickness_m();
        let mut data = Vec::with_capacity(heights * angles);
        for j in 0..angles {
            let theta = PI * j as f64 / (angles - 1) as f64;
            let mu = theta.cos();
            for i in 0..heights {
                let h = thickness * i as f64 / (heights - 1) as f64;
                let r = bottom + h;
                let lengths = line_column(atmosphere, r, mu, ray_samples);
                let (rho_r, rho_m) = if ray_hits_ground(r, mu, bottom) {
                    (0.0, 0.0)
                } else {
                    (
                        atmosphere.rayleigh.density.density(h),
                        atmosphere.mie.density.density(h),
                    )
                };
                data.push([
                    rho_r as f32,
                    lengths[0] as f32,
                    rho_m as f32,
                    lengths[1] as f32,
                ]);
            }
        }
        OpticalDepthTable {
            heights,
            angles,
            bottom_radius_m: bottom,
            thickness_m: thickness,
            data,
        }
    }

    pub fn heights(&self) -> usize {
        self.heights
    }

    pub fn angles(&self) -> usize {
        self.angles
    }

    /// Height above the ground of node row `i`, m.
    pub fn node_height_m(&self, i: usize) -> f64 {
        self.thickness_m * i as f64 / (self.heights - 1) as f64
    }

    /// Angle from the vertical of node column `j`, radians.
    pub fn node_angle_rad(&self, j: usize) -> f64 {
        PI * j as f64 / (self.angles - 1) as f64
    }

    /// The stored channels of node (i, j).
    pub fn node(&self, i: usize, j: usize) -> [f32; 4] {
        self.data[j * self.heights + i]
    }

    /// The four channels at radius `r` (clamped to the atmosphere) for a ray whose cosine
    /// with the local vertical is `mu`, interpolated bilinearly in height and angle.
    pub fn lookup(&self, r: f64, mu: f64) -> [f64; 4] {
        let x = ((r - self.bottom_radius_m) / self.thickness_m).clamp(0.0, 1.0)
            * (self.heights - 1) as f64;
        let y = (mu.clamp(-1.0, 1.0).acos() / PI).clamp(0.0, 1.0) * (self.angles - 1) as f64;
        let i = (x.floor() as usize).min(self.heights - 2);
        let j = (y.floor() as usize).min(self.angles - 2);
        let (fx, fy) = (x - i as f64, y - j as f64);
        let (a, b) = (self.node(i, j), self.node(i + 1, j));
        let (c, d) = (self.node(i, j + 1), self.node(i + 1, j + 1));
        let mut out = [0.0; 4];
        for k in 0..4 {
            let low = a[k] as f64 * (1.0 - fx) + b[k] as f64 * fx;
            let high = c[k] as f64 * (1.0 - fx) + d[k] as f64 * fx;
            out[k] = low * (1.0 - fy) + high * fy;
        }
        out
    }
}

/// Rayleigh and Mie columns (m) along the whole line from (r, mu) to where it leaves the
/// top sphere, through the planet if it meets it, by the midpoint rule with `samples`
/// samples (the demo's `MakeOpticalDepthBuffer`). Inside the planet the density is held at
/// its ground value: the demo lets exp(-h/H) grow with depth and zeroes sums past 1e25,
/// which is not usable; holding it keeps the lengths continuous across the horizon
/// (a grazing chord through the planet has zero length).
pub fn line_column(atmosphere: &Atmosphere, r: f64, mu: f64, samples: usize) -> [f64; 2] {
    let bottom = atmosphere.bottom_radius_m;
    let length = distance_to_exit(r, mu, atmosphere.top_radius_m);
    let step = length / samples as f64;
    let mut sum = [0.0; 2];
    for k in 0..samples {
        let t = (k as f64 + 0.5) * step;
        let h = (crate::optics::geometry::radius_at(r, mu, t) - bottom).max(0.0);
        sum[0] += atmosphere.rayleigh.density.density(h);
        sum[1] += atmosphere.mie.density.density(h);
    }
    [sum[0] * step, sum[1] * step]
}

/// O'Neil's model, prepared for one atmosphere.
#[derive(Debug)]
pub struct Oneil {
    atmosphere: Atmosphere,
    /// `with_mie` false when pruning at zero aerosol: the Mie terms are skipped (the
    /// table's Mie channels are density integrals, built in the same pass as the
    /// Rayleigh ones).
    base: ModelBase,
    settings: OneilSettings,
    table: OpticalDepthTable,
    /// The terrain's shadow in the air, when light shafts are on (docs/shafts.md).
    shadow: Option<ShadowMap>,
}

impl Oneil {
    /// Prepares the table. `settings.max_orders` is ignored: the model has single
    /// scattering only, as in the paper.
    pub fn prepare(
        atmosphere: &Atmosphere,
        settings: &ModelSettings,
        oneil: OneilSettings,
    ) -> Result<Oneil, ModelError> {
        let base = ModelBase::checked(ModelId::Oneil, atmosphere, settings)?;
        oneil.validate()?;
        Ok(Oneil {
            atmosphere: atmosphere.clone(),
            base,
            settings: oneil,
            table: OpticalDepthTable::build(
                atmosphere,
                oneil.table_heights,
                oneil.table_angles,
                oneil.table_ray_samples,
            ),
            shadow: None,
        })
    }

    /// The terrain's shadow the view samples test from now on (`None`: no light shafts):
    /// each sample's single scattering times its sun visibility.
    pub fn set_terrain_shadow(&mut self, shadow: Option<ShadowMap>) {
        self.shadow = shadow;
    }

    pub fn table(&self) -> &OpticalDepthTable {
        &self.table
    }

    pub fn settings(&self) -> &OneilSettings {
        &self.settings
    }
}

impl SkyModel for Oneil {
    fn base(&self) -> &ModelBase {
        &self.base
    }

    fn table_bytes(&self) -> usize {
        self.table.bytes()
    }

    fn update(&mut self, atmosphere: &Atmosphere) -> Result<Vec<&'static str>, ModelError> {
        let mut update = self.base.adopt(&mut self.atmosphere, atmosphere)?;
        let s = self.settings;
        update.rebuild(
            OpticalDepthTable::INPUTS,
            "optical depth",
            &mut self.table,
            || {
                OpticalDepthTable::build(
                    atmosphere,
                    s.table_heights,
                    s.table_angles,
                    s.table_ray_samples,
                )
            },
        );
        Ok(update.rebuilt())
    }

    /// The transmitted sun only (single scattering has no sky light): the sun's columns
    /// from the table at the element's height and sun angle (O'Neil 2004's ground
    /// shader reads the same lookup), zero where the planet hides the sun's centre, the table's
    /// own shadow test (its density channels are 0 where `ray_hits_ground`).
    fn surface_irradiance(&self, surface: &SurfacePoint) -> Result<Vec<f64>, ModelError> {
        let e = SurfaceElement::new(&self.atmosphere, surface)?;
        let s = &self.base.spectra;
        let lit =
            e.sun_cosine > 0.0 && !ray_hits_ground(e.r, e.mu_s, self.atmosphere.bottom_radius_m);
        let column = lit.then(|| {
            let light = self.table.lookup(e.r, e.mu_s);
            [light[RAYLEIGH_LENGTH], light[MIE_LENGTH]]
        });
        Ok(e.sun_irradiances(&s.solar_irradiance, |w| {
            column.map_or(0.0, |c| {
                (-(s.extinction[w][0] * c[0] + s.extinction[w][1] * c[1])).exp()
            })
        }))
    }

    fn radiance(&self, ray: &ViewRay) -> Result<RayRadiance, ModelError> {
        let n = self.base.spectra.wavelengths_nm.len();
        let Some(seg) = ViewSegment::new(&self.atmosphere, ray)? else {
            return Ok(RayRadiance::unattenuated(n));
        };
        let table = &self.table;
        let sun = ray.sun_direction.normalize();
        let dir = seg.direction;
        let end = seg.start + dir * seg.length;
        // "When a point is above the camera the angle to the camera points down, putting
        // you in the wrong spot in your lookup buffer ... reverse the ray direction for
        // both lookups when the target vertex is higher than the camera" (O'Neil 2004). The
        // test is made for each point, not once per ray: then neither lookup ray meets the
        // planet (the line climbs beyond the higher of the two points), and where a point
        // crosses the camera's height the two forms read mirror-image texels and agree,
        // so the result is continuous. A camera in space stands at the entry point on the
        // top boundary, above every point, as the paper says.
        let r_camera = seg.start.length();
        let camera_forward = table.lookup(r_camera, seg.start.dot(dir) / r_camera);
        let camera_back = table.lookup(r_camera, -seg.start.dot(dir) / r_camera);
        // Columns (Rayleigh, Mie) from the camera to a point, by two lookups.
        let to_camera = |p: DVec3| {
            let r = p.length();
            let (a, b) = if r <= r_camera {
                (table.lookup(r, -p.dot(dir) / r), camera_back)
            } else {
                (camera_forward, table.lookup(r, p.dot(dir) / r))
            };
            [
                (a[RAYLEIGH_LENGTH] - b[RAYLEIGH_LENGTH]).max(0.0),
                (a[MIE_LENGTH] - b[MIE_LENGTH]).max(0.0),
            ]
        };
        let ext = &self.base.spectra.extinction;
        let depth = |w: usize, c: [f64; 2]| ext[w][0] * c[0] + ext[w][1] * c[1];

        let nu = dir.dot(sun);
        let phase_r = crate::optics::phase::rayleigh(nu);
        let phase_m = if self.base.with_mie {
            self.atmosphere.mie.phase.eval(nu)
        } else {
            0.0
        };
        let mut radiance = vec![0.0; n];
        let ds = seg.length / self.settings.samples as f64;
        for k in 0..self.settings.samples {
            let p = seg.start + dir * ((k as f64 + 0.5) * ds);
            let r = p.length();
            let light = table.lookup(r, p.dot(sun) / r);
            let (rho_r, rho_m) = (light[RAYLEIGH_DENSITY], light[MIE_DENSITY]);
            if rho_r <= 0.0 && rho_m <= 0.0 {
                continue; // in the planet's shadow
            }
            let visible = self.shadow.as_ref().map_or(1.0, |m| m.sun_visible(p, sun));
            let view = to_camera(p);
            let column = [
                light[RAYLEIGH_LENGTH] + view[0],
                light[MIE_LENGTH] + view[1],
            ];
            for w in 0..n {
                let mut j = self.base.spectra.rayleigh_scattering[w] * rho_r * phase_r;
                if self.base.with_mie {
                    j += self.base.spectra.mie_scattering[w] * rho_m * phase_m;
                }
                j *= visible;
                radiance[w] +=
                    ds * j * self.base.spectra.solar_irradiance[w] * (-depth(w, column)).exp();
            }
        }
        let total = to_camera(end);
        let transmittance: Vec<f64> = (0..n).map(|w| (-depth(w, total)).exp()).collect();
        // The ground's Lambertian reflection of the transmitted sun (O'Neil 2004's
        // ground shader), as any surface element facing up.
        if seg.end == SegmentEnd::Ground {
            let albedo = self.atmosphere.ground_albedo;
            add_ground_light(self, end, sun, albedo, &transmittance, &mut radiance)?;
        }
        Ok(RayRadiance {
            radiance,
            transmittance,
            radiance_std_error: vec![0.0; n],
        })
    }
}
