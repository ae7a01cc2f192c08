//! The sun's irradiance at a point of the atmosphere on a plane facing it: the solar
//! irradiance at the top times the transmittance of the air towards the sun, read from
//! the columns of matter of a transmittance table T(r, mu_s) (Bruneton and Neyret 2008,
//! section 4); none where the ground hides the sun. The sun is a point.

use glam::DVec3;

use crate::atmosphere::Atmosphere;
use crate::atmosphere::spectra::Spectra;
use crate::optics::column::optical_depth;
use crate::optics::geometry::ray_hits_ground;
use crate::optics::transmittance_table::{BRUNETON_TABLE_SIZE, TransmittanceTable};

/// The solar irradiance through the atmosphere at the wavelengths of a [`Spectra`].
#[derive(Clone, Debug)]
pub struct SunThroughAtmosphere {
    table: TransmittanceTable,
    extinction: Vec<[f64; 3]>,
    solar_irradiance: Vec<f64>,
    bottom_radius_m: f64,
    top_radius_m: f64,
}

impl SunThroughAtmosphere {
    /// The table of `atmosphere` at Bruneton's size, the coefficients of `spectra`.
    pub fn new(atmosphere: &Atmosphere, spectra: &Spectra) -> SunThroughAtmosphere {
        let (width, height) = BRUNETON_TABLE_SIZE;
        SunThroughAtmosphere {
            table: TransmittanceTable::build(atmosphere, width, height),
            extinction: spectra.extinction.clone(),
            solar_irradiance: spectra.solar_irradiance.clone(),
            bottom_radius_m: atmosphere.bottom_radius_m,
            top_radius_m: atmosphere.top_radius_m,
        }
    }

    pub fn wavelengths(&self) -> usize {
        self.solar_irradiance.len()
    }

    /// The irradiance at `point` (planet-centred, m) from the sun in the unit direction
    /// `sun`, W m^-2 nm^-1, into `out` (one value per wavelength).
    pub fn irradiance(&self, point: DVec3, sun: DVec3, out: &mut [f64]) {
        let length = point.length();
        let mu_s = (point.dot(sun) / length).clamp(-1.0, 1.0);
        let r = length.clamp(self.bottom_radius_m, self.top_radius_m);
        if ray_hits_ground(r, mu_s, self.bottom_radius_m) {
            out.fill(0.0);
            return;
        }
        let column = if length >= self.top_radius_m && mu_s >= 0.0 {
            [0.0; 3]
        } else {
            self.table.column(r, mu_s)
        };
        for ((o, e), s) in out
            .iter_mut()
            .zip(&self.extinction)
            .zip(&self.solar_irradiance)
        {
            *o = s * (-optical_depth(column, *e)).exp();
        }
    }
}
