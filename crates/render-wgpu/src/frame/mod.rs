//! What one frame shows: the camera (f64 position relative to the planet's centre,
//! orientation, vertical field of view), the sun, the atmosphere, the model with its
//! settings, the exposure and the image size. A frame is a plain description; the
//! [`crate::renderer::Renderer`] turns it into pixels.

pub mod atmosphere_uniform;
pub mod ground_in_view;
pub mod plan;
pub mod surface_buffer;
pub mod uniform;

use atmosphere_core::atmosphere::{Atmosphere, presets};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::check_settings;
use atmosphere_core::models::sky_model::{ModelSettings, ViewRay};
use atmosphere_core::optics::sea_surface::{DEFAULT_WIND_M_S, check_wind};
use glam::{DMat3, DQuat, DVec3};

use crate::gpu::error::RenderError;

/// Largest image side, px (WebGPU's default texture limit).
pub const MAX_SIDE_PX: u32 = 8192;

/// One frame to render.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Camera position relative to the planet's centre, m.
    pub camera_position_m: DVec3,
    /// Rotation from camera axes (x right, y up, -z forward) to planet axes.
    pub orientation: DQuat,
    /// Vertical field of view, degrees, in (0, 180).
    pub vertical_fov_deg: f64,
    /// Unit vector towards the sun's centre.
    pub sun_direction: DVec3,
    pub atmosphere: Atmosphere,
    /// The sky model; one of [`crate::sky::registry::GPU_MODELS`] to be rendered.
    pub model: ModelId,
    pub settings: ModelSettings,
    /// Exposure value at ISO 100: the tone map scales luminance by 1 / (1.2 * 2^EV100).
    pub exposure_ev100: f64,
    pub width: u32,
    pub height: u32,
    /// Terrain over the planet from the shipped Earth maps; `None`: the smooth sphere.
    pub terrain: Option<TerrainOptions>,
}

/// Terrain drawn over the planet (`terrain/pass.rs`): the Earth's height and colour maps
/// of `assets/earth` on the atmosphere's bottom sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TerrainOptions {
    /// Vertical exaggeration of the heights (1 = true scale; docs/terrain.md), in
    /// (0, MAX_EXAGGERATION].
    pub exaggeration: f64,
    /// Wind speed 12.5 m above the sea, m/s, in
    /// [`atmosphere_core::optics::sea_surface::WIND_RANGE_M_S`]: the roughness of the
    /// sea's glint (Cox and Munk 1954; docs/terrain.md, "Water"). A caller's surface
    /// ([`crate::Renderer::render_with_surface`]) takes its sea from here too.
    pub wind_m_s: f64,
    /// Whether a frame waits for every chunk mesh it chooses (on: offline rendering,
    /// whose image then depends on the frame alone) or draws what is built and covers
    /// the rest while a worker builds it (off: the viewer, whose frames never wait;
    /// docs/terrain.md, "No popping").
    pub wait_for_chunks: bool,
    /// Light shafts: the terrain's shadow in the air, in the models that have them
    /// (docs/shafts.md).
    pub shafts: bool,
}

/// The largest vertical exaggeration: the Earth's relief times 100 reaches 880 km, far
/// above any atmosphere.
pub const MAX_EXAGGERATION: f64 = 100.0;

impl Default for TerrainOptions {
    fn default() -> Self {
        TerrainOptions {
            exaggeration: 1.0,
            wind_m_s: DEFAULT_WIND_M_S,
            wait_for_chunks: true,
            shafts: true,
        }
    }
}

/// Whether the Earth's terrain may be drawn on `atmosphere`'s planet: the maps are the
/// Earth's relief, so only on a ground sphere of the Earth's radius.
pub fn terrain_fits(atmosphere: &Atmosphere) -> bool {
    atmosphere.bottom_radius_m == presets::earth().bottom_radius_m
}

/// The orientation of a camera looking along `forward` with `up` as near its up axis as
/// possible; `None` when the two are parallel or either is zero.
pub fn look_orientation(forward: DVec3, up: DVec3) -> Option<DQuat> {
    let back = -forward.try_normalize()?;
    let right = up.cross(back).try_normalize()?;
    let up = back.cross(right);
    Some(DQuat::from_mat3(&DMat3::from_cols(right, up, back)))
}

/// A camera placed by angles, in the convention of `ViewRay::from_angles` (the probe's
/// columns): the camera `altitude_m` above the ground on the planet's z axis, azimuths
/// from the x axis towards y, zenith angles from the local vertical.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalView {
    pub altitude_m: f64,
    pub view_zenith_deg: f64,
    pub view_azimuth_deg: f64,
    pub sun_zenith_deg: f64,
    pub sun_azimuth_deg: f64,
}

/// The unit vector at `zenith_deg` from z and `azimuth_deg` from x towards y.
fn from_zenith_azimuth(zenith_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (z, a) = (zenith_deg.to_radians(), azimuth_deg.to_radians());
    DVec3::new(z.sin() * a.cos(), z.sin() * a.sin(), z.cos())
}

impl LocalView {
    /// Camera position relative to the planet's centre, m.
    pub fn position_m(&self, bottom_radius_m: f64) -> DVec3 {
        DVec3::new(0.0, 0.0, bottom_radius_m + self.altitude_m)
    }

    /// Looking along the view angles with the local zenith up; looking straight up or
    /// down, the image's top points along the view azimuth.
    pub fn orientation(&self) -> DQuat {
        let forward = from_zenith_azimuth(self.view_zenith_deg, self.view_azimuth_deg);
        look_orientation(forward, DVec3::Z)
            .or_else(|| look_orientation(forward, from_zenith_azimuth(90.0, self.view_azimuth_deg)))
            .unwrap_or(DQuat::IDENTITY)
    }

    /// Unit vector towards the sun.
    pub fn sun_direction(&self) -> DVec3 {
        from_zenith_azimuth(self.sun_zenith_deg, self.sun_azimuth_deg)
    }
}

/// The rotation that carries a [`LocalView`] (camera on the z axis) to the point at
/// latitude `lat_deg` and longitude `lon_deg` (east positive) in the planet-fixed axes
/// of `terrain::geo_grid`: x to local north, y to local west, z to local up. A local
/// view's azimuth `a` there points `a` degrees from north towards west, so a geographic
/// azimuth `b` (from north towards east) is the local view's `-b`.
pub fn location_rotation(lat_deg: f64, lon_deg: f64) -> DQuat {
    let (lat, lon) = (lat_deg.to_radians(), lon_deg.to_radians());
    let up = DVec3::new(lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin());
    let east = DVec3::new(-lon.sin(), lon.cos(), 0.0);
    let north = up.cross(east);
    DQuat::from_mat3(&DMat3::from_cols(north, -east, up))
}

impl Frame {
    /// Why this frame cannot be rendered, if it cannot: non-finite or zero vectors, a
    /// camera below the ground, a field of view outside (0, 180) degrees, an empty or too
    /// large image, terrain on a planet that is not the Earth's size, a model setting
    /// unknown or out of its range.
    pub fn validate(&self) -> Result<(), RenderError> {
        let bad = |message: String| Err(RenderError::Frame(message));
        if !self.camera_position_m.is_finite() {
            return bad("camera position must be finite".into());
        }
        let altitude_m = self.camera_position_m.length() - self.atmosphere.bottom_radius_m;
        if altitude_m < 0.0 {
            return bad(format!("camera is {:.3} m below the ground", -altitude_m));
        }
        if !(self.orientation.is_finite() && self.orientation.length() > 0.5) {
            return bad("camera orientation must be a finite rotation".into());
        }
        if self.sun_direction.try_normalize().is_none() {
            return bad("sun direction must be a finite non-zero vector".into());
        }
        if !(self.vertical_fov_deg > 0.0 && self.vertical_fov_deg < 180.0) {
            return bad(format!(
                "vertical field of view {} deg must lie strictly between 0 and 180",
                self.vertical_fov_deg
            ));
        }
        if !self.exposure_ev100.is_finite() {
            return bad("exposure must be finite".into());
        }
        if self.terrain.is_some() && !terrain_fits(&self.atmosphere) {
            return bad(format!(
                "the terrain is the Earth's relief, drawn on a ground radius of {} m only \
                 (this planet's is {} m)",
                presets::earth().bottom_radius_m,
                self.atmosphere.bottom_radius_m
            ));
        }
        if let Some(t) = self.terrain
            && !(t.exaggeration > 0.0 && t.exaggeration <= MAX_EXAGGERATION)
        {
            return bad(format!(
                "terrain exaggeration {} must lie in (0, {MAX_EXAGGERATION}]",
                t.exaggeration
            ));
        }
        if let Some(t) = self.terrain {
            check_wind(t.wind_m_s).map_err(|e| RenderError::Frame(format!("terrain {e}")))?;
        }
        if !(1..=MAX_SIDE_PX).contains(&self.width) || !(1..=MAX_SIDE_PX).contains(&self.height) {
            return bad(format!(
                "image {}x{} px: each side must be 1 to {MAX_SIDE_PX}",
                self.width, self.height
            ));
        }
        check_settings(self.model, &self.settings)?;
        Ok(())
    }

    /// The camera's right, up and forward unit vectors in planet axes.
    pub fn axes(&self) -> [DVec3; 3] {
        let q = self.orientation.normalize();
        [q * DVec3::X, q * DVec3::Y, q * -DVec3::Z]
    }

    /// Half the image's width and height on the plane at unit distance in front of the
    /// camera.
    pub fn half_extent(&self) -> (f64, f64) {
        let half_height = (0.5 * self.vertical_fov_deg.to_radians()).tan();
        let aspect = f64::from(self.width) / f64::from(self.height);
        (half_height * aspect, half_height)
    }

    /// The unnormalised direction through image point (x, y) in pixels from the top-left
    /// corner (a pixel's centre is at +0.5): the ray the shaders trace.
    pub fn direction_through(&self, x: f64, y: f64) -> DVec3 {
        let [right, up, forward] = self.axes();
        let (half_w, half_h) = self.half_extent();
        let ndc_x = 2.0 * x / f64::from(self.width) - 1.0;
        let ndc_y = 1.0 - 2.0 * y / f64::from(self.height);
        forward + right * (ndc_x * half_w) + up * (ndc_y * half_h)
    }

    /// The view ray through the centre of pixel (column, row), for the CPU models.
    pub fn pixel_ray(&self, column: u32, row: u32) -> ViewRay {
        ViewRay {
            origin_m: self.camera_position_m,
            direction: self
                .direction_through(f64::from(column) + 0.5, f64::from(row) + 0.5)
                .normalize(),
            sun_direction: self.sun_direction.normalize(),
            max_distance_m: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> Frame {
        let up = DVec3::Z;
        Frame {
            camera_position_m: DVec3::new(0.0, 0.0, 6_361_000.0),
            orientation: look_orientation(DVec3::X, up).unwrap(),
            vertical_fov_deg: 90.0,
            sun_direction: up,
            atmosphere: Atmosphere::preset("earth").unwrap(),
            model: ModelId::Nishita,
            settings: ModelSettings::default(),
            exposure_ev100: 14.0,
            width: 4,
            height: 2,
            terrain: None,
        }
    }

    #[test]
    fn pixel_rays_span_the_field_of_view() {
        let f = frame();
        let [right, up, forward] = f.axes();
        assert!((forward - DVec3::X).length() < 1e-12);
        assert!((up - DVec3::Z).length() < 1e-12);
        assert!((right - DVec3::NEG_Y).length() < 1e-12, "{right}");
        // The image's top edge is 45 degrees above the view direction.
        let top = f.direction_through(2.0, 0.0).normalize();
        assert!((top.dot(DVec3::X) - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-12);
        assert!(f.pixel_ray(0, 0).direction.z > 0.0);
        assert!(f.validate().is_ok());
    }

    #[test]
    fn local_views_look_where_asked() {
        let view = LocalView {
            altitude_m: 10.0,
            view_zenith_deg: 0.0,
            view_azimuth_deg: 90.0,
            sun_zenith_deg: 90.0,
            sun_azimuth_deg: 0.0,
        };
        let mut f = frame();
        f.orientation = view.orientation();
        let [_, up, forward] = f.axes();
        assert!((forward - DVec3::Z).length() < 1e-12);
        assert!((up - DVec3::Y).length() < 1e-12, "{up}");
        assert!((view.sun_direction() - DVec3::X).length() < 1e-12);
        assert_eq!(view.position_m(100.0), DVec3::new(0.0, 0.0, 110.0));
    }

    #[test]
    fn locations_rotate_the_pole_onto_their_point() {
        let r = location_rotation(46.0, 7.8);
        let up = r * DVec3::Z;
        let (lat, lon) = (up.z.asin().to_degrees(), up.y.atan2(up.x).to_degrees());
        assert!((lat - 46.0).abs() < 1e-12 && (lon - 7.8).abs() < 1e-12);
        // x points north (towards the pole along the surface), -y east.
        assert!((r * DVec3::X).z > 0.0 && (r * DVec3::X).dot(up).abs() < 1e-12);
        let east = r * DVec3::NEG_Y;
        assert!(
            east.z.abs() < 1e-12
                && east.dot(DVec3::new(
                    -7.8f64.to_radians().sin(),
                    7.8f64.to_radians().cos(),
                    0.0
                )) > 0.999_999
        );
        // At the equator and longitude 0, north is +z.
        assert!((location_rotation(0.0, 0.0) * DVec3::X - DVec3::Z).length() < 1e-12);
    }

    #[test]
    fn bad_frames_are_refused() {
        let mut f = frame();
        f.vertical_fov_deg = 180.0;
        assert!(
            f.validate()
                .unwrap_err()
                .to_string()
                .contains("field of view")
        );
        let mut f = frame();
        f.camera_position_m.z = 6_359_000.0;
        assert!(
            f.validate()
                .unwrap_err()
                .to_string()
                .contains("below the ground")
        );
        let mut f = frame();
        f.width = 0;
        assert!(f.validate().is_err());
        let mut f = frame();
        f.terrain = Some(TerrainOptions {
            exaggeration: 0.0,
            ..TerrainOptions::default()
        });
        assert!(
            f.validate()
                .unwrap_err()
                .to_string()
                .contains("exaggeration")
        );
        f.terrain = Some(TerrainOptions {
            wind_m_s: 25.0,
            ..TerrainOptions::default()
        });
        let e = f.validate().unwrap_err().to_string();
        assert!(e.contains("wind_m_s 25") && e.contains("[0, 20]"), "{e}");
        let mut f = frame();
        f.terrain = Some(TerrainOptions::default());
        assert!(f.validate().is_ok());
        f.atmosphere = Atmosphere::preset("mars").unwrap();
        f.camera_position_m.z = 3_400_000.0;
        let e = f.validate().unwrap_err().to_string();
        assert!(e.contains("Earth's relief") && e.contains("3389500"), "{e}");
        let mut f = frame();
        f.settings.options.set("samples", 0);
        let e = f.validate().unwrap_err().to_string();
        assert!(e.contains("samples=0 is outside"), "{e}");
        assert!(look_orientation(DVec3::Z, DVec3::Z).is_none());
    }
}
