//! Half-angle slicing on the GPU as Riley et al. 2004 (section 5, after Kniss et al.
//! 2002) do it: the slices drawn in order as proxy polygons (`slice_polygons.rs`), each
//! first into the eye buffer, composited by blending (front to back or back to front by
//! the half vector's side), then into the light buffer, which reads the previous light
//! buffer at its own texel and writes the next (two `Rgba32Float` images alternating;
//! the previous is copied first so that texels outside the polygon keep their light).
//! Twin of atmosphere-core's `clouds/volume/slicing.rs`, checked by
//! `tests/tests/gpu_cloud_volume_parity.rs`.

use atmosphere_core::clouds::layer::orders::{ORDERS, ScatteringOrders};
use atmosphere_core::clouds::volume::camera::{VolumeCamera, VolumeSun};
use atmosphere_core::clouds::volume::cloud::VoxelCloud;
use atmosphere_core::clouds::volume::half_angle::HalfAngle;
use atmosphere_core::clouds::volume::image::VolumeImage;
use atmosphere_core::clouds::volume::light_buffer::LightBuffer;
use atmosphere_core::clouds::volume::march_image::check_wavelengths;
use atmosphere_core::clouds::volume::settings::VolumeSettings;
use wgpu::util::DeviceExt;

use super::slice_polygons::slice_triangles;
use super::slicing_uniform::SlicingUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{
    float_texture_entry, in_stage, ordered_bind_group, read_only_storage_buffer_entry,
    shader_module, texture_entry, uniform_entry,
};
use crate::gpu::readback::read_texture;

/// The eye and light buffers' format.
const BUFFER_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// Renders `cloud` through `camera` under `sun` by half-angle slicing with `settings`
/// and the tables `orders` (680, 550, 440 nm); reads the eye buffer back.
pub fn slicing_image_gpu(
    gpu: &GpuContext,
    cloud: &VoxelCloud,
    camera: &VolumeCamera,
    sun: &VolumeSun,
    orders: &ScatteringOrders,
    settings: &VolumeSettings,
) -> Result<VolumeImage, RenderError> {
    let refused = |e: atmosphere_core::clouds::error::CloudError| RenderError::Frame(e.to_string());
    settings.check().map_err(refused)?;
    check_wavelengths(sun, orders).map_err(refused)?;
    if orders.wavelengths() != 3 {
        return Err(RenderError::Frame(format!(
            "volume slicing on the GPU takes three wavelengths, not {}",
            orders.wavelengths()
        )));
    }
    if !gpu
        .device
        .features()
        .contains(wgpu::Features::FLOAT32_BLENDABLE)
    {
        return Err(RenderError::Unsupported(
            "volume slicing blends into an Rgba32Float eye buffer; this device lacks FLOAT32_BLENDABLE".into(),
        ));
    }
    let corners = cloud.corners();
    let slices =
        HalfAngle::new(camera, sun.direction, &corners, settings.slices).map_err(refused)?;
    let light = LightBuffer::new(slices.light, &corners, settings.light_buffer_px as usize, 3);
    let uniform = SlicingUniform::new(cloud, camera, sun, &slices, &light, settings);
    let (triangles, ranges) = slice_triangles(&slices, &corners, camera.position_m);
    let device = &gpu.device;
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let init = |label: &str, contents: &[u8], usage| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents,
            usage,
        })
    };
    let uniform_buffer = init(
        "slicing uniform",
        bytemuck::bytes_of(&uniform),
        wgpu::BufferUsages::UNIFORM,
    );
    let mut table: Vec<f32> = Vec::new();
    for w in 0..3 {
        table.extend(orders.table(w).iter().map(|&a| a as f32));
    }
    for w in 0..3 {
        table.extend((1..=ORDERS).map(|n| orders.forward_fraction(w, n) as f32));
    }
    let orders_buffer = init(
        "slicing orders",
        bytemuck::cast_slice(&table),
        wgpu::BufferUsages::STORAGE,
    );
    let vertex_bytes: &[u8] = if triangles.is_empty() {
        &[0; 12]
    } else {
        bytemuck::cast_slice(&triangles)
    };
    let vertices = init("slice polygons", vertex_bytes, wgpu::BufferUsages::VERTEX);
    let [nx, ny, nz] = cloud.grid().dims();
    let density = device.create_texture_with_data(
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some("volume density"),
            size: wgpu::Extent3d {
                width: nx as u32,
                height: ny as u32,
                depth_or_array_layers: nz as u32,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D3,
            format: wgpu::TextureFormat::R32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(cloud.grid().values()),
    );
    let side = settings.light_buffer_px;
    let lit: Vec<[f32; 4]> = vec![[1.0, 1.0, 1.0, 0.0]; (side * side) as usize];
    let light_usage = wgpu::TextureUsages::TEXTURE_BINDING
        | wgpu::TextureUsages::RENDER_ATTACHMENT
        | wgpu::TextureUsages::COPY_SRC
        | wgpu::TextureUsages::COPY_DST;
    let light_textures: Vec<wgpu::Texture> = (0..2)
        .map(|_| {
            device.create_texture_with_data(
                &gpu.queue,
                &image_descriptor("light buffer", (side, side), light_usage),
                wgpu::util::TextureDataOrder::LayerMajor,
                bytemuck::cast_slice(&lit),
            )
        })
        .collect();
    let eye = device.create_texture(&image_descriptor(
        "eye buffer",
        (camera.width_px, camera.height_px),
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
    ));
    let stages = wgpu::ShaderStages::VERTEX_FRAGMENT;
    let entries = [
        in_stage(
            stages,
            uniform_entry(0, std::mem::size_of::<SlicingUniform>()),
        ),
        in_stage(stages, texture_entry(1, wgpu::TextureViewDimension::D3)),
        in_stage(stages, read_only_storage_buffer_entry(2, 4)),
        in_stage(
            stages,
            float_texture_entry(3, wgpu::TextureViewDimension::D2, false),
        ),
    ];
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("volume slicing"),
        entries: &entries,
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("volume slicing"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let (src, dst) = if slices.front_to_back {
        (wgpu::BlendFactor::OneMinusDstAlpha, wgpu::BlendFactor::One)
    } else {
        (wgpu::BlendFactor::One, wgpu::BlendFactor::OneMinusSrcAlpha)
    };
    let composite = wgpu::BlendComponent {
        src_factor: src,
        dst_factor: dst,
        operation: wgpu::BlendOperation::Add,
    };
    let eye_pipeline = slice_pipeline(
        gpu,
        &pipeline_layout,
        "clouds/volume/eye_slice.wgsl",
        Some(wgpu::BlendState {
            color: composite,
            alpha: composite,
        }),
    )?;
    let light_pipeline = slice_pipeline(
        gpu,
        &pipeline_layout,
        "clouds/volume/light_slice.wgsl",
        None,
    )?;
    let views: Vec<wgpu::TextureView> = light_textures
        .iter()
        .map(|t| t.create_view(&Default::default()))
        .collect();
    let density_view = density.create_view(&Default::default());
    let groups: Vec<wgpu::BindGroup> = views
        .iter()
        .map(|view| {
            ordered_bind_group(
                device,
                Some("volume slicing"),
                &layout,
                &[
                    uniform_buffer.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&density_view),
                    orders_buffer.as_entire_binding(),
                    wgpu::BindingResource::TextureView(view),
                ],
            )
        })
        .collect();
    let eye_view = eye.create_view(&Default::default());
    let mut encoder = device.create_command_encoder(&Default::default());
    // The eye buffer starts with no light and no opacity.
    drop(begin(
        &mut encoder,
        &eye_view,
        wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
    ));
    for (k, range) in ranges.iter().enumerate() {
        let (current, next) = (k % 2, (k + 1) % 2);
        if !range.is_empty() {
            let mut pass = begin(&mut encoder, &eye_view, wgpu::LoadOp::Load);
            pass.set_pipeline(&eye_pipeline);
            pass.set_bind_group(0, &groups[current], &[]);
            pass.set_vertex_buffer(0, vertices.slice(..));
            pass.draw(range.clone(), 0..1);
        }
        encoder.copy_texture_to_texture(
            light_textures[current].as_image_copy(),
            light_textures[next].as_image_copy(),
            light_textures[current].size(),
        );
        if !range.is_empty() {
            let mut pass = begin(&mut encoder, &views[next], wgpu::LoadOp::Load);
            pass.set_pipeline(&light_pipeline);
            pass.set_bind_group(0, &groups[current], &[]);
            pass.set_vertex_buffer(0, vertices.slice(..));
            pass.draw(range.clone(), 0..1);
        }
    }
    gpu.queue.submit([encoder.finish()]);
    if let Some(source) = pollster::block_on(scope.pop()) {
        return Err(GpuError::Validation {
            what: "volume slicing",
            source,
        }
        .into());
    }
    let bytes = read_texture(gpu, &eye, 16)?;
    let texels: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
    let mut image = VolumeImage::clear(camera.width_px, camera.height_px, 3);
    for (k, texel) in texels.iter().enumerate() {
        image.radiance[3 * k..3 * k + 3]
            .copy_from_slice(&texel[..3].iter().map(|&v| f64::from(v)).collect::<Vec<_>>());
        image.transmittance[k] = 1.0 - f64::from(texel[3]);
    }
    Ok(image)
}

fn image_descriptor(
    label: &'static str,
    (width, height): (u32, u32),
    usage: wgpu::TextureUsages,
) -> wgpu::TextureDescriptor<'static> {
    wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: BUFFER_FORMAT,
        usage,
        view_formats: &[],
    }
}

/// A pipeline drawing slice polygons (vertices of three f32) with `shader`'s `vertex`
/// and `fragment`, blended by `blend`.
fn slice_pipeline(
    gpu: &GpuContext,
    layout: &wgpu::PipelineLayout,
    shader: &'static str,
    blend: Option<wgpu::BlendState>,
) -> Result<wgpu::RenderPipeline, GpuError> {
    let module = shader_module(&gpu.device, shader)?;
    let attributes = wgpu::vertex_attr_array![0 => Float32x3];
    Ok(gpu
        .device
        .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(shader),
            layout: Some(layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vertex"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: 12,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &attributes,
                })],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fragment"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: BUFFER_FORMAT,
                    blend,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        }))
}

/// A render pass into `target`, loaded by `load`.
fn begin<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    target: &wgpu::TextureView,
    load: wgpu::LoadOp<wgpu::Color>,
) -> wgpu::RenderPass<'e> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("volume slice"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load,
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}
