//! The cloud layer's ground truth on the planet: a Monte Carlo path tracer through the
//! layer's field (all orders of scattering, the droplets' tabulated phase function at
//! each wavelength), with next-event estimation of the sun through the atmosphere at
//! every collision, composited with a sky model's air in front of and behind the cloud
//! as the layer's march is (`layer/composite.rs`), and a reported standard error:
//! [`sun_light`] the sun's irradiance through the atmosphere, [`settings`] how many
//! paths, [`camera_path`] one path's light, [`environment`] the light around the cloud, [`phase_sampler`] the phase function drawn exactly, [`forward_peak`] the
//! droplets' forward peak taken as no scattering (a setting of the voxel cloud's
//! tracer), [`ray`] a view ray's answer.

pub mod camera_path;
pub mod environment;
pub mod forward_peak;
pub mod phase_sampler;
pub mod ray;
pub mod settings;
pub mod sun_light;
