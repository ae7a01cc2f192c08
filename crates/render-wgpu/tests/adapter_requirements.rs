//! The suitability check of adapters, without a GPU: an adapter offering full WebGPU
//! passes; one short of a capability, a limit or a format's usage is refused with a
//! reason naming it; every format the passes create is checked.

use render_wgpu::frame::surface_buffer::{ALBEDO_FORMAT, GEOMETRY_FORMAT};
use render_wgpu::gpu::formats::{HDR_FORMAT, LDR_FORMAT};
use render_wgpu::gpu::requirements::{FORMATS, shortfalls};
use render_wgpu::sky::transmittance::TABLE_FORMAT;
use wgpu::{
    DownlevelCapabilities, DownlevelFlags, Limits, TextureFormat, TextureFormatFeatureFlags,
    TextureFormatFeatures, TextureUsages,
};

/// Every usage and flag, for every format.
fn everything(_: TextureFormat) -> TextureFormatFeatures {
    TextureFormatFeatures {
        allowed_usages: TextureUsages::all(),
        flags: TextureFormatFeatureFlags::all(),
    }
}

#[test]
fn full_webgpu_passes() {
    let reasons = shortfalls(
        &DownlevelCapabilities::default(),
        &Limits::default(),
        everything,
    );
    assert!(reasons.is_empty(), "{reasons:?}");
}

#[test]
fn a_float_target_that_cannot_be_rendered_to_is_named() {
    // wgpu's GL backend on llvmpipe: Rgba32Float can be stored to but not rendered to.
    let gl = |format| {
        let mut features = everything(format);
        if format == TextureFormat::Rgba32Float {
            features
                .allowed_usages
                .remove(TextureUsages::RENDER_ATTACHMENT);
        }
        features
    };
    let reasons = shortfalls(&DownlevelCapabilities::default(), &Limits::default(), gl);
    assert_eq!(
        reasons,
        ["Rgba32Float (tables and surface geometry) lacks RENDER_ATTACHMENT"]
    );
}

#[test]
fn write_only_storage_is_required_of_the_hdr_format() {
    let no_storage = |format| {
        let mut features = everything(format);
        if format == HDR_FORMAT {
            features
                .flags
                .remove(TextureFormatFeatureFlags::STORAGE_WRITE_ONLY);
        }
        features
    };
    let reasons = shortfalls(
        &DownlevelCapabilities::default(),
        &Limits::default(),
        no_storage,
    );
    assert_eq!(
        reasons,
        ["Rgba16Float (HDR image) lacks STORAGE_WRITE_ONLY"]
    );
}

#[test]
fn a_webgl2_class_device_is_refused_for_compute_and_its_limits() {
    let downlevel = DownlevelCapabilities {
        flags: DownlevelFlags::all().difference(DownlevelFlags::COMPUTE_SHADERS),
        ..DownlevelCapabilities::default()
    };
    let reasons = shortfalls(&downlevel, &Limits::downlevel_webgl2_defaults(), everything);
    assert_eq!(
        reasons[0],
        "no compute shaders (every table and pixel pass)"
    );
    assert!(
        reasons.contains(&"max_storage_textures_per_shader_stage is 0 (needs 4)".to_string()),
        "{reasons:?}"
    );
    assert!(
        reasons.contains(&"max_compute_invocations_per_workgroup is 0 (needs 256)".to_string()),
        "{reasons:?}"
    );
}

#[test]
fn every_format_the_passes_create_is_checked() {
    let checked: Vec<TextureFormat> = FORMATS.iter().map(|f| f.format).collect();
    for format in [
        TABLE_FORMAT,
        GEOMETRY_FORMAT,
        ALBEDO_FORMAT,
        HDR_FORMAT,
        LDR_FORMAT,
        TextureFormat::Depth32Float,
    ] {
        assert!(checked.contains(&format), "{format:?} is not checked");
    }
}
