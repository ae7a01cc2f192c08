//! Which adapter atmos runs on, chosen from the environment as wgpu's own tools do:
//! `WGPU_BACKEND` limits the backends, `WGPU_ADAPTER_NAME` picks adapters by name,
//! `WGPU_POWER_PREF` (`low`) prefers an integrated GPU. Of the adapters that can run
//! every pass ([`requirements`](super::requirements)), a real GPU wins over a software
//! one (lavapipe, llvmpipe) and a native backend over GL; an adapter that cannot is
//! passed over with its reasons, which the error lists when none is left.

use crate::gpu::error::GpuError;
use crate::gpu::requirements::adapter_shortfalls;

/// The adapters atmos can use, best first, and one line per adapter passed over saying
/// why. With `WGPU_ADAPTER_NAME` set only the adapters whose name contains it count
/// (an error when there is none); with a `surface`, only those that can present to it.
pub fn usable_adapters(
    adapters: Vec<wgpu::Adapter>,
    surface: Option<&wgpu::Surface<'_>>,
) -> Result<(Vec<wgpu::Adapter>, Vec<String>), GpuError> {
    let adapters = named_adapters(adapters)?;
    let mut usable = Vec::new();
    let mut refused = Vec::new();
    for adapter in adapters {
        let mut reasons = adapter_shortfalls(&adapter);
        if surface.is_some_and(|s| !adapter.is_surface_supported(s)) {
            reasons.push("cannot present to the window".to_string());
        }
        if reasons.is_empty() {
            usable.push(adapter);
        } else {
            refused.push(refusal(&adapter, &reasons.join("; ")));
        }
    }
    let low_power = wgpu::PowerPreference::from_env() == Some(wgpu::PowerPreference::LowPower);
    usable.sort_by_key(|a| rank(&a.get_info(), low_power));
    Ok((usable, refused))
}

/// The best adapter of [`usable_adapters`], for a device made elsewhere (the viewer's,
/// by eframe); `backends` are those the adapters were enumerated on, for the error.
pub fn choose_adapter(
    adapters: &[wgpu::Adapter],
    backends: wgpu::Backends,
    surface: Option<&wgpu::Surface<'_>>,
) -> Result<wgpu::Adapter, GpuError> {
    let (usable, refused) = usable_adapters(adapters.to_vec(), surface)?;
    usable
        .into_iter()
        .next()
        .ok_or_else(|| no_adapter(backends, &refused))
}

/// The error when no adapter on `backends` is left, listing the `refused` ones.
pub fn no_adapter(backends: wgpu::Backends, refused: &[String]) -> GpuError {
    let refused = if refused.is_empty() {
        "  (no adapter found)".to_string()
    } else {
        refused
            .iter()
            .map(|line| format!("  - {line}"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    // The backends this build has, less the no-op one, which draws nothing.
    let tried =
        (backends & wgpu::Instance::enabled_backend_features()).difference(wgpu::Backends::NOOP);
    GpuError::NoAdapter {
        backends: tried
            .iter_names()
            .map(|(name, _)| name.to_lowercase())
            .collect::<Vec<_>>()
            .join(", "),
        refused,
    }
}

/// `adapter` and why it was passed over, as one line of [`GpuError::NoAdapter`].
pub fn refusal(adapter: &wgpu::Adapter, reason: &str) -> String {
    format!("{}: {reason}", summary(&adapter.get_info()))
}

/// Name, backend and device type of an adapter, for logs and messages.
pub fn summary(info: &wgpu::AdapterInfo) -> String {
    format!("{} ({}, {:?})", info.name, info.backend, info.device_type)
}

/// The adapters whose name contains `WGPU_ADAPTER_NAME` (case-insensitive), or all of
/// them when it is unset.
fn named_adapters(adapters: Vec<wgpu::Adapter>) -> Result<Vec<wgpu::Adapter>, GpuError> {
    let Ok(wanted) = std::env::var("WGPU_ADAPTER_NAME") else {
        return Ok(adapters);
    };
    let lower = wanted.to_lowercase();
    let available = adapters
        .iter()
        .map(|a| summary(&a.get_info()))
        .collect::<Vec<_>>()
        .join(", ");
    let named: Vec<wgpu::Adapter> = adapters
        .into_iter()
        .filter(|a| a.get_info().name.to_lowercase().contains(&lower))
        .collect();
    if named.is_empty() {
        return Err(GpuError::NoAdapterNamed { wanted, available });
    }
    Ok(named)
}

/// Lower is better: real GPUs before virtual and software ones, native backends before GL.
fn rank(info: &wgpu::AdapterInfo, low_power: bool) -> (u8, bool) {
    let device = match info.device_type {
        wgpu::DeviceType::DiscreteGpu if low_power => 1,
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu if low_power => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Other => 3,
        wgpu::DeviceType::Cpu => 4,
    };
    (device, info.backend == wgpu::Backend::Gl)
}
