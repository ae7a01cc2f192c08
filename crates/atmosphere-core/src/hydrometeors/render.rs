//! Rain and ice volumes in a sky model's frame on the CPU: the specification of
//! render-wgpu's `precipitation/` pass. Single scattering (Riley et al. 2004, section
//! 4.2.3, Eq. 26 with the first order only): along a view ray's interval [t0, t1] in a
//! homogeneous volume of extinction beta_c per channel (albedo 1), in MARCH_STEPS equal
//! steps of length dt, each step adds
//!     T_v(t_k) (1 - e^(-beta_c dt)) [P_c(theta) E_sun e^(-beta_c s_k) + L_sky],
//! where T_v(t_k) is the volume's transmittance in channel c from t0 to the step's
//! start, beta_c = beta (1 - f_c) with the forward peak taken as no scattering
//! (`forward_peak.rs`, delta-M: f_c = 0 where the peak counts as extinction), P_c the
//! phase function at the frame's wavelengths (`channel_phase.rs`; truncated alike) at
//! the scattering angle theta between the sun and the view (falling plates: at the
//! view's elevation and azimuth from the sun about the camera's vertical), E_sun the
//! sun's irradiance through the atmosphere (one value per volume, at its
//! `light_point`), s_k the sun's path inside the volume from the step's middle, and
//! L_sky the sky's light scattered isotropically (`sky_light.rs`: the model's radiance
//! averaged over the sphere there, or E_sky / (2 pi) from its horizontal irradiance).
//! With probes of the sun's light scattered more than once (`sun_orders.rs`) the bracket
//! gains E_sun S(x, w), w = -direction the way the light travels to the camera, read
//! once per ORDERS_EVERY steps at their group's middle.
//! The volume is composited over the model's pixel
//! L_full (its surface and sun included) as
//!     L = L_front + T_v (L_full - L_front) + T_front L_v,   L_front = (1 - T_front) L_full,
//! Riley et al. 2004's (section 5) split of the atmosphere in front of and behind the
//! volume, with T_front the atmosphere's transmittance from the camera to t0 (its columns
//! by the midpoint rule over FRONT_STEPS steps in s, t = t0 s^2) and the light in front of the volume
//! taken as the fraction 1 - T_front of the whole ray's: exact where the atmosphere's
//! source function is uniform along the ray, and it needs no second run of the model
//! (the cloud composite, `clouds/layer/composite.rs`, runs one). Several volumes
//! composite from the farthest entry to the nearest.

use std::f64::consts::PI;

use glam::DVec3;

use super::channel_phase::ChannelPhase;
use super::sky_light::{SkyLight, sphere_mean_radiance};
use super::sun_orders::SunOrders;
use super::volumes::Volume;
use crate::atmosphere::Atmosphere;
use crate::clouds::layer::composite::light_at;
use crate::models::error::ModelError;
use crate::models::sky_model::SkyModel;
use crate::optics::column::{densities, optical_depth};

/// Steps of the march through a volume, and of the atmosphere's columns in front of it.
pub const MARCH_STEPS: usize = 12;
/// The probes' light is read once per this many steps, at their group's middle (it
/// varies slowly along a ray; each read is the costliest part of a step).
pub const ORDERS_EVERY: usize = 3;
pub const FRONT_STEPS: usize = 8;

/// The light on a volume at the frame's three wavelengths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeLight {
    /// Unit vector towards the sun.
    pub sun_direction: DVec3,
    /// The sun's irradiance on a plane facing it, through the atmosphere, W m^-2 nm^-1.
    pub sun_irradiance: [f64; 3],
    /// The radiance the march scatters isotropically as the sky's light
    /// (`sky_light.rs`), W m^-2 sr^-1 nm^-1.
    pub sky_radiance: [f64; 3],
}

/// A volume with its phase function and light.
#[derive(Clone, Debug, PartialEq)]
pub struct LitVolume {
    pub volume: Volume,
    /// The table the march reads: truncated where `peak_fraction` is not zero.
    pub phase: ChannelPhase,
    /// f_c: each channel's share of the scattering taken out of the extinction with
    /// the forward peak (`forward_peak.rs`); zero where the peak counts as extinction.
    pub peak_fraction: [f64; 3],
    pub light: VolumeLight,
    /// The probes of the sun's light scattered more than once; `None`: left out.
    pub orders: Option<SunOrders>,
}

impl LitVolume {
    /// The extinction the march attenuates with per channel, beta (1 - f_c), m^-1.
    pub fn extinction_per_m(&self) -> [f64; 3] {
        self.peak_fraction
            .map(|f| self.volume.extinction_per_m * (1.0 - f))
    }
}

/// What a view ray meets in one volume: its entry distance, radiance and transmittance
/// per channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeSegment {
    pub entry_m: f64,
    pub radiance: [f64; 3],
    pub transmittance: [f64; 3],
}

/// The march of the ray from `origin` along the unit `direction` (ended at
/// `max_distance_m`) through `lit`, if it meets it, in [`MARCH_STEPS`] steps.
pub fn march(
    lit: &LitVolume,
    origin: DVec3,
    direction: DVec3,
    max_distance_m: f64,
) -> Option<VolumeSegment> {
    march_in_steps(lit, origin, direction, max_distance_m, MARCH_STEPS)
}

/// [`march`] in `steps` steps (at least one): the report's rows of other step counts.
pub fn march_in_steps(
    lit: &LitVolume,
    origin: DVec3,
    direction: DVec3,
    max_distance_m: f64,
    steps: usize,
) -> Option<VolumeSegment> {
    let (t0, t1) = lit.volume.segment(origin, direction, max_distance_m)?;
    let steps = steps.max(1);
    let beta = lit.extinction_per_m();
    let dt = (t1 - t0) / steps as f64;
    let step_transmittance = beta.map(|b| (-b * dt).exp());
    let up = origin.normalize_or(DVec3::Z);
    let p = lit
        .phase
        .value_toward(direction, lit.light.sun_direction, up);
    let mut radiance = [0.0; 3];
    let mut t_v = [1.0; 3];
    let mut orders = [0.0; 3];
    for k in 0..steps {
        let x = origin + direction * (t0 + (k as f64 + 0.5) * dt);
        let sun_path = lit.volume.exit_distance(x, lit.light.sun_direction);
        if k % ORDERS_EVERY == 0 {
            let group = ORDERS_EVERY.min(steps - k) as f64;
            let middle = origin + direction * (t0 + (k as f64 + 0.5 * group) * dt);
            orders = lit.orders.as_ref().map_or([0.0; 3], |o| {
                o.source(&lit.volume, lit.light.sun_direction, middle, -direction)
            });
        }
        for c in 0..3 {
            let sun = (-beta[c] * sun_path).exp();
            radiance[c] += t_v[c]
                * (1.0 - step_transmittance[c])
                * (lit.light.sun_irradiance[c] * (p[c] * sun + orders[c])
                    + lit.light.sky_radiance[c]);
            t_v[c] *= step_transmittance[c];
        }
    }
    Some(VolumeSegment {
        entry_m: t0,
        radiance,
        transmittance: t_v,
    })
}

/// The atmosphere's transmittance at `extinction` (per species, at the frame's three
/// wavelengths) from `origin` over `distance_m` along the unit `direction`.
pub fn front_transmittance(
    atmosphere: &Atmosphere,
    extinction: &[[f64; 3]; 3],
    origin: DVec3,
    direction: DVec3,
    distance_m: f64,
) -> [f64; 3] {
    // t = distance s^2: the midpoint rule in s, its steps short near the camera, where
    // the air is densest.
    let ds = 1.0 / FRONT_STEPS as f64;
    let mut column = [0.0; 3];
    for k in 0..FRONT_STEPS {
        let s = (k as f64 + 0.5) * ds;
        let x = origin + direction * (distance_m * s * s);
        let rho = densities(atmosphere, x.length() - atmosphere.bottom_radius_m);
        for c in 0..3 {
            column[c] += 2.0 * distance_m * s * ds * rho[c];
        }
    }
    extinction.map(|e| (-optical_depth(column, e)).exp())
}

/// The model's pixel `full` with `volumes` composited over it for the ray from `origin`
/// along the unit `direction`, ended at `max_distance_m` (its surface, or infinity).
pub fn composite(
    atmosphere: &Atmosphere,
    extinction: &[[f64; 3]; 3],
    volumes: &[LitVolume],
    origin: DVec3,
    direction: DVec3,
    max_distance_m: f64,
    full: [f64; 3],
) -> [f64; 3] {
    let ray = (origin, direction, max_distance_m);
    composite_in_steps(atmosphere, extinction, volumes, ray, full, MARCH_STEPS)
}

/// [`composite`] with the volumes marched in `steps` steps, for the ray `(origin,
/// direction, max_distance_m)`.
pub fn composite_in_steps(
    atmosphere: &Atmosphere,
    extinction: &[[f64; 3]; 3],
    volumes: &[LitVolume],
    ray: (DVec3, DVec3, f64),
    full: [f64; 3],
    steps: usize,
) -> [f64; 3] {
    composite_terms(atmosphere, extinction, volumes, ray, steps).over(full)
}

/// What the volumes make of the pixel behind them, L = A L_full + B per channel:
/// the composite is linear in L_full.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompositeTerms {
    pub times_full: [f64; 3],
    pub added: [f64; 3],
}

impl CompositeTerms {
    /// Nothing in front of the pixel.
    pub const NONE: CompositeTerms = CompositeTerms {
        times_full: [1.0; 3],
        added: [0.0; 3],
    };

    /// The pixel `full` seen through these terms.
    pub fn over(&self, full: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|c| self.times_full[c] * full[c] + self.added[c])
    }
}

/// The composite's terms for the ray `(origin, direction, max_distance_m)`, the
/// volumes marched in `steps` steps, the farthest first.
pub fn composite_terms(
    atmosphere: &Atmosphere,
    extinction: &[[f64; 3]; 3],
    volumes: &[LitVolume],
    (origin, direction, max_distance_m): (DVec3, DVec3, f64),
    steps: usize,
) -> CompositeTerms {
    let mut met: Vec<VolumeSegment> = volumes
        .iter()
        .filter_map(|v| march_in_steps(v, origin, direction, max_distance_m, steps))
        .collect();
    met.sort_by(|a, b| b.entry_m.total_cmp(&a.entry_m));
    met.iter().fold(CompositeTerms::NONE, |behind, s| {
        let front = front_transmittance(atmosphere, extinction, origin, direction, s.entry_m);
        let keep: [f64; 3] = std::array::from_fn(|c| 1.0 - front[c] * (1.0 - s.transmittance[c]));
        CompositeTerms {
            times_full: std::array::from_fn(|c| behind.times_full[c] * keep[c]),
            added: std::array::from_fn(|c| behind.added[c] * keep[c] + front[c] * s.radiance[c]),
        }
    })
}

/// The light of `model` (at its wavelengths, which must be three) on `volume` seen from
/// `camera_m`: the sun through the atmosphere at the volume's `light_point`
/// (`clouds/layer/composite.rs`, `light_at`) and the sky's light there as `sky` says.
pub fn light_of(
    model: &dyn SkyModel,
    volume: &Volume,
    (camera_m, sun_direction): (DVec3, DVec3),
    sky: SkyLight,
) -> Result<VolumeLight, ModelError> {
    let sun = sun_direction
        .try_normalize()
        .ok_or_else(|| ModelError::Settings("the sun direction must be non-zero".into()))?;
    let point = volume.light_point(camera_m);
    let light = light_at(model, point, sun)?;
    let three = |v: &[f64]| -> Result<[f64; 3], ModelError> {
        v.try_into().map_err(|_| {
            ModelError::Settings(format!(
                "volumes are lit at three wavelengths, the model answers {}",
                v.len()
            ))
        })
    };
    let sky_radiance = match sky {
        SkyLight::Sphere => three(&sphere_mean_radiance(model, point, sun)?)?,
        SkyLight::Horizontal => three(&light.sky_irradiance)?.map(|e| e / (2.0 * PI)),
    };
    Ok(VolumeLight {
        sun_direction: sun,
        sun_irradiance: three(&light.sun_irradiance)?,
        sky_radiance,
    })
}
