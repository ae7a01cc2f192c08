//! The cloud layer seen from far away as Dobashi, Yamamoto and Nishita 2002, section 5.4
//! draw the Earth's clouds from space: m concentric cloud spheres through the layer
//! ([`shells`], [`settings`]), each with a cloud texture of its part of the layer's cloud
//! ([`cloud_textures`]) and an attenuation texture of the sun's light reaching it
//! ([`attenuation`]), lit and crossed by view rays ([`field`], [`crossing`]; under the
//! layer's slab methods [`slab_light`]) and composited back to
//! front with a sky model ([`composite`]), in frames at a reduced resolution brought to
//! full size by segment ([`reduced`]); [`handover`] chooses between them and the layer
//! by the camera's altitude.

pub mod attenuation;
pub mod cloud_textures;
pub mod composite;
pub mod crossing;
pub mod field;
pub mod handover;
pub mod reduced;
pub mod settings;
pub mod shells;
pub mod slab_light;
