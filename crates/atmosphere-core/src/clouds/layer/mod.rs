//! The cloud layer around the planet, seen near and from inside: its settings
//! ([`settings`]), the shell it fills ([`shell`]), its density from the cover, a vertical
//! profile and detail noise ([`profile`], [`field`]), Riley et al. 2004's
//! multiple-scattering tables ([`orders`]) of the droplets' Mie phase function
//! ([`droplets`]), the delta-Eddington slab of the `eddington` method ([`eddington`]),
//! the ray march of a view ray ([`march`]), its
//! interactive, offline and finest settings ([`presets`]), the reduced-resolution march's
//! interpolation ([`upsample`]), in frames
//! by the segment each ray marched ([`segment_upsample`]), and its compositing with a
//! sky model's light ([`composite`], the air in front of the cloud from a reduced run
//! [`front_upsample`]); the
//! sun's attenuation through the layer over the view's region, once a frame
//! ([`sun_map`]), the surface in its shadow ([`shadowed_surface`]) and the air under it
//! ([`air_shadow`], at a reduced resolution [`air_shadow_upsample`]).

pub mod air_shadow;
pub mod air_shadow_upsample;
pub mod composite;
pub mod direct_shade;
pub mod droplets;
pub mod eddington;
pub mod field;
pub mod four_stream;
pub mod front_upsample;
pub mod march;
pub mod orders;
pub mod presets;
pub mod profile;
pub mod segment_upsample;
pub mod settings;
pub mod shadowed_air;
pub mod shadowed_surface;
pub mod shell;
pub mod sun_map;
pub mod upsample;
