//! The cloud spheres' own settings, each with its range: how many spheres cut the layer,
//! how fine the attenuation textures are, and at what fraction of a frame's resolution
//! they are shaded. Where the spheres lie, how dense and how
//! lit the cloud is, are the layer's settings (`layer/settings.rs`): one cloud field.

use crate::clouds::error::CloudError;

/// The most spheres.
pub const MAX_COUNT: u32 = 16;
/// The narrowest and widest attenuation textures, texels (the height is half).
pub const MIN_ATTENUATION_WIDTH: usize = 8;
pub const MAX_ATTENUATION_WIDTH: usize = 4096;
/// The largest resolution divisor (the layer's own range).
pub const MAX_RESOLUTION_DIVISOR: u32 = 4;

/// Settings of the spheres. Every field has a range ([`SphereSettings::check`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereSettings {
    /// m, the number of cloud spheres, in [1, 16]; Dobashi et al. 2002 section 6 use 5.
    pub count: u32,
    /// Width of each attenuation texture G_i on its equirectangular grid, texels, in
    /// [8, 4096]; the height is half of it.
    pub attenuation_width: usize,
    /// In frames, the spheres are shaded for one ray per `resolution_divisor` squared
    /// pixels and brought to full size by segment (`reduced.rs`), in [1, 4]; 1 shades
    /// every pixel.
    pub resolution_divisor: u32,
}

impl Default for SphereSettings {
    fn default() -> Self {
        SphereSettings {
            count: 5,
            attenuation_width: 1024,
            resolution_divisor: 1,
        }
    }
}

impl SphereSettings {
    /// `Ok` when every field lies in its range, else an error naming it, its value and
    /// its range.
    pub fn check(&self) -> Result<(), CloudError> {
        if !(1..=MAX_COUNT).contains(&self.count) {
            return Err(CloudError(format!(
                "cloud sphere count = {} must lie in [1, {MAX_COUNT}]",
                self.count
            )));
        }
        if !(MIN_ATTENUATION_WIDTH..=MAX_ATTENUATION_WIDTH).contains(&self.attenuation_width) {
            return Err(CloudError(format!(
                "cloud sphere attenuation_width = {} must lie in [{MIN_ATTENUATION_WIDTH}, \
                 {MAX_ATTENUATION_WIDTH}]",
                self.attenuation_width
            )));
        }
        if !(1..=MAX_RESOLUTION_DIVISOR).contains(&self.resolution_divisor) {
            return Err(CloudError(format!(
                "cloud sphere resolution_divisor = {} must lie in [1, {MAX_RESOLUTION_DIVISOR}]",
                self.resolution_divisor
            )));
        }
        Ok(())
    }

    /// The attenuation textures' height, texels.
    pub fn attenuation_height(&self) -> usize {
        self.attenuation_width / 2
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_of_range_settings_are_named() {
        assert!(SphereSettings::default().check().is_ok());
        let e = SphereSettings {
            count: 0,
            ..SphereSettings::default()
        }
        .check()
        .unwrap_err();
        assert!(
            e.0.contains("cloud sphere count = 0 must lie in [1, 16]"),
            "{e}"
        );
        let e = SphereSettings {
            attenuation_width: 5000,
            ..SphereSettings::default()
        }
        .check()
        .unwrap_err();
        assert!(e.0.contains("attenuation_width = 5000"), "{e}");
        for divisor in [0, 5] {
            let e = SphereSettings {
                resolution_divisor: divisor,
                ..SphereSettings::default()
            }
            .check()
            .unwrap_err();
            let named = format!("resolution_divisor = {divisor} must lie in [1, 4]");
            assert!(e.0.contains(&named), "{e}");
        }
    }
}
