//! Rain, water droplets and ice crystals as volumes in planet scenes: their phase
//! functions at many wavelengths, fast enough to render with ([`spectral_phase`]: rain by
//! geometric optics, [`drop_rays`]; small drops and cloud droplets by Lorenz-Mie,
//! [`mie_droplets`]; ice by the crystal ray tracer of `optics/ice/`), seen with the sun's
//! disc ([`sun_disk_blur`]) and reduced to a frame's three wavelengths through the CIE
//! functions ([`channel_phase`]); a rain shaft, a cirrus layer and a droplet deck
//! ([`volumes`]) lit by a sky model's sun in single scattering, the forward peak taken
//! as no scattering ([`forward_peak`]), with the sun's light scattered more than once
//! from a grid of probes ([`sun_orders`]), and by its sky ([`sky_light`]), and composited over the model's frame
//! ([`render`]), the twin of render-wgpu's `precipitation/`; [`scene`] places them
//! around a camera from a scene's settings.
//!
//! Conventions, once: scattering angles from the sun's direction of travel (0: forward,
//! 180: back towards the sun, the antisolar point); phase functions in sr^-1 with unit
//! integral over the sphere, tabulated at the centres of equal bins of angle.

pub mod channel_phase;
pub mod drop_rays;
pub mod error;
pub mod forward_peak;
pub mod mie_droplets;
pub mod reduced;
pub mod reference;
pub mod render;
pub mod scene;
pub mod sky_light;
pub mod spectral_phase;
pub mod sun_disk_blur;
pub mod sun_orders;
pub mod volumes;
