//! The hillaire model's parameters on the GPU (WGSL `HillaireParams`): the view of the
//! per-view tables, the settings' sample counts, the anisotropic term's order and Mie
//! moments, the similarity-scaled medium's delta fraction, and the camera's frame.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::hillaire::HillaireSettings;
use atmosphere_core::models::hillaire::directions::horizon_zenith;
use atmosphere_core::models::hillaire::moments::PhaseMoments;
use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use crate::gpu::error::RenderError;

/// WGSL `HillaireParams`, 128 bytes: the view of the per-view tables, the settings'
/// sample counts, the multiple-scattering term's settings, and the camera's frame for the
/// pass's view angles.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct HillaireUniform {
    pub view_r: f32,
    pub view_q: f32,
    pub view_mu_s: f32,
    pub aerial_range_m: f32,
    pub ms_sqrt_directions: u32,
    pub ms_samples: u32,
    pub sky_view_samples: u32,
    pub ap_samples_per_slice: u32,
    pub march_samples: u32,
    pub ground_zenith_panels: u32,
    pub ground_azimuths: u32,
    pub multiple_on: u32,
    pub view_theta_h: f32,
    pub ms_order: u32,
    pub mie_g1: f32,
    pub mie_g2: f32,
    /// `ms_delta` with orders two and up on, else 0.
    pub ms_delta: f32,
    pub pad_0: f32,
    pub pad_1: f32,
    pub pad_2: f32,
    pub view_up: [f32; 4],
    pub view_sun_side: [f32; 4],
    pub view_across: [f32; 4],
}

/// A count as the shaders' u32, or an error naming it.
pub fn count(name: &str, n: usize) -> Result<u32, RenderError> {
    u32::try_from(n).map_err(|_| RenderError::Unsupported(format!("hillaire {name} = {n}")))
}

impl HillaireUniform {
    /// The settings for a view (camera radius, sun zenith cosine: `view_key`) of
    /// `atmosphere`, with the camera's zenith `up` and the sun's direction.
    pub fn new(
        settings: &HillaireSettings,
        atmosphere: &Atmosphere,
        view: (f64, f64),
        (up, sun): (DVec3, DVec3),
        multiple_on: bool,
    ) -> Result<HillaireUniform, RenderError> {
        let bottom = atmosphere.bottom_radius_m;
        let (r, mu_s) = view;
        let sun_side = (sun - up * sun.dot(up))
            .try_normalize()
            .unwrap_or_else(|| up.any_orthonormal_vector());
        let v4 = |v: DVec3| [v.x as f32, v.y as f32, v.z as f32, 0.0];
        // The Mie phase function's Legendre moments, for the anisotropic term only.
        let mie = if settings.multiple_scattering_order > 0 {
            PhaseMoments::new(&atmosphere.mie.phase).mie
        } else {
            [1.0, 0.0, 0.0]
        };
        Ok(HillaireUniform {
            view_r: r as f32,
            view_q: ((r - bottom) * (r + bottom)) as f32,
            view_mu_s: mu_s as f32,
            aerial_range_m: settings.aerial_range_m as f32,
            ms_sqrt_directions: count("ms_directions", settings.multiple_scattering_directions)?
                .isqrt(),
            ms_samples: count("ms_samples", settings.multiple_scattering_samples)?,
            sky_view_samples: count("sky_view_samples", settings.sky_view_samples)?,
            ap_samples_per_slice: count("ap_samples_per_slice", settings.aerial_samples_per_slice)?,
            march_samples: count("march_samples", settings.march_samples)?,
            ground_zenith_panels: count("ground_zenith_panels", settings.ground_zenith_panels)?,
            ground_azimuths: count("ground_azimuths", settings.ground_azimuths)?,
            multiple_on: u32::from(multiple_on),
            view_theta_h: horizon_zenith(r, bottom) as f32,
            ms_order: count("ms_order", settings.multiple_scattering_order)?,
            mie_g1: mie[1] as f32,
            mie_g2: mie[2] as f32,
            ms_delta: if multiple_on {
                settings.multiple_scattering_delta as f32
            } else {
                0.0
            },
            pad_0: 0.0,
            pad_1: 0.0,
            pad_2: 0.0,
            view_up: v4(up),
            view_sun_side: v4(sun_side),
            view_across: v4(up.cross(sun_side)),
        })
    }
}
