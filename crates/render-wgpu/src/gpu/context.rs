//! The GPU context that lives for the whole program: instance, adapter, device, queue.
//!
//! The adapter is chosen from the environment as wgpu's own tools do: `WGPU_BACKEND`
//! limits the backends, `WGPU_ADAPTER_NAME` picks an adapter by name, `WGPU_POWER_PREF`
//! (`low`) prefers an integrated GPU. Otherwise a real GPU wins over a software adapter
//! (lavapipe, llvmpipe), which is used when it is all there is.

use crate::gpu::error::GpuError;

/// Instance, adapter, device and queue.
#[derive(Debug)]
pub struct GpuContext {
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
}

impl GpuContext {
    /// A context without a window, for table building, tests and off-screen rendering.
    pub fn headless() -> Result<GpuContext, GpuError> {
        pollster::block_on(Self::headless_async(wgpu::Features::empty()))
    }

    /// As [`GpuContext::headless`], with a device that lacks the optional `features`
    /// even where the adapter has them: to test the passes' ways round a missing one
    /// (e.g. `FLOAT32_FILTERABLE`) on any adapter.
    pub fn headless_without(features: wgpu::Features) -> Result<GpuContext, GpuError> {
        pollster::block_on(Self::headless_async(features))
    }

    async fn headless_async(without: wgpu::Features) -> Result<GpuContext, GpuError> {
        let descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        let backends = descriptor.backends;
        if backends.is_empty() {
            return Err(GpuError::UnknownBackend {
                value: std::env::var("WGPU_BACKEND").unwrap_or_default(),
            });
        }
        let instance = wgpu::Instance::new(descriptor);
        let adapter = choose_adapter(instance.enumerate_adapters(backends).await, backends)?;
        let mut descriptor = device_descriptor(&adapter);
        descriptor.required_features.remove(without);
        let (device, queue) = adapter
            .request_device(&descriptor)
            .await
            .map_err(|source| GpuError::RequestDevice {
                adapter: summary(&adapter.get_info()),
                source,
            })?;
        Ok(GpuContext {
            instance,
            adapter,
            device,
            queue,
        })
    }

    /// A context on a device made elsewhere, e.g. by a window's renderer (eframe's
    /// `RenderState`), so that frames render with the window's device. The device should
    /// have been requested with [`device_descriptor`]; without its optional features the
    /// passes still work, only the pass timings are missing.
    pub fn from_existing(
        instance: wgpu::Instance,
        adapter: wgpu::Adapter,
        device: wgpu::Device,
        queue: wgpu::Queue,
    ) -> GpuContext {
        GpuContext {
            instance,
            adapter,
            device,
            queue,
        }
    }

    /// Queues the write of the plain data `value` at the start of `buffer` (a uniform's
    /// upload, a state buffer's reset).
    pub fn write_uniform<T: bytemuck::Pod>(&self, buffer: &wgpu::Buffer, value: &T) {
        self.queue
            .write_buffer(buffer, 0, bytemuck::bytes_of(value));
    }

    /// Name, backend and device type of the adapter, for logs.
    pub fn adapter_summary(&self) -> String {
        summary(&self.adapter.get_info())
    }
}

/// The device the passes want on `adapter`. Only what they need: storage textures of
/// Rgba32Float are core WebGPU; filtering them is optional (samplers fall back to nearest
/// or manual lerp), and so are the timestamps of pass timings.
pub fn device_descriptor(adapter: &wgpu::Adapter) -> wgpu::DeviceDescriptor<'static> {
    wgpu::DeviceDescriptor {
        label: Some("atmos"),
        required_features: adapter.features()
            & (wgpu::Features::FLOAT32_FILTERABLE | wgpu::Features::TIMESTAMP_QUERY),
        required_limits: wgpu::Limits::default(),
        ..Default::default()
    }
}

fn summary(info: &wgpu::AdapterInfo) -> String {
    format!("{} ({}, {:?})", info.name, info.backend, info.device_type)
}

/// The adapter named by `WGPU_ADAPTER_NAME` if set, else the best by device type; only
/// adapters with compute shaders count.
fn choose_adapter(
    adapters: Vec<wgpu::Adapter>,
    backends: wgpu::Backends,
) -> Result<wgpu::Adapter, GpuError> {
    let mut usable: Vec<wgpu::Adapter> = adapters
        .into_iter()
        .filter(|a| {
            a.get_downlevel_capabilities()
                .flags
                .contains(wgpu::DownlevelFlags::COMPUTE_SHADERS)
        })
        .collect();
    if let Ok(wanted) = std::env::var("WGPU_ADAPTER_NAME") {
        let available = usable
            .iter()
            .map(|a| summary(&a.get_info()))
            .collect::<Vec<_>>()
            .join(", ");
        let lower = wanted.to_lowercase();
        usable.retain(|a| a.get_info().name.to_lowercase().contains(&lower));
        if usable.is_empty() {
            return Err(GpuError::NoAdapterNamed { wanted, available });
        }
    }
    let low_power = wgpu::PowerPreference::from_env() == Some(wgpu::PowerPreference::LowPower);
    usable
        .into_iter()
        .min_by_key(|a| rank(&a.get_info(), low_power))
        .ok_or_else(|| GpuError::NoAdapter {
            backends: backends
                .iter_names()
                .map(|(name, _)| name.to_lowercase())
                .collect::<Vec<_>>()
                .join(", "),
        })
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
