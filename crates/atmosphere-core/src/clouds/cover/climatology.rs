//! The zonal mean of the Earth's total cloud cover by latitude and season: the fraction of
//! the sky covered by cloud, averaged around each circle of latitude.
//!
//! Its shape follows the satellite climatologies (ISCCP, Rossow and Schiffer 1999; MODIS,
//! King et al. 2013): about 0.7 in the intertropical convergence zone a few degrees north
//! of the equator, minima near 0.5 over the subtropical highs 20 to 30 degrees either side
//! of it, the storm tracks cloudiest (over 0.8 over the Southern Ocean at 60 S, near 0.75
//! at 55 N), 0.55 to 0.6 over the poles; a global mean near two thirds. The
//! convergence zone follows the sun: about 5 N on the year's average, 5 degrees further
//! north in August and south in February.
//!
//! Written as a sum of Gaussian bands in latitude: a base, the convergence zone, the two
//! subtropical dips that move with it, and the two storm tracks.

/// Latitude of the intertropical convergence zone, degrees, on day `day_of_year` (1 to
/// 366): 5 N on average, furthest north (10 N) in mid-August.
pub fn itcz_latitude_deg(day_of_year: f64) -> f64 {
    let phase = std::f64::consts::TAU * (day_of_year - 136.0) / 365.25;
    5.0 + 5.0 * phase.sin()
}

fn band(lat_deg: f64, centre_deg: f64, width_deg: f64) -> f64 {
    let x = (lat_deg - centre_deg) / width_deg;
    (-0.5 * x * x).exp()
}

/// Zonal mean total cloud cover (0 to 1) at `lat_deg` on day `day_of_year`.
pub fn zonal_mean_cover(lat_deg: f64, day_of_year: f64) -> f64 {
    let itcz = itcz_latitude_deg(day_of_year);
    let cover = 0.56 + 0.15 * band(lat_deg, itcz, 7.0)
        - 0.08 * band(lat_deg, itcz + 21.0, 8.0)
        - 0.07 * band(lat_deg, itcz - 25.0, 8.0)
        + 0.27 * band(lat_deg, -60.0, 11.0)
        + 0.18 * band(lat_deg, 55.0, 13.0);
    cover.clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bands_sit_where_the_climatologies_put_them() {
        let day = 172.0;
        let itcz = itcz_latitude_deg(day);
        assert!((5.0..=10.0).contains(&itcz), "{itcz}");
        let at = |lat| zonal_mean_cover(lat, day);
        assert!((at(itcz) - 0.7).abs() < 0.03);
        assert!(at(itcz + 21.0) < 0.52 && at(itcz - 25.0) < 0.52);
        assert!((at(-60.0) - 0.83).abs() < 0.03);
        assert!((at(55.0) - 0.74).abs() < 0.03);
        // The area-weighted global mean, near the climatologies' two thirds.
        let n = 1800;
        let (mut sum, mut weight) = (0.0, 0.0);
        for k in 0..n {
            let lat = -90.0 + (k as f64 + 0.5) * 180.0 / n as f64;
            let w = lat.to_radians().cos();
            sum += w * at(lat);
            weight += w;
        }
        let global = sum / weight;
        assert!((0.6..=0.7).contains(&global), "{global}");
    }

    #[test]
    fn the_convergence_zone_follows_the_sun() {
        assert!(itcz_latitude_deg(228.0) > 9.9);
        assert!(itcz_latitude_deg(45.0) < 0.1);
    }
}
