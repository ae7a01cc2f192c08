//! The report's fixed set of views: each a pinhole camera whose pixel centres give a grid
//! of view rays, in the sun's frame (local up = z at the camera, the sun in the x-z
//! plane).

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::sky_model::ViewRay;
use glam::DVec3;

/// One view of the report.
#[derive(Clone, Debug, PartialEq)]
pub struct ReportView {
    pub id: &'static str,
    pub title: &'static str,
    /// An atmosphere preset.
    pub atmosphere: &'static str,
    pub altitude_m: f64,
    /// Angle of the sun's centre from the camera's zenith.
    pub sun_zenith_deg: f64,
    /// Elevation of the optical axis above the local horizontal.
    pub look_elevation_deg: f64,
    /// Azimuth of the optical axis from the sun's azimuth.
    pub look_azimuth_deg: f64,
    /// Horizontal field of view.
    pub fov_deg: f64,
    pub columns: usize,
    pub rows: usize,
}

impl ReportView {
    /// True when the sun's centre is above the camera's horizontal plane: the views on
    /// which the daytime error targets are measured.
    pub fn is_daytime(&self) -> bool {
        self.sun_zenith_deg < 90.0
    }

    /// The index of ray `i`'s mirror image about the sun's vertical plane, where the
    /// optical axis lies in that plane (the same row, the column counted from the other
    /// side); `None` elsewhere and for a middle column, its own mirror.
    pub fn mirror_ray(&self, i: usize) -> Option<usize> {
        if self.look_azimuth_deg.rem_euclid(180.0) != 0.0 {
            return None;
        }
        let (row, column) = (i / self.columns, i % self.columns);
        let mirror = row * self.columns + self.columns - 1 - column;
        (mirror != i).then_some(mirror)
    }

    /// The rays through the pixel centres, row by row from the top left.
    pub fn rays(&self, atmosphere: &Atmosphere) -> Vec<ViewRay> {
        let origin = DVec3::new(0.0, 0.0, atmosphere.bottom_radius_m + self.altitude_m);
        let sz = self.sun_zenith_deg.to_radians();
        let sun_direction = DVec3::new(sz.sin(), 0.0, sz.cos());
        let (e, a) = (
            self.look_elevation_deg.to_radians(),
            self.look_azimuth_deg.to_radians(),
        );
        let forward = DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin());
        let right = forward.cross(DVec3::Z).try_normalize().unwrap_or(DVec3::Y);
        let up = right.cross(forward);
        let half_width = (0.5 * self.fov_deg.to_radians()).tan();
        let half_height = half_width * self.rows as f64 / self.columns as f64;
        let mut rays = Vec::with_capacity(self.columns * self.rows);
        for j in 0..self.rows {
            let y = half_height * (1.0 - 2.0 * (j as f64 + 0.5) / self.rows as f64);
            for i in 0..self.columns {
                let x = half_width * (2.0 * (i as f64 + 0.5) / self.columns as f64 - 1.0);
                rays.push(ViewRay {
                    origin_m: origin,
                    direction: (forward + x * right + y * up).normalize(),
                    sun_direction,
                    max_distance_m: None,
                });
            }
        }
        rays
    }
}

/// The views of the issue: ground at noon, at sunset and in civil twilight; 10 km;
/// 100 km; the limb from orbit; heavy aerosol; then twilight seen from orbit across the
/// terminator, towards the sun (where Bruneton's 2017 tables err most), and nautical
/// twilight from the ground. `columns x rows` rays each.
pub fn report_views(columns: usize, rows: usize) -> Vec<ReportView> {
    let view =
        |id, title, atmosphere, altitude_m, sun_zenith_deg, elevation, azimuth, fov| ReportView {
            id,
            title,
            atmosphere,
            altitude_m,
            sun_zenith_deg,
            look_elevation_deg: elevation,
            look_azimuth_deg: azimuth,
            fov_deg: fov,
            columns,
            rows,
        };
    // The horizon seen from 400 km lies acos(6360 / 6760) = 19.8 deg below horizontal.
    let limb_dip_deg = (6360.0f64 / 6760.0).acos().to_degrees();
    vec![
        view(
            "noon",
            "ground, noon",
            "earth",
            2.0,
            30.0,
            30.0,
            90.0,
            120.0,
        ),
        view(
            "sunset",
            "ground, sunset",
            "earth",
            2.0,
            88.0,
            10.0,
            0.0,
            120.0,
        ),
        view(
            "twilight",
            "ground, civil twilight",
            "earth",
            2.0,
            96.0,
            15.0,
            0.0,
            120.0,
        ),
        view("10km", "10 km", "earth", 10_000.0, 45.0, -10.0, 90.0, 120.0),
        view(
            "100km", "100 km", "earth", 100_000.0, 45.0, -10.0, 60.0, 120.0,
        ),
        view(
            "limb",
            "orbit limb (400 km)",
            "earth",
            400_000.0,
            60.0,
            -limb_dip_deg,
            90.0,
            40.0,
        ),
        view(
            "hazy",
            "ground, heavy aerosol",
            "hazy",
            2.0,
            45.0,
            20.0,
            45.0,
            120.0,
        ),
        view(
            "orbit-twilight",
            "orbit across the terminator (400 km)",
            "earth",
            400_000.0,
            100.0,
            -limb_dip_deg,
            0.0,
            40.0,
        ),
        view(
            "nautical",
            "ground, nautical twilight",
            "earth",
            2.0,
            102.0,
            10.0,
            0.0,
            120.0,
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rays_cover_the_field_of_view_symmetrically() {
        let earth = Atmosphere::preset("earth").unwrap();
        let v = report_views(16, 9).remove(0);
        let rays = v.rays(&earth);
        assert_eq!(rays.len(), 144);
        let first = rays[0].direction;
        let last = rays[143].direction;
        // Top-left and bottom-right are mirror images about the optical axis.
        let axis = DVec3::new(0.0, 30f64.to_radians().cos(), 30f64.to_radians().sin());
        assert!((first.dot(axis) - last.dot(axis)).abs() < 1e-12);
        // The outermost pixel centres are 15/16 of the half-width from the axis.
        let half = (60f64.to_radians().tan() * 15.0 / 16.0).atan();
        let middle_row = v.rays(&earth)[4 * 16].direction;
        assert!((middle_row.dot(axis) - half.cos()).abs() < 1e-9);
        assert!(
            rays.iter()
                .all(|r| (r.direction.length() - 1.0).abs() < 1e-12)
        );
    }

    #[test]
    fn the_limb_view_looks_at_the_horizon_from_orbit() {
        let earth = Atmosphere::preset("earth").unwrap();
        let limb = report_views(16, 9)
            .into_iter()
            .find(|v| v.id == "limb")
            .unwrap();
        let rays = limb.rays(&earth);
        // Some rays hit the ground, some pass above the atmosphere's top.
        let r = earth.bottom_radius_m + limb.altitude_m;
        let grazing = |ray: &ViewRay, radius: f64| {
            let mu = ray.direction.z;
            r * r * (1.0 - mu * mu) < radius * radius && mu < 0.0
        };
        assert!(rays.iter().any(|ray| grazing(ray, earth.bottom_radius_m)));
        assert!(rays.iter().any(|ray| !grazing(ray, earth.top_radius_m)));
    }
}
