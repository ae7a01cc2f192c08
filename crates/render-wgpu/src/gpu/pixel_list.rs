//! A list of a frame's pixels that an upsample could not interpolate, marched by a pass
//! of its own through an indirect dispatch over the list alone
//! (`shaders/common/pixel_list.wgsl`). A software rasteriser such as lavapipe pays for a
//! branch that any invocation of a group takes, and for a march compiled into a pass
//! even where no invocation runs it (docs/clouds.md, "At a reduced resolution"), so the
//! upsample stays a plain read and the march runs where it is needed.

use crate::gpu::context::GpuContext;
use crate::gpu::pipeline::storage_buffer_entry;

/// The list's count before its pixels (one u32 each).
const HEADER_BYTES: usize = 4;
/// The indirect dispatch's three workgroup counts.
const DISPATCH_BYTES: usize = 12;

/// A list with a place for each pixel of a frame of `size`, and the workgroup counts of
/// the dispatch that marches it; empty, (0, 1, 1), once [`PixelList::reset`].
#[derive(Debug)]
pub struct PixelList {
    pub list: wgpu::Buffer,
    pub dispatch: wgpu::Buffer,
    pub size: (u32, u32),
}

impl PixelList {
    /// The list's layout entry at `binding`.
    pub fn list_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
        storage_buffer_entry(binding, HEADER_BYTES + 4)
    }

    /// The dispatch's layout entry at `binding` (for the upsample that fills the list; the
    /// marching pass reads the counts as its dispatch, not as a binding).
    pub fn dispatch_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
        storage_buffer_entry(binding, DISPATCH_BYTES)
    }

    /// An empty list of `label` for a frame of `size` px, or why the device cannot hold
    /// it (its storage binding limit).
    pub fn new(gpu: &GpuContext, label: &str, size: (u32, u32)) -> Result<PixelList, String> {
        let bytes = HEADER_BYTES + 4 * size.0 as usize * size.1 as usize;
        let limit = gpu.device.limits().max_storage_buffer_binding_size as usize;
        if bytes > limit {
            return Err(format!(
                "a {} x {} frame needs a list of {bytes} bytes of the pixels to march, over \
                 the device's storage binding limit of {limit}",
                size.0, size.1
            ));
        }
        let buffer = |what: &str, size: usize, usage| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(&format!("{label}: {what}")),
                size: size as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | usage,
                mapped_at_creation: false,
            })
        };
        let list = buffer("pixels to march", bytes, wgpu::BufferUsages::empty());
        let dispatch = buffer(
            "their dispatch",
            DISPATCH_BYTES,
            wgpu::BufferUsages::INDIRECT,
        );
        let made = PixelList {
            list,
            dispatch,
            size,
        };
        made.reset(gpu);
        Ok(made)
    }

    /// Empties the list before the next submission's commands: each frame that marches
    /// from it resets it first (a list is kept for the frames of its size that follow).
    pub fn reset(&self, gpu: &GpuContext) {
        gpu.queue
            .write_buffer(&self.list, 0, bytemuck::cast_slice(&[0u32]));
        gpu.queue
            .write_buffer(&self.dispatch, 0, bytemuck::cast_slice(&[0u32, 1, 1]));
    }
}
