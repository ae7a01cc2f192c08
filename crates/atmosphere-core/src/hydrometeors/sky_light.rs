//! The sky's light a volume scatters, as one radiance L_sky the march scatters
//! isotropically: each step adds T_v (1 - e^(-beta dt)) L_sky. The volumes do not absorb
//! (albedo 1), and in a medium that does not absorb inside a uniform radiance field L_0
//! the radiance is L_0 everywhere, every order of scattering counted (the field is the
//! radiative transfer equation's solution whatever the phase function): the march then
//! answers L_0 (1 - T_v) over a background of L_0, the all-orders answer. With
//! [`SkyLight::Sphere`] L_sky is the model's radiance averaged over every direction
//! around the volume's light point (the sky above, the air and the lit ground below, the
//! sun's disc excluded): the all-orders answer for the uniform field of that mean. With
//! [`SkyLight::Horizontal`] it is E_sky / (2 pi), the sky's irradiance on a horizontal
//! plane as a uniform upper hemisphere of radiance E_sky / pi over a black ground.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::models::error::ModelError;
use crate::models::sky_model::{SkyModel, ViewRay};

/// Cosines of the zenith angle of the sphere's average (midpoints of equal steps).
pub const SPHERE_MU_STEPS: usize = 32;
/// Azimuths from the sun's, over 0 to 180 degrees (the sky is symmetric about the
/// sun's vertical plane).
pub const SPHERE_AZIMUTH_STEPS: usize = 16;

/// Which radiance the march scatters as the sky's light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum SkyLight {
    /// The model's radiance averaged over the sphere around the volume.
    #[default]
    Sphere,
    /// E_sky / (2 pi): the horizontal irradiance, the ground black.
    Horizontal,
}

impl SkyLight {
    /// The setting's name on command lines and in scene files.
    pub fn name(self) -> &'static str {
        match self {
            SkyLight::Sphere => "sphere",
            SkyLight::Horizontal => "horizontal",
        }
    }
}

/// The mean over the sphere of `model`'s radiance (at its wavelengths) seen from
/// `point`, with the sun towards the unit `sun`: the midpoint rule in the zenith cosine
/// and in the azimuth from the sun's.
pub fn sphere_mean_radiance(
    model: &dyn SkyModel,
    point: DVec3,
    sun: DVec3,
) -> Result<Vec<f64>, ModelError> {
    let up = point.normalize();
    let flat = sun - up * sun.dot(up);
    let towards_sun = flat
        .try_normalize()
        .unwrap_or_else(|| up.any_orthonormal_vector());
    let across = up.cross(towards_sun);
    let mut mean = vec![0.0; model.wavelengths_nm().len()];
    let weight = 1.0 / (SPHERE_MU_STEPS * SPHERE_AZIMUTH_STEPS) as f64;
    for i in 0..SPHERE_MU_STEPS {
        let mu = -1.0 + 2.0 * (i as f64 + 0.5) / SPHERE_MU_STEPS as f64;
        let sin = (1.0 - mu * mu).sqrt();
        for j in 0..SPHERE_AZIMUTH_STEPS {
            let phi = std::f64::consts::PI * (j as f64 + 0.5) / SPHERE_AZIMUTH_STEPS as f64;
            let direction = up * mu + (towards_sun * phi.cos() + across * phi.sin()) * sin;
            let answer = model.radiance(&ViewRay {
                origin_m: point,
                direction,
                sun_direction: sun,
                max_distance_m: None,
            })?;
            for (m, l) in mean.iter_mut().zip(&answer.radiance) {
                *m += weight * l;
            }
        }
    }
    Ok(mean)
}
