//! The bruneton model on the GPU against its CPU twin (atmosphere-core `bruneton`): every
//! table read back texel by texel, the number of scattering orders, rendered pixels
//! against `Bruneton::radiance` on the same pixel rays (plus the sun disk), and the
//! frame plan's table skipping.
//!
//! Needs a GPU adapter (lavapipe will do), with the skip policy of the other GPU tests.

mod support;

use atmosphere_core::models::bruneton::Bruneton;
use atmosphere_core::models::id::ModelId;
use render_wgpu::frame::Frame;
use render_wgpu::sky::bruneton::BrunetonPass;
use render_wgpu::{RenderError, Renderer};
use support::bruneton::{compare_tables, frame, settings};
use support::{
    BRUNETON_TABLES, check, check_surface, check_texel_reads, gpu_or_skip, standard_frames, view,
};

/// Reduced table sizes for the parity tests (S 8 x 32 x 16 x 8, the paper's sample
/// counts), so that the CPU and lavapipe build them in seconds.
const REDUCED: [&str; 4] = ["r=8", "mu=32", "mu_s=16", "nu=8"];

#[test]
fn tables_match_the_cpu() {
    let Some(gpu) = gpu_or_skip("bruneton tables") else {
        return;
    };
    let errors = compare_tables(&gpu, "earth", &REDUCED);
    assert!(errors.iter().all(|e| *e < 1e-2), "{errors:?}");
}

/// Mie's Delta J by quadrature about the view (`mie_directions`), in the hazy atmosphere
/// whose forward-peaked aerosol it is for.
#[test]
fn tables_match_the_cpu_with_the_mie_quadrature() {
    let Some(gpu) = gpu_or_skip("bruneton tables with the Mie quadrature") else {
        return;
    };
    let mut options = REDUCED.to_vec();
    options.push("mie_directions=8");
    let errors = compare_tables(&gpu, "hazy", &options);
    assert!(errors.iter().all(|e| *e < 1e-2), "{errors:?}");
}

/// Mie's quadrature in the texel's frame, split at the view and the horizon
/// (`mie_horizon`), in the hazy atmosphere whose bright horizon it is for: in every order,
/// and in order two alone (`mie_horizon_order_two`, the later orders' parameters about
/// the view).
#[test]
fn tables_match_the_cpu_with_the_mie_quadrature_in_the_horizon_frame() {
    let Some(gpu) = gpu_or_skip("bruneton tables with the Mie quadrature in the horizon frame")
    else {
        return;
    };
    for extra in [&[][..], &["mie_horizon_order_two=true"][..]] {
        let mut options = REDUCED.to_vec();
        options.extend(["mie_directions=8", "mie_horizon=true"]);
        options.extend(extra);
        let errors = compare_tables(&gpu, "hazy", &options);
        // The multiple part's worst texel (1.4e-2) is the ground's horizon texel, whose
        // view lies on the step from sky to ground, the phase function's peak on it.
        assert!(errors[2] < 2e-2, "{extra:?}: {errors:?}");
        assert!(
            [errors[0], errors[1], errors[3]].iter().all(|e| *e < 1e-2),
            "{extra:?}: {errors:?}"
        );
    }
}

/// Nodes along each texel's ray placed by density (`density_nodes`), in the hazy
/// atmosphere whose boundary layer they are for.
#[test]
fn tables_match_the_cpu_with_density_nodes() {
    let Some(gpu) = gpu_or_skip("bruneton tables with density nodes") else {
        return;
    };
    let mut options = REDUCED.to_vec();
    options.push("density_nodes=true");
    let errors = compare_tables(&gpu, "hazy", &options);
    assert!(errors.iter().all(|e| *e < 1e-2), "{errors:?}");
}

/// The nu weights between the texels' clamped positions (`nu_edge`), with u_nu by angle,
/// in the hazy atmosphere whose forward lobe about the sun they are for: every table, then
/// frames from the ground (the view slice) and from orbit (the 3D textures) whose rays
/// pass near the edge of their nu range.
#[test]
fn tables_and_frames_match_the_cpu_with_the_nu_edge_weights() {
    let Some(gpu) = gpu_or_skip("bruneton nu edge") else {
        return;
    };
    let mut options = REDUCED.to_vec();
    options.extend(["nu_by_angle=true", "nu_edge=true"]);
    let errors = compare_tables(&gpu, "hazy", &options);
    assert!(errors.iter().all(|e| *e < 1e-2), "{errors:?}");
    let mut renderer = Renderer::new(gpu).unwrap();
    let mut low_sun = view(2.0, 84.0, 45.0);
    low_sun.sun_azimuth_deg = 30.0;
    for (name, v, fov) in [
        ("hazy, towards the sun", low_sun, 90.0),
        ("hazy, from orbit", view(400_000.0, 110.0, 60.0), 40.0),
    ] {
        let f = frame("hazy", settings(&options), v, fov, 48, 27);
        check(&mut renderer, name, &f, MAX_RELATIVE_ERROR);
    }
}

/// The fourth coordinate as the azimuth between the view's and the sun's vertical planes
/// (`nu_by_azimuth`) and the sky's mu texels spread towards the zenith (`mu_zenith`),
/// with the sun's axis down to 18 deg below the horizon: every table,
/// then frames of nautical twilight from the ground (the view slice) and of the
/// terminator from orbit (the 3D textures), whose rays towards the sun lie in or near
/// its vertical plane.
#[test]
fn tables_and_frames_match_the_cpu_with_the_azimuth_axis_and_the_zenith_texels() {
    let Some(gpu) = gpu_or_skip("bruneton azimuth axis") else {
        return;
    };
    let mut options = REDUCED.to_vec();
    options.extend([
        "nu_by_azimuth=true",
        "mu_zenith=true",
        "min_mu_s=-0.31",
        "mu_s_knee=true",
    ]);
    let errors = compare_tables(&gpu, "earth", &options);
    // As with the twilight sun angles, single Mie's worst texel sits on the shadow's edge.
    assert!(errors[1] < 0.15, "{errors:?}");
    assert!(
        [errors[0], errors[2], errors[3]].iter().all(|e| *e < 1e-2),
        "{errors:?}"
    );
    let mut renderer = Renderer::new(gpu).unwrap();
    let mut in_the_sun_s_plane = view(2.0, 60.0, 102.0);
    in_the_sun_s_plane.sun_azimuth_deg = 0.0;
    for (name, v, fov) in [
        (
            "nautical twilight, towards the sun",
            in_the_sun_s_plane,
            90.0,
        ),
        (
            "the terminator from orbit",
            view(400_000.0, 110.0, 100.0),
            40.0,
        ),
    ] {
        let f = frame("earth", settings(&options), v, fov, 48, 27);
        check(&mut renderer, name, &f, MAX_RELATIVE_ERROR);
    }
}

/// The twilight settings: S and E down to the sun 20 deg below the horizon, u_nu linear
/// in the scattering angle.
const TWILIGHT: [&str; 6] = [
    "r=8",
    "mu=32",
    "mu_s=16",
    "nu=8",
    "min_mu_s=-0.35",
    "nu_by_angle=true",
];

#[test]
fn tables_match_the_cpu_with_the_twilight_mappings() {
    let Some(gpu) = gpu_or_skip("bruneton twilight tables") else {
        return;
    };
    let errors = compare_tables(&gpu, "earth", &TWILIGHT);
    assert!(errors.iter().all(|e| *e < 1e-2), "{errors:?}");
}

#[test]
fn twilight_frames_match_the_cpu_with_the_twilight_mappings() {
    let Some(gpu) = gpu_or_skip("bruneton twilight frames") else {
        return;
    };
    let mut renderer = Renderer::new(gpu).unwrap();
    let mut toward_the_sun = view(2.0, 80.0, 102.0);
    toward_the_sun.sun_azimuth_deg = 10.0;
    let frames = [
        ("nautical twilight", toward_the_sun, 90.0),
        (
            "orbit over the terminator",
            view(400_000.0, 110.0, 100.0),
            40.0,
        ),
        ("noon", view(1.0, 60.0, 30.0), 70.0),
    ];
    for (name, v, fov) in frames {
        let f = frame("earth", settings(&TWILIGHT), v, fov, 48, 27);
        check(&mut renderer, name, &f, MAX_RELATIVE_ERROR);
    }
}

/// The sun to 18 deg below the horizon (min_mu_s = -0.31), u_mu_s continued linearly
/// below the paper's -0.2 (`mu_s_knee`), S and E read geometrically along mu_s below the
/// horizontal (`geometric_mu_s`).
const KNEE: [&str; 7] = [
    "r=8",
    "mu=32",
    "mu_s=16",
    "nu=8",
    "min_mu_s=-0.31",
    "mu_s_knee=true",
    "geometric_mu_s=true",
];

#[test]
fn tables_and_frames_match_the_cpu_with_the_twilight_sun_angles() {
    let Some(gpu) = gpu_or_skip("bruneton mu_s knee and geometric mu_s") else {
        return;
    };
    let errors = compare_tables(&gpu, "earth", &KNEE);
    // Single Mie's worst texel (r at the top, the ray grazing the ground, the sun at
    // mu_s = -0.049) sits on the shadow's edge, 1e7 times brighter than its neighbour
    // below: f32 sun angles move it by 1.2e-4 of the table's peak, 0.12 of the floor.
    assert!(errors[1] < 0.15, "{errors:?}");
    assert!(
        [errors[0], errors[2], errors[3]].iter().all(|e| *e < 1e-2),
        "{errors:?}"
    );
    let mut renderer = Renderer::new(gpu).unwrap();
    let mut toward_the_sun = view(2.0, 80.0, 106.0);
    toward_the_sun.sun_azimuth_deg = 10.0;
    for (name, v) in [
        ("the sun 16 deg down", toward_the_sun),
        ("civil twilight", view(2.0, 80.0, 96.0)),
    ] {
        let f = frame("earth", settings(&KNEE), v, 90.0, 48, 27);
        check(&mut renderer, name, &f, MAX_RELATIVE_ERROR);
    }
}

/// The sun as a disk where it meets the horizon (`sun_disk`): the tables, and frames with
/// the disk's centre on the horizon and 0.2 deg below it, the ground in view.
#[test]
fn tables_and_frames_match_the_cpu_with_the_sun_disk() {
    let Some(gpu) = gpu_or_skip("bruneton sun disk") else {
        return;
    };
    let mut options = REDUCED.to_vec();
    options.push("sun_disk=true");
    let errors = compare_tables(&gpu, "earth", &options);
    // Single Rayleigh's worst texel (measured 1.24e-2: the sun 2 deg down, the ray away
    // from it) integrates across the edge of the shadow, where the disk's visible part
    // changes within a few of f32's sun angles.
    assert!(errors[0] < 2e-2, "{errors:?}");
    assert!(errors[1..].iter().all(|e| *e < 1e-2), "{errors:?}");
    let mut renderer = Renderer::new(gpu).unwrap();
    for (name, sun_zenith_deg) in [
        ("the sun's centre on the horizon", 90.0),
        ("the sun's centre 0.2 deg down", 90.2),
    ] {
        let mut v = view(2.0, 85.0, sun_zenith_deg);
        v.sun_azimuth_deg = 10.0;
        let f = frame("earth", settings(&options), v, 90.0, 48, 27);
        check(&mut renderer, name, &f, MAX_RELATIVE_ERROR);
    }
}

/// Largest allowed |L_gpu - L_cpu| / max(L_cpu, FLOOR) per pixel and channel: the f16
/// HDR store (4.9e-4), the tables' f32 build differences (above: up to 3e-3 relative
/// where Mie dominates) and f32 texel positions in the look-ups. Measured on lavapipe:
/// see the test output and docs/rendering.md.
const MAX_RELATIVE_ERROR: f64 = 5e-3;

#[test]
fn frames_match_the_cpu_from_the_ground_to_far_orbit() {
    let Some(gpu) = gpu_or_skip("bruneton frames") else {
        return;
    };
    let mut renderer = Renderer::new(gpu).unwrap();
    let s = settings(&REDUCED);
    let mut sunset = view(2_000.0, 88.0, 89.0);
    sunset.sun_azimuth_deg = 5.0;
    let frames = [
        ("ground, noon", view(1.0, 80.0, 10.0), 70.0),
        ("sunset", sunset, 60.0),
        ("10 km", view(10_000.0, 95.0, 60.0), 60.0),
        ("100 km limb", view(100_000.0, 100.0, 60.0), 40.0),
        ("1e8 m", view(1e8, 180.0, 80.0), 9.0),
        ("sun disk", view(500.0, 60.0, 60.0), 1.0),
    ];
    for (name, v, fov) in frames {
        let mut v = v;
        if name == "sun disk" {
            v.sun_azimuth_deg = 0.0;
        }
        let f = frame("earth", s.clone(), v, fov, 48, 27);
        check(&mut renderer, name, &f, MAX_RELATIVE_ERROR);
    }
}

#[test]
fn bruneton_lights_surfaces_and_sees_them_through_the_air_as_on_the_cpu() {
    let Some(gpu) = gpu_or_skip("bruneton surfaces") else {
        return;
    };
    let mut renderer = Renderer::new(gpu).unwrap();
    // The aerial perspective's second look-up where a surface cuts the ray short, none
    // where it lies beyond the ground; the tables reduced as above.
    for (name, f) in standard_frames(ModelId::Bruneton).iter().take(4) {
        let f = Frame {
            settings: settings(&REDUCED),
            ..f.clone()
        };
        check_surface(&mut renderer, name, &f, MAX_RELATIVE_ERROR);
    }
}

/// The pass's texel-by-texel reads, which a device without `FLOAT32_FILTERABLE` runs,
/// against the CPU on the ground and with a surface cutting rays short, and against the
/// filtered reads (the default where the adapter filters Rgba32Float, as lavapipe does)
/// pixel by pixel.
#[test]
fn texel_reads_match_the_cpu_and_the_filtered_reads() {
    let s = settings(&REDUCED);
    let frames = [
        (
            "ground, noon",
            frame("earth", s.clone(), view(1.0, 80.0, 10.0), 70.0, 48, 27),
        ),
        (
            "10 km",
            frame("earth", s.clone(), view(10_000.0, 95.0, 60.0), 60.0, 48, 27),
        ),
    ];
    let (name, surface) = &standard_frames(ModelId::Bruneton)[0];
    let surface = Frame {
        settings: s,
        ..surface.clone()
    };
    check_texel_reads(
        "bruneton",
        &frames,
        Some((name, &surface)),
        MAX_RELATIVE_ERROR,
    );
}

#[test]
fn unchanged_tables_and_sun_changes_rebuild_nothing() {
    let Some(gpu) = gpu_or_skip("bruneton plan") else {
        return;
    };
    let mut renderer = Renderer::new(gpu).unwrap();
    let tables = BRUNETON_TABLES;
    let mut f = frame(
        "earth",
        settings(&REDUCED),
        view(100.0, 85.0, 40.0),
        60.0,
        32,
        18,
    );
    let first = renderer.render(&f).unwrap();
    assert!(tables.iter().all(|t| first.runs(t)), "{first}");
    let again = renderer.render(&f).unwrap();
    assert!(tables.iter().all(|t| !again.runs(t)), "{again}");
    // A new sun rebuilds nothing and renders what a full build renders.
    f.sun_direction = view(100.0, 85.0, 70.0).sun_direction();
    let moved = renderer.render(&f).unwrap();
    assert!(tables.iter().all(|t| !moved.runs(t)), "{moved}");
    let image = renderer.read_hdr().unwrap();
    let mut fresh = Renderer::headless().unwrap();
    fresh.render(&f).unwrap();
    assert_eq!(image, fresh.read_hdr().unwrap());
    // The ground albedo rebuilds the orders, not single scattering.
    f.atmosphere.ground_albedo = 0.3;
    let albedo = renderer.render(&f).unwrap();
    assert!(
        albedo.runs("scattering_orders") && !albedo.runs("single_scattering"),
        "{albedo}"
    );
    // Aerosol 0 prunes Mie: no Mie table and the image of the CPU's pruned model.
    f.atmosphere = f.atmosphere.with_aerosol_scale(0.0);
    let pruned = renderer.render(&f).unwrap();
    assert!(pruned.runs("single_scattering"), "{pruned}");
    let cpu = Bruneton::prepare(&f.atmosphere, &f.settings).unwrap();
    assert!(cpu.mie_pruned());
    check(&mut renderer, "aerosol 0", &f, MAX_RELATIVE_ERROR);
}

#[test]
fn unsupported_sizes_are_errors_naming_them() {
    let Some(gpu) = gpu_or_skip("bruneton sizes") else {
        return;
    };
    let mut renderer = Renderer::new(gpu).unwrap();
    let f = frame(
        "earth",
        settings(&["r=2", "mu=4", "mu_s=256", "nu=64"]),
        view(10.0, 80.0, 50.0),
        60.0,
        8,
        8,
    );
    let err = renderer.render(&f).unwrap_err();
    // WebGPU's default limit, which the device is created with, is 2048 texels a side.
    assert!(
        matches!(err, RenderError::Unsupported(_)) && err.to_string().contains("3D texture"),
        "{err}"
    );
}

/// More sun angles and scattering angles than a 256-invocation workgroup holds per row
/// (mu_s x nu = 512), more texels than one row of flat workgroups (131072), and E with
/// four times the paper's sun angles.
const WIDE_ROWS: [&str; 5] = ["r=8", "mu=32", "mu_s=32", "nu=16", "e_mu_s=256"];

#[test]
fn tables_with_wide_rows_match_the_cpu() {
    let Some(gpu) = gpu_or_skip("bruneton wide rows") else {
        return;
    };
    let errors = compare_tables(&gpu, "earth", &WIDE_ROWS);
    assert!(errors.iter().all(|e| *e < 1e-2), "{errors:?}");
    let mut renderer = Renderer::new(gpu).unwrap();
    let f = frame(
        "earth",
        settings(&WIDE_ROWS),
        view(2.0, 80.0, 96.0),
        90.0,
        48,
        27,
    );
    check(
        &mut renderer,
        "civil twilight, wide rows",
        &f,
        MAX_RELATIVE_ERROR,
    );
}

/// Options from environment variable `name`: `key=value` items separated by spaces or
/// commas (none when unset).
fn env_options(name: &str) -> Vec<String> {
    std::env::var(name)
        .unwrap_or_default()
        .split([' ', ','])
        .filter(|s| !s.is_empty())
        .map(str::to_string)
        .collect()
}

/// The cost target, measured rather than asserted (lavapipe's times depend on
/// the machine's load): `atmos bench`'s ground view at 1280x720 with the paper's tables
/// against the 16-sample nishita frame, frames interleaved (load varies), wall-clock
/// from `render` to the GPU's end (tone map included in both) and the pass's GPU time
/// from the plan. `ATMOS_BRUNETON_COST_SET="view_samples=2 sphere_azimuth=2"` builds the
/// tables with other options (the pass's cost depends on the table sizes only);
/// `ATMOS_COST_RUNS` frames (5). Run with `./scripts/test.sh -p atmos-tests --test
/// gpu_bruneton_parity cost -- --ignored --nocapture`.
#[test]
#[ignore = "a benchmark: minutes on lavapipe"]
fn cost_at_1280x720_against_nishita_16() {
    let Some(gpu) = gpu_or_skip("bruneton cost") else {
        return;
    };
    let mut renderer = Renderer::new(gpu).unwrap();
    let ground = atmos::bench::views::BENCH_VIEWS[0];
    let mut nishita = frame(
        "earth",
        settings(&["samples=16"]),
        ground.view,
        ground.fov_deg,
        1280,
        720,
    );
    nishita.model = ModelId::Nishita;
    let options = env_options("ATMOS_BRUNETON_COST_SET");
    let options: Vec<&str> = options.iter().map(String::as_str).collect();
    let mut bruneton = nishita.clone();
    bruneton.model = ModelId::Bruneton;
    bruneton.settings = settings(&options);
    let runs: usize = std::env::var("ATMOS_COST_RUNS").map_or(5, |v| v.parse().unwrap());
    let timed = |renderer: &mut Renderer, f: &Frame| {
        let start = std::time::Instant::now();
        let plan = renderer.render(f).unwrap();
        (start.elapsed().as_secs_f64() * 1e3, plan)
    };
    let (build, plan) = timed(&mut renderer, &bruneton);
    println!("bruneton {options:?}: first frame (tables built) {build:.0} ms: {plan}");
    timed(&mut renderer, &nishita);
    let (mut n_ms, mut b_ms, mut ratios) = (Vec::new(), Vec::new(), Vec::new());
    for run in 0..runs {
        let (n, n_plan) = timed(&mut renderer, &nishita);
        let (b, b_plan) = timed(&mut renderer, &bruneton);
        println!(
            "run {run}: wall nishita 16 {n:.0} ms, bruneton {b:.0} ms, ratio {:.3}\n  nishita: {n_plan}\n  bruneton: {b_plan}",
            b / n
        );
        n_ms.push(n);
        b_ms.push(b);
        ratios.push(b / n);
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[(v.len() - 1) / 2]
    };
    println!(
        "medians of {runs}: frame wall nishita 16 {:.0} ms, bruneton {:.0} ms; ratio {:.3}",
        median(&mut n_ms),
        median(&mut b_ms),
        median(&mut ratios)
    );
}

/// The table build one dispatch at a time, wall-clock, at the paper's sizes (or with
/// `ATMOS_BRUNETON_PROFILE_SET` options): per step and per step of the loop over orders,
/// summed over orders. Run with `./scripts/test.sh -p atmos-tests --test
/// gpu_bruneton_parity profile -- --ignored --nocapture`.
#[test]
#[ignore = "a profile: minutes on lavapipe"]
fn profile_the_table_build() {
    let Some(gpu) = gpu_or_skip("bruneton build profile") else {
        return;
    };
    let options = env_options("ATMOS_BRUNETON_PROFILE_SET");
    let options: Vec<&str> = options.iter().map(String::as_str).collect();
    let f = frame(
        "earth",
        settings(&options),
        view(10.0, 80.0, 50.0),
        60.0,
        8,
        8,
    );
    let mut pass = BrunetonPass::new(&gpu).unwrap();
    // A first build compiles lavapipe's shaders; the second is measured.
    let start = std::time::Instant::now();
    pass.build_tables(&gpu, &f).unwrap();
    println!("first build {:.1} s", start.elapsed().as_secs_f64());
    let times = pass.profile_build(&gpu, &f).unwrap();
    let mut by_step: Vec<(String, f64, usize)> = Vec::new();
    for (name, ms) in &times {
        if *ms > 1.0 {
            println!("{name}: {ms:.1} ms");
        }
        let key = match name.strip_prefix("scattering_orders order ") {
            Some(rest) => format!("orders: {}", rest.split_once(' ').unwrap().1),
            None => name.clone(),
        };
        match by_step.iter_mut().find(|(k, _, _)| *k == key) {
            Some(e) => {
                e.1 += ms;
                e.2 += 1;
            }
            None => by_step.push((key, *ms, 1)),
        }
    }
    let total: f64 = times.iter().map(|(_, ms)| ms).sum();
    println!("bruneton {options:?}: build {:.2} s in all", total / 1e3);
    for (k, ms, n) in by_step {
        println!("  {k}: {:.2} s ({n} dispatches)", ms / 1e3);
    }
}
