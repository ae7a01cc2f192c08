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
//! P_c by its own sun and transmittance in its three channels. A table over the sky
//! (falling plates) is reduced bin by bin alike and read by the direction seen
//! ([`ChannelPhase::value_toward`]).

use crate::atmosphere::solar::astm_g173_irradiance_w_m2_nm;
use crate::color::SpectrumToColor;

use glam::DVec3;

use super::error::HydrometeorError;
use super::spectral_phase::SpectralPhase;
use crate::optics::ice::sky_table::SkyGrid;

/// A phase function at a frame's three wavelengths, in bins of `bin_deg` from 0 degrees
/// (values at the centres), sr^-1; or, with `sky`, over its grid of the sky (row-major:
/// elevation rows from -90 degrees, azimuth columns from the sun's).
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelPhase {
    pub bin_deg: f64,
    pub sky: Option<SkyGrid>,
    pub values: Vec<[f64; 3]>,
}

/// The elevation of the unit `seen` above the plane normal to the unit `up`, and its
/// azimuth from the unit `sun`'s, degrees, both by atan2 (as the shader does);
/// an azimuth about the vertical itself is 0.
pub fn sky_angles_deg(seen: DVec3, sun: DVec3, up: DVec3) -> (f64, f64) {
    let z = seen.dot(up);
    let flat = seen - up * z;
    let sun_flat = sun - up * sun.dot(up);
    let elevation = z.atan2(flat.length()).to_degrees();
    let across = flat.cross(sun_flat).dot(up).abs();
    let along = flat.dot(sun_flat);
    let azimuth = if flat.length() * sun_flat.length() < 1e-12 {
        0.0
    } else {
        across.atan2(along).to_degrees()
    };
    (elevation, azimuth)
}

/// `i` and the fraction `t` for reading `n` bins of `width` at `x` (a position from the
/// first bin's start), linear between centres, the end bins' values beyond them.
pub(super) fn between_centres(x: f64, width: f64, n: usize) -> (usize, f64) {
    let u = (x / width - 0.5).clamp(0.0, (n - 1) as f64);
    let i = (u.floor() as usize).min(n - 2);
    (i, u - i as f64)
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
            sky: spectral.sky,
            values,
        })
    }

    /// The value at `angle_deg`, linear between bin centres (a table by angle).
    pub fn value_at(&self, angle_deg: f64) -> [f64; 3] {
        let v = &self.values;
        let (i, t) = between_centres(angle_deg, self.bin_deg, v.len());
        std::array::from_fn(|c| v[i][c] * (1.0 - t) + v[i + 1][c] * t)
    }

    /// The rule the table's unit integral holds by (a table by angle): per bin, the
    /// cosine of its centre and its width in cosine, so that the integral of P over
    /// the sphere is 2 pi sum_b w_b P_b.
    pub fn cosine_rule(&self) -> Vec<(f64, f64)> {
        (0..self.values.len())
            .map(|b| {
                let [from, to] = [b, b + 1].map(|k| (k as f64 * self.bin_deg).to_radians());
                let centre = ((b as f64 + 0.5) * self.bin_deg).to_radians().cos();
                (centre, from.cos() - to.cos())
            })
            .collect()
    }

    /// The value for light seen along the unit `seen` (a view ray's direction) with the
    /// sun towards the unit `sun` and the local vertical `up`: by the angle between
    /// `seen` and `sun`, or, over the sky, bilinear in elevation and azimuth.
    pub fn value_toward(&self, seen: DVec3, sun: DVec3, up: DVec3) -> [f64; 3] {
        let Some(grid) = self.sky else {
            return self.value_at(seen.dot(sun).clamp(-1.0, 1.0).acos().to_degrees());
        };
        let (elevation, azimuth) = sky_angles_deg(seen, sun, up);
        let columns = grid.azimuth_bins();
        let (i, s) = between_centres(
            elevation + 90.0,
            grid.elevation_bin_deg,
            grid.elevation_bins(),
        );
        let (j, t) = between_centres(azimuth, grid.azimuth_bin_deg, columns);
        let v = |r: usize, k: usize| self.values[r * columns + k];
        std::array::from_fn(|c| {
            let low = v(i, j)[c] * (1.0 - t) + v(i, j + 1)[c] * t;
            let high = v(i + 1, j)[c] * (1.0 - t) + v(i + 1, j + 1)[c] * t;
            low * (1.0 - s) + high * s
        })
    }
}
