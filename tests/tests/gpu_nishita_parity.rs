//! The GPU nishita frame (`shaders/sky/nishita/pixel.wgsl` through the `Renderer`) against the CPU
//! model (`atmosphere_core::models::registry::prepare(ModelId::Nishita, ..)`) on the same pixel rays, the
//! sun disk against `atmosphere_core::optics::sun_disk`, and the tone map against its CPU twin
//! (`render_wgpu::post::tone_map`); see `support/mod.rs`.

mod support;

use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::nishita::SAMPLES;
use atmosphere_core::models::options::ModelOptions;
use render_wgpu::frame::LocalView;
use support::{
    check, check_each, check_standard_surfaces, check_sun_disk, frame, renderer_or_skip,
    standard_frames,
};

/// Largest allowed |L_gpu - L_cpu| / max(L_cpu, FLOOR) per pixel and channel. The HDR
/// target stores f16 (relative rounding 4.9e-4); the rest is f32 arithmetic along 100
/// samples and the f32 table. Measured on lavapipe: see the test output.
const MAX_RELATIVE_ERROR: f64 = 2e-3;

#[test]
fn nishita_frames_match_the_cpu_from_the_ground_to_far_orbit() {
    let Some(mut renderer) = renderer_or_skip("nishita parity") else {
        return;
    };
    let frames = standard_frames(ModelId::Nishita);
    check_each(&mut renderer, &frames[..4], MAX_RELATIVE_ERROR);
}

/// The most samples a setting allows: one GPU loop of that many trips runs in full (on
/// lavapipe, loops past 65535 trips in all end early, silently).
#[test]
fn the_largest_sample_count_matches_the_cpu() {
    let Some(mut renderer) = renderer_or_skip("nishita largest samples") else {
        return;
    };
    let most = *SAMPLES.range.end();
    let mut f = frame(ModelId::Nishita, support::view(1.0, 85.0, 50.0), 60.0, 8, 6);
    f.settings.options = ModelOptions::parse(&[format!("samples={most}")]).unwrap();
    check(
        &mut renderer,
        "samples at their most",
        &f,
        MAX_RELATIVE_ERROR,
    );
}

#[test]
fn nishita_lights_surfaces_and_sees_them_through_the_air_as_on_the_cpu() {
    check_standard_surfaces("nishita surfaces", ModelId::Nishita, MAX_RELATIVE_ERROR);
}

#[test]
fn the_sun_disk_is_limb_darkened_as_on_the_cpu() {
    check_sun_disk("sun disk", ModelId::Nishita, MAX_RELATIVE_ERROR);
}

#[test]
fn tables_are_rebuilt_only_when_their_inputs_change_and_unknown_models_are_refused() {
    let Some(mut renderer) = renderer_or_skip("plan") else {
        return;
    };
    let view = LocalView {
        altitude_m: 10.0,
        view_zenith_deg: 80.0,
        view_azimuth_deg: 0.0,
        sun_zenith_deg: 40.0,
        sun_azimuth_deg: 0.0,
    };
    let mut f = frame(ModelId::Nishita, view, 60.0, 16, 9);
    assert!(renderer.render(&f).unwrap().runs("g_l"));
    f.exposure_ev100 = 12.0;
    assert!(!renderer.render(&f).unwrap().runs("g_l"));
    // g_l holds columns of matter: twice the aerosol changes coefficients, not columns,
    // and the frame that skips the table equals one built from scratch.
    f.atmosphere = f.atmosphere.with_aerosol_scale(2.0);
    let plan = renderer.render(&f).unwrap();
    assert!(!plan.runs("g_l"), "{plan}");
    let skipped = renderer.read_hdr().unwrap();
    let mut fresh = renderer_or_skip("plan").unwrap();
    assert!(fresh.render(&f).unwrap().runs("g_l"));
    assert_eq!(skipped, fresh.read_hdr().unwrap());
    // Another aerosol profile changes the Mie columns.
    f.atmosphere.mie.density =
        atmosphere_core::atmosphere::density::DensityProfile::exponential(1_500.0);
    assert!(renderer.render(&f).unwrap().runs("g_l"));
    f.model = ModelId::Reference;
    let err = renderer.render(&f).unwrap_err();
    assert!(
        err.to_string()
            .contains("'reference' is not yet on the GPU"),
        "{err}"
    );
}
