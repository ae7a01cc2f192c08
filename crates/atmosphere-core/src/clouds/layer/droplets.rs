//! The cloud layer's droplets: water spheres in a lognormal distribution of effective
//! radius 10 um (sigma 0.1), a typical stratocumulus droplet (docs/particles.md), whose
//! Lorenz-Mie phase function at each wavelength, as a Legendre series, makes Riley et
//! al. 2004's A_n and F_n tables (`orders.rs`; A_1 is the phase function itself, with
//! its forward peak, the cloudbow near 140 degrees and the glory at 180 degrees). The
//! series take tens of seconds to build; [`droplet_orders_cached`] keeps them in a
//! [`TableCache`].

use crate::clouds::error::CloudError;
use crate::clouds::layer::orders::ScatteringOrders;
use crate::optics::legendre_series::LegendreSeries;
use crate::optics::mie::legendre::mie_legendre_series;
use crate::optics::mie::size_distribution::SizeDistribution;
use crate::optics::refractive_index::water::water_refractive_index;
use crate::table_cache::TableCache;

/// The droplets' effective radius, m.
pub const EFFECTIVE_RADIUS_M: f64 = 10e-6;
/// The lognormal distribution's width (the standard deviation of ln r).
pub const SIGMA: f64 = 0.1;
/// The size average's relative tolerance (`particle_optics`).
const TOLERANCE: f64 = 1e-3;

/// The Legendre series of the droplets' phase function at `wavelength_nm`.
pub fn droplet_series(wavelength_nm: f64) -> Result<LegendreSeries, CloudError> {
    let m = water_refractive_index(wavelength_nm)
        .map_err(|e| CloudError(format!("cloud droplets at {wavelength_nm} nm: {e}")))?;
    let distribution = SizeDistribution::lognormal(EFFECTIVE_RADIUS_M, SIGMA)
        .map_err(|e| CloudError(format!("cloud droplets: {e}")))?;
    mie_legendre_series(m, wavelength_nm * 1e-9, &distribution, TOLERANCE)
        .map(|mie| mie.series)
        .map_err(|e| CloudError(format!("cloud droplets at {wavelength_nm} nm: {e}")))
}

/// A_n and F_n of the droplets at each of `wavelengths_nm`.
pub fn droplet_orders(wavelengths_nm: &[f64]) -> Result<ScatteringOrders, CloudError> {
    let series = wavelengths_nm
        .iter()
        .map(|&w| droplet_series(w))
        .collect::<Result<Vec<_>, _>>()?;
    ScatteringOrders::new(&series)
}

/// [`droplet_orders`] with the Legendre series kept in `cache`, keyed by the droplets'
/// distribution, the tolerance and the wavelengths.
pub fn droplet_orders_cached(
    wavelengths_nm: &[f64],
    cache: &TableCache,
) -> Result<ScatteringOrders, CloudError> {
    let key = format!(
        "lognormal effective_radius_m={EFFECTIVE_RADIUS_M:?} sigma={SIGMA:?} \
         tolerance={TOLERANCE:?} wavelengths_nm={wavelengths_nm:?}"
    );
    let rows = cache.load_or_build("droplet-series", &key, || {
        wavelengths_nm
            .iter()
            .map(|&w| droplet_series(w).map(|s| s.coefficients().to_vec()))
            .collect::<Result<Vec<_>, _>>()
    })?;
    if rows.len() != wavelengths_nm.len() || rows.iter().any(Vec::is_empty) {
        return droplet_orders(wavelengths_nm);
    }
    let series: Vec<LegendreSeries> = rows
        .into_iter()
        .map(LegendreSeries::from_coefficients)
        .collect();
    ScatteringOrders::new(&series)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tables_hold_the_droplets_asymmetry_cloudbow_and_glory() {
        let orders = droplet_orders(&[680.0, 550.0, 440.0]).unwrap();
        let a1 = |w: usize, deg: f64| orders.distribution(w, 1, deg.to_radians().cos());
        for w in 0..3 {
            // The glory: the backscatter rises towards 180 degrees.
            assert!(a1(w, 180.0) > 2.0 * a1(w, 172.0), "{w}: {}", a1(w, 180.0));
            // The cloudbow: a maximum between 135 and 150 degrees over the side
            // scattering near 120.
            let bow = (135..=150).map(|d| a1(w, f64::from(d))).fold(0.0, f64::max);
            assert!(bow > 1.5 * a1(w, 120.0), "{w}: {bow} {}", a1(w, 120.0));
        }
        // The green series' asymmetry is the droplets' (docs/particles.md: 0.8654).
        let g = droplet_series(550.0).unwrap().asymmetry();
        assert!((g - 0.8654).abs() < 1e-3, "{g}");
        let e = droplet_orders(&[1500.0]).unwrap_err().to_string();
        assert!(e.contains("1500 nm"), "{e}");
    }
}
