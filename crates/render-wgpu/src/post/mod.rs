//! After the sky: the tone map from spectral radiance to display sRGB, and the frame's
//! log-average luminance for automatic exposure.

pub mod luminance;
pub mod tone_map;
pub mod tone_map_pass;
