//! Raindrop sizes by rain rate: Marshall and Palmer 1948 ("The distribution of raindrops
//! with size", Journal of Meteorology 5, 165-166), n(D) dD = N0 exp(-Lambda D) dD with
//! N0 = 8000 m^-3 mm^-1 and Lambda = 4.1 R^-0.21 mm^-1 for a rain rate R in mm/h and drop
//! diameters D in mm, here over drop radii 0.1 to 3 mm (smaller drops are drizzle and
//! cloud, larger ones break up).

use super::error::MieError;

/// N0, drops per m^3 per mm of diameter.
pub const INTERCEPT_PER_M3_MM: f64 = 8000.0;

/// The drop radii the distribution covers, m.
pub const RADIUS_RANGE_M: [f64; 2] = [1e-4, 3e-3];

/// The rain rates accepted, mm/h: from light rain to a cloudburst. At zero there are no
/// drops and no phase function to give, so zero is refused like any other rate outside.
pub const RAIN_RATE_RANGE_MM_H: [f64; 2] = [0.1, 300.0];

/// The Marshall-Palmer distribution of one rain rate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MarshallPalmer {
    rain_rate_mm_h: f64,
}

impl MarshallPalmer {
    pub fn new(rain_rate_mm_h: f64) -> Result<MarshallPalmer, MieError> {
        let [lo, hi] = RAIN_RATE_RANGE_MM_H;
        if (lo..=hi).contains(&rain_rate_mm_h) {
            Ok(MarshallPalmer { rain_rate_mm_h })
        } else {
            Err(MieError::Distribution {
                what: "rain rate (mm/h)",
                value: rain_rate_mm_h,
                range: "[0.1, 300] (no rain, rate 0, has no drops to scatter)",
            })
        }
    }

    pub fn rain_rate_mm_h(&self) -> f64 {
        self.rain_rate_mm_h
    }

    /// Lambda, per mm of diameter.
    pub fn slope_per_mm(&self) -> f64 {
        4.1 * self.rain_rate_mm_h.powf(-0.21)
    }

    /// n(D), drops per m^3 per mm of diameter, at a drop radius in m.
    pub fn density_per_m3_mm(&self, radius_m: f64) -> f64 {
        let diameter_mm = 2.0 * radius_m * 1e3;
        INTERCEPT_PER_M3_MM * (-self.slope_per_mm() * diameter_mm).exp()
    }

    /// Drops per m^3 between the radii covered: N0 (e^-Lambda D1 - e^-Lambda D2) / Lambda.
    pub fn number_density_m3(&self) -> f64 {
        let slope = self.slope_per_mm();
        let [d1, d2] = RADIUS_RANGE_M.map(|r| 2.0 * r * 1e3);
        INTERCEPT_PER_M3_MM * ((-slope * d1).exp() - (-slope * d2).exp()) / slope
    }
}
