//! What atmos needs of an adapter, and why a given adapter falls short.
//!
//! What the passes use is checked before a device is made, so that an adapter that
//! cannot run them (wgpu's GL backend on llvmpipe cannot render to `Rgba32Float`) is
//! passed over with its reasons rather than failing in the middle of a frame. No
//! optional feature is required: filtering `Rgba32Float` and timestamp queries are used
//! where present (`device_descriptor`).

use wgpu::{DownlevelFlags as Down, TextureFormat, TextureFormatFeatureFlags, TextureUsages};

use crate::gpu::formats::{HDR_FORMAT, LDR_FORMAT};

/// The downlevel capabilities (parts of WebGPU that some adapters lack) the passes use,
/// each with what uses it.
pub const DOWNLEVEL: &[(Down, &str)] = &[
    (
        Down::COMPUTE_SHADERS,
        "compute shaders (every table and pixel pass)",
    ),
    (
        Down::INDIRECT_EXECUTION,
        "indirect dispatch (bruneton's orders)",
    ),
    (
        Down::VERTEX_STORAGE,
        "storage buffers in vertex shaders (terrain)",
    ),
    (
        Down::NON_POWER_OF_TWO_MIPMAPPED_TEXTURES,
        "mipmaps of non-power-of-two textures (terrain colour)",
    ),
];

/// A texture format and what the passes do with it.
#[derive(Debug, Clone, Copy)]
pub struct FormatUse {
    pub format: TextureFormat,
    /// Every usage its textures are created with.
    pub usages: TextureUsages,
    /// The feature flags they need (write-only storage, filtering samplers).
    pub flags: TextureFormatFeatureFlags,
    /// Which textures these are, for messages.
    pub what: &'static str,
}

/// Every texture format atmos creates, with the union of its usages.
pub const FORMATS: &[FormatUse] = &[
    FormatUse {
        format: TextureFormat::Rgba32Float,
        usages: TextureUsages::STORAGE_BINDING
            .union(TextureUsages::TEXTURE_BINDING)
            .union(TextureUsages::RENDER_ATTACHMENT)
            .union(TextureUsages::COPY_SRC)
            .union(TextureUsages::COPY_DST),
        flags: TextureFormatFeatureFlags::STORAGE_WRITE_ONLY,
        what: "tables and surface geometry",
    },
    FormatUse {
        format: HDR_FORMAT,
        usages: TextureUsages::STORAGE_BINDING
            .union(TextureUsages::TEXTURE_BINDING)
            .union(TextureUsages::COPY_SRC),
        flags: TextureFormatFeatureFlags::STORAGE_WRITE_ONLY,
        what: "HDR image",
    },
    FormatUse {
        format: LDR_FORMAT,
        usages: TextureUsages::RENDER_ATTACHMENT
            .union(TextureUsages::TEXTURE_BINDING)
            .union(TextureUsages::COPY_SRC)
            .union(TextureUsages::COPY_DST),
        flags: TextureFormatFeatureFlags::FILTERABLE,
        what: "display image and terrain colour",
    },
    FormatUse {
        format: TextureFormat::Rgba8Unorm,
        usages: TextureUsages::RENDER_ATTACHMENT
            .union(TextureUsages::TEXTURE_BINDING)
            .union(TextureUsages::COPY_SRC)
            .union(TextureUsages::COPY_DST),
        flags: TextureFormatFeatureFlags::empty(),
        what: "surface albedo",
    },
    FormatUse {
        format: TextureFormat::Depth32Float,
        usages: TextureUsages::RENDER_ATTACHMENT,
        flags: TextureFormatFeatureFlags::empty(),
        what: "terrain depth",
    },
];

/// The limits the device is requested with: WebGPU's defaults, within which the passes'
/// workgroups, bindings and frame sizes stay.
pub fn required_limits() -> wgpu::Limits {
    wgpu::Limits::default()
}

/// The limits the device is created with: [`required_limits`], with the buffer sizes
/// raised to all that the adapter offers, so that larger tables (bruneton's S at more
/// texels than the paper's) are built where the adapter holds them; each table checks
/// its size against the device's limits and names what does not fit.
pub fn device_limits(adapter: &wgpu::Limits) -> wgpu::Limits {
    let base = required_limits();
    wgpu::Limits {
        max_storage_buffer_binding_size: base
            .max_storage_buffer_binding_size
            .max(adapter.max_storage_buffer_binding_size),
        max_buffer_size: base.max_buffer_size.max(adapter.max_buffer_size),
        ..base
    }
}

/// Why `adapter` cannot run atmos (see [`shortfalls`]); empty when it can.
pub fn adapter_shortfalls(adapter: &wgpu::Adapter) -> Vec<String> {
    shortfalls(
        &adapter.get_downlevel_capabilities(),
        &adapter.limits(),
        |format| adapter.get_texture_format_features(format),
    )
}

/// Why an adapter with these downlevel capabilities, limits and texture format features
/// cannot run atmos, one reason per missing capability, limit or format feature; empty
/// when it can.
pub fn shortfalls(
    downlevel: &wgpu::DownlevelCapabilities,
    limits: &wgpu::Limits,
    format_features: impl Fn(TextureFormat) -> wgpu::TextureFormatFeatures,
) -> Vec<String> {
    let mut reasons: Vec<String> = DOWNLEVEL
        .iter()
        .filter(|(flag, _)| !downlevel.flags.contains(*flag))
        .map(|(_, what)| format!("no {what}"))
        .collect();
    if downlevel.shader_model < wgpu::ShaderModel::Sm5 {
        let model = downlevel.shader_model;
        reasons.push(format!("shader model {model:?} (needs Sm5)"));
    }
    required_limits().check_limits_with_fail_fn(limits, false, |name, needed, has| {
        reasons.push(format!("{name} is {has} (needs {needed})"));
    });
    for need in FORMATS {
        let has = format_features(need.format);
        let usages = need.usages.difference(has.allowed_usages);
        let flags = need.flags.difference(has.flags);
        let missing: Vec<&str> = (usages.iter_names().map(|(name, _)| name))
            .chain(flags.iter_names().map(|(name, _)| name))
            .collect();
        if !missing.is_empty() {
            let (format, what) = (need.format, need.what);
            reasons.push(format!("{format:?} ({what}) lacks {}", missing.join(", ")));
        }
    }
    reasons
}
