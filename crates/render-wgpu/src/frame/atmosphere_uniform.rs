//! The Rust twin of `AtmosphereParams` in `shaders/common/atmosphere_params.wgsl`: an
//! [`Atmosphere`] at three wavelengths, in f32, laid out byte for byte as WGSL's uniform
//! rules want it (every struct a multiple of 16 bytes, padding explicit).

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::density::{DensityLayer, DensityProfile};
use atmosphere_core::optics::phase::PhaseFunction;
use bytemuck::{Pod, Zeroable};

use crate::gpu::error::{GpuError, RenderError};

/// The wavelengths of the red, green and blue channels, nm.
pub const RGB_WAVELENGTHS_NM: [f64; 3] = [680.0, 550.0, 440.0];

/// One density layer (WGSL `DensityLayer`), 32 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct DensityLayerUniform {
    pub width_m: f32,
    pub exp_term: f32,
    pub exp_scale_per_m: f32,
    pub linear_term_per_m: f32,
    pub constant_term: f32,
    pub pad: [f32; 3],
}

impl From<&DensityLayer> for DensityLayerUniform {
    fn from(layer: &DensityLayer) -> Self {
        DensityLayerUniform {
            width_m: layer.width_m as f32,
            exp_term: layer.exp_term as f32,
            exp_scale_per_m: layer.exp_scale_per_m as f32,
            linear_term_per_m: layer.linear_term_per_m as f32,
            constant_term: layer.constant_term as f32,
            pad: [0.0; 3],
        }
    }
}

/// A profile of two layers (WGSL `DensityProfile`), 64 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct DensityProfileUniform {
    pub layers: [DensityLayerUniform; 2],
}

impl DensityProfileUniform {
    /// The profile's layers; a one-layer profile fills both slots, so the shader's choice
    /// by altitude does not matter, and an empty one is zero everywhere, as on the CPU.
    fn new(profile: &DensityProfile, species: &'static str) -> Result<Self, GpuError> {
        let layers = match profile.layers.as_slice() {
            [] => [DensityLayerUniform::default(); 2],
            [only] => [only.into(); 2],
            [lower, upper] => [lower.into(), upper.into()],
            more => {
                return Err(GpuError::TooManyDensityLayers {
                    species,
                    layers: more.len(),
                });
            }
        };
        Ok(DensityProfileUniform { layers })
    }
}

/// WGSL `AtmosphereParams`, 320 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct AtmosphereUniform {
    pub bottom_radius_m: f32,
    pub top_radius_m: f32,
    pub pad: [f32; 2],
    pub rayleigh_density: DensityProfileUniform,
    pub mie_density: DensityProfileUniform,
    pub ozone_density: DensityProfileUniform,
    /// Extinction per unit column at the three wavelengths (xyz), w = 0.
    pub rayleigh_extinction_per_m: [f32; 4],
    pub mie_extinction_per_m: [f32; 4],
    pub ozone_extinction_per_m: [f32; 4],
    /// Scattering per unit column at the three wavelengths (xyz), w = 0.
    pub rayleigh_scattering_per_m: [f32; 4],
    pub mie_scattering_per_m: [f32; 4],
    /// Solar irradiance at the top of the atmosphere, W m^-2 nm^-1 (xyz), w = 0.
    pub solar_irradiance: [f32; 4],
    /// The Mie phase function: 0 Cornette-Shanks, 1 Henyey-Greenstein, 2 Nishita's hazy
    /// form (`PhaseFunction`), with its asymmetry `mie_g`.
    pub mie_phase_kind: u32,
    pub mie_g: f32,
    /// Lambertian albedo of the ground.
    pub ground_albedo: f32,
    pub pad1: f32,
}

impl AtmosphereUniform {
    /// `atmosphere` at `wavelengths_nm` (one per channel); fails when a density profile
    /// has more layers than the shader holds or the Mie phase function is one the
    /// shaders do not evaluate (tabulated).
    pub fn new(atmosphere: &Atmosphere, wavelengths_nm: [f64; 3]) -> Result<Self, GpuError> {
        let coefficients = wavelengths_nm.map(|l| atmosphere.coefficients(l));
        let extinctions = coefficients.map(|c| c.extinction_per_species());
        let row = |species: usize| {
            let [a, b, c] = extinctions.map(|e| e[species] as f32);
            [a, b, c, 0.0]
        };
        let per_channel = |f: &dyn Fn(usize) -> f64| [f(0) as f32, f(1) as f32, f(2) as f32, 0.0];
        let (mie_phase_kind, mie_g) = match atmosphere.mie.phase {
            PhaseFunction::CornetteShanks { g } => (0, g),
            PhaseFunction::HenyeyGreenstein { g } => (1, g),
            PhaseFunction::NishitaHazy => (2, 0.0),
            PhaseFunction::Rayleigh | PhaseFunction::Tabulated { .. } => {
                return Err(GpuError::UnsupportedPhase(format!(
                    "{:?}",
                    atmosphere.mie.phase
                )));
            }
        };
        Ok(AtmosphereUniform {
            bottom_radius_m: atmosphere.bottom_radius_m as f32,
            top_radius_m: atmosphere.top_radius_m as f32,
            pad: [0.0; 2],
            rayleigh_density: DensityProfileUniform::new(&atmosphere.rayleigh.density, "rayleigh")?,
            mie_density: DensityProfileUniform::new(&atmosphere.mie.density, "mie")?,
            ozone_density: DensityProfileUniform::new(&atmosphere.ozone.density, "ozone")?,
            rayleigh_extinction_per_m: row(0),
            mie_extinction_per_m: row(1),
            ozone_extinction_per_m: row(2),
            rayleigh_scattering_per_m: per_channel(&|w| coefficients[w].rayleigh_scattering_per_m),
            mie_scattering_per_m: per_channel(&|w| coefficients[w].mie_scattering_per_m),
            solar_irradiance: per_channel(&|w| coefficients[w].solar_irradiance_w_m2_nm),
            mie_phase_kind,
            mie_g: mie_g as f32,
            ground_albedo: atmosphere.ground_albedo as f32,
            pad1: 0.0,
        })
    }
}

/// Checks that `wavelengths_nm` are the GPU's channels.
pub fn check_wavelengths(wavelengths_nm: &[f64]) -> Result<(), RenderError> {
    if wavelengths_nm == RGB_WAVELENGTHS_NM {
        Ok(())
    } else {
        Err(RenderError::Unsupported(format!(
            "the GPU renders at {RGB_WAVELENGTHS_NM:?} nm, not {wavelengths_nm:?}"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn earth_fills_the_uniform_and_three_layers_are_refused() {
        let earth = Atmosphere::preset("earth").unwrap();
        let u = AtmosphereUniform::new(&earth, RGB_WAVELENGTHS_NM).unwrap();
        assert_eq!(size_of::<AtmosphereUniform>(), 320);
        assert_eq!(u.mie_extinction_per_m, [4.44e-6, 4.44e-6, 4.44e-6, 0.0]);
        assert_eq!(u.rayleigh_density.layers[0], u.rayleigh_density.layers[1]);
        assert_eq!(u.ozone_density.layers[0].width_m, 25_000.0);

        let mut three = earth;
        three.ozone.density.layers.push(DensityLayer::default());
        let err = AtmosphereUniform::new(&three, RGB_WAVELENGTHS_NM).unwrap_err();
        assert!(
            matches!(
                err,
                GpuError::TooManyDensityLayers {
                    species: "ozone",
                    layers: 3
                }
            ),
            "{err}"
        );
    }
}
