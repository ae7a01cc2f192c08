//! The cloud layer's shadow in the air in renderer frames (crepuscular rays under a deck
//! with gaps): a pass after the sun map's fill marches what the cloud takes out below
//! the layer's base (`shaders/clouds/air_shadow.wgsl`) and every model subtracts it,
//! against the CPU twin, atmosphere-core's `clouds/layer/air_shadow.rs`
//! (`CloudAirShadow::radiance` for the whole ray and for the ray ended where it enters
//! the cloud, composited with the CPU march by `composite.rs`), on a 64 x 36 frame 300 m
//! up under the default layer over a cover with gaps, the sun 12 degrees up, no surface:
//! the sun map is made for the air alone. hillaire is checked whole; each other model's
//! air loses what the CPU's march takes (`AirShadow::cloud_single`), within
//! `LOSS_RELATIVE` of it and the f16 image's rounding of the two frames. With a wall 2 km
//! off over a third of the frame and the shadow's resolution divisor 3
//! (`air_shadow_divisor`), the reduced march upsampled by span, its pixels without taps
//! of their span marched by a pass of their own, against its CPU twin
//! (`air_shadow_upsample.rs`; one value in a hundred may be outside, none beyond
//! `JUMP_FACTOR` times), and at divisor 1 against the full march.
//!
//! Tolerance: the air's pixels (rays that meet no cloud) within `AIR_RELATIVE` of
//! themselves (hillaire's own parity is 2e-3; the map's f32 fill and read add theirs,
//! `gpu_cloud_sun_map.rs`); the pixels that see the deck as `gpu_cloud_frames.rs` states
//! (4 % plus 1 % of the frame's brightest, one value in a hundred up to four times
//! that). The shafts must be there: without the cloud's shadow in the air
//! (`FrameClouds::shafts` off) the air's pixels are brighter, by more than ten times
//! the tolerance in three quarters of their values, and never darker beyond it; the
//! light they keep varies by more than 0.1 over the frame (beams through the gaps beside
//! the deck's shadow: a shadow of one value fails). Pruning
//! (the camera inside the layer looking up: no air below the base in view) changes
//! nothing.
//!
//! Needs a GPU adapter (lavapipe will do); see `support`.

mod support;

use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::air_shadow::{AirShadow, CloudAirShadow};
use atmosphere_core::clouds::layer::air_shadow_upsample::{
    ReducedAirShadow, interpolate, upsampled_loss,
};
use atmosphere_core::clouds::layer::composite::composite;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::march::CloudSegment;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::layer::upsample::{marched_coordinate, nearest_pixel, reduced_size};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::spheres::handover::CloudForm;
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::geo::equirectangular::lat_lon;
use atmosphere_core::models::hillaire::{Hillaire, HillaireSettings};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::sky_model::{RayRadiance, ViewRay};
use atmosphere_core::optics::phase::PhaseFunction;
use atmosphere_core::optics::view_segment::ViewSegment;
use glam::DVec3;
use render_wgpu::Renderer;
use render_wgpu::clouds::frame_cloud_shafts::{CLOUD_SHAFTS, NO_AIR_BELOW};
use render_wgpu::clouds::frame_clouds::{FrameClouds, frame_light};
use render_wgpu::clouds::frame_sun_map::NO_SURFACE;
use render_wgpu::frame::{Frame, look_orientation};
use support::clouds::{cpu_march, frame_sun_map};

const AIR_RELATIVE: f64 = 0.02;
const LOSS_RELATIVE: f64 = 0.02;
/// The f16 image's rounding of one value, relative (2^-11), times the two frames.
const HALF_ROUNDING: f64 = 2.0 * 4.9e-4;
const RELATIVE: f64 = 0.04;
const OF_BRIGHTEST: f64 = 0.01;
const JUMP_FACTOR: f64 = 4.0;

/// Cells about 50 km across near (0 N, 0 E) with gaps where the product dips below 0.
fn cover() -> CoverGrid {
    CoverGrid::rasterize(2048, 1024, |p| {
        let (lat, lon) = lat_lon(p);
        0.5 + 0.8 * (lat * 400.0).sin() * (lon * 300.0).cos()
    })
    .unwrap()
}

fn settings() -> LayerSettings {
    LayerSettings {
        steps: 24,
        shadow_steps: 6,
        ..LayerSettings::default()
    }
}

/// `altitude_m` above (0 N, 0 E), pitched `pitch_deg`, the sun 12 degrees up, 30
/// degrees to the right of the view's azimuth.
fn frame(altitude_m: f64, pitch_deg: f64) -> Frame {
    let atmosphere = atmosphere_core::atmosphere::Atmosphere::preset("earth").unwrap();
    let up = DVec3::X;
    let pitch = pitch_deg.to_radians();
    let (elevation, azimuth) = (12f64.to_radians(), 30f64.to_radians());
    Frame {
        camera_position_m: up * (atmosphere.bottom_radius_m + altitude_m),
        orientation: look_orientation(DVec3::new(pitch.sin(), pitch.cos(), 0.0), up).unwrap(),
        vertical_fov_deg: 40.0,
        sun_direction: DVec3::new(
            elevation.sin(),
            elevation.cos() * azimuth.cos(),
            elevation.cos() * azimuth.sin(),
        ),
        atmosphere,
        model: ModelId::Hillaire,
        settings: Default::default(),
        exposure_ev100: 14.0,
        width: 64,
        height: 36,
        terrain: None,
    }
}

fn clouds(frame: &Frame, shafts: bool, prune: bool) -> FrameClouds {
    let model = cpu_model(frame);
    FrameClouds {
        settings: settings(),
        light: frame_light(&model, frame, &settings()).unwrap(),
        form: CloudForm::Layer,
        spheres: SphereSettings::default(),
        prune,
        shafts,
    }
}

fn cpu_model(frame: &Frame) -> Hillaire {
    Hillaire::prepare(
        &frame.atmosphere,
        &frame.settings,
        HillaireSettings::default(),
    )
    .unwrap()
}

fn render(renderer: &mut Renderer, frame: &Frame, clouds: FrameClouds) -> Vec<[f32; 4]> {
    renderer.set_clouds(Some(clouds)).unwrap();
    let plan = renderer.render(frame).unwrap();
    assert!(plan.runs("clouds"), "{plan}");
    renderer.read_hdr().unwrap()
}

#[test]
fn cloud_shafts_darken_the_air_below_a_deck_with_gaps_as_the_cpu_twin_does() {
    let Some(mut renderer) = support::renderer_or_skip("cloud shafts") else {
        return;
    };
    let (orders, cover) = (support::clouds::orders(), cover());
    renderer.set_cloud_inputs(&cover, &orders).unwrap();
    let frame = frame(300.0, 0.0);
    renderer
        .set_clouds(Some(clouds(&frame, true, true)))
        .unwrap();
    let plan = renderer.render(&frame).unwrap();
    assert!(
        plan.runs("cloud_shadow"),
        "the map for the air alone: {plan}"
    );
    assert!(
        !plan.skipped.iter().any(|(name, _)| *name == CLOUD_SHAFTS),
        "{plan}"
    );
    let gpu = renderer.read_hdr().unwrap();
    let plain = render(&mut renderer, &frame, clouds(&frame, false, true));

    let model = cpu_model(&frame);
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    let radius = frame.atmosphere.bottom_radius_m;
    let layer = CloudLayer::new(settings(), radius, cover, phase).unwrap();
    let map = frame_sun_map(&layer, &frame);
    let light = frame_light(&model, &frame, &settings()).unwrap();
    let shadow = CloudAirShadow::new(&frame.atmosphere, &model);
    let air_shadow = AirShadow {
        terrain: None,
        clouds: &map,
    };
    let brightest = gpu
        .iter()
        .flat_map(|p| p[..3].to_vec())
        .fold(0.0f32, f32::max);
    let (mut worst_air, mut worst_cloud, mut outside, mut far_outside) = (0.0f64, 0.0f64, 0, 0);
    let (mut air, mut darkened, mut brighter) = (0, 0, 0);
    let (mut cloudy, mut least, mut most) = (0, f64::INFINITY, 0.0f64);
    for row in 0..frame.height {
        for column in 0..frame.width {
            let k = (row * frame.width + column) as usize;
            let ray = frame.pixel_ray(column, row);
            let full = shadow.radiance(&model, &ray, &air_shadow).unwrap();
            let segment = layer
                .shell()
                .first_segment(ray.origin_m, ray.direction, f64::INFINITY);
            let Some((t0, t1)) = segment else {
                // Air and ground only: the model's answer with the cloud's shafts.
                air += 1;
                let kept = f64::from(gpu[k][1]) / f64::from(plain[k][1]);
                (least, most) = (least.min(kept), most.max(kept));
                for w in 0..3 {
                    let (g, c) = (f64::from(gpu[k][w]), full.radiance[w]);
                    worst_air = worst_air.max((g - c).abs() / (AIR_RELATIVE * c));
                    let lost = f64::from(plain[k][w]) - g;
                    darkened += usize::from(lost > 10.0 * AIR_RELATIVE * c);
                    brighter += usize::from(-lost > AIR_RELATIVE * c);
                }
                continue;
            };
            let front = shadow
                .radiance(
                    &model,
                    &ViewRay {
                        max_distance_m: Some(t0),
                        ..ray
                    },
                    &air_shadow,
                )
                .unwrap();
            let [r, g, b, t] = cpu_march(
                &layer,
                &orders,
                (&light, &map),
                (ray.origin_m, ray.direction),
                (t0, t1),
            );
            cloudy += 1;
            let cloud = CloudSegment {
                radiance: vec![r, g, b],
                transmittance: vec![t; 3],
            };
            let cpu: RayRadiance = composite(&full, &front, &cloud);
            for w in 0..3 {
                let error = (f64::from(gpu[k][w]) - cpu.radiance[w]).abs();
                let allowed = RELATIVE * cpu.radiance[w] + OF_BRIGHTEST * f64::from(brightest);
                worst_cloud = worst_cloud.max(error / allowed);
                outside += usize::from(error > allowed);
                far_outside += usize::from(error > JUMP_FACTOR * allowed);
            }
        }
    }
    println!(
        "{air} air pixels: worst {worst_air:.3} of the tolerance; {darkened} of {} values \
         darkened by the shafts beyond ten times it, {brighter} brighter, the air's \
         light kept {least:.3} to {most:.3} (550 nm); {cloudy} pixels see the deck: worst \
         {worst_cloud:.3} of the tolerance, {outside} values outside",
        3 * air
    );
    assert!(air > 500 && cloudy > 500, "{air} air, {cloudy} deck pixels");
    // Beams: air lit through the gaps beside air in the deck's shadow.
    assert!(
        least < 0.8 && most - least > 0.1,
        "the air keeps {least:.3} to {most:.3} of its light: no beams"
    );
    assert!(
        worst_air <= 1.0,
        "air pixels: worst {worst_air:.3} of the tolerance"
    );
    assert!(
        outside * 100 <= 3 * cloudy && far_outside == 0,
        "deck pixels: {outside} values outside, {far_outside} far outside"
    );
    assert!(darkened * 4 >= 3 * air, "only {darkened} values darkened");
    assert_eq!(brighter, 0, "values brighter with the cloud's shadow");
}

#[test]
fn every_model_subtracts_the_cloud_shadow_in_the_air() {
    let Some(mut renderer) = support::renderer_or_skip("cloud shafts of every model") else {
        return;
    };
    let cover = cover();
    renderer
        .set_cloud_inputs(&cover, &support::clouds::orders())
        .unwrap();
    let hillaire = frame(300.0, 0.0);
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    let radius = hillaire.atmosphere.bottom_radius_m;
    let layer = CloudLayer::new(settings(), radius, cover, phase).unwrap();
    let map = frame_sun_map(&layer, &hillaire);
    let shadow = CloudAirShadow::new(&hillaire.atmosphere, &cpu_model(&hillaire));
    let medium = shadow.medium();
    let solar = &medium.spectra.solar_irradiance;
    let air_shadow = AirShadow {
        terrain: None,
        clouds: &map,
    };
    for model in [
        ModelId::Nishita,
        ModelId::Oneil,
        ModelId::Bruneton,
        ModelId::Dobashi,
        ModelId::Riley,
    ] {
        let frame = Frame {
            model,
            ..hillaire.clone()
        };
        let shaded = render(&mut renderer, &frame, clouds(&frame, true, true));
        let plain = render(&mut renderer, &frame, clouds(&frame, false, true));
        let (mut air, mut worst, mut taken) = (0, 0.0f64, 0);
        for row in 0..frame.height {
            for column in 0..frame.width {
                let ray = frame.pixel_ray(column, row);
                let through_cloud =
                    layer
                        .shell()
                        .first_segment(ray.origin_m, ray.direction, f64::INFINITY);
                let Some(segment) = ViewSegment::new(&frame.atmosphere, &ray).unwrap() else {
                    continue;
                };
                if through_cloud.is_some() {
                    continue;
                }
                air += 1;
                let mut lost = vec![0.0; 3];
                air_shadow.cloud_single(&medium, &segment, &mut lost);
                let k = (row * frame.width + column) as usize;
                for w in 0..3 {
                    let (p, s) = (f64::from(plain[k][w]), f64::from(shaded[k][w]));
                    // `CloudAirShadow::radiance` keeps the radiance at least 0.
                    let expected = (lost[w] * solar[w]).min(p);
                    let allowed = LOSS_RELATIVE * expected + HALF_ROUNDING * p;
                    worst = worst.max(((p - s) - expected).abs() / allowed);
                    taken += usize::from(expected > 0.1 * p);
                }
            }
        }
        println!(
            "{model:?}: {air} air pixels, worst {worst:.3} of the tolerance, {taken} values \
             losing more than a tenth"
        );
        assert!(air > 500, "{model:?}: {air} air pixels");
        assert!(worst <= 1.0, "{model:?}: worst {worst:.3} of the tolerance");
        assert!(
            taken * 2 >= 3 * air,
            "{model:?}: only {taken} values darkened"
        );
    }
}

/// The loss per unit solar irradiance and the span's end of the ray along `direction`
/// from `frame`'s camera ended at `end_m` (0: no surface).
fn cpu_air(
    frame: &Frame,
    (air, medium): (
        &AirShadow<'_>,
        &atmosphere_core::models::hillaire::medium::Medium<'_>,
    ),
    direction: DVec3,
    end_m: f32,
) -> ([f64; 3], Option<f64>) {
    let ray = ViewRay {
        origin_m: frame.camera_position_m,
        direction,
        sun_direction: frame.sun_direction.normalize(),
        max_distance_m: (end_m > 0.0).then_some(f64::from(end_m)),
    };
    let Some(segment) = ViewSegment::new(&frame.atmosphere, &ray).unwrap() else {
        return ([0.0; 3], None);
    };
    let mut lost = [0.0; 3];
    air.cloud_single(medium, &segment, &mut lost);
    (lost, air.span_end(&segment))
}

#[test]
fn a_reduced_march_of_the_shadow_upsamples_by_span_as_the_cpu_twin_does() {
    let Some(mut renderer) = support::renderer_or_skip("reduced cloud shafts") else {
        return;
    };
    const DIVISOR: u32 = 3;
    let cover = cover();
    renderer
        .set_cloud_inputs(&cover, &support::clouds::orders())
        .unwrap();
    let frame = Frame {
        model: ModelId::Nishita,
        ..frame(300.0, 0.0)
    };
    let surface = support::wall(&frame, frame.width / 3, 2_000.0);
    let reduced_settings = LayerSettings {
        air_shadow_divisor: DIVISOR,
        ..settings()
    };
    let with = |shafts: bool| FrameClouds {
        settings: reduced_settings,
        shafts,
        ..clouds(&frame, shafts, true)
    };
    let mut render = |clouds: FrameClouds| {
        renderer.set_clouds(Some(clouds)).unwrap();
        let plan = renderer.render_with_surface(&frame, &surface).unwrap();
        (plan, renderer.read_hdr().unwrap())
    };
    let (plan, shaded) = render(with(true));
    assert!(plan.runs(CLOUD_SHAFTS), "{plan}");
    let (_, plain) = render(with(false));
    // The same frame at full resolution: every pixel marched.
    let (_, shaded_full) = render(FrameClouds {
        settings: settings(),
        ..with(true)
    });
    let (_, plain_full) = render(FrameClouds {
        settings: settings(),
        ..with(false)
    });

    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    let radius = frame.atmosphere.bottom_radius_m;
    let layer = CloudLayer::new(reduced_settings, radius, cover, phase).unwrap();
    let map = frame_sun_map(&layer, &frame);
    let shadow = CloudAirShadow::new(&frame.atmosphere, &cpu_model(&frame));
    let medium = shadow.medium();
    let solar = &medium.spectra.solar_irradiance;
    let air = AirShadow {
        terrain: None,
        clouds: &map,
    };
    // The CPU twin: the reduced march, each ray ended on its nearest pixel's surface.
    let (w, h) = reduced_size(frame.width, frame.height, DIVISOR);
    let (mut loss, mut span_ends) = (Vec::new(), Vec::new());
    for j in 0..h {
        for i in 0..w {
            let x = marched_coordinate(i, w, frame.width);
            let y = marched_coordinate(j, h, frame.height);
            let d = frame.direction_through(x + 0.5, y + 0.5).normalize();
            let near = nearest_pixel(y, frame.height) * frame.width + nearest_pixel(x, frame.width);
            let (l, end) = cpu_air(
                &frame,
                (&air, &medium),
                d,
                surface[near as usize].distance_m,
            );
            loss.push(l);
            span_ends.push(end);
        }
    }
    let reduced = ReducedAirShadow {
        loss: &loss,
        span_ends: &span_ends,
        size: (w, h),
    };
    let size = (frame.width, frame.height);
    let (mut air_pixels, mut marched, mut values, mut outside, mut far_outside) = (0, 0, 0, 0, 0);
    let (mut worst, mut worst_full, mut full_error, mut full_lost) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for row in 0..frame.height {
        for column in 0..frame.width {
            let k = (row * frame.width + column) as usize;
            let ray = frame.pixel_ray(column, row);
            let end = surface[k].distance_m;
            let far = if end > 0.0 {
                f64::from(end)
            } else {
                f64::INFINITY
            };
            if layer
                .shell()
                .first_segment(ray.origin_m, ray.direction, far)
                .is_some()
            {
                continue;
            }
            air_pixels += 1;
            let (exact, span_end) = cpu_air(&frame, (&air, &medium), ray.direction, end);
            if let Some(e) = span_end {
                marched += usize::from(interpolate(&reduced, size, (column, row), e).is_none());
            }
            let twin = upsampled_loss(&reduced, size, (column, row), span_end, || exact);
            for c in 0..3 {
                let (p, s) = (f64::from(plain[k][c]), f64::from(shaded[k][c]));
                let expected = (twin[c] * solar[c]).min(p);
                let allowed = LOSS_RELATIVE * expected + HALF_ROUNDING * p;
                let error = ((p - s) - expected).abs();
                worst = worst.max(error / allowed);
                outside += usize::from(error > allowed);
                far_outside += usize::from(error > JUMP_FACTOR * allowed);
                values += 1;
                // The full-resolution frame against the full march.
                let (pf, sf) = (f64::from(plain_full[k][c]), f64::from(shaded_full[k][c]));
                let full = (exact[c] * solar[c]).min(pf);
                let allowed_full = LOSS_RELATIVE * full + HALF_ROUNDING * pf;
                worst_full = worst_full.max(((pf - sf) - full).abs() / allowed_full);
                // The reduced frame against the full march: what the divisor costs.
                full_error += ((p - s) - full).powi(2);
                full_lost += full * full;
            }
        }
    }
    let rms = (full_error / full_lost).sqrt();
    println!(
        "{air_pixels} air pixels ({marched} marched in full): worst {worst:.3} of the \
         tolerance, {outside} of {values} values outside it, {far_outside} beyond \
         {JUMP_FACTOR}x; against the full-resolution march {:.2} % of the loss (RMS); \
         the full-resolution frame: worst {worst_full:.3} of the tolerance",
        100.0 * rms
    );
    assert!(
        worst_full <= 1.0,
        "full resolution: worst {worst_full:.3} of the tolerance"
    );
    assert!(air_pixels > 500, "{air_pixels} air pixels");
    // Both ways are taken: the wall's edge is marched, the open air interpolated.
    assert!(marched > 0 && marched * 4 < air_pixels, "{marched} marched");
    assert!(
        outside * 100 <= values && far_outside == 0,
        "{outside} values outside, {far_outside} far outside"
    );
    // A reduced ray here spans 1.9 degrees, wider than the beams' edges seen 20 km off:
    // the divisor blurs them (at 1280 x 720 a reduced ray of the interactive quality's
    // divisor 6 spans 0.5 degree).
    assert!(rms < 0.08, "{rms:.3} of the loss against the full march");
}

#[test]
fn pruning_the_cloud_shafts_changes_nothing() {
    let Some(mut renderer) = support::renderer_or_skip("cloud shafts pruning") else {
        return;
    };
    renderer
        .set_cloud_inputs(&cover(), &support::clouds::orders())
        .unwrap();
    // Inside the layer (1.5 to 3 km) looking 40 degrees up: no ray comes down to the
    // base.
    let frame = frame(2_000.0, 40.0);
    renderer
        .set_clouds(Some(clouds(&frame, true, true)))
        .unwrap();
    let plan = renderer.render(&frame).unwrap();
    assert!(
        plan.skipped.contains(&(CLOUD_SHAFTS, NO_AIR_BELOW)),
        "{plan}"
    );
    assert!(
        plan.skipped.contains(&("cloud_shadow", NO_SURFACE)),
        "{plan}"
    );
    let pruned = renderer.read_hdr().unwrap();
    renderer
        .set_clouds(Some(clouds(&frame, true, false)))
        .unwrap();
    let plan = renderer.render(&frame).unwrap();
    assert!(plan.runs("cloud_shadow"), "{plan}");
    assert_eq!(pruned, renderer.read_hdr().unwrap());
}
