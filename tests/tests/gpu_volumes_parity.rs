//! Rain and ice volumes composited into `Renderer` frames (`precipitation/`,
//! `shaders/precipitation/`) against their CPU twin, atmosphere-core's
//! `hydrometeors/render.rs`, on 64 x 36 frames of two models: a rain shaft and a cirrus
//! layer over the model's own GPU pixels (the frame rendered without them), with a wall
//! in front of the shaft over the left quarter, with the shipped settings (the forward
//! peak taken as no scattering: the truncated tables, each channel's own extinction; the
//! sky's light averaged over the sphere, the sun's higher orders from the volumes'
//! probes) and the march before them (the peak as extinction, the sky's horizontal
//! irradiance, single scattering); the shaft alone, whose pass runs over
//! the rows above the ground only; no volume leaves the frame exactly as it was; more
//! than two volumes are refused by name.
//!
//! Tolerance: each pixel within 0.5 % of itself plus 0.1 % of the frame's brightest
//! value: the march and the atmosphere's columns in front of the volumes in f32, and the
//! f16 image written. The scattering angle is computed without the shader's acos, which
//! put the bow's sharp red edge out of this tolerance (docs/optics-rendering.md).
//!
//! Needs a GPU adapter (lavapipe will do); see `support`.

mod support;

use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::hydrometeors::forward_peak::ForwardPeak;
use atmosphere_core::hydrometeors::reduced::frame_terms;
use atmosphere_core::hydrometeors::render::{LitVolume, MARCH_STEPS, composite_terms};
use atmosphere_core::hydrometeors::scene::{
    CirrusSettings, RainShaftSettings, VolumeOptics, lit_volume,
};
use atmosphere_core::hydrometeors::sky_light::SkyLight;
use atmosphere_core::hydrometeors::sun_orders::MultipleScattering;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::table_cache::TableCache;
use glam::DVec3;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::frame::surface_buffer::SurfaceTexel;
use render_wgpu::frame::{Frame, look_orientation};
use render_wgpu::precipitation::screen_rect::volumes_rect;

const RELATIVE: f64 = 0.005;
const OF_BRIGHTEST: f64 = 0.001;
const WALL_COLUMNS: u32 = 16;
const WALL_M: f32 = 800.0;

/// 2 m above (0 N, 0 E), looking 10 degrees up towards the antisolar azimuth, the sun 30
/// degrees up behind the camera.
fn frame(model: ModelId) -> Frame {
    let atmosphere = atmosphere_core::atmosphere::Atmosphere::preset("earth").unwrap();
    let up = DVec3::X;
    let pitch = 10f64.to_radians();
    let forward = DVec3::new(pitch.sin(), pitch.cos(), 0.0);
    let sun = 30f64.to_radians();
    Frame {
        camera_position_m: up * (atmosphere.bottom_radius_m + 2.0),
        orientation: look_orientation(forward, up).unwrap(),
        vertical_fov_deg: 70.0,
        sun_direction: DVec3::new(sun.sin(), -sun.cos(), 0.0),
        atmosphere,
        model,
        settings: Default::default(),
        exposure_ev100: 14.0,
        width: 64,
        height: 36,
        terrain: None,
    }
}

fn volumes(
    frame: &Frame,
    (forward_peak, sky_light, multiple_scattering): (ForwardPeak, SkyLight, MultipleScattering),
) -> Vec<LitVolume> {
    let model = prepare(frame.model, &frame.atmosphere, &frame.settings).unwrap();
    let ground = frame.atmosphere.bottom_radius_m;
    let view = (frame.camera_position_m, frame.sun_direction);
    let optics = VolumeOptics {
        wavelengths: 16,
        sun_radius_rad: frame.atmosphere.sun.angular_radius_rad,
        forward_peak,
        sky_light,
        multiple_scattering,
    };
    let shaft = RainShaftSettings::default()
        .volume(frame.camera_position_m, DVec3::Y, ground)
        .unwrap();
    let cirrus = CirrusSettings {
        rays: 20_000,
        ..CirrusSettings::default()
    }
    .volume(ground, 20.0)
    .unwrap();
    [shaft, cirrus]
        .into_iter()
        .map(|v| {
            lit_volume(
                model.as_ref(),
                v,
                view,
                optics,
                RGB_WAVELENGTHS_NM,
                &TableCache::off(),
            )
            .unwrap()
        })
        .collect()
}

fn wall(frame: &Frame) -> Vec<SurfaceTexel> {
    support::wall(frame, WALL_COLUMNS, WALL_M)
}

/// Renders `frame` over `surface` without volumes and with `lit` marched at `divisor`,
/// checks every pixel of the second against the CPU composite over the first (its
/// terms upsampled as `hydrometeors/reduced.rs` says); returns how many values the
/// volumes changed by more than 1 %.
fn check(
    renderer: &mut render_wgpu::Renderer,
    frame: &Frame,
    lit: &[LitVolume],
    divisor: u32,
) -> usize {
    let surface = wall(frame);
    renderer.set_volumes_divisor(divisor).unwrap();
    renderer.set_volumes(Vec::new()).unwrap();
    let plan = renderer.render_with_surface(frame, &surface).unwrap();
    assert!(plan.steps.iter().all(|s| s.name != "volumes"));
    let without = renderer.read_hdr().unwrap();
    renderer.set_volumes(lit.to_vec()).unwrap();
    let plan = renderer.render_with_surface(frame, &surface).unwrap();
    assert!(plan.steps.iter().any(|s| s.name == "volumes"));
    let with = renderer.read_hdr().unwrap();
    let spectra = Spectra::new(&frame.atmosphere, &RGB_WAVELENGTHS_NM);
    let extinction: [[f64; 3]; 3] = std::array::from_fn(|c| spectra.extinction[c]);
    let ray = |column: u32, row: u32| {
        let ray = frame.pixel_ray(column, row);
        let end = if column < WALL_COLUMNS {
            f64::from(WALL_M)
        } else {
            f64::INFINITY
        };
        (ray.origin_m, ray.direction, end)
    };
    let terms = |r| composite_terms(&frame.atmosphere, &extinction, lit, r, MARCH_STEPS);
    let size = (frame.width, frame.height);
    let cpu: Vec<[f64; 3]> = frame_terms(size, divisor, lit, ray, terms)
        .iter()
        .zip(&without)
        .map(|(t, w)| t.over(std::array::from_fn(|c| f64::from(w[c]))))
        .collect();
    let brightest = cpu.iter().flatten().fold(0.0f64, |m, v| m.max(*v));
    let (mut changed, mut worst) = (0, 0.0f64);
    for (i, (c, g)) in cpu.iter().zip(&with).enumerate() {
        for k in 0..3 {
            let gpu = f64::from(g[k]);
            let error = (gpu - c[k]).abs() / (RELATIVE * c[k].abs() + OF_BRIGHTEST * brightest);
            worst = worst.max(error);
            assert!(
                error <= 1.0,
                "{} pixel {i} channel {k}: GPU {gpu}, CPU {}",
                frame.model,
                c[k]
            );
            if (c[k] - f64::from(without[i][k])).abs() > 0.01 * c[k].abs() {
                changed += 1;
            }
        }
    }
    eprintln!(
        "{} at divisor {divisor}, the first volume's f_c {:.3?}: worst error {worst:.3} of \
         the tolerance",
        frame.model, lit[0].peak_fraction
    );
    changed
}

#[test]
fn volumes_match_the_cpu_composite_for_two_models() {
    let Some(mut renderer) = support::renderer_or_skip("volumes parity") else {
        return;
    };
    for model_id in [ModelId::Nishita, ModelId::Hillaire] {
        let frame = frame(model_id);
        // The shipped settings, and the march before them.
        for (peak, sky, orders) in [
            (
                ForwardPeak::Unscattered,
                SkyLight::Sphere,
                MultipleScattering::Probes,
            ),
            (
                ForwardPeak::Extinction,
                SkyLight::Horizontal,
                MultipleScattering::None,
            ),
        ] {
            let lit = volumes(&frame, (peak, sky, orders));
            // Truncated, each channel's extinction its own; the probes there or not.
            let f = lit[0].peak_fraction;
            assert_eq!(peak == ForwardPeak::Unscattered, f[0] > 0.3, "{f:?}");
            assert!(
                lit.iter()
                    .all(|v| v.orders.is_some() == (orders == MultipleScattering::Probes))
            );
            let changed = check(&mut renderer, &frame, &lit, 1);
            // The volumes change most of the frame: the test compares something.
            let values = 3 * (frame.width * frame.height) as usize;
            assert!(
                changed > values / 3,
                "{model_id} {peak:?}: {changed} values changed"
            );
        }
    }
    let lit = volumes(&frame(ModelId::Nishita), Default::default());
    assert!(renderer.set_volumes(vec![lit[0].clone(); 3]).is_err());
}

/// The shaft alone: the pass runs over the rows above the ground only (the shaft's
/// rectangle), and the frame still matches the CPU composite everywhere, the rows below
/// left as the model drew them.
#[test]
fn a_shaft_alone_is_composited_over_its_rectangle_only() {
    let Some(mut renderer) = support::renderer_or_skip("volumes parity") else {
        return;
    };
    let frame = frame(ModelId::Nishita);
    let lit = vec![volumes(&frame, Default::default())[0].clone()];
    let rect = volumes_rect(&frame, &lit).unwrap();
    assert!(rect.size[1] < frame.height, "{rect:?}");
    let changed = check(&mut renderer, &frame, &lit, 1);
    assert!(changed > frame.width as usize, "{changed} values changed");
}

/// The volumes marched for one pixel in 2 x 2 and 3 x 3 and upsampled where the rays'
/// spans agree (the wall's edge, the shaft's and the layer's edges marched per pixel),
/// against the CPU twin's upsample; and the upsample is not the full march everywhere
/// (some values differ from it by more than the tolerance), so the test sees it.
#[test]
fn volumes_at_a_reduced_resolution_match_the_cpu_upsample() {
    let Some(mut renderer) = support::renderer_or_skip("volumes parity") else {
        return;
    };
    let frame = frame(ModelId::Hillaire);
    let lit = volumes(&frame, Default::default());
    for divisor in [2, 3] {
        let changed = check(&mut renderer, &frame, &lit, divisor);
        assert!(changed > frame.width as usize, "{changed} values changed");
    }
    let spectra = Spectra::new(&frame.atmosphere, &RGB_WAVELENGTHS_NM);
    let extinction: [[f64; 3]; 3] = std::array::from_fn(|c| spectra.extinction[c]);
    let ray = |column: u32, row: u32| {
        let ray = frame.pixel_ray(column, row);
        (ray.origin_m, ray.direction, f64::INFINITY)
    };
    let terms = |r| composite_terms(&frame.atmosphere, &extinction, &lit, r, MARCH_STEPS);
    let size = (frame.width, frame.height);
    let exact = frame_terms(size, 1, &lit, ray, terms);
    let reduced = frame_terms(size, 3, &lit, ray, terms);
    let differ = exact
        .iter()
        .zip(&reduced)
        .filter(|(a, b)| {
            let (a, b) = (a.over([0.0; 3]), b.over([0.0; 3]));
            (0..3).any(|c| (a[c] - b[c]).abs() > RELATIVE * a[c].abs())
        })
        .count();
    eprintln!("divisor 3: {differ} pixels differ from the full march by more than the tolerance");
    assert!(differ > 0);
    assert!(renderer.set_volumes_divisor(5).is_err());
}
