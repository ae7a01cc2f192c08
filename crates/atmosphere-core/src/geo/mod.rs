//! Places on a planet: latitude, longitude and the planet-fixed frame; the land's cover
//! (rock, snow) by slope, height, latitude and season.

pub mod equirectangular;
pub mod land_cover;
