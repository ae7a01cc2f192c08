//! The GPU context that lives for the whole program: instance, adapter, device, queue.
//! The adapter is the best that can run atmos ([`adapter_choice`](super::adapter_choice));
//! where its device cannot be made, the next is tried.

use crate::gpu::adapter_choice::{no_adapter, refusal, summary, usable_adapters};
use crate::gpu::error::GpuError;
use crate::gpu::requirements::device_limits;

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
        let (usable, mut refused) =
            usable_adapters(instance.enumerate_adapters(backends).await, None)?;
        for adapter in usable {
            let mut descriptor = device_descriptor(&adapter);
            descriptor.required_features.remove(without);
            match adapter.request_device(&descriptor).await {
                Ok((device, queue)) => {
                    return Ok(GpuContext {
                        instance,
                        adapter,
                        device,
                        queue,
                    });
                }
                Err(e) => refused.push(refusal(&adapter, &format!("no device: {e}"))),
            }
        }
        Err(no_adapter(backends, &refused))
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
/// or manual lerp), and so are blending them (the beams' virtual planes need it and say
/// so) and the timestamps of pass timings.
pub fn device_descriptor(adapter: &wgpu::Adapter) -> wgpu::DeviceDescriptor<'static> {
    wgpu::DeviceDescriptor {
        label: Some("atmos"),
        required_features: adapter.features()
            & (wgpu::Features::FLOAT32_FILTERABLE
                | wgpu::Features::FLOAT32_BLENDABLE
                | wgpu::Features::TIMESTAMP_QUERY),
        required_limits: device_limits(&adapter.limits()),
        ..Default::default()
    }
}
