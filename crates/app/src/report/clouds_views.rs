//! The fixed views of the report's clouds section: a camera, a sun and a cloud (where
//! the layer lies, how dense, over which synthetic cover), each placed at
//! [`PLACE`] over the planet so that the path-traced reference, the layer's march, the
//! cloud spheres and the GPU frames answer the same rays (docs/clouds.md, "The clouds
//! in the report").
//!
//! The views are small (12 rays each) and their clouds thinner than the layer's default
//! deck where the path tracer's cost demands it: a path through optical depth tau
//! scatters about tau^2 times (docs/clouds.md, "Limits of the reference").

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::reference::settings::PathSettings;
use atmosphere_core::models::sky_model::ViewRay;
use glam::{DQuat, DVec3};
use render_wgpu::frame::location_rotation;

use crate::probe_terrain::TerrainPlace;
use crate::report::views::ReportView;

/// Where every view stands: 10 N, 20 E, the sun at azimuth 90 (east).
pub const PLACE: TerrainPlace = TerrainPlace {
    latitude_deg: 10.0,
    longitude_deg: 20.0,
    sun_azimuth_deg: 90.0,
};

/// The cover under a view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ViewCover {
    /// The same cover everywhere.
    Uniform(f64),
    /// Cells of cover: smoothstep(-0.2, 0.4, sin(k lat) sin(k lon)) with k =
    /// `per_radian`, on a 2048 x 1024 grid (cells of pi / k radians).
    Cells { per_radian: f64 },
}

impl ViewCover {
    /// The cover's grid.
    pub fn grid(&self) -> anyhow::Result<CoverGrid> {
        Ok(match *self {
            ViewCover::Uniform(c) => {
                CoverGrid::from_values("uniform cover", 64, 32, vec![c as f32; 64 * 32])?
            }
            ViewCover::Cells { per_radian } => CoverGrid::rasterize(2048, 1024, |p| {
                let p = p.normalize();
                let (lat, lon) = (p.z.asin(), p.y.atan2(p.x));
                let wave = (per_radian * lat).sin() * (per_radian * lon).sin();
                let t = ((wave + 0.2) / 0.6).clamp(0.0, 1.0);
                t * t * (3.0 - 2.0 * t)
            })?,
        })
    }
}

/// One view of the section.
#[derive(Clone, Debug, PartialEq)]
pub struct CloudView {
    /// The camera and sun in the probe's local frame (atmosphere, altitude, sun zenith,
    /// look, field of view, rays), placed at [`PLACE`].
    pub camera: ReportView,
    /// The cloud: base, thickness, extinction and detail noise (the march's own settings
    /// come from each row).
    pub cloud: LayerSettings,
    pub cover: ViewCover,
    /// The path tracer's stopping rule on this view.
    pub paths: PathSettings,
    /// Whether the cloud spheres' row is measured here (the view from orbit).
    pub spheres: bool,
    /// Whether the cloud shadows the air below its base, as frames take it by default
    /// (`--cloud-shafts`): the methods' air from the sun map, the path tracer's from
    /// the field (`cloud_rays.rs`).
    pub shafts: bool,
}

impl CloudView {
    pub fn id(&self) -> &'static str {
        self.camera.id
    }

    /// The view's rays, placed over the planet.
    pub fn rays(&self) -> anyhow::Result<Vec<ViewRay>> {
        let atmosphere = Atmosphere::preset(self.camera.atmosphere)?;
        Ok(self
            .camera
            .rays(&atmosphere)
            .iter()
            .map(|r| PLACE.placed(r))
            .collect())
    }

    /// The rotation that takes the local frame of [`ReportView::rays`] (the sun at
    /// azimuth 0) to [`PLACE`], as [`TerrainPlace::placed`] turns each ray.
    pub fn placement(&self) -> DQuat {
        location_rotation(PLACE.latitude_deg, PLACE.longitude_deg)
            * DQuat::from_rotation_z(-PLACE.sun_azimuth_deg.to_radians())
    }
}

/// The report's four views with `columns` x `rows` rays each.
pub fn cloud_views(columns: usize, rows: usize) -> Vec<CloudView> {
    let camera = |id, title, altitude_m, sun_zenith_deg, elevation, azimuth, fov| ReportView {
        id,
        title,
        atmosphere: "earth",
        altitude_m,
        sun_zenith_deg,
        look_elevation_deg: elevation,
        look_azimuth_deg: azimuth,
        fov_deg: fov,
        columns,
        rows,
    };
    let cloud = |base_m, thickness_m, extinction_per_m, detail_strength| LayerSettings {
        base_m,
        thickness_m,
        extinction_per_m,
        detail_strength,
        ..LayerSettings::default()
    };
    let paths = |target_relative_error, max_paths| PathSettings {
        target_relative_error,
        max_paths,
        ..PathSettings::default()
    };
    vec![
        // 400 m below the top of a full deck of optical depth about 6, looking level.
        CloudView {
            camera: camera(
                "inside",
                "inside a cloud (1.6 km)",
                1_600.0,
                40.0,
                0.0,
                90.0,
                60.0,
            ),
            cloud: cloud(1_000.0, 1_000.0, 0.01, 0.5),
            cover: ViewCover::Uniform(1.0),
            paths: paths(0.04, 40_000),
            spheres: false,
            shafts: true,
        },
        // 2 km above a full deck of optical depth about 11, looking 30 degrees down
        // across the sun's azimuth.
        CloudView {
            camera: camera(
                "above",
                "above a deck (4 km)",
                4_000.0,
                50.0,
                -30.0,
                90.0,
                60.0,
            ),
            cloud: cloud(1_000.0, 1_000.0, 0.015, 0.5),
            cover: ViewCover::Uniform(1.0),
            paths: paths(0.04, 40_000),
            spheres: false,
            shafts: true,
        },
        // The layer's own cumulus-type cloud: a thin cover makes shallow clouds (their
        // top at 0.35 + 0.65 cover of the layer) and full-strength detail noise breaks
        // them; seen from the ground 10 degrees up, 45 degrees from the sun 4 degrees
        // above the horizon.
        CloudView {
            camera: camera(
                "cumulus",
                "cumulus at sunset (ground)",
                2.0,
                86.0,
                10.0,
                45.0,
                60.0,
            ),
            cloud: cloud(1_000.0, 2_000.0, 0.02, 1.0),
            cover: ViewCover::Uniform(0.4),
            paths: paths(0.05, 40_000),
            spheres: false,
            shafts: true,
        },
        // 400 km up, looking 60 degrees down at cells of deck about 300 km across.
        CloudView {
            camera: camera(
                "orbit",
                "a deck from orbit (400 km)",
                400_000.0,
                40.0,
                -60.0,
                90.0,
                20.0,
            ),
            cloud: cloud(1_500.0, 1_500.0, 0.015, 0.5),
            cover: ViewCover::Cells { per_radian: 70.0 },
            paths: paths(0.05, 40_000),
            spheres: true,
            shafts: true,
        },
    ]
}

/// The view's camera position, orientation and sun, placed (for a GPU frame).
pub fn placed_camera(view: &CloudView, bottom_radius_m: f64) -> (DVec3, DQuat, DVec3) {
    let local = render_wgpu::frame::LocalView {
        altitude_m: view.camera.altitude_m,
        view_zenith_deg: 90.0 - view.camera.look_elevation_deg,
        view_azimuth_deg: view.camera.look_azimuth_deg,
        sun_zenith_deg: view.camera.sun_zenith_deg,
        sun_azimuth_deg: 0.0,
    };
    let q = view.placement();
    (
        q * local.position_m(bottom_radius_m),
        q * local.orientation(),
        q * local.sun_direction(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_view_is_valid_and_placed_as_the_probe_places_rays() {
        for view in cloud_views(4, 3) {
            assert!(view.cloud.check().is_ok(), "{}", view.id());
            assert!(view.paths.check().is_ok(), "{}", view.id());
            let rays = view.rays().unwrap();
            assert_eq!(rays.len(), 12);
            let (camera, orientation, sun) = placed_camera(&view, 6_360_000.0);
            assert!((rays[0].origin_m - camera).length() < 1e-6, "{}", view.id());
            assert!(rays[0].sun_direction.dot(sun) > 1.0 - 1e-12);
            let centre = (rays[0].direction + rays[rays.len() - 1].direction).normalize();
            assert!(centre.dot(orientation * DVec3::NEG_Z) > 1.0 - 1e-9);
        }
    }

    #[test]
    fn the_cells_hold_cloud_and_clear_sky() {
        let grid = ViewCover::Cells { per_radian: 70.0 }.grid().unwrap();
        let full = grid.values().iter().filter(|&&c| c > 0.99).count();
        let clear = grid.values().iter().filter(|&&c| c < 0.01).count();
        let n = grid.values().len();
        assert!(full > n / 5 && clear > n / 5, "{full} {clear} of {n}");
    }
}
