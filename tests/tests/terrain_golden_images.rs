//! Golden images of the terrain (docs/terrain.md, "Golden images"): hillaire frames,
//! 96 x 54, of the Earth's refined relief at true scale, 2 m above the Pennine Alps, 3 km
//! above them at sunset (the default scene's view), 20 km above them in the afternoon,
//! and 400 km above the Ligurian coast at noon, compared with the PNGs committed in
//! `tests/golden/` (`terrain_SCENE.png`) as `support/golden.rs` says: within a few 8-bit
//! levels per pixel, and a uniform shift of 1 % of the radiance fails. Regenerate them
//! after an intended change with
//!
//! ```sh
//! ATMOS_UPDATE_GOLDEN=1 ./scripts/test.sh --test terrain_golden_images
//! ```
//!
//! and look at the new images before committing them.
//!
//! Needs a GPU adapter (lavapipe will do), with the skip policy of the other GPU tests;
//! the check itself is tested on the committed goldens without one.

mod support;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use render_wgpu::Frame;
use render_wgpu::frame::{LocalView, TerrainOptions, location_rotation};
use render_wgpu::terrain::{EarthData, TerrainSurface};
use support::golden::{Framing, Image, check_fails_shifted, check_or_update};
use support::{frame_in, renderer_or_skip};

const WIDTH: u32 = 96;
const HEIGHT: u32 = 54;

/// The camera's height: above sea level, or above the terrain under it.
#[derive(Clone, Copy)]
enum Height {
    AboveSea(f64),
    AboveGround(f64),
}

/// A terrain golden: a place, the camera's height, a view and a sun (azimuths
/// geographic, from north towards east), the field of view and the exposure.
struct Scene {
    name: &'static str,
    lat_lon_deg: (f64, f64),
    height: Height,
    /// View zenith and azimuth, degrees.
    view_deg: (f64, f64),
    /// Sun zenith and azimuth, degrees.
    sun_deg: (f64, f64),
    fov_deg: f64,
    ev100: f64,
}

fn scenes() -> [Scene; 4] {
    [
        // Looking down a slope with the afternoon sun behind: the refined relief's
        // metre-scale facets, rock on its steep parts and snow.
        Scene {
            name: "alps_2m",
            lat_lon_deg: (46.0, 7.8),
            height: Height::AboveGround(2.0),
            view_deg: (97.0, 40.0),
            sun_deg: (45.0, 220.0),
            fov_deg: 60.0,
            ev100: 14.5,
        },
        // The default scene's view (assets/scenes/default.toml).
        Scene {
            name: "alps_3km_sunset",
            lat_lon_deg: (46.0, 7.8),
            height: Height::AboveSea(5_600.0),
            view_deg: (93.0, 240.0),
            sun_deg: (84.6, 251.0),
            fov_deg: 60.0,
            ev100: 13.5,
        },
        Scene {
            name: "alps_20km",
            lat_lon_deg: (46.0, 7.8),
            height: Height::AboveSea(20_000.0),
            view_deg: (120.0, 240.0),
            sun_deg: (60.0, 220.0),
            fov_deg: 60.0,
            ev100: 14.5,
        },
        // Corsica, the Ligurian Sea and the coast from Nice to Genoa, the Alps behind.
        Scene {
            name: "coast_400km_noon",
            lat_lon_deg: (43.0, 8.5),
            height: Height::AboveSea(400_000.0),
            view_deg: (170.0, 0.0),
            sun_deg: (25.0, 180.0),
            fov_deg: 60.0,
            ev100: 14.5,
        },
    ]
}

impl Scene {
    fn framing(&self) -> Framing {
        Framing {
            width: WIDTH,
            height: HEIGHT,
            crop: (0..WIDTH, 0..HEIGHT),
        }
    }

    /// The hillaire frame with terrain at true scale, every chunk mesh waited for.
    fn frame(&self) -> Frame {
        let atmosphere = Atmosphere::preset("earth").unwrap();
        let radius_m = atmosphere.bottom_radius_m;
        let local = LocalView {
            altitude_m: 0.0,
            view_zenith_deg: self.view_deg.0,
            view_azimuth_deg: -self.view_deg.1,
            sun_zenith_deg: self.sun_deg.0,
            sun_azimuth_deg: -self.sun_deg.1,
        };
        let mut f = frame_in(
            atmosphere,
            ModelId::Hillaire,
            local,
            self.fov_deg,
            WIDTH,
            HEIGHT,
        );
        let place = location_rotation(self.lat_lon_deg.0, self.lat_lon_deg.1);
        let up = place * f.camera_position_m.normalize();
        let altitude_m = match self.height {
            Height::AboveSea(h) => h,
            Height::AboveGround(h) => {
                let heights = EarthData::BuiltIn.refined_heights().unwrap();
                TerrainSurface::new(heights, radius_m).elevation_m(up) + h
            }
        };
        f.camera_position_m = up * (radius_m + altitude_m);
        f.orientation = place * f.orientation;
        f.sun_direction = place * f.sun_direction;
        f.exposure_ev100 = self.ev100;
        f.terrain = Some(TerrainOptions::default());
        f
    }
}

#[test]
fn terrain_renders_match_the_golden_images() {
    let Some(mut renderer) = renderer_or_skip("terrain golden images") else {
        return;
    };
    let mut failures = Vec::new();
    for scene in scenes() {
        let name = format!("terrain_{}", scene.name);
        let plan = renderer.render(&scene.frame()).unwrap();
        assert!(plan.runs("terrain"), "{name}: {plan}");
        let image = Image::captured(&renderer, scene.ev100);
        check_or_update(&name, &image, &scene.framing(), &mut failures);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The check on the committed goldens: each matches itself, and fails once its radiance
/// is 1 % higher or lower.
#[test]
fn every_terrain_golden_matches_itself_and_fails_shifted_by_one_percent() {
    for scene in scenes() {
        check_fails_shifted(&format!("terrain_{}", scene.name), &scene.framing());
    }
}
