//! The GPU resources of one set of table sizes: the store and the loop's state, the
//! transmittance tables, the textures the shaders read, and the progressive build's
//! position.

use atmosphere_core::models::bruneton::BrunetonSettings;

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::{buffer, texture_2d, uniform_buffer};
use crate::sky::bruneton::built::Built;
use crate::sky::bruneton::order_state::{MAX_ORDERS, OrderState};
use crate::sky::bruneton::progressive::Share;
use crate::sky::bruneton::store::{DENSITY_SAMPLES, StoreLayout};
use crate::sky::bruneton::store_chunks::{STORE_BINDINGS, StoreChunks};
use crate::sky::bruneton::uniform::BrunetonUniform;
use crate::sky::bruneton::workgroups::{FLAT, delta_s_slices, flat_groups};
use crate::sky::transmittance::{TableOutput, TransmittancePass};

/// The tables of one set of sizes.
#[derive(Debug)]
pub struct Tables {
    pub settings: BrunetonSettings,
    pub max_orders: u32,
    pub layout: StoreLayout,
    /// The store's split over its bindings.
    pub chunks: StoreChunks,
    /// The most bytes one binding of the store was asked to cover.
    pub binding_bytes: u64,
    pub columns: TransmittancePass,
    pub transmittance: TransmittancePass,
    pub store: wgpu::Buffer,
    /// [`OrderState`], also the indirect dispatch sizes of the loop's steps.
    pub state: wgpu::Buffer,
    /// The parameters of order 2 (`previous_is_single` = 1) and of every other step.
    pub params_first: wgpu::Buffer,
    pub params: wgpu::Buffer,
    /// Single Rayleigh, single Mie, multiple.
    pub textures: [wgpu::Texture; 3],
    /// E, copied from the store with S for the pass's reads.
    pub irradiance: wgpu::Texture,
    /// The density table, copied from the store for the shaders' reads.
    pub density: wgpu::Texture,
    /// Delta J as a 3D texture like S's, written with the store's copy, read by Delta S.
    pub delta_j: wgpu::Texture,
    /// The first texel of each Delta S slice (`vec4<u32>`, x), one per uniform offset
    /// alignment.
    pub slice_starts: wgpu::Buffer,
    /// Bytes between two slices' starts in `slice_starts`.
    pub slice_stride: u64,
    /// Delta S slices per order.
    pub slices: u32,
    /// S of the three textures at the camera's r and mu_s per (mu, nu) node, side by
    /// side (`sky/bruneton/view_slice.wgsl`).
    pub view_slice: wgpu::Texture,
    pub built: Built,
    /// The share of the loop over orders that the next progressive frame records;
    /// `None` when no progressive build is under way.
    pub next: Option<Share>,
}

/// Why the GPU cannot build tables of `settings` with `max_orders`, if it cannot; else
/// the store's split over bindings of at most `binding_bytes`.
fn check_limits(
    gpu: &GpuContext,
    settings: &BrunetonSettings,
    max_orders: u32,
    layout: &StoreLayout,
    binding_bytes: u64,
) -> Result<StoreChunks, RenderError> {
    let s = settings.scattering_size;
    let e_texels = settings.irradiance_size.0 * settings.irradiance_size.1;
    if max_orders > MAX_ORDERS {
        return Err(RenderError::Unsupported(format!(
            "{max_orders} scattering orders (the GPU records at most {MAX_ORDERS})"
        )));
    }
    let limits = gpu.device.limits();
    let too_big = |what: String| {
        Err(RenderError::Unsupported(format!(
            "bruneton tables of r={} mu={} mu_s={} nu={} e_mu_s={} e_r={}: {what}",
            s.r, s.mu, s.mu_s, s.nu, settings.irradiance_size.0, settings.irradiance_size.1
        )))
    };
    if layout.bytes() > limits.max_buffer_size {
        return too_big(format!(
            "{} bytes of tables being built, more than the device's largest buffer ({} bytes)",
            layout.bytes(),
            limits.max_buffer_size
        ));
    }
    let binding_bytes = binding_bytes.min(limits.max_storage_buffer_binding_size);
    let alignment = u64::from(limits.min_storage_buffer_offset_alignment);
    let chunks = match StoreChunks::new(layout.texels(), binding_bytes, alignment) {
        Ok(chunks) => chunks,
        Err(chunk_bytes) => {
            return too_big(format!(
                "{} bytes of tables being built, more than {STORE_BINDINGS} storage bindings \
                 of {chunk_bytes} bytes hold (bindings of at most {binding_bytes} bytes, the \
                 device's largest is {} bytes, at multiples of {alignment} bytes)",
                layout.bytes(),
                limits.max_storage_buffer_binding_size
            ));
        }
    };
    let width = (s.nu * s.mu_s) as u64;
    let largest = width.max(s.mu as u64).max(s.r as u64);
    if largest > u64::from(limits.max_texture_dimension_3d) {
        return too_big(format!(
            "a 3D texture of {} x {} x {} texels (mu_s x nu, mu, r), more than the device's \
             {} per side",
            width, s.mu, s.r, limits.max_texture_dimension_3d
        ));
    }
    let [_, rows, _] = flat_groups(s.texels().max(e_texels) as u32);
    let moments = (s.r * s.mu_s) as u64;
    if u64::from(rows).max(moments.div_ceil(u64::from(FLAT)))
        > u64::from(limits.max_compute_workgroups_per_dimension)
    {
        return too_big(format!(
            "more workgroups per dispatch dimension than the device's {}",
            limits.max_compute_workgroups_per_dimension
        ));
    }
    Ok(chunks)
}

impl Tables {
    /// The tables for `settings`, the store bound in ranges of at most `binding_bytes`
    /// (the device's largest storage buffer binding or less), or why the GPU cannot hold
    /// them.
    pub fn new(
        gpu: &GpuContext,
        settings: &BrunetonSettings,
        max_orders: u32,
        binding_bytes: u64,
    ) -> Result<Tables, RenderError> {
        let s = settings.scattering_size;
        let (e_mu_s, e_r) = settings.irradiance_size;
        let layout = StoreLayout::new(s, e_mu_s * e_r);
        let chunks = check_limits(gpu, settings, max_orders, &layout, binding_bytes)?;
        let device = &gpu.device;
        let (slices, slice_texels) = delta_s_slices(s.texels() as u32);
        let slice_stride = u64::from(device.limits().min_uniform_buffer_offset_alignment).max(16);
        let slice_starts = uniform_buffer(
            device,
            "bruneton Delta S slices",
            (slice_stride * u64::from(slices)) as usize,
        );
        for k in 0..slices {
            gpu.queue.write_buffer(
                &slice_starts,
                slice_stride * u64::from(k),
                bytemuck::bytes_of(&[k * slice_texels, 0, 0, 0]),
            );
        }
        let (t_width, t_height) = (
            settings.transmittance_size.0 as u32,
            settings.transmittance_size.1 as u32,
        );
        let scattering_texture = |label| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: (s.nu * s.mu_s) as u32,
                    height: s.mu as u32,
                    depth_or_array_layers: s.r as u32,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D3,
                format: wgpu::TextureFormat::Rgba32Float,
                usage: wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        };
        let storage_2d = |label, size| {
            texture_2d(
                device,
                label,
                size,
                wgpu::TextureFormat::Rgba32Float,
                wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
            )
        };
        use wgpu::BufferUsages as U;
        let copies = U::COPY_SRC | U::COPY_DST;
        Ok(Tables {
            settings: settings.clone(),
            max_orders,
            layout,
            chunks,
            binding_bytes,
            columns: TransmittancePass::with(gpu, TableOutput::Columns, t_width, t_height)?,
            transmittance: TransmittancePass::with(
                gpu,
                TableOutput::Transmittance,
                t_width,
                t_height,
            )?,
            store: buffer(
                device,
                "bruneton store",
                layout.bytes(),
                U::STORAGE | copies,
            ),
            state: buffer(
                device,
                "bruneton order state",
                size_of::<OrderState>() as u64,
                U::STORAGE | U::INDIRECT | copies,
            ),
            params_first: uniform_buffer(device, "bruneton order 2", size_of::<BrunetonUniform>()),
            params: uniform_buffer(device, "bruneton", size_of::<BrunetonUniform>()),
            density: device.create_texture(&wgpu::TextureDescriptor {
                label: Some("bruneton densities"),
                size: Self::density_extent(),
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D1,
                format: wgpu::TextureFormat::Rgba32Float,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            }),
            delta_j: scattering_texture("bruneton Delta J"),
            irradiance: storage_2d("bruneton irradiance", (e_mu_s as u32, e_r as u32)),
            view_slice: storage_2d("bruneton view slice", (3 * s.nu as u32, s.mu as u32)),
            textures: [
                scattering_texture("bruneton single Rayleigh"),
                scattering_texture("bruneton single Mie"),
                scattering_texture("bruneton multiple scattering"),
            ],
            slice_starts,
            slice_stride,
            slices,
            built: Built::default(),
            next: None,
        })
    }

    /// The size of the density table's texture.
    pub fn density_extent() -> wgpu::Extent3d {
        wgpu::Extent3d {
            width: DENSITY_SAMPLES,
            height: 1,
            depth_or_array_layers: 1,
        }
    }

    /// Views of the three scattering textures (single Rayleigh, single Mie, multiple).
    pub fn scattering_views(&self) -> [wgpu::TextureView; 3] {
        self.textures
            .each_ref()
            .map(|t| t.create_view(&Default::default()))
    }

    /// Writes the parameters of every step for `uniform`, those of order 2 with
    /// `previous_is_single` set; with `mie_horizon_order_two` the later orders' Mie
    /// quadrature about the view.
    pub fn write_params(&self, gpu: &GpuContext, uniform: &BrunetonUniform) {
        let first = BrunetonUniform {
            previous_is_single: 1,
            ..*uniform
        };
        let later = BrunetonUniform {
            mie_horizon: if self.settings.mie_horizon_order_two {
                0
            } else {
                uniform.mie_horizon
            },
            ..*uniform
        };
        gpu.write_uniform(&self.params, &later);
        gpu.write_uniform(&self.params_first, &first);
    }

    /// Bytes of GPU memory the tables hold.
    pub fn bytes(&self) -> u64 {
        let s = self.settings.scattering_size;
        let (e_mu_s, e_r) = self.settings.irradiance_size;
        let (w, h) = self.settings.transmittance_size;
        self.layout.bytes()
            + 3 * 16 * s.texels() as u64
            + 2 * 16 * (w * h) as u64
            + 3 * 16 * (s.nu * s.mu) as u64
            + 16 * (e_mu_s * e_r) as u64
    }
}
