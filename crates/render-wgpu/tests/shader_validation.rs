//! Every entry pass of `shaders/` (a file with `@compute`, `@vertex` or `@fragment`
//! functions), composed, passes naga's front end and validator without a GPU; a library
//! is validated inside the passes importing it and must have one (it may call a function
//! its importer defines, as `common/shade_pixel.wgsl` does); uniform layouts match Rust's.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use naga::valid::{Capabilities, ValidationFlags, Validator};
use render_wgpu::frame::atmosphere_uniform::{
    AtmosphereUniform, DensityLayerUniform, DensityProfileUniform,
};
use render_wgpu::gpu::shaders;
use render_wgpu::shafts::beams::gpu_scene::{
    BeamsUniform, LightUniform, NodeUniform, PrimitiveUniform, ShadowViewUniform,
};
use render_wgpu::shafts::beams::planes_pass::PlanesUniform;
use render_wgpu::shafts::beams::qtable_pass::QtableUniform;

/// What the device offers shaders: WebGPU's defaults (naga's default capabilities).
/// Add a capability here when `GpuContext` starts requesting the feature behind it.
const PROJECT_CAPABILITIES: Capabilities =
    Capabilities::MULTISAMPLED_SHADING.union(Capabilities::CUBE_ARRAY_TEXTURES);

/// Parses and validates `source`; the error is naga's report with source lines.
fn validate(name: &str, source: &str) -> Result<naga::Module, String> {
    let module = naga::front::wgsl::parse_str(source)
        .map_err(|e| e.emit_to_string_with_path(source, name))?;
    Validator::new(ValidationFlags::all(), PROJECT_CAPABILITIES)
        .validate(&module)
        .map_err(|e| e.emit_to_string_with_path(source, name))?;
    Ok(module)
}

/// The folder `shaders/` of the workspace.
fn shader_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shaders")
}

/// The paths below `dir` of the `.wgsl` files in it and its subfolders, with `/`.
fn wgsl_paths(dir: &Path, prefix: &str, out: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let entry = entry.unwrap();
        let name = format!("{prefix}{}", entry.file_name().to_string_lossy());
        if entry.file_type().unwrap().is_dir() {
            wgsl_paths(&entry.path(), &format!("{name}/"), out);
        } else if name.ends_with(".wgsl") {
            out.push(name);
        }
    }
}

/// The text of shader `name` as it is on disk, imports unresolved.
fn raw_source(name: &str) -> String {
    std::fs::read_to_string(shader_dir().join(name)).unwrap()
}

/// Whether shader `name` is an entry pass: a line of it (comments aside) starts with a
/// stage attribute.
fn is_entry_pass(name: &str) -> bool {
    raw_source(name).lines().any(|line| {
        let line = line.trim_start();
        ["@compute", "@vertex", "@fragment"]
            .iter()
            .any(|stage| line.starts_with(stage))
    })
}

/// The files shader `name` imports, directly or through other imports.
fn imported_files(name: &str, found: &mut BTreeSet<String>) {
    for line in raw_source(name).lines() {
        if let Some(import) = line.trim().strip_prefix("#import") {
            let import = import.trim().to_string();
            if found.insert(import.clone()) {
                imported_files(&import, found);
            }
        }
    }
}

#[test]
fn every_shader_file_is_embedded() {
    let mut on_disk = Vec::new();
    wgsl_paths(&shader_dir(), "", &mut on_disk);
    on_disk.sort();
    let mut embedded: Vec<String> = shaders::shader_names().map(String::from).collect();
    embedded.sort();
    assert_eq!(on_disk, embedded, "shaders/ and build.rs disagree");
}

#[test]
fn every_entry_pass_validates() {
    let shaders = shaders::all_composed().unwrap();
    let failures: Vec<String> = shaders
        .iter()
        .filter(|(name, _)| is_entry_pass(name))
        .filter_map(|(name, source)| validate(name, source).err())
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn every_library_is_imported_by_an_entry_pass() {
    let names: Vec<&str> = shaders::shader_names().collect();
    let mut imported = BTreeSet::new();
    for name in names.iter().filter(|name| is_entry_pass(name)) {
        imported_files(name, &mut imported);
    }
    let orphans: Vec<&&str> = names
        .iter()
        .filter(|name| !is_entry_pass(name) && !imported.contains(**name))
        .collect();
    assert!(
        orphans.is_empty(),
        "libraries no entry pass imports (so never validated): {orphans:?}"
    );
}

#[test]
fn broken_shaders_are_rejected() {
    // A type error, caught by the front end.
    let err = validate("type.wgsl", "fn f() -> f32 { return vec2<f32>(1.0); }").unwrap_err();
    assert!(err.contains("type.wgsl"), "{err}");
    // An array of stride 4 in a uniform, caught by the validator.
    let uniform = "struct S { a: array<f32, 4> }\n@group(0) @binding(0) var<uniform> s: S;\n";
    assert!(validate("layout.wgsl", uniform).is_err());
}

#[test]
fn atmosphere_uniform_matches_its_wgsl_layout() {
    let layout = |name: &str| wgsl_layout("common/atmosphere_params.wgsl", name);
    let (span, members) = layout("AtmosphereParams");
    assert_eq!(span, size_of::<AtmosphereUniform>());
    let rust = [
        (
            "bottom_radius_m",
            std::mem::offset_of!(AtmosphereUniform, bottom_radius_m),
        ),
        (
            "top_radius_m",
            std::mem::offset_of!(AtmosphereUniform, top_radius_m),
        ),
        (
            "rayleigh_density",
            std::mem::offset_of!(AtmosphereUniform, rayleigh_density),
        ),
        (
            "mie_density",
            std::mem::offset_of!(AtmosphereUniform, mie_density),
        ),
        (
            "ozone_density",
            std::mem::offset_of!(AtmosphereUniform, ozone_density),
        ),
        (
            "rayleigh_extinction_per_m",
            std::mem::offset_of!(AtmosphereUniform, rayleigh_extinction_per_m),
        ),
        (
            "mie_extinction_per_m",
            std::mem::offset_of!(AtmosphereUniform, mie_extinction_per_m),
        ),
        (
            "ozone_extinction_per_m",
            std::mem::offset_of!(AtmosphereUniform, ozone_extinction_per_m),
        ),
        (
            "rayleigh_scattering_per_m",
            std::mem::offset_of!(AtmosphereUniform, rayleigh_scattering_per_m),
        ),
        (
            "mie_scattering_per_m",
            std::mem::offset_of!(AtmosphereUniform, mie_scattering_per_m),
        ),
        (
            "solar_irradiance",
            std::mem::offset_of!(AtmosphereUniform, solar_irradiance),
        ),
        (
            "mie_phase_kind",
            std::mem::offset_of!(AtmosphereUniform, mie_phase_kind),
        ),
        ("mie_g", std::mem::offset_of!(AtmosphereUniform, mie_g)),
        (
            "ground_albedo",
            std::mem::offset_of!(AtmosphereUniform, ground_albedo),
        ),
    ];
    for (name, offset) in rust {
        assert!(
            members.contains(&(name.to_string(), offset)),
            "{name} at {offset}: WGSL has {members:?}"
        );
    }
    assert_eq!(
        layout("DensityProfile").0,
        size_of::<DensityProfileUniform>()
    );
    let (span, members) = layout("DensityLayer");
    assert_eq!(span, size_of::<DensityLayerUniform>());
    assert_eq!(
        members[4],
        (
            "constant_term".to_string(),
            std::mem::offset_of!(DensityLayerUniform, constant_term)
        )
    );
}

/// Size and member offsets (by name) of WGSL struct `name` in composed shader `shader`.
fn wgsl_layout(shader: &str, name: &str) -> (usize, Vec<(String, usize)>) {
    let source = shaders::composed(shader).unwrap();
    let module = validate(shader, &source).unwrap();
    module
        .types
        .iter()
        .find_map(|(_, ty)| match (&ty.name, &ty.inner) {
            (Some(n), naga::TypeInner::Struct { members, span }) if n == name => Some((
                *span as usize,
                members
                    .iter()
                    .map(|m| (m.name.clone().unwrap(), m.offset as usize))
                    .collect(),
            )),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no struct {name} in {shader}"))
}

/// Asserts that a Rust uniform has the WGSL struct's size and these member offsets.
macro_rules! assert_layout {
    ($shader:literal, $wgsl:literal, $rust:ty, [$($field:ident),+ $(,)?]) => {{
        let (span, members) = wgsl_layout($shader, $wgsl);
        assert_eq!(span, size_of::<$rust>(), "size of {}", $wgsl);
        let rust = [$((stringify!($field).to_string(), std::mem::offset_of!($rust, $field))),+];
        assert_eq!(members.len(), rust.len(), "{}: WGSL has {members:?}", $wgsl);
        for field in rust {
            assert!(members.contains(&field), "{field:?}: WGSL has {members:?}");
        }
    }};
}

#[test]
fn frame_nishita_and_tone_map_uniforms_match_their_wgsl_layouts() {
    use render_wgpu::frame::uniform::FrameUniform;
    use render_wgpu::post::tone_map::ToneMapUniform;
    use render_wgpu::sky::nishita::NishitaUniform;
    assert_layout!(
        "sky/nishita/pixel.wgsl",
        "FrameParams",
        FrameUniform,
        [
            camera_m,
            camera_height,
            right,
            up,
            forward,
            sun_direction,
            sun_centre_radiance,
            sun_limb_exponent,
            size_px,
            sea
        ]
    );
    assert_layout!(
        "sky/nishita/pixel.wgsl",
        "NishitaParams",
        NishitaUniform,
        [view_samples, pad0, pad1, pad2]
    );
    assert_layout!(
        "post/tone_map.wgsl",
        "ToneMapParams",
        ToneMapUniform,
        [red, green, blue]
    );
}

#[test]
fn terrain_uniform_matches_its_wgsl_layout() {
    use render_wgpu::terrain::terrain_pipeline::{ChunkUniform, TerrainUniform};
    assert_layout!(
        "terrain/terrain.wgsl",
        "TerrainParams",
        TerrainUniform,
        [right, up, forward, near, sea_albedo, snow_line, rock, snow]
    );
    assert_layout!(
        "terrain/terrain.wgsl",
        "Chunk",
        ChunkUniform,
        [offset, origin, morph]
    );
}

#[test]
fn hillaire_uniform_matches_its_wgsl_layout() {
    use render_wgpu::sky::hillaire::HillaireUniform;
    assert_layout!(
        "sky/hillaire/pixel.wgsl",
        "HillaireParams",
        HillaireUniform,
        [
            view_r,
            view_q,
            view_mu_s,
            aerial_range_m,
            ms_sqrt_directions,
            ms_samples,
            sky_view_samples,
            ap_samples_per_slice,
            march_samples,
            ground_zenith_panels,
            ground_azimuths,
            multiple_on,
            view_theta_h,
            ms_order,
            mie_g1,
            mie_g2,
            ms_delta,
            pad_0,
            pad_1,
            pad_2,
            view_up,
            view_sun_side,
            view_across
        ]
    );
}

#[test]
fn shadow_map_uniform_matches_its_wgsl_layout() {
    use render_wgpu::shafts::terrain::uniform::ShadowMapUniform;
    assert_layout!(
        "sky/hillaire/pixel.wgsl",
        "ShadowMapParams",
        ShadowMapUniform,
        [east_cell, north_slope, up_top, size]
    );
}

#[test]
fn cloud_sun_map_uniform_matches_its_wgsl_layout() {
    use render_wgpu::clouds::sun_map_texture::SunMapUniform;
    assert_layout!(
        "clouds/sun_map_fill.wgsl",
        "SunMapParams",
        SunMapUniform,
        [east_cell, north, up, sun, radii, counts]
    );
}

#[test]
fn riley_and_oneil_uniforms_match_their_wgsl_layouts() {
    use render_wgpu::sky::oneil::{OneilTableUniform, OneilUniform};
    use render_wgpu::sky::riley::RileyUniform;
    assert_layout!(
        "sky/riley/pixel.wgsl",
        "RileyParams",
        RileyUniform,
        [
            scale_heights_m,
            rayleigh_extinction_per_m,
            mie_extinction_per_m,
            ozone_extinction_per_m,
            rayleigh_albedo,
            mie_albedo,
            options
        ]
    );
    assert_layout!(
        "sky/oneil/pixel.wgsl",
        "OneilParams",
        OneilUniform,
        [samples, pad0, pad1, pad2]
    );
    assert_layout!(
        "sky/oneil/optical_depth_table.wgsl",
        "OneilTableParams",
        OneilTableUniform,
        [ray_samples, pad0, pad1, pad2]
    );
}

#[test]
fn dobashi_uniforms_match_their_wgsl_layouts() {
    use render_wgpu::sky::dobashi::{DobashiTableUniform, DobashiUniform};
    assert_layout!(
        "sky/dobashi/tables.wgsl",
        "DobashiTableParams",
        DobashiTableUniform,
        [interval_m, plane_panels, sphere_panels, pad0]
    );
    // Declared once for the per-pixel pass and the ambient table's build.
    assert_layout!(
        "sky/dobashi/bindings.wgsl",
        "DobashiParams",
        DobashiUniform,
        [
            interval_m,
            use_spheres,
            ambient_on,
            max_orders,
            ambient_directions,
            spheres,
            pad0,
            pad1
        ]
    );
}

#[test]
fn bruneton_uniforms_match_their_wgsl_layouts() {
    use render_wgpu::sky::bruneton::order_state::OrderState;
    use render_wgpu::sky::bruneton::uniform::BrunetonUniform;
    assert_layout!(
        "sky/bruneton/bindings.wgsl",
        "BrunetonParams",
        BrunetonUniform,
        [
            r_size,
            mu_size,
            mu_s_size,
            nu_size,
            irradiance_mu_s_size,
            irradiance_r_size,
            sphere_panels,
            sphere_azimuths,
            view_samples,
            mie_on,
            previous_is_single,
            max_orders,
            density_offset,
            single_rayleigh_offset,
            single_mie_offset,
            multiple_offset,
            delta_s_offset,
            delta_j_offset,
            delta_e_offset,
            irradiance_offset,
            moments_offset,
            partials_offset,
            scattering_texels,
            irradiance_texels,
            mie_forward_fraction,
            mie_chi1,
            mie_chi2,
            order_threshold,
            density_step_m,
            min_mu_s,
            nu_by_angle,
            mie_directions,
            store_chunk_texels,
            mu_s_knee,
            geometric_mu_s,
            density_nodes,
            sun_disk,
            sun_angular_radius,
            nu_edge,
            nu_by_azimuth,
            mu_zenith,
            mie_horizon
        ]
    );
    assert_layout!(
        "sky/bruneton/orders.wgsl",
        "OrderState",
        OrderState,
        [
            totals,
            previous_added,
            order,
            running,
            last_order,
            has_previous,
            args,
            full,
            shares
        ]
    );
}

#[test]
fn beams_structs_match_their_wgsl_layouts() {
    assert_layout!(
        "shafts/beams/march.wgsl",
        "BeamsParams",
        BeamsUniform,
        [
            camera_right,
            camera_up,
            camera_forward,
            scattering_per_m,
            extinction_per_m,
            channel_weights,
            size_steps_lights,
            counts,
            phase
        ]
    );
    assert_layout!(
        "shafts/beams/planes.wgsl",
        "PlanesParams",
        PlanesUniform,
        [planes_lattice_lights, spacing_m]
    );
    assert_layout!(
        "shafts/beams/qtable.wgsl",
        "QtableParams",
        QtableUniform,
        [interval_m, ranges, nodes, upsample]
    );
    assert_layout!(
        "shafts/beams/march.wgsl",
        "BeamLight",
        LightUniform,
        [
            position, frame_x, frame_y, frame_z, beam, emission, kind, map_offset, map_width,
            map_height, first_view, view_count, pad0, pad1
        ]
    );
    assert_layout!(
        "shafts/beams/march.wgsl",
        "ShadowView",
        ShadowViewUniform,
        [
            origin, frame_x, frame_y, frame_z, half, kind, size, offset, pad
        ]
    );
    assert_layout!(
        "shafts/beams/march.wgsl",
        "Primitive",
        PrimitiveUniform,
        [a, b, c, kind, pad0, pad1, pad2]
    );
    assert_layout!(
        "shafts/beams/march.wgsl",
        "BvhNode",
        NodeUniform,
        [min, first, max, count]
    );
}

#[test]
fn cloud_uniforms_match_their_wgsl_layouts() {
    use render_wgpu::clouds::layer_uniform::LayerUniform;
    use render_wgpu::clouds::spheres::sphere_uniform::SphereUniform;
    assert_layout!(
        "clouds/layer_image.wgsl",
        "LayerParams",
        LayerUniform,
        [
            camera_m,
            forward,
            right,
            up,
            sun_direction,
            sun_irradiance,
            sky_irradiance,
            radii_m,
            medium,
            detail,
            counts,
            sizes,
            noise
        ]
    );
    assert_layout!(
        "clouds/spheres/image.wgsl",
        "SphereParams",
        SphereUniform,
        [
            camera_m,
            forward,
            right,
            up,
            sun_direction,
            sun_irradiance,
            sky_irradiance,
            radii_m,
            medium,
            counts,
            grids
        ]
    );
}
