//! A spectral phase function reduced to a frame's three wavelengths. The light a volume
//! scatters, E_sun(lambda) T(lambda) p(theta, lambda), has the sun's spectrum, the
//! atmosphere's smooth transmittance and the phase function's sharp colours (the bows'
//! and halos' dispersion). The phase function is carried at N wavelengths: under the
//! sun's spectrum its colour is the CIE 1931 XYZ of E_sun p(theta, .)
//! (`color/mod.rs`, [`SpectrumToColor`]), which becomes radiance at the frame's three
//! wavelengths by the inverse of their own 3 x 3 map to XYZ, and is divided by E_sun
//! there:
//!     P_c(theta) = [W_3^-1 W_N (E_sun p(theta, .))]_c / E_sun(lambda_c).
//! A phase function equal at every wavelength comes out unchanged (the colour
//! conversion reproduces anything grey under the sun exactly), and the frame multiplies
//! P_c by its own sun and transmittance in its three channels.

use crate::atmosphere::solar::astm_g173_irradiance_w_m2_nm;
use crate::color::SpectrumToColor;

use super::error::HydrometeorError;
use super::spectral_phase::SpectralPhase;

/// A phase function at a frame's three wavelengths, in bins of `bin_deg` from 0 degrees
/// (values at the centres), sr^-1.
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelPhase {
    pub bin_deg: f64,
    pub values: Vec<[f64; 3]>,
}

/// The inverse of a 3 x 3 matrix (by cofactors), `None` when singular.
fn invert(m: [[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let c = |r: usize, k: usize| {
        let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
        let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
        m[r1][k1] * m[r2][k2] - m[r1][k2] * m[r2][k1]
    };
    let det: f64 = (0..3).map(|k| m[0][k] * c(0, k)).sum();
    (det.abs() > 1e-300).then(|| std::array::from_fn(|i| std::array::from_fn(|j| c(j, i) / det)))
}

impl ChannelPhase {
    /// `spectral` reduced to radiance at `channels_nm` (the frame's wavelengths).
    pub fn new(
        spectral: &SpectralPhase,
        channels_nm: [f64; 3],
    ) -> Result<ChannelPhase, HydrometeorError> {
        let many = SpectrumToColor::new(&spectral.wavelengths_nm)?;
        let three = SpectrumToColor::new(&channels_nm)?;
        // Rows X, Y, Z; columns the three wavelengths.
        let w3: [[f64; 3]; 3] =
            std::array::from_fn(|row| std::array::from_fn(|c| three.xyz_weights()[c][row]));
        let inverse = invert(w3).ok_or(HydrometeorError::Setting {
            what: "frame wavelengths (their colours are not independent)",
            value: channels_nm[0],
            range: "three distinct wavelengths of independent colour",
        })?;
        let sun_many: Vec<f64> = spectral
            .wavelengths_nm
            .iter()
            .map(|&l| astm_g173_irradiance_w_m2_nm(l))
            .collect();
        let sun_three = channels_nm.map(astm_g173_irradiance_w_m2_nm);
        let bins = spectral.phase[0].len();
        let values = (0..bins)
            .map(|b| {
                let mut xyz = [0.0; 3];
                for (w, weights) in many.xyz_weights().iter().enumerate() {
                    let radiance = sun_many[w] * spectral.phase[w][b];
                    for k in 0..3 {
                        xyz[k] += weights[k] * radiance;
                    }
                }
                std::array::from_fn(|c| {
                    (0..3).map(|k| inverse[c][k] * xyz[k]).sum::<f64>() / sun_three[c]
                })
            })
            .collect();
        Ok(ChannelPhase {
            bin_deg: spectral.bin_deg,
            values,
        })
    }

    /// The value at `angle_deg`, linear between bin centres.
    pub fn value_at(&self, angle_deg: f64) -> [f64; 3] {
        let v = &self.values;
        let x = (angle_deg / self.bin_deg - 0.5).clamp(0.0, (v.len() - 1) as f64);
        let i = (x.floor() as usize).min(v.len() - 2);
        let t = x - i as f64;
        std::array::from_fn(|c| v[i][c] * (1.0 - t) + v[i + 1][c] * t)
    }
}
