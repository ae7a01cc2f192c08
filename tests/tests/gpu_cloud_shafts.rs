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
//! `JUMP_FACTOR` times), and at divisor 1 against the full march. From 20 km above a
//! thin deck at 4 km the shadowed air lies behind the cloud: every deck pixel within the
//! tolerance (the model's run in front of the cloud taking the whole ray's shadow put
//! 373 values outside), the shadow changing more than one in fifty beyond it.
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

/// What a frame with the cloud's shadow showed against the CPU twin: its air pixels
/// (rays that meet no cloud) and those that see the deck.
#[derive(Debug, Default)]
struct Compared {
    air: usize,
    worst_air: f64,
    /// Values darkened by the shafts beyond ten times the air's tolerance, and brighter.
    darkened: usize,
    brighter: usize,
    /// The least and most light the air keeps at 550 nm (with the shadow / without).
    least: f64,
    most: f64,
    cloudy: usize,
    worst_cloud: f64,
    outside: usize,
    far_outside: usize,
    /// Deck pixels whose 550 nm value the shadow changes beyond the deck's tolerance.
    shaded_cloudy: usize,
}

/// Renders `frame` with and without the cloud's shadow in the air and compares the
/// first with the CPU twin: the model's answer with the shadow for the air's pixels,
/// `composite.rs` of the shadowed model's whole ray and its ray ended at the cloud with
/// the CPU march for the deck's.
fn against_cpu(renderer: &mut Renderer, frame: &Frame, settings: LayerSettings) -> Compared {
    let (orders, cover) = (support::clouds::orders(), cover());
    renderer.set_cloud_inputs(&cover, &orders).unwrap();
    let model = cpu_model(frame);
    let light = frame_light(&model, frame, &settings).unwrap();
    let with = |shafts: bool| FrameClouds {
        settings,
        light: light.clone(),
        ..clouds(frame, shafts, true)
    };
    renderer.set_clouds(Some(with(true))).unwrap();
    let plan = renderer.render(frame).unwrap();
    assert!(plan.runs("cloud_shadow"), "the map for the air: {plan}");
    assert!(
        !plan.skipped.iter().any(|(name, _)| *name == CLOUD_SHAFTS),
        "{plan}"
    );
    let gpu = renderer.read_hdr().unwrap();
    let plain = render(renderer, frame, with(false));

    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    let radius = frame.atmosphere.bottom_radius_m;
    let layer = CloudLayer::new(settings, radius, cover, phase).unwrap();
    let map = frame_sun_map(&layer, frame);
    let shadow = CloudAirShadow::new(&frame.atmosphere, &model);
    let air_shadow = AirShadow {
        terrain: None,
        clouds: &map,
    };
    let brightest = gpu
        .iter()
        .flat_map(|p| p[..3].to_vec())
        .fold(0.0f32, f32::max);
    let mut c = Compared {
        least: f64::INFINITY,
        ..Compared::default()
    };
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
                c.air += 1;
                let kept = f64::from(gpu[k][1]) / f64::from(plain[k][1]);
                (c.least, c.most) = (c.least.min(kept), c.most.max(kept));
                for w in 0..3 {
                    let (g, cpu) = (f64::from(gpu[k][w]), full.radiance[w]);
                    c.worst_air = c.worst_air.max((g - cpu).abs() / (AIR_RELATIVE * cpu));
                    let lost = f64::from(plain[k][w]) - g;
                    c.darkened += usize::from(lost > 10.0 * AIR_RELATIVE * cpu);
                    c.brighter += usize::from(-lost > AIR_RELATIVE * cpu);
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
            c.cloudy += 1;
            let cloud = CloudSegment {
                radiance: vec![r, g, b],
                transmittance: vec![t; 3],
            };
            let cpu: RayRadiance = composite(&full, &front, &cloud);
            for w in 0..3 {
                let error = (f64::from(gpu[k][w]) - cpu.radiance[w]).abs();
                let allowed = RELATIVE * cpu.radiance[w] + OF_BRIGHTEST * f64::from(brightest);
                c.worst_cloud = c.worst_cloud.max(error / allowed);
                c.outside += usize::from(error > allowed);
                c.far_outside += usize::from(error > JUMP_FACTOR * allowed);
            }
            let change = f64::from(plain[k][1] - gpu[k][1]).abs();
            let allowed = RELATIVE * cpu.radiance[1] + OF_BRIGHTEST * f64::from(brightest);
            c.shaded_cloudy += usize::from(change > allowed);
        }
    }
    println!("{c:?}");
    c
}

#[test]
fn cloud_shafts_darken_the_air_below_a_deck_with_gaps_as_the_cpu_twin_does() {
    let Some(mut renderer) = support::renderer_or_skip("cloud shafts") else {
        return;
    };
    let frame = frame(300.0, 0.0);
    let c = against_cpu(&mut renderer, &frame, settings());
    assert!(c.air > 500 && c.cloudy > 500, "{c:?}");
    // Beams: air lit through the gaps beside air in the deck's shadow.
    assert!(
        c.least < 0.8 && c.most - c.least > 0.1,
        "the air keeps {:.3} to {:.3} of its light: no beams",
        c.least,
        c.most
    );
    assert!(c.worst_air <= 1.0, "air pixels: {c:?}");
    assert!(
        c.outside * 100 <= 3 * c.cloudy && c.far_outside == 0,
        "deck pixels: {c:?}"
    );
    assert!(
        c.darkened * 4 >= 3 * c.air,
        "too few values darkened: {c:?}"
    );
    assert_eq!(
        c.brighter, 0,
        "values brighter with the cloud's shadow: {c:?}"
    );
}

/// From above the deck the air in the cloud's shadow lies behind the cloud: seen through
/// the gaps it is as dark as the CPU's, and behind the cloud it is dimmed with the
/// light behind the cloud, not taken from the air in front of it.
#[test]
fn from_above_the_deck_the_shadowed_air_lies_behind_the_cloud() {
    let Some(mut renderer) = support::renderer_or_skip("cloud shafts from above") else {
        return;
    };
    let frame = frame(20_000.0, -30.0);
    let thin_and_high = LayerSettings {
        base_m: 4_000.0,
        thickness_m: 500.0,
        extinction_per_m: 0.004,
        ..settings()
    };
    let c = against_cpu(&mut renderer, &frame, thin_and_high);
    assert!(c.cloudy > 1500, "{c:?}");
    assert!(
        c.shaded_cloudy * 50 >= c.cloudy,
        "the shadow hardly shows: {c:?}"
    );
    assert!(c.worst_cloud <= 1.0, "deck pixels: {c:?}");
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
