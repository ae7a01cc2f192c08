//! Whether a frame shows ground near the camera: the frame planner's test for passes that
//! only serve surfaces within some distance (the aerial-perspective volume). Decided on
//! the CPU from the camera alone, without touching the pixels, and conservatively: a
//! frame where any pixel centre's ray meets the ground within the distance is always
//! found; a frame that only comes within a pixel of it may be found too.
//!
//! The rays that meet the ground within `d` of a camera at radius r are those with zenith
//! cosine mu <= mu_d: mu_d = -(r^2 - R^2 + d^2) / (2 r d) (the cosine of the ray through
//! the ground point at distance d), or the horizon's cosine when the whole visible ground
//! is nearer than d. They form a cone around the nadir, whose trace on the image plane is
//! convex. So if a pixel centre lies in it, either the nadir's image lies in the image, or
//! the trace crosses the border of the pixel centres' rectangle, between two border
//! pixels whose rays are at most one pixel step from it (the image plane is at unit
//! distance, so a step there turns a ray by at most its length).

use atmosphere_core::optics::geometry::horizon_mu;

use crate::frame::Frame;

/// Slack in the cosine for the shaders' f32 decisions (a ray's mu carries about 1e-7).
const F32_SLACK: f64 = 1e-4;

/// Whether some pixel of `frame` may see the ground within `range_m` of the camera.
pub fn ground_within(frame: &Frame, range_m: f64) -> bool {
    let bottom = frame.atmosphere.bottom_radius_m;
    let camera = frame.camera_position_m;
    let r = camera.length();
    let q = (r - bottom) * (r + bottom);
    let mu_max = if q.sqrt() <= range_m {
        horizon_mu(r, bottom)
    } else {
        -(q + range_m * range_m) / (2.0 * r * range_m)
    };
    if mu_max < -1.0 {
        return false;
    }
    let up = camera / r;
    let [right, image_up, forward] = frame.axes();
    let (half_w, half_h) = frame.half_extent();
    let down_ahead = -up.dot(forward);
    if down_ahead > 0.0 {
        let x = -up.dot(right) / down_ahead / half_w;
        let y = -up.dot(image_up) / down_ahead / half_h;
        if x.abs() <= 1.0 && y.abs() <= 1.0 {
            return true;
        }
    }
    let step = (2.0 * half_w / f64::from(frame.width)).max(2.0 * half_h / f64::from(frame.height));
    let limit = mu_max + step + F32_SLACK;
    let (w, h) = (frame.width, frame.height);
    let border = (0..w)
        .flat_map(|c| [(c, 0), (c, h - 1)])
        .chain((0..h).flat_map(|row| [(0, row), (w - 1, row)]));
    border
        .into_iter()
        .any(|(c, row)| frame.pixel_ray(c, row).direction.dot(up) <= limit)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::LocalView;
    use atmosphere_core::atmosphere::Atmosphere;
    use atmosphere_core::models::sky_model::ModelSettings;
    use atmosphere_core::optics::view_segment::{SegmentEnd, ViewSegment};

    fn frame(altitude_m: f64, view_zenith_deg: f64, fov: f64) -> Frame {
        let atmosphere = Atmosphere::preset("earth").unwrap();
        let view = LocalView {
            altitude_m,
            view_zenith_deg,
            view_azimuth_deg: 10.0,
            sun_zenith_deg: 40.0,
            sun_azimuth_deg: 0.0,
        };
        Frame {
            camera_position_m: view.position_m(atmosphere.bottom_radius_m),
            orientation: view.orientation(),
            vertical_fov_deg: fov,
            sun_direction: view.sun_direction(),
            atmosphere,
            model: atmosphere_core::models::id::ModelId::Hillaire,
            settings: ModelSettings::default(),
            exposure_ev100: 14.0,
            width: 40,
            height: 24,
            terrain: None,
        }
    }

    /// Whether any pixel's ray ends on the ground within `range_m`, ray by ray.
    fn any_pixel_within(f: &Frame, range_m: f64) -> bool {
        (0..f.height).any(|row| {
            (0..f.width).any(|c| {
                ViewSegment::new(&f.atmosphere, &f.pixel_ray(c, row))
                    .unwrap()
                    .is_some_and(|s| s.end == SegmentEnd::Ground && s.length <= range_m)
            })
        })
    }

    #[test]
    fn the_test_finds_every_frame_with_near_ground_and_skips_clear_skies() {
        let mut found = 0;
        for altitude in [1.0, 500.0, 10_000.0, 40_000.0] {
            for zenith in [0.0, 30.0, 60.0, 80.0, 88.0, 90.0, 92.0, 100.0, 135.0, 180.0] {
                for fov in [1.0, 20.0, 60.0, 120.0] {
                    let f = frame(altitude, zenith, fov);
                    let exact = any_pixel_within(&f, 32_000.0);
                    let test = ground_within(&f, 32_000.0);
                    assert!(
                        test || !exact,
                        "missed ground at {altitude} m, {zenith} deg, fov {fov}"
                    );
                    found += usize::from(exact);
                    // Looking up, nothing is found.
                    if zenith <= 30.0 && fov <= 60.0 {
                        assert!(!test, "{altitude} m, {zenith} deg, fov {fov}");
                    }
                }
            }
        }
        assert!(found > 20, "{found}");
        // From 40 km the nearest ground is 40 km away.
        assert!(!ground_within(&frame(40_000.0, 180.0, 60.0), 32_000.0));
    }
}
