//! Places on a planet: latitude, longitude and the planet-fixed frame.

pub mod equirectangular;
