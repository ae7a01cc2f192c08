//! The parameters of every bruneton shader (`BrunetonParams` of
//! `sky/bruneton/bindings.wgsl`).

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::bruneton::BrunetonSettings;
use atmosphere_core::models::bruneton::delta_m::DeltaM;
use bytemuck::{Pod, Zeroable};

use crate::sky::bruneton::store::{DENSITY_SAMPLES, StoreLayout, StoreTable};
use crate::sky::bruneton::store_chunks::StoreChunks;

/// WGSL `BrunetonParams`, 160 bytes: the sizes of the tables and of the sphere integrals,
/// the store's offsets (texels), and what the build depends on besides the atmosphere.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BrunetonUniform {
    /// Texels of S along r, mu, mu_s and nu.
    pub r_size: u32,
    pub mu_size: u32,
    pub mu_s_size: u32,
    pub nu_size: u32,
    /// Texels of E along mu_s and r.
    pub irradiance_mu_s_size: u32,
    pub irradiance_r_size: u32,
    /// The sphere integrals: Gauss-Legendre panels of 8 zenith angles on each side of the
    /// horizon, and azimuths over [0, pi].
    pub sphere_panels: u32,
    pub sphere_azimuths: u32,
    /// Trapezoid intervals along each texel's ray.
    pub view_samples: u32,
    /// 1 when Mie is computed (not pruned).
    pub mie_on: u32,
    /// 1 for order 2: the previous order is single scattering, the previous irradiance
    /// direct sunlight.
    pub previous_is_single: u32,
    /// The most orders.
    pub max_orders: u32,
    /// The first texel of each table of the store ([`StoreTable`]).
    pub density_offset: u32,
    pub single_rayleigh_offset: u32,
    pub single_mie_offset: u32,
    pub multiple_offset: u32,
    pub delta_s_offset: u32,
    pub delta_j_offset: u32,
    pub delta_e_offset: u32,
    pub irradiance_offset: u32,
    pub moments_offset: u32,
    pub partials_offset: u32,
    /// Texels of S (and of each table of its size), and of E.
    pub scattering_texels: u32,
    pub irradiance_texels: u32,
    /// The delta-M Mie phase function (`DeltaM`): forward fraction, chi1, chi2.
    pub mie_forward_fraction: f32,
    pub mie_chi1: f32,
    pub mie_chi2: f32,
    /// The share below which an order ends the loop.
    pub order_threshold: f32,
    /// Step of the density table, m.
    pub density_step_m: f32,
    /// The lowest sun cosine of S and E (`AngleMapping::min_mu_s`).
    pub min_mu_s: f32,
    /// 1 when u_nu is linear in the scattering angle (`AngleMapping::nu_by_angle`).
    pub nu_by_angle: u32,
    /// Mie's Delta J by a quadrature of this many directions squared about the view
    /// (`BrunetonSettings::mie_directions`); 0 for the delta-M form.
    pub mie_directions: u32,
    /// Texels of the store each of its bindings covers (`store_chunks.rs`).
    pub store_chunk_texels: u32,
    /// 1 when u_mu_s continues the paper's curve linearly below -0.2
    /// (`AngleMapping::mu_s_knee`).
    pub mu_s_knee: u32,
    /// 1 when S is read geometrically along mu_s between texels whose sun is below the
    /// horizontal (`AngleMapping::geometric_mu_s`).
    pub geometric_mu_s: u32,
    /// 1 when the nodes along each texel's ray are placed by density
    /// (`BrunetonSettings::density_nodes`).
    pub density_nodes: u32,
    /// 1 when the sun is a disk where it meets the horizon (`BrunetonSettings::sun_disk`),
    /// of this angular radius (radians).
    pub sun_disk: u32,
    pub sun_angular_radius: f32,
    /// 1 when look-ups weigh their nu texels between the texels' positions clamped to
    /// the ray's range of nu (`AngleMapping::nu_edge`).
    pub nu_edge: u32,
    /// 1 when the fourth coordinate is the azimuth between the view's and the sun's
    /// vertical planes (`AngleMapping::nu_by_azimuth`).
    pub nu_by_azimuth: u32,
    /// 1 when the sky half of the mu axis spreads its texels towards the zenith
    /// (`AngleMapping::mu_zenith`).
    pub mu_zenith: u32,
    /// 1 when Mie's quadrature lays its directions out in the texel's frame, split at
    /// the view and the horizon (`BrunetonSettings::mie_horizon`).
    pub mie_horizon: u32,
}

impl BrunetonUniform {
    /// The parameters of tables of `settings` laid out as `layout` and bound as `chunks`,
    /// recording at most
    /// `max_orders`, for `atmosphere` with Mie computed or not (`mie`).
    pub fn new(
        settings: &BrunetonSettings,
        layout: &StoreLayout,
        chunks: &StoreChunks,
        max_orders: u32,
        atmosphere: &Atmosphere,
        mie: bool,
    ) -> BrunetonUniform {
        let s = settings.scattering_size;
        let delta_m = if mie {
            let d = DeltaM::new(&atmosphere.mie.phase);
            [d.forward_fraction, d.chi1, d.chi2]
        } else {
            [0.0; 3]
        };
        let u = |x: usize| x as u32;
        let offset = |table| layout.offset(table);
        BrunetonUniform {
            r_size: u(s.r),
            mu_size: u(s.mu),
            mu_s_size: u(s.mu_s),
            nu_size: u(s.nu),
            irradiance_mu_s_size: u(settings.irradiance_size.0),
            irradiance_r_size: u(settings.irradiance_size.1),
            sphere_panels: u(settings.sphere_samples.0.div_ceil(16).max(1)),
            sphere_azimuths: u((settings.sphere_samples.1 / 2).max(1)),
            view_samples: u(settings.view_samples),
            mie_on: u32::from(mie),
            previous_is_single: 0,
            max_orders,
            density_offset: offset(StoreTable::Density),
            single_rayleigh_offset: offset(StoreTable::SingleRayleigh),
            single_mie_offset: offset(StoreTable::SingleMie),
            multiple_offset: offset(StoreTable::Multiple),
            delta_s_offset: offset(StoreTable::DeltaS),
            delta_j_offset: offset(StoreTable::DeltaJ),
            delta_e_offset: offset(StoreTable::DeltaE),
            irradiance_offset: offset(StoreTable::Irradiance),
            moments_offset: offset(StoreTable::Moments),
            partials_offset: offset(StoreTable::Partials),
            scattering_texels: layout.length(StoreTable::SingleRayleigh),
            irradiance_texels: layout.length(StoreTable::DeltaE),
            mie_forward_fraction: delta_m[0] as f32,
            mie_chi1: delta_m[1] as f32,
            mie_chi2: delta_m[2] as f32,
            order_threshold: settings.order_threshold as f32,
            density_step_m: (atmosphere.thickness_m() / f64::from(DENSITY_SAMPLES - 1)) as f32,
            min_mu_s: s.angles.min_mu_s as f32,
            nu_by_angle: u32::from(s.angles.nu_by_angle),
            mie_directions: u(settings.mie_directions),
            store_chunk_texels: chunks.chunk_texels,
            mu_s_knee: u32::from(s.angles.mu_s_knee),
            geometric_mu_s: u32::from(s.angles.geometric_mu_s),
            density_nodes: u32::from(settings.density_nodes),
            sun_disk: u32::from(settings.sun_disk),
            sun_angular_radius: atmosphere.sun.angular_radius_rad as f32,
            nu_edge: u32::from(s.angles.nu_edge),
            nu_by_azimuth: u32::from(s.angles.nu_by_azimuth),
            mu_zenith: u32::from(s.angles.mu_zenith),
            mie_horizon: u32::from(settings.mie_horizon),
        }
    }
}
