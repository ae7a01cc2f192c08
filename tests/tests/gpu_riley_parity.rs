//! The GPU riley frame (`shaders/sky/riley/pixel.wgsl` through the `Renderer`) against the CPU
//! model (`atmosphere_core::models::riley`) on the same pixel rays: the standard frames, frames
//! whose pixel rays pass through the closed form's stiff directions (view elevation equal
//! to the sun's, horizontal rays), other atmospheres; see `support/mod.rs`.

mod support;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::riley::RileySettings;
use render_wgpu::frame::{Frame, LocalView};
use support::{
    FLOOR, check, check_each, check_standard_frames, check_standard_surfaces, frame,
    ground_frame_in, other_atmosphere_frames, renderer_or_skip, standard_frames, view,
};

/// Largest allowed |L_gpu - L_cpu| / max(L_cpu, FLOOR) per pixel and channel: the f16
/// store (4.9e-4) and f32 arithmetic in a closed form. Measured on lavapipe: see the
/// test output.
const MAX_RELATIVE_ERROR: f64 = 2e-3;

/// The same for rays ending on nearby surfaces: on the sphere, a short piece's column is
/// the difference of two Chapman columns up to 3e5 m, each a few f32 roundings off, an
/// absolute error of about 2.5e-7 W m^-2 sr^-1 nm^-1 in radiance (2.4e-3 of `FLOOR`)
/// where the air's light over a short path is faint.
const MAX_SURFACE_RELATIVE_ERROR: f64 = 3e-3;

#[test]
fn riley_frames_match_the_cpu_from_the_ground_to_far_orbit() {
    let Some(mut renderer) = renderer_or_skip("riley parity") else {
        return;
    };
    check_standard_frames(&mut renderer, ModelId::Riley, MAX_RELATIVE_ERROR);
    // The ground frame in other atmospheres: the fit is redone on the CPU and the uniform
    // uploaded again; at zero aerosol the Mie terms are pruned.
    let mut others = other_atmosphere_frames(ModelId::Riley);
    let no_aerosol = Atmosphere::preset("earth").unwrap().with_aerosol_scale(0.0);
    others.push(("no aerosol", ground_frame_in(no_aerosol, ModelId::Riley)));
    // The sun below the horizon: the planet's shadow cuts the rays (civil and nautical
    // twilight from the ground, the limb across the terminator from 400 km).
    let at = |altitude_m, view_zenith_deg, sun_zenith_deg| LocalView {
        altitude_m,
        view_zenith_deg,
        view_azimuth_deg: 0.0,
        sun_zenith_deg,
        sun_azimuth_deg: 10.0,
    };
    let limb_zenith = 90.0 + (6360.0f64 / 6760.0).acos().to_degrees();
    for (name, view, fov) in [
        ("civil twilight", at(2.0, 75.0, 96.0), 60.0),
        ("nautical twilight", at(2.0, 80.0, 102.0), 60.0),
        ("orbit terminator", at(400_000.0, limb_zenith, 100.0), 40.0),
    ] {
        others.push((name, frame(ModelId::Riley, view, fov, 64, 36)));
    }
    check_each(&mut renderer, &others, MAX_RELATIVE_ERROR);
}

/// The paper's flat form (`sphere=false shared_extinction=false ozone=false pieces=1`)
/// and the sphere with each species by itself, on the standard frames.
#[test]
fn riley_settings_match_the_cpu() {
    let Some(mut renderer) = renderer_or_skip("riley settings") else {
        return;
    };
    let forms = [
        RileySettings::PAPER,
        RileySettings {
            shared_extinction: false,
            ozone: false,
            pieces: 9,
            ..RileySettings::default()
        },
        RileySettings {
            sphere: false,
            pieces: 3,
            ..RileySettings::default()
        },
    ];
    for form in forms {
        let mut frames = standard_frames(ModelId::Riley);
        for (name, f) in &mut frames {
            f.settings.options = form.to_options();
            println!("riley {form:?}:");
            check(&mut renderer, name, f, MAX_RELATIVE_ERROR);
        }
    }
}

#[test]
fn riley_lights_surfaces_and_sees_them_through_the_air_as_on_the_cpu() {
    check_standard_surfaces("riley surfaces", ModelId::Riley, MAX_SURFACE_RELATIVE_ERROR);
}

/// A 33 x 33 frame 0.01 deg high around `view`: the centre row is the view direction
/// itself, the rows step by about 5e-6 rad in elevation across it.
fn narrow(view: LocalView) -> Frame {
    frame(ModelId::Riley, view, 0.01, 33, 33)
}

/// The largest step between vertically neighbouring pixels of the centre column of the
/// last frame, green channel, relative to the larger of the two or `FLOOR`.
fn largest_vertical_step(renderer: &render_wgpu::Renderer, f: &Frame) -> f64 {
    let hdr = renderer.read_hdr().unwrap();
    let column = f.width / 2;
    (1..f.height)
        .map(|row| {
            let a = f64::from(hdr[(row * f.width + column) as usize][1]);
            let b = f64::from(hdr[((row - 1) * f.width + column) as usize][1]);
            (a - b).abs() / a.abs().max(b.abs()).max(FLOOR)
        })
        .fold(0.0, f64::max)
}

#[test]
fn stiff_directions_stay_finite_and_match_the_cpu() {
    let Some(mut renderer) = renderer_or_skip("riley stiff directions") else {
        return;
    };
    let at = |altitude_m, view_zenith_deg, sun_zenith_deg, sun_azimuth_deg| LocalView {
        altitude_m,
        view_zenith_deg,
        view_azimuth_deg: 0.0,
        sun_zenith_deg,
        sun_azimuth_deg,
    };
    let cases = [
        // View elevation equal to the sun's (p_y = l_y), 90 deg of azimuth away.
        ("p = l at 500 m", narrow(at(500.0, 60.0, 60.0, 90.0))),
        // The same towards the sun itself: p_y = l_y and nu = 1, on the disk.
        ("p = l on the sun", narrow(at(500.0, 60.0, 60.0, 0.0))),
        // Low sun, p_y = l_y = 1.7e-3 with both near the horizon, from 20 km.
        (
            "p = l near the horizon",
            narrow(at(20_000.0, 89.9, 89.9, 120.0)),
        ),
        // Horizontal rays (p_y = 0): one leg up, two legs down past the limb.
        ("p = 0 at 1 km", narrow(at(1_000.0, 90.0, 40.0, 30.0))),
        ("p = 0 at 20 km", narrow(at(20_000.0, 90.0, 70.0, 150.0))),
        ("p = 0 at the top", narrow(at(59_999.0, 90.0, 30.0, 30.0))),
        // A wide frame through both at once.
        (
            "wide",
            frame(ModelId::Riley, at(3_000.0, 75.0, 75.0, 60.0), 40.0, 64, 37),
        ),
    ];
    for (name, f) in &cases {
        check(&mut renderer, name, f, MAX_RELATIVE_ERROR);
        if f.vertical_fov_deg < 1.0 {
            // Rays 5e-6 rad apart see nearly the same sky: no jump beyond the f16 store's
            // rounding (9.8e-4 relative at most) in either neighbour.
            let step = largest_vertical_step(&renderer, f);
            println!("riley {name}: largest step between neighbours {step:.2e}");
            assert!(
                step < 2.5e-3,
                "{name}: a step of {step:e} between neighbours"
            );
        }
    }
}

#[test]
fn riley_runs_one_pass_and_no_table() {
    let Some(mut renderer) = renderer_or_skip("riley plan") else {
        return;
    };
    let mut f = frame(ModelId::Riley, view(10.0, 80.0, 40.0), 60.0, 16, 9);
    let plan = renderer.render(&f).unwrap();
    let names: Vec<_> = plan.steps.iter().map(|s| s.name).collect();
    assert_eq!(names, ["riley", "tone_map"]);
    assert_eq!(renderer.table_bytes(), 0);
    f.settings.options =
        atmosphere_core::models::options::ModelOptions::parse(&["samples=3"]).unwrap();
    let err = renderer.render(&f).unwrap_err();
    assert!(err.to_string().contains("samples"), "{err}");
}
