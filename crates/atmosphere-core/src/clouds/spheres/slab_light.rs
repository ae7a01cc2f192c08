//! The light of a crossing of a cloud sphere's shell under the layer's slab methods
//! (`eddington`, `four-stream`; `layer/march.rs`): the cloud spheres then shade as the
//! layer's march does, so that the two forms agree where one hands over to the other and
//! a thick deck seen from orbit keeps the light that diffuses through it.
//!
//! The crossing is cut into [`SLAB_STEPS`] equal steps of view optical depth, each
//! sampled at its middle p. At p the sun's optical depth tau_s comes from the attenuation
//! texture (`field.rs`, `sun_depth_at`); the slab around p has tau_above = tau_s mu0
//! (mu0 the sun's cosine from p's vertical) and tau_below = sigma_k (r - r_k) plus the
//! cloud textures' vertical optical depths T_j of the shells below (r_k the shell's inner
//! radius). Its sources are the march's (`slab_source`): the diffuse light and the broad
//! part of the sun's single scattering seen through the delta-scaled medium, the rest of
//! A_1 through the real one, the sky's light the slab's. A step of optical depth d adds,
//! with the march's energy-conserving step integral,
//!     T (1 - e^(-d)) albedo J_real + T' (1 - e^(-s d)) / s albedo J_scaled,
//! s = 1 - albedo f, T and T' the real and scaled transmittances from the crossing's
//! start. In the planet's shadow (tau_s at the attenuation textures' cap) the sun adds
//! nothing; the sky still does.

use glam::DVec3;

use super::attenuation::SHADOWED_DEPTH;
use super::crossing::{ShellSegment, SphereCrossing};
use crate::clouds::layer::eddington::MIN_SUN_COSINE;
use crate::clouds::layer::four_stream::FourStreamSlab;
use crate::clouds::layer::march::{CloudLight, SlabGeometry, peak_share, slab_parts, slab_source};
use crate::clouds::layer::orders::ScatteringOrders;
use crate::clouds::layer::settings::LayerMethod;

/// Steps of a crossing's view optical depth (a shell is a fifth of the layer by default,
/// so about as many steps through the layer as the interactive march takes through a
/// deck's top).
pub const SLAB_STEPS: usize = 4;

/// What the slab light reads of the spheres (`field.rs`'s `CloudSpheres`).
pub trait SlabColumn {
    /// The layer's method (a slab method).
    fn method(&self) -> LayerMethod;
    /// The droplets' single-scattering albedo.
    fn albedo(&self) -> f64;
    /// The inner radius of shell `k`, m.
    fn inner_radius_m(&self, k: usize) -> f64;
    /// The sun's optical depth at `point` inside shell `k` of mean extinction `sigma`
    /// towards the unit `sun`.
    fn sun_depth_at(&self, k: usize, point: DVec3, sigma: f64, sun: DVec3) -> f64;
    /// The vertical optical depth of the shells below shell `k` at `point`.
    fn depth_below(&self, k: usize, point: DVec3) -> f64;
}

/// The crossing's light under the spheres' slab method (the module's equations).
pub fn shade_slab(
    spheres: &impl SlabColumn,
    segment: &ShellSegment,
    light: &CloudLight,
    orders: &ScatteringOrders,
) -> SphereCrossing {
    let waves = light.sun_irradiance.len();
    let ShellSegment {
        shell: k,
        start,
        end,
        direction,
        extinction: sigma,
    } = *segment;
    let mut shaded = SphereCrossing::clear(waves);
    let method = spheres.method();
    let albedo = spheres.albedo();
    let scales: Vec<f64> = (0..waves)
        .map(|w| 1.0 - albedo * peak_share(method, orders, w))
        .collect();
    let length = (end - start).length();
    let d = sigma * length / SLAB_STEPS as f64;
    let nu = direction.dot(light.sun_direction);
    let inner = spheres.inner_radius_m(k);
    let sun = light.sun_direction;
    // Where a point lies in its column: its sun depth, the sun's cosine, the slab (the
    // depth below only where `below`: four streams read it once, at the middle).
    let place = |p: DVec3, below: bool| {
        let up = p.normalize();
        let tau_sun = spheres.sun_depth_at(k, p, sigma, sun);
        let tau_below = if below {
            sigma * (p.length() - inner).max(0.0) + spheres.depth_below(k, p)
        } else {
            0.0
        };
        let slab = SlabGeometry {
            mu0: sun.dot(up),
            mu_out: -direction.dot(up),
            tau_below,
        };
        (tau_sun, slab)
    };
    let four_streams = method == LayerMethod::FourStream;
    let solved: Vec<FourStreamSlab> = if four_streams {
        let (tau_sun, middle) = place((start + end) / 2.0, true);
        let mu0 = middle.mu0.max(MIN_SUN_COSINE);
        (0..waves)
            .map(|w| {
                let column = tau_sun * mu0 + middle.tau_below;
                FourStreamSlab::new(column, middle.mu0, albedo, &orders.moments(w))
            })
            .collect()
    } else {
        Vec::new()
    };
    let step_real = (-d).exp();
    for step in 0..SLAB_STEPS {
        let p = start + direction * (length * (step as f64 + 0.5) / SLAB_STEPS as f64);
        let (tau_sun, slab) = place(p, !four_streams);
        let lit = if tau_sun >= SHADOWED_DEPTH { 0.0 } else { 1.0 };
        for w in 0..waves {
            let (scaled, real, sky) = match solved.get(w) {
                Some(column) => {
                    let above = tau_sun * slab.mu0.max(MIN_SUN_COSINE);
                    let diffuse = column.diffuse_source(above, slab.mu_out);
                    slab_parts(method, w, tau_sun, orders, (nu, albedo), diffuse)
                }
                None => slab_source(method, w, tau_sun, orders, &slab, nu, albedo),
            };
            let sun = lit * light.sun_irradiance[w];
            let step_scaled = (-scales[w] * d).exp();
            shaded.radiance[w] += shaded.transmittance[w] * (1.0 - step_real) * albedo * sun * real;
            shaded.scaled_radiance[w] += shaded.scaled_transmittance[w] * (1.0 - step_scaled)
                / scales[w]
                * albedo
                * (sun * scaled + light.sky_irradiance[w] * sky);
            shaded.transmittance[w] *= step_real;
            shaded.scaled_transmittance[w] *= step_scaled;
        }
    }
    shaded
}
