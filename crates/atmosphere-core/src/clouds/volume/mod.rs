//! A local volume: a voxel cloud given in a file ([`grid`], [`raw_file`], [`scene`]),
//! placed in a scene as a medium ([`cloud`]), seen by a pinhole camera under the sun
//! ([`camera`]), and rendered two ways to compare them ([`settings`]): by the cloud
//! layer's ray march ([`march_image`]) and by half-angle slicing with a light buffer and
//! an eye buffer, as Riley et al. 2004 (sections 4.2 and 5, after Kniss et al. 2002) do
//! ([`half_angle`], [`light_buffer`], [`slicing`]); both give a [`image::VolumeImage`].
//! The cloud path tracer's image of the same scene ([`path_traced`]) is their ground
//! truth.
//! [`cumulus`] generates the shipped cumulus.

pub mod camera;
pub mod cloud;
pub mod cumulus;
pub mod grid;
pub mod half_angle;
pub mod image;
pub mod light_buffer;
pub mod march_image;
pub mod path_traced;
pub mod raw_file;
pub mod scene;
pub mod settings;
pub mod slicing;
