//! The place flags that `atmos view` and `atmos render` share: the camera's latitude and
//! longitude, given together, and the one check of their ranges both commands apply
//! ([`check_lat_lon`]).

use anyhow::bail;
use clap::Args;

/// `--latitude-deg` and `--longitude-deg` (for `atmos render`, the scene's
/// `latitude_deg` and `longitude_deg`).
#[derive(Clone, Debug, Default, PartialEq, Args)]
pub struct LocationFlags {
    /// Camera latitude, degrees north, in [-90, 90].
    #[arg(
        long,
        value_name = "DEG",
        allow_negative_numbers = true,
        requires = "longitude_deg"
    )]
    pub latitude_deg: Option<f64>,
    /// Camera longitude, degrees east, in [-180, 180].
    #[arg(
        long,
        value_name = "DEG",
        allow_negative_numbers = true,
        requires = "latitude_deg"
    )]
    pub longitude_deg: Option<f64>,
}

/// The latitude and longitude, degrees, if they lie in [-90, 90] and [-180, 180]; values
/// outside are refused rather than wrapped, as a longitude of 1000 is more likely a
/// mistake than a place.
pub fn check_lat_lon(latitude_deg: f64, longitude_deg: f64) -> anyhow::Result<(f64, f64)> {
    if !(latitude_deg.is_finite() && (-90.0..=90.0).contains(&latitude_deg)) {
        bail!("--latitude-deg {latitude_deg} must lie in [-90, 90]");
    }
    if !(longitude_deg.is_finite() && (-180.0..=180.0).contains(&longitude_deg)) {
        bail!("--longitude-deg {longitude_deg} must lie in [-180, 180]");
    }
    Ok((latitude_deg, longitude_deg))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn places_outside_the_globe_are_named() {
        assert_eq!(check_lat_lon(-90.0, 180.0).unwrap(), (-90.0, 180.0));
        let err = |lat, lon| check_lat_lon(lat, lon).unwrap_err().to_string();
        assert_eq!(
            err(0.0, 1000.0),
            "--longitude-deg 1000 must lie in [-180, 180]"
        );
        assert_eq!(
            err(0.0, 180.5),
            "--longitude-deg 180.5 must lie in [-180, 180]"
        );
        assert_eq!(err(95.0, 0.0), "--latitude-deg 95 must lie in [-90, 90]");
        assert_eq!(
            err(f64::NAN, 0.0),
            "--latitude-deg NaN must lie in [-90, 90]"
        );
    }
}
