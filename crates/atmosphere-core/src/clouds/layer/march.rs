//! The ray march of one view ray through a cloud medium: the light it scatters towards
//! the camera and its transmittance, per wavelength.
//!
//! The segment `[t0, t1]` is cut into `steps` equal steps, each sampled at its middle.
//! A step of extinction sigma adds, with the energy-conserving integral over the step of
//! Hillaire 2016 ("Physically based sky, atmosphere and cloud rendering in Frostbite"),
//!     T_view (1 - exp(-sigma dt)) albedo (J_sun + J_sky)
//! and multiplies T_view by exp(-sigma dt). The sun's source J_sun comes from a shadow
//! march of `shadow_steps` equal steps from the sample to the medium's boundary towards
//! the sun:
//! - Riley et al. 2004 section 4.2 ([`LayerMethod::Riley`]): walking in from the
//!   boundary, the intensity keeps per step I <- I (T + (1 - T) (albedo F_m)^(sigma ds))
//!   with m = floor(n + 1 + sigma ds) (Eq. 25, the worst case of Eq. 24), n = albedo tau
//!   the expected number of scatterings so far (Eq. 22); then
//!   J_sun = E_sun I (A_(floor(n)+1)(theta) + xi) (Eq. 26), theta the angle between the
//!   view ray and the sun.
//! - the octaves of Wrenninge et al. 2013 ([`LayerMethod::Octaves`]):
//!   J_sun = E_sun sum_i a^i exp(-b^i tau) (c^i A_1(theta) + (1 - c^i) / (4 pi)),
//!   a = b = c = 1/2.
//! - delta-Eddington ([`LayerMethod::Eddington`], `eddington.rs`): the diffuse light of
//!   the slab through the sample lit by the sun and the sky, with tau_above = tau mu0
//!   (mu0 the sun's cosine from the vertical; exact for a horizontally uniform layer)
//!   and tau_below by a march of `shadow_steps` equal steps straight down to the
//!   boundary, plus the beam scattered once: the smooth part
//!   (1 - g^2) p_HG(g / (1 + g), theta) of the phase function (delta-Eddington's
//!   truncated one) from the scaled beam exp(-(1 - albedo g^2) tau), the rest,
//!   A_1(theta) minus that part, from the real beam exp(-tau). The diffuse light and the
//!   smooth part are seen through the scaled medium (the forward peak's light goes on
//!   towards the eye), the rest through the real one; the sky's term below is the
//!   slab's instead. The march stops once the scaled view transmittance, not the real
//!   one, falls below `min_transmittance`.
//! - delta-M four-stream ([`LayerMethod::FourStream`], `four_stream.rs`): the same, with
//!   the slab's diffuse light from four streams, the forward peak's share f = chi_4
//!   instead of g^2 and the smooth part (1 - f) p_HG((g - f) / (1 - f), theta).
//!
//! The sky's light is isotropic from the upper hemisphere: a horizontal irradiance E_sky
//! is a radiance E_sky / pi over 2 pi sr, of which an isotropic scatterer sends
//! E_sky / (2 pi) per steradian, dimmed by exp(-sigma h) with h the distance to the
//! boundary straight up (one sample of the density above: the ambient's attenuation).
//! The shadow march reads the medium's [`CloudMedium::light_extinction`] (for the layer,
//! its density with `shadow_octaves` octaves of detail noise).
//!
//! With [`march_in_sun_map`] (the setting `sun_light = map`) the shadow march is
//! replaced by a read of the frame's sun map (`sun_map.rs`), the optical depth tau
//! towards the sun stored once a frame, after Dobashi, Yamamoto and Nishita 2002
//! section 5.4's attenuation textures rendered from the sun; Riley's walk then takes tau
//! in `shadow_steps` equal parts, as through a homogeneous path. The march stops once
//! T_view < `min_transmittance`: what lies behind would add at most that fraction of
//! its light.

use glam::DVec3;

use super::eddington::MIN_SUN_COSINE;
use super::orders::ScatteringOrders;
use super::settings::{LayerMethod, LayerSettings, MAX_SHADOW_STEPS};
use super::sun_map::CloudSunMap;
use super::{eddington, four_stream};
use crate::clouds::medium::CloudMedium;
use crate::optics::phase::henyey_greenstein;

/// Wrenninge et al. 2013's octave factors a (scattering), b (extinction), c (phase).
pub const OCTAVE_A: f64 = 0.5;
pub const OCTAVE_B: f64 = 0.5;
pub const OCTAVE_C: f64 = 0.5;

/// What lights the cloud, per wavelength, taken where the view ray enters it.
#[derive(Clone, Debug, PartialEq)]
pub struct CloudLight {
    /// Unit vector towards the sun.
    pub sun_direction: DVec3,
    /// The sun's irradiance on a plane facing it, through the atmosphere, W m^-2 nm^-1.
    pub sun_irradiance: Vec<f64>,
    /// The sky's irradiance on a horizontal plane, W m^-2 nm^-1.
    pub sky_irradiance: Vec<f64>,
    /// The local vertical (unit).
    pub up: DVec3,
}

/// A view ray's segment through the medium.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MarchRay {
    pub origin: DVec3,
    /// Unit vector.
    pub direction: DVec3,
    pub t0: f64,
    pub t1: f64,
}

/// What the march answers, per wavelength.
#[derive(Clone, Debug, PartialEq)]
pub struct CloudSegment {
    /// Radiance scattered towards the camera at the segment's start, W m^-2 sr^-1 nm^-1.
    pub radiance: Vec<f64>,
    /// Transmittance of the segment.
    pub transmittance: Vec<f64>,
}

/// Marches `ray` through `medium` lit by `light`, with the multiple-scattering tables
/// `orders` (one per wavelength of the light) and the method and steps of `settings`,
/// each sample's sun by its own shadow march (`sun_light = march`).
pub fn march(
    medium: &impl CloudMedium,
    ray: &MarchRay,
    light: &CloudLight,
    orders: &ScatteringOrders,
    settings: &LayerSettings,
) -> CloudSegment {
    march_lit(medium, ray, light, orders, settings, |p| {
        shadow_march(medium, p, light.sun_direction, settings)
    })
}

/// [`march`] with each sample's optical depth towards the sun read from the frame's
/// sun `map` (`sun_light = map`), cut into `shadow_steps` equal parts.
pub fn march_in_sun_map(
    medium: &impl CloudMedium,
    ray: &MarchRay,
    light: &CloudLight,
    orders: &ScatteringOrders,
    settings: &LayerSettings,
    map: &CloudSunMap,
) -> CloudSegment {
    let parts = settings.shadow_steps.clamp(1, MAX_SHADOW_STEPS) as usize;
    march_lit(medium, ray, light, orders, settings, |p| {
        let mut depths = [0.0; MAX_SHADOW_STEPS as usize];
        depths[..parts].fill(map.optical_depth(p) / parts as f64);
        (depths, parts)
    })
}

/// The optical depths of a path towards the sun, from the boundary inwards, and how
/// many of them there are.
type ShadowDepths = ([f64; MAX_SHADOW_STEPS as usize], usize);

/// The march of the module's equations, with the sun's optical depths at a sample from
/// `sun_depths`.
fn march_lit(
    medium: &impl CloudMedium,
    ray: &MarchRay,
    light: &CloudLight,
    orders: &ScatteringOrders,
    settings: &LayerSettings,
    sun_depths: impl Fn(DVec3) -> ShadowDepths,
) -> CloudSegment {
    let waves = light.sun_irradiance.len();
    let mut radiance = vec![0.0; waves];
    let mut transmittance = 1.0;
    // The view's transmittance through the delta-scaled medium, which the diffuse part
    // of a slab method's light sees (1 - albedo f of the extinction).
    let mut scaled_transmittance = vec![1.0; waves];
    let slab_method = settings.method.is_slab();
    let dt = (ray.t1 - ray.t0).max(0.0) / settings.steps as f64;
    let nu = ray.direction.dot(light.sun_direction);
    for i in 0..settings.steps {
        let p = ray.origin + ray.direction * (ray.t0 + (i as f64 + 0.5) * dt);
        let sigma = medium.extinction(p);
        if sigma <= 0.0 {
            continue;
        }
        let albedo = medium.single_scattering_albedo(p);
        let step_t = (-sigma * dt).exp();
        let weight = transmittance * (1.0 - step_t) * albedo;
        let up_depth = sigma * medium.distance_to_boundary(p, light.up);
        let sky = (-up_depth).exp() / (2.0 * std::f64::consts::PI);
        let (depths, count) = sun_depths(p);
        let slab = SlabGeometry {
            mu0: light.sun_direction.dot(light.up),
            mu_out: -ray.direction.dot(light.up),
            tau_below: if slab_method {
                vertical_depth(medium, p, -light.up, settings)
            } else {
                0.0
            },
        };
        let sources = sample_sources(&depths[..count], orders, settings, nu, albedo, &slab);
        for w in 0..waves {
            let sun = light.sun_irradiance[w];
            let sky_light = light.sky_irradiance[w];
            if slab_method {
                radiance[w] += weight * sun * sources.unscaled[w];
                let scale = 1.0 - albedo * peak_share(settings.method, orders, w);
                let step = (-scale * sigma * dt).exp();
                radiance[w] += scaled_transmittance[w] * (1.0 - step) / scale
                    * albedo
                    * (sun * sources.scaled[w] + sky_light * sources.scaled_sky[w]);
                scaled_transmittance[w] *= step;
            } else {
                radiance[w] += weight * (sun * sources.unscaled[w] + sky_light * sky);
            }
        }
        transmittance *= step_t;
        let seen = if slab_method {
            scaled_transmittance.iter().copied().fold(0.0, f64::max)
        } else {
            transmittance
        };
        if seen < settings.min_transmittance {
            break;
        }
    }
    CloudSegment {
        radiance,
        transmittance: vec![transmittance; waves],
    }
}

/// The optical depths of `shadow_steps` equal steps from `p` to the medium's boundary
/// towards the unit `sun`, through its light extinction, from the boundary inwards.
fn shadow_march(
    medium: &impl CloudMedium,
    p: DVec3,
    sun: DVec3,
    settings: &LayerSettings,
) -> ShadowDepths {
    let steps = settings.shadow_steps.min(MAX_SHADOW_STEPS) as usize;
    let length = medium.distance_to_boundary(p, sun);
    let ds = length / steps as f64;
    let mut depths = [0.0; MAX_SHADOW_STEPS as usize];
    for (k, depth) in depths.iter_mut().enumerate().take(steps) {
        let q = p + sun * (length - (k as f64 + 0.5) * ds);
        *depth = medium.light_extinction(q) * ds;
    }
    (depths, steps)
}

/// The optical depth of `shadow_steps` equal steps from `p` to the medium's boundary
/// along the unit `direction`, through its light extinction.
fn vertical_depth(
    medium: &impl CloudMedium,
    p: DVec3,
    direction: DVec3,
    settings: &LayerSettings,
) -> f64 {
    let steps = settings.shadow_steps.clamp(1, MAX_SHADOW_STEPS);
    let ds = medium.distance_to_boundary(p, direction) / steps as f64;
    (0..steps)
        .map(|k| medium.light_extinction(p + direction * ((k as f64 + 0.5) * ds)) * ds)
        .sum()
}

/// Where a sample lies in the slab a slab method ([`LayerMethod::is_slab`]) takes
/// around it (only those read `tau_below`).
#[derive(Clone, Copy, Debug)]
pub struct SlabGeometry {
    /// The sun's cosine from the upward vertical.
    pub mu0: f64,
    /// The cosine from the upward vertical of the light's way to the camera.
    pub mu_out: f64,
    /// The optical depth straight down to the medium's boundary.
    pub tau_below: f64,
}

/// The forward peak's share f of the droplets' scattering that a slab method puts back
/// into the beam at wavelength `w`: g^2 (delta-Eddington) or chi_4 (delta-M, four
/// streams).
pub fn peak_share(method: LayerMethod, orders: &ScatteringOrders, w: usize) -> f64 {
    match method {
        LayerMethod::FourStream => four_stream::truncation(&orders.moments(w)).0,
        _ => orders.asymmetry(w).powi(2),
    }
}

/// J_sun / E_sun at wavelength `w`, sr^-1, of a slab method (the module's equations),
/// for the optical depth `tau` of the path towards the sun: the part seen through the
/// delta-scaled medium and the part seen through the real one; then J_sky / E_sky,
/// seen through the scaled medium.
pub fn slab_source(
    method: LayerMethod,
    w: usize,
    tau: f64,
    orders: &ScatteringOrders,
    slab: &SlabGeometry,
    nu: f64,
    albedo: f64,
) -> (f64, f64, f64) {
    let tau_above = tau * slab.mu0.max(MIN_SUN_COSINE);
    let diffuse = match method {
        LayerMethod::FourStream => four_stream::diffuse_source(
            tau_above,
            slab.tau_below,
            slab.mu0,
            albedo,
            &orders.moments(w),
            slab.mu_out,
        ),
        _ => {
            let g = orders.asymmetry(w);
            eddington::diffuse_source(tau_above, slab.tau_below, slab.mu0, albedo, g, slab.mu_out)
        }
    };
    slab_parts(method, w, tau, orders, (nu, albedo), diffuse)
}

/// [`slab_source`] with the slab's diffuse sources (beam, sky) given: the sun's single
/// scattering split into its broad part (1 - f) p_HG((g - f) / (1 - f)) from the scaled
/// beam and the rest of A_1 from the real one, at the scattering angle of cosine `nu`.
pub fn slab_parts(
    method: LayerMethod,
    w: usize,
    tau: f64,
    orders: &ScatteringOrders,
    (nu, albedo): (f64, f64),
    (diffuse, sky): (f64, f64),
) -> (f64, f64, f64) {
    let g = orders.asymmetry(w);
    let f = peak_share(method, orders, w);
    let broad = (1.0 - f) * henyey_greenstein((g - f) / (1.0 - f), nu);
    let scaled_beam = (-(1.0 - albedo * f) * tau).exp();
    let beam = (-tau).exp();
    (
        diffuse + broad * scaled_beam,
        (orders.distribution(w, 1, nu) - broad) * beam,
        sky,
    )
}

/// What a sample scatters towards the eye per unit of extinction and albedo, per
/// wavelength, sr^-1: J_sun / E_sun seen through the real medium and, for
/// a slab method, J_sun / E_sun and J_sky / E_sky seen through the
/// delta-scaled one (zero for the other methods, whose sky term is the march's).
struct SampleSources {
    unscaled: Vec<f64>,
    scaled: Vec<f64>,
    scaled_sky: Vec<f64>,
}

/// The sources of a sample (the module's equations), for the optical depths `depths`
/// of the path towards the sun, from the boundary inwards, at a sample placed in its
/// slab by `slab`.
fn sample_sources(
    depths: &[f64],
    orders: &ScatteringOrders,
    settings: &LayerSettings,
    nu: f64,
    albedo: f64,
    slab: &SlabGeometry,
) -> SampleSources {
    let tau: f64 = depths.iter().sum();
    let waves = orders.wavelengths();
    let unscaled_only = |unscaled: Vec<f64>| SampleSources {
        unscaled,
        scaled: vec![0.0; waves],
        scaled_sky: vec![0.0; waves],
    };
    match settings.method {
        LayerMethod::Riley => unscaled_only(
            (0..waves)
                .map(|w| {
                    let mut intensity = 1.0;
                    let mut walked = 0.0;
                    for &d in depths {
                        intensity *= riley_step(orders, w, albedo, walked, d);
                        walked += d;
                    }
                    riley_source(
                        orders,
                        w,
                        intensity,
                        tau,
                        albedo,
                        nu,
                        settings.backscatter_xi,
                    )
                })
                .collect(),
        ),
        LayerMethod::Octaves => unscaled_only(
            (0..waves)
                .map(|w| octaves_source(orders, w, tau, nu, settings.octaves))
                .collect(),
        ),
        LayerMethod::Eddington | LayerMethod::FourStream => {
            let mut sources = unscaled_only(vec![0.0; waves]);
            for w in 0..waves {
                let (scaled, unscaled, sky) =
                    slab_source(settings.method, w, tau, orders, slab, nu, albedo);
                sources.unscaled[w] = unscaled;
                sources.scaled[w] = scaled;
                sources.scaled_sky[w] = sky;
            }
            sources
        }
    }
}

/// Riley et al. 2004 Eq. 25: the factor the sun's intensity keeps at wavelength `w` over
/// a step of optical depth `d`, after an optical depth `walked` from the boundary,
/// exp(-d) + (1 - exp(-d)) (albedo F_m)^d with m = floor(albedo walked + 1 + d).
pub fn riley_step(orders: &ScatteringOrders, w: usize, albedo: f64, walked: f64, d: f64) -> f64 {
    let n = albedo * walked;
    let m = (n + 1.0 + d).floor() as usize;
    let kept = albedo * orders.forward_fraction(w, m);
    let t = (-d).exp();
    t + (1.0 - t) * kept.powf(d)
}

/// Riley et al. 2004 Eq. 26's source towards the eye over E_sun, sr^-1: the sun's
/// `intensity` after an optical depth `tau` times A_(floor(albedo tau)+1)(theta) + xi,
/// `nu` the cosine of theta.
pub fn riley_source(
    orders: &ScatteringOrders,
    w: usize,
    intensity: f64,
    tau: f64,
    albedo: f64,
    nu: f64,
    xi: f64,
) -> f64 {
    let n = (albedo * tau).floor() as usize + 1;
    intensity * (orders.distribution(w, n, nu) + xi)
}

/// Wrenninge et al. 2013's octaves over E_sun, sr^-1, after an optical depth `tau`
/// towards the sun: sum over i < `octaves` of a^i exp(-b^i tau) (c^i A_1 + (1 - c^i) / (4 pi)).
pub fn octaves_source(orders: &ScatteringOrders, w: usize, tau: f64, nu: f64, octaves: u32) -> f64 {
    let single = orders.distribution(w, 1, nu);
    let isotropic = 1.0 / (4.0 * std::f64::consts::PI);
    (0..octaves as i32)
        .map(|i| {
            let c = OCTAVE_C.powi(i);
            OCTAVE_A.powi(i)
                * (-OCTAVE_B.powi(i) * tau).exp()
                * (c * single + (1.0 - c) * isotropic)
        })
        .sum()
}
