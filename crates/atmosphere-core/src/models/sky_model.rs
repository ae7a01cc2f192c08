//! The one interface every scattering model answers on the CPU: prepare tables from an
//! atmosphere, then give the radiance and transmittance of any view ray. The probe
//! command, the report and the tests treat all models alike through it.

use glam::DVec3;

use crate::atmosphere::Atmosphere;
use crate::atmosphere::spectra::Spectra;
use crate::models::error::ModelError;
use crate::models::id::ModelId;
use crate::models::model_base::ModelBase;
/// The settings moved to their own module; named here too for the callers outside the
/// crate, which know them as `sky_model::ModelSettings`.
pub use crate::models::settings::ModelSettings;

/// A view ray: where the camera is, where it looks, where the sun is, and optionally an
/// object ending the ray. Positions are relative to the planet's centre, in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewRay {
    pub origin_m: DVec3,
    /// Unit vector.
    pub direction: DVec3,
    /// Unit vector towards the sun's centre.
    pub sun_direction: DVec3,
    /// The ray ends on an object at this distance (or on the ground if that comes first,
    /// which then counts as the object's end: the model adds no ground term); `None`: on
    /// the ground or in space.
    pub max_distance_m: Option<f64>,
}

impl ViewRay {
    /// The ray of the probe's columns: the camera `altitude_m` above the ground on the z
    /// axis, the view `view_zenith_deg` from the zenith in the x-z plane, the sun
    /// `sun_zenith_deg` from the zenith at azimuth `view_sun_azimuth_deg` from the view.
    pub fn from_angles(
        bottom_radius_m: f64,
        altitude_m: f64,
        view_zenith_deg: f64,
        sun_zenith_deg: f64,
        view_sun_azimuth_deg: f64,
        distance_m: Option<f64>,
    ) -> Result<ViewRay, ModelError> {
        let check = |name: &str, v: f64| {
            if v.is_finite() {
                Ok(v)
            } else {
                Err(ModelError::Ray(format!("{name} must be finite, got {v}")))
            }
        };
        let altitude_m = check("altitude_m", altitude_m)?;
        if altitude_m < 0.0 {
            return Err(ModelError::Ray(format!(
                "altitude_m {altitude_m} is below the ground"
            )));
        }
        let vz = check("view_zenith_deg", view_zenith_deg)?.to_radians();
        let sz = check("sun_zenith_deg", sun_zenith_deg)?.to_radians();
        let az = check("view_sun_azimuth_deg", view_sun_azimuth_deg)?.to_radians();
        if let Some(d) = distance_m {
            if !d.is_finite() {
                return Err(ModelError::Ray(format!(
                    "distance_m must be finite, got {d}"
                )));
            }
            if d <= 0.0 {
                return Err(ModelError::Ray(format!("distance_m {d} must be > 0")));
            }
        }
        Ok(ViewRay {
            origin_m: DVec3::new(0.0, 0.0, bottom_radius_m + altitude_m),
            direction: DVec3::new(vz.sin(), 0.0, vz.cos()),
            sun_direction: DVec3::new(sz.sin() * az.cos(), sz.sin() * az.sin(), sz.cos()),
            max_distance_m: distance_m,
        })
    }
}

/// A surface element to light: where it is, which way it faces, where the sun is.
/// Positions are relative to the planet's centre, in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// On or above the ground.
    pub point_m: DVec3,
    /// Outward normal (made unit length where the element is built).
    pub normal: DVec3,
    /// Unit vector towards the sun's centre.
    pub sun_direction: DVec3,
}

impl SurfacePoint {
    /// The element at `point_m` facing up (its normal the local vertical): the ground.
    pub fn facing_up(point_m: DVec3, sun_direction: DVec3) -> SurfacePoint {
        SurfacePoint {
            point_m,
            normal: point_m,
            sun_direction,
        }
    }
}

/// What a model answers for one view ray, at each of its wavelengths.
#[derive(Clone, Debug, PartialEq)]
pub struct RayRadiance {
    /// Radiance scattered and reflected towards the camera, sun disk excluded,
    /// W m^-2 sr^-1 nm^-1.
    pub radiance: Vec<f64>,
    /// Transmittance of the ray from the camera to its end.
    pub transmittance: Vec<f64>,
    /// Standard error of `radiance` (zero for deterministic models).
    pub radiance_std_error: Vec<f64>,
}

impl RayRadiance {
    /// The answer for a ray that meets no atmosphere: no light, full transmittance, at
    /// `wavelengths` wavelengths.
    pub fn unattenuated(wavelengths: usize) -> RayRadiance {
        RayRadiance {
            radiance: vec![0.0; wavelengths],
            transmittance: vec![1.0; wavelengths],
            radiance_std_error: vec![0.0; wavelengths],
        }
    }
}

/// A scattering model on the CPU.
pub trait SkyModel: Send + Sync {
    /// What every model keeps of its preparation: its id, spectra and Mie switch.
    fn base(&self) -> &ModelBase;
    /// The model's id, as on the command line.
    fn id(&self) -> ModelId {
        self.base().id
    }
    /// The atmosphere's coefficients at the model's wavelengths.
    fn spectra(&self) -> &Spectra {
        &self.base().spectra
    }
    /// The wavelengths (nm) of every answer, in the order of the settings.
    fn wavelengths_nm(&self) -> &[f64] {
        &self.spectra().wavelengths_nm
    }
    /// The solar irradiance at the top of the atmosphere used at each wavelength.
    fn solar_irradiance_w_m2_nm(&self) -> &[f64] {
        &self.spectra().solar_irradiance
    }
    /// Radiance and transmittance of one ray.
    fn radiance(&self, ray: &ViewRay) -> Result<RayRadiance, ModelError>;
    /// Irradiance (W m^-2 nm^-1, per wavelength) on the surface element `surface`: the
    /// model's own sun transmittance and sky irradiance combined as in
    /// [`crate::optics::surface_lighting`]. A Lambertian element of albedo `a` ending a view
    /// ray adds `transmittance a / pi` times this to the ray's radiance: the models'
    /// ground on the sphere, and terrain on the GPU.
    fn surface_irradiance(&self, surface: &SurfacePoint) -> Result<Vec<f64>, ModelError> {
        let _ = surface;
        Err(ModelError::Unsupported {
            model: self.id(),
            what: "light surface elements (it answers view rays only)",
        })
    }
    /// Bytes held by the model's precomputed tables.
    fn table_bytes(&self) -> usize;
    /// Adopts a changed atmosphere, rebuilding only the tables that depend on an input
    /// that changed ([`crate::atmosphere::table_inputs::Inputs`]); returns the names of the tables
    /// rebuilt. Answers afterwards equal those of a model prepared from scratch.
    fn update(&mut self, atmosphere: &Atmosphere) -> Result<Vec<&'static str>, ModelError>;
}
