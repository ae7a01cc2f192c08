//! The cloud spheres shaded at a reduced resolution and brought to full size by span
//! (`clouds/spheres/reduced.rs`): the span of a ray against its closed form; at divisor
//! 1 the image is `spheres_only` at every pixel; at divisor 3, on a view from 400 km
//! over the limb with a wall 100 km away over the left third of the frame, the wall's
//! pixels stay exactly clear (a bilinear upsample would smear the cloud behind onto
//! the columns next to its edge) and the rest is close to the image shaded at every
//! pixel (`-- --nocapture` prints how close).

use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::spheres::composite::spheres_only;
use atmosphere_core::clouds::spheres::field::CloudSpheres;
use atmosphere_core::clouds::spheres::reduced::{SphereView, span, spheres_image};
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::geo::equirectangular::lat_lon;
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;

const BOTTOM_M: f64 = 6_360_000.0;
const ALTITUDE_M: f64 = 400_000.0;
const WALL_M: f64 = 100_000.0;
const SIZE: (u32, u32) = (48, 27);

fn spheres(sun: DVec3) -> CloudSpheres {
    let cover = CoverGrid::rasterize(512, 256, |p| {
        let (lat, lon) = lat_lon(p);
        0.5 + 0.8 * (lat * 60.0).sin() * (lon * 45.0).cos()
    })
    .unwrap();
    let settings = LayerSettings {
        extinction_per_m: 0.004,
        method: LayerMethod::Octaves,
        ..LayerSettings::default()
    };
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    let layer = CloudLayer::new(settings, BOTTOM_M, cover, phase).unwrap();
    let settings = SphereSettings {
        attenuation_width: 256,
        ..SphereSettings::default()
    };
    CloudSpheres::new(&layer, &settings, sun).unwrap()
}

/// A pinhole camera 400 km up over (0 N, 0 E) looking 35 degrees below the horizon
/// towards the north (the limb in the frame's top), 60 degrees of vertical field.
fn direction(x: f64, y: f64) -> DVec3 {
    let pitch = (-35.0f64).to_radians();
    let forward = DVec3::new(pitch.sin(), 0.0, pitch.cos());
    let right = DVec3::Y;
    let up = right.cross(forward);
    let t = 30.0f64.to_radians().tan();
    let aspect = f64::from(SIZE.0) / f64::from(SIZE.1);
    let sx = (2.0 * (x + 0.5) / f64::from(SIZE.0) - 1.0) * t * aspect;
    let sy = (2.0 * (y + 0.5) / f64::from(SIZE.1) - 1.0) * t;
    (forward + sx * right - sy * up).normalize()
}

fn light() -> CloudLight {
    let sun = DVec3::new(0.6, 0.48, 0.64).normalize();
    CloudLight {
        sun_direction: sun,
        sun_irradiance: vec![1.47, 1.85, 1.91],
        sky_irradiance: vec![0.05, 0.12, 0.25],
        up: DVec3::X,
    }
}

fn orders() -> ScatteringOrders {
    ScatteringOrders::new(&vec![LegendreSeries::henyey_greenstein(0.85, 300); 3]).unwrap()
}

#[test]
fn a_span_is_the_ray_inside_the_top_sphere_ended_on_the_ground_and_the_surface() {
    let s = spheres(DVec3::X);
    let origin = DVec3::new(BOTTOM_M + ALTITUDE_M, 0.0, 0.0);
    // Straight down: from the layer's top (3 km) to the ground.
    let (t0, t1) = span(s.shells(), origin, -DVec3::X, f64::INFINITY).unwrap();
    assert!((t0 - (ALTITUDE_M - 3_000.0)).abs() < 1e-6, "{t0}");
    assert!((t1 - ALTITUDE_M).abs() < 1e-6, "{t1}");
    // Ended on a surface inside the layer, or none before one above it.
    let (_, t1) = span(s.shells(), origin, -DVec3::X, ALTITUDE_M - 1_000.0).unwrap();
    assert!((t1 - (ALTITUDE_M - 1_000.0)).abs() < 1e-6, "{t1}");
    assert_eq!(span(s.shells(), origin, -DVec3::X, WALL_M), None);
    // Into space.
    assert_eq!(span(s.shells(), origin, DVec3::X, f64::INFINITY), None);
    // From the ground, straight up: inside the top sphere from the start.
    let ground = DVec3::new(BOTTOM_M + 1.0, 0.0, 0.0);
    let (t0, t1) = span(s.shells(), ground, DVec3::X, f64::INFINITY).unwrap();
    assert_eq!(t0, 0.0);
    assert!((t1 - 2_999.0).abs() < 1e-6, "{t1}");
}

#[test]
fn the_reduced_image_keeps_a_wall_clear_and_is_close_to_every_pixel_shaded() {
    let light = light();
    let orders = orders();
    let s = spheres(light.sun_direction);
    let origin = DVec3::new(BOTTOM_M + ALTITUDE_M, 0.0, 0.0);
    let on_wall = |x: u32| x < SIZE.0 / 3;
    let end_m = |x: u32, _: u32| if on_wall(x) { WALL_M } else { f64::INFINITY };
    let view = SphereView {
        origin,
        size: SIZE,
        direction: &direction,
        end_m: &end_m,
    };
    let full = spheres_image(&s, &orders, &light, &view, 1).unwrap();
    for (i, p) in full.iter().enumerate() {
        let (x, y) = (i as u32 % SIZE.0, i as u32 / SIZE.0);
        let (cloud, _) = spheres_only(
            &s,
            &orders,
            &light,
            origin,
            direction(f64::from(x), f64::from(y)),
            end_m(x, y),
        );
        let want = [
            cloud.radiance[0],
            cloud.radiance[1],
            cloud.radiance[2],
            cloud.transmittance[0],
        ];
        assert_eq!(*p, want, "pixel ({x}, {y})");
    }
    let reduced = spheres_image(&s, &orders, &light, &view, 3).unwrap();
    let (mut difference, mut total, mut worst_t, mut worst_at) = (0.0, 0.0, 0.0f64, 0);
    let mut clouded = 0;
    for (i, (p, q)) in reduced.iter().zip(&full).enumerate() {
        if on_wall(i as u32 % SIZE.0) {
            assert_eq!(*p, [0.0, 0.0, 0.0, 1.0], "wall pixel {i}");
            continue;
        }
        clouded += usize::from(q[3] < 0.5);
        difference += (0..3).map(|c| (p[c] - q[c]).abs()).sum::<f64>();
        total += q[..3].iter().sum::<f64>();
        if (p[3] - q[3]).abs() > worst_t {
            (worst_t, worst_at) = ((p[3] - q[3]).abs(), i);
        }
    }
    let error = difference / total;
    println!(
        "divisor 3 against 1 off the wall: mean radiance error {:.2} % of the mean, \
         largest transmittance error {worst_t:.3} (pixel {}, {}), {clouded} clouded pixels",
        100.0 * error,
        worst_at as u32 % SIZE.0,
        worst_at as u32 / SIZE.0
    );
    assert!(clouded > 200, "the view must hold cloud: {clouded} pixels");
    assert!(error < 0.1, "mean radiance error {error}");
    assert!(worst_t < 0.75, "largest transmittance error {worst_t}");
    // Bad input is refused by name.
    let e = spheres_image(&s, &orders, &light, &view, 0).unwrap_err();
    assert!(e.0.contains("divisor 0"), "{e}");
}
