//! How a voxel cloud is rendered, each setting with its range: by half-angle slicing, by
//! the ray march or by the path tracer (their ground truth), the light's multiple
//! scattering (the layer's [`LayerMethod`]:
//! Riley et al. 2004 or the octaves), and the steps of each method.

use std::fmt;
use std::str::FromStr;

use crate::clouds::error::{CloudError, check_range};
use crate::clouds::layer::settings::{
    LayerMethod, LayerSettings, MAX_OCTAVES, MAX_SHADOW_STEPS, MAX_STEPS, MIN_STOP_TRANSMITTANCE,
};

/// The fewest and most slices.
pub const MIN_SLICES: u32 = 2;
pub const MAX_SLICES: u32 = 4096;
/// The smallest and largest light buffer, texels on a side.
pub const MIN_LIGHT_BUFFER_PX: u32 = 8;
pub const MAX_LIGHT_BUFFER_PX: u32 = 4096;

/// Which algorithm renders the volume.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VolumeMethod {
    /// Half-angle slicing with a light and an eye buffer (Kniss et al. 2002; Riley et
    /// al. 2004 sections 4.2 and 5).
    Slicing,
    /// A ray march per pixel with a shadow march per sample (the layer's `march.rs`).
    March,
    /// The cloud path tracer, all orders of scattering (`path_traced.rs`): the ground
    /// truth of the other two.
    PathTraced,
}

impl fmt::Display for VolumeMethod {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            VolumeMethod::Slicing => "slicing",
            VolumeMethod::March => "march",
            VolumeMethod::PathTraced => "path",
        })
    }
}

impl FromStr for VolumeMethod {
    type Err = CloudError;

    fn from_str(s: &str) -> Result<Self, CloudError> {
        match s {
            "slicing" => Ok(VolumeMethod::Slicing),
            "march" => Ok(VolumeMethod::March),
            "path" => Ok(VolumeMethod::PathTraced),
            other => Err(CloudError(format!(
                "volume method {other:?} is not one of slicing, march, path"
            ))),
        }
    }
}

/// The settings of both methods. Every field has a range ([`VolumeSettings::check`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeSettings {
    /// How light scattered more than once is computed (riley or octaves).
    pub light: LayerMethod,
    /// Slices through the volume, in [2, 4096].
    pub slices: u32,
    /// Light buffer texels on a side, in [8, 4096].
    pub light_buffer_px: u32,
    /// The march's view steps per ray, in [1, 512].
    pub steps: u32,
    /// The march's shadow steps per view step, in [1, 64].
    pub shadow_steps: u32,
    /// Riley et al. 2004's back-scattering term xi (Eq. 26), sr^-1, in [0, 1].
    pub backscatter_xi: f64,
    /// Octaves of [`LayerMethod::Octaves`], in [1, 8].
    pub octaves: u32,
}

impl Default for VolumeSettings {
    fn default() -> Self {
        VolumeSettings {
            light: LayerMethod::Riley,
            slices: 256,
            light_buffer_px: 256,
            steps: 256,
            shadow_steps: 32,
            backscatter_xi: 0.05,
            octaves: 4,
        }
    }
}

impl VolumeSettings {
    /// `Ok` when every field lies in its range, else an error naming the first that does
    /// not, with its value and range.
    pub fn check(&self) -> Result<(), CloudError> {
        if self.light.is_slab() {
            return Err(CloudError(format!(
                "volume light = {}: the slab methods are the planet layer's (a horizontal \
                 layer); a local volume takes riley or octaves",
                self.light
            )));
        }
        check_count("volume slices", self.slices, MIN_SLICES, MAX_SLICES)?;
        check_count(
            "volume light_buffer_px",
            self.light_buffer_px,
            MIN_LIGHT_BUFFER_PX,
            MAX_LIGHT_BUFFER_PX,
        )?;
        check_count("volume steps", self.steps, 1, MAX_STEPS)?;
        check_count(
            "volume shadow_steps",
            self.shadow_steps,
            1,
            MAX_SHADOW_STEPS,
        )?;
        check_range("volume backscatter_xi", self.backscatter_xi, 0.0, 1.0)?;
        check_count("volume octaves", self.octaves, 1, MAX_OCTAVES)
    }

    /// The layer march's settings with these steps and light: the march never stops
    /// early but at the layer's smallest stopping transmittance, as slicing never does.
    pub fn march_settings(&self) -> LayerSettings {
        LayerSettings {
            method: self.light,
            steps: self.steps,
            shadow_steps: self.shadow_steps,
            backscatter_xi: self.backscatter_xi,
            octaves: self.octaves,
            min_transmittance: MIN_STOP_TRANSMITTANCE,
            ..LayerSettings::default()
        }
    }
}

fn check_count(what: &str, value: u32, min: u32, max: u32) -> Result<(), CloudError> {
    if (min..=max).contains(&value) {
        Ok(())
    } else {
        Err(CloudError(format!(
            "{what} = {value} must lie in [{min}, {max}]"
        )))
    }
}
