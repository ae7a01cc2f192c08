//! The water's colour where the terrain shader draws water: the colour map's mean over
//! the open sea.
//!
//! The Blue Marble's texels are about 10 km wide, so near a coast a texel mixes land and
//! sea; the terrain shader decides water per pixel from the refined height instead (below
//! 0 where the 1 km land mask says sea, `coastline.rs`) and gives it this colour, the mean
//! linear colour of the texels over open sea (the data's height below
//! [`OPEN_SEA_BELOW_M`] and, where a mask is given, its cell sea).

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use super::colour_map::ColourMap;
use super::height_map::HeightMap;
use super::land_mask::LandMask;

/// Texels over water at least this deep count as open sea, m.
pub const OPEN_SEA_BELOW_M: f64 = -1000.0;

/// The mean linear colour of `colours`' texels over open sea (every fourth texel along
/// each axis); mid grey if there is none.
pub fn open_sea_albedo(
    colours: &ColourMap,
    heights: &HeightMap,
    mask: Option<&LandMask>,
) -> [f64; 3] {
    let (mut sum, mut count) = ([0.0; 3], 0usize);
    for j in (0..colours.height).step_by(4) {
        let lat = FRAC_PI_2 - (j as f64 + 0.5) / colours.height as f64 * PI;
        for i in (0..colours.width).step_by(4) {
            let lon = -PI + (i as f64 + 0.5) / colours.width as f64 * TAU;
            let sea = heights.sample(lat, lon) < OPEN_SEA_BELOW_M
                && mask.is_none_or(|m| !m.is_land(lat, lon));
            if sea {
                let c = colours.sample_linear(lat, lon);
                for (s, c) in sum.iter_mut().zip(c) {
                    *s += c;
                }
                count += 1;
            }
        }
    }
    if count == 0 {
        return [0.5; 3];
    }
    sum.map(|s| s / count as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::earth_data::EarthData;

    /// The Blue Marble's open sea is dark and blue.
    #[test]
    fn the_open_sea_is_dark_blue() {
        let data = EarthData::BuiltIn;
        let mask = data.land_mask().unwrap();
        let sea = open_sea_albedo(
            &data.colours().unwrap(),
            &data.heights().unwrap(),
            mask.as_ref(),
        );
        assert!(sea[2] > sea[1] && sea[1] > sea[0], "{sea:?}");
        assert!(sea[2] < 0.1 && sea[0] > 0.0, "{sea:?}");
    }
}
