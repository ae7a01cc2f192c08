//! The pinhole camera a volume is rendered through, and the sun that lights it.

use glam::DVec3;

use crate::clouds::error::{CloudError, check_range};
use crate::clouds::layer::march::CloudLight;

/// The narrowest and widest vertical field of view, degrees.
pub const MIN_FOV_DEG: f64 = 1.0;
pub const MAX_FOV_DEG: f64 = 120.0;
/// The largest image side, pixels.
pub const MAX_IMAGE_PX: u32 = 8192;

/// A pinhole camera, m; `forward`, `right` and `up` are orthonormal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeCamera {
    pub position_m: DVec3,
    pub forward: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    pub vertical_fov_deg: f64,
    pub width_px: u32,
    pub height_px: u32,
}

impl VolumeCamera {
    /// A camera at `position_m` looking at `look_at_m` with +z up in the image (+y when
    /// it looks straight up or down), checked: distinct points, fov in [1, 120] degrees,
    /// sides in [1, 8192] pixels.
    pub fn looking_at(
        position_m: DVec3,
        look_at_m: DVec3,
        vertical_fov_deg: f64,
        width_px: u32,
        height_px: u32,
    ) -> Result<VolumeCamera, CloudError> {
        if !(position_m.is_finite() && look_at_m.is_finite()) {
            return Err(CloudError(format!(
                "volume camera position_m {position_m} and look_at_m {look_at_m} must be finite"
            )));
        }
        let forward = (look_at_m - position_m).normalize_or_zero();
        if forward == DVec3::ZERO {
            return Err(CloudError(format!(
                "volume camera look_at_m {look_at_m} must differ from position_m"
            )));
        }
        check_range(
            "volume camera vertical_fov_deg",
            vertical_fov_deg,
            MIN_FOV_DEG,
            MAX_FOV_DEG,
        )?;
        for (name, side) in [("width_px", width_px), ("height_px", height_px)] {
            if !(1..=MAX_IMAGE_PX).contains(&side) {
                return Err(CloudError(format!(
                    "volume camera {name} = {side} must lie in [1, {MAX_IMAGE_PX}]"
                )));
            }
        }
        let hint = if forward.z.abs() > 0.999 {
            DVec3::Y
        } else {
            DVec3::Z
        };
        let right = forward.cross(hint).normalize();
        Ok(VolumeCamera {
            position_m,
            forward,
            right,
            up: right.cross(forward),
            vertical_fov_deg,
            width_px,
            height_px,
        })
    }

    /// The unit direction through the point (x, y) of the image, in pixels from its top
    /// left corner (pixel centres at half-integers).
    pub fn direction(&self, x_px: f64, y_px: f64) -> DVec3 {
        let tan_half = (0.5 * self.vertical_fov_deg.to_radians()).tan();
        let aspect = f64::from(self.width_px) / f64::from(self.height_px);
        let sx = (2.0 * x_px / f64::from(self.width_px) - 1.0) * tan_half * aspect;
        let sy = (1.0 - 2.0 * y_px / f64::from(self.height_px)) * tan_half;
        (self.forward + self.right * sx + self.up * sy).normalize()
    }

    /// The directions through the image's four corners.
    pub fn corner_directions(&self) -> [DVec3; 4] {
        let (w, h) = (f64::from(self.width_px), f64::from(self.height_px));
        [(0.0, 0.0), (w, 0.0), (0.0, h), (w, h)].map(|(x, y)| self.direction(x, y))
    }
}

/// The sun lighting a volume: parallel light, no sky (as Riley et al. 2004 light their
/// volumes).
#[derive(Clone, Debug, PartialEq)]
pub struct VolumeSun {
    /// Unit vector towards the sun.
    pub direction: DVec3,
    /// Irradiance on a plane facing the sun at each wavelength, W m^-2 nm^-1.
    pub irradiance: Vec<f64>,
}

impl VolumeSun {
    /// The sun at `elevation_deg` above the horizon (z = 0) and `azimuth_deg` from +x
    /// towards +y, checked: elevation in [-90, 90], azimuth in [-360, 360], irradiance
    /// finite and in [0, 1e4].
    pub fn new(
        elevation_deg: f64,
        azimuth_deg: f64,
        irradiance: Vec<f64>,
    ) -> Result<VolumeSun, CloudError> {
        check_range("volume sun elevation_deg", elevation_deg, -90.0, 90.0)?;
        check_range("volume sun azimuth_deg", azimuth_deg, -360.0, 360.0)?;
        if irradiance.is_empty() {
            return Err(CloudError(
                "volume sun irradiance: no wavelength given".into(),
            ));
        }
        for &e in &irradiance {
            check_range("volume sun irradiance_w_m2_nm", e, 0.0, 1e4)?;
        }
        let (el, az) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
        Ok(VolumeSun {
            direction: DVec3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin()),
            irradiance,
        })
    }

    /// The layer march's light: this sun, no sky.
    pub fn cloud_light(&self) -> CloudLight {
        CloudLight {
            sun_direction: self.direction,
            sun_irradiance: self.irradiance.clone(),
            sky_irradiance: vec![0.0; self.irradiance.len()],
            up: DVec3::Z,
        }
    }
}
