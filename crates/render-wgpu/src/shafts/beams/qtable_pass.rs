//! The q(u, v) table with adaptive sub-planes of Dobashi et al. 2002 section 4.2 on the
//! GPU: the ray ends as for the virtual planes (`ray_end_pass.rs`), then the planes and
//! sub-planes over the part of the screen each light's bounding volume projects to,
//! summed by additive blending, f_l read from the table as a texture. By default each
//! light's samples are walked per pixel in one pass (`qtable_walk.rs`,
//! `shaders/shafts/beams/qtable_walk.wgsl`); with `gpu_raster_planes=true` one plane per
//! light, plane interval and sample (main plane or sub-plane) is drawn, as the paper
//! does (`shaders/shafts/beams/qtable.wgsl`). The table, its interval and the sub-plane
//! counts are the CPU's (atmosphere-core's `beams/methods/qtable2002/`, the twin),
//! uploaded. With `resolution_divisor` above 1 the planes are rendered at the reduced
//! size and brought to the frame's by `qtable_upsample.rs`.

use atmosphere_core::beams::methods::qtable2002::Qtable2002;
use atmosphere_core::beams::methods::qtable2002::upsample::DEPTH_TOLERANCE;
use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::texture_2d;
use crate::gpu::pipeline::{in_stage, texture_entry, uniform_entry};
use crate::shafts::beams::blended_planes::BlendedPlanes;
use crate::shafts::beams::gpu_scene::GpuScene;
use crate::shafts::beams::image::BeamImage;
use crate::shafts::beams::planes_frame::{PlanesFrame, RayEnds};
use crate::shafts::beams::qtable_upsample::{GpuUpsample, MARK_FORMAT, UpsamplePipelines};
use crate::shafts::beams::qtable_walk::{LightWalk, WalkedPlanes, samples_entry};
use crate::shafts::beams::ray_end_pass::RayEndPass;

/// The table's parameters (WGSL `QtableParams`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct QtableUniform {
    /// x: the plane interval dt, m; y: 1 where each sample is weighted by g at it
    /// (`weighted_samples`); z: the most samples of an interval (1 + `max_subplanes`);
    /// w: 1 where each ray counts its own sub-planes (`subplanes_per_ray`).
    pub interval_m: [f32; 4],
    /// The ranges the nodes span evenly: asinh(u / dt) (x, y) and ln v (z, w).
    pub ranges: [f32; 4],
    /// Nodes along u and along v.
    pub nodes: [u32; 4],
    /// The upsample's tolerances: the taps' spread of radiance (x, a share of the
    /// brightest) and of ray ends (y, a share of the nearest); z: 1 where the frame's
    /// own ray ends are traced first for the pixels walked at full size (the scene has
    /// glTF meshes).
    pub upsample: [f32; 4],
}

/// One drawn plane: an instance's vertex attributes (WGSL `vertex`'s inputs).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct PlaneInstance {
    /// Light, plane interval k, sample j (0 the main plane), samples m_k.
    pub plane: [u32; 4],
    /// The light's first plane's depth along the view, m.
    pub first_depth_m: f32,
    /// The part of the screen drawn, normalised device coordinates [x0, y0, x1, y1]:
    /// the light's bounding volume (`Qtable2002::screen_bounds`).
    pub bounds: [f32; 4],
}

/// How the planes are drawn (the setting `gpu_raster_planes`).
#[derive(Clone, Debug, PartialEq)]
pub enum QtablePlanes {
    /// One instance per light, plane interval and sample, as the paper draws them.
    Raster(Vec<PlaneInstance>),
    /// One instance per light, its samples walked per pixel.
    PerPixel(WalkedPlanes),
}

/// A beams scene with the table and planes of a prepared CPU `qtable2002`.
#[derive(Clone, Debug, PartialEq)]
pub struct GpuQtable {
    pub scene: GpuScene,
    pub uniform: QtableUniform,
    /// q at the three wavelengths (xyz) per node, v rows of u nodes.
    pub table: Vec<[f32; 4]>,
    pub planes: QtablePlanes,
    /// The reduced walk, where `resolution_divisor` is above 1.
    pub upsample: Option<GpuUpsample>,
}

impl GpuQtable {
    /// The scene, table and planes of `method` (its wavelengths three).
    pub fn new(method: &Qtable2002) -> GpuQtable {
        let scene = GpuScene::from_parts(method.scattering(), method.shadow_maps(), 0);
        let table = method.table();
        let [nu, nv] = table.nodes();
        let [x, y] = table.coordinate_ranges();
        let values = table.values();
        let layer = nu * nv;
        let wavelengths = values.len() / layer;
        let texels = (0..layer)
            .map(|n| {
                std::array::from_fn(|w| {
                    if w < wavelengths {
                        values[w * layer + n] as f32
                    } else {
                        0.0
                    }
                })
            })
            .collect();
        let planes = if method.gpu_raster_planes() {
            QtablePlanes::Raster(plane_instances(method))
        } else {
            QtablePlanes::PerPixel(WalkedPlanes::new(method))
        };
        let [width, height, ..] = scene.uniform.size_steps_lights;
        let upsample = method
            .upsample()
            .map(|up| GpuUpsample::new(&up, (width, height), WalkedPlanes::new(method)));
        let tolerance = method.upsample().map_or(0.0, |up| up.tolerance as f32);
        let per_ray = method.subplanes_per_ray();
        let meshes = !scene.triangles.is_empty();
        GpuQtable {
            scene,
            uniform: QtableUniform {
                interval_m: [
                    method.interval_m() as f32,
                    f32::from(u8::from(method.weighted_samples())),
                    per_ray.map_or(1, |rule| 1 + rule.max_subplanes) as f32,
                    f32::from(u8::from(per_ray.is_some())),
                ],
                ranges: [x.0, x.1, y.0, y.1].map(|v| v as f32),
                nodes: [nu as u32, nv as u32, 0, 0],
                upsample: [
                    tolerance,
                    DEPTH_TOLERANCE as f32,
                    f32::from(u8::from(meshes)),
                    0.0,
                ],
            },
            table: texels,
            planes,
            upsample,
        }
    }

    /// The planes and sub-planes of every light together.
    pub fn plane_count(&self) -> usize {
        match &self.planes {
            QtablePlanes::Raster(instances) => instances.len(),
            QtablePlanes::PerPixel(walks) => walks.samples.iter().map(|&m| m as usize).sum(),
        }
    }

    /// The sub-planes drawn: instances past each interval's main plane, or the
    /// sub-planes each walk visits.
    pub fn subplane_count(&self) -> usize {
        match &self.planes {
            QtablePlanes::Raster(instances) => instances.iter().filter(|i| i.plane[2] > 0).count(),
            QtablePlanes::PerPixel(walks) => walks.subplane_count(),
        }
    }
}

/// One instance per light, plane interval k and sample j < m_k.
fn plane_instances(method: &Qtable2002) -> Vec<PlaneInstance> {
    let mut instances = Vec::new();
    for (l, planes) in method.planes().iter().enumerate() {
        let bounds = method.screen_bounds()[l].map(|v| v as f32);
        for (k, &m) in planes.samples.iter().enumerate() {
            instances.extend((0..m).map(|j| PlaneInstance {
                plane: [l as u32, k as u32, j as u32, m as u32],
                first_depth_m: planes.first_depth_m as f32,
                bounds,
            }));
        }
    }
    instances
}

/// The table pass's pipelines, made once per device.
#[derive(Debug)]
pub struct QtablePass {
    ray_end: RayEndPass,
    planes: BlendedPlanes,
    walk: BlendedPlanes,
    /// Boxed: only frames with `resolution_divisor` above 1 use it.
    upsample: Box<UpsamplePipelines>,
}

impl QtablePass {
    /// The pipelines; an error where the device cannot blend `Rgba32Float` targets.
    pub fn new(gpu: &GpuContext) -> Result<QtablePass, RenderError> {
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let dimension = wgpu::TextureViewDimension::D2;
        // A plane and a light's walk: four whole numbers, a depth and the bounds.
        let attributes = &wgpu::vertex_attr_array![0 => Uint32x4, 1 => Float32, 2 => Float32x4];
        let instance = |stride: usize| wgpu::VertexBufferLayout {
            array_stride: stride as u64,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes,
        };
        let entries = [
            in_stage(fragment, uniform_entry(0, size_of::<QtableUniform>())),
            in_stage(fragment, texture_entry(1, dimension)),
            in_stage(fragment, texture_entry(2, dimension)),
            samples_entry(),
        ];
        let planes = BlendedPlanes::new(
            gpu,
            "shafts/beams/qtable.wgsl",
            "beams qtable2002",
            &entries[..3],
            &[Some(instance(size_of::<PlaneInstance>()))],
        )?;
        let walk = BlendedPlanes::new(
            gpu,
            "shafts/beams/qtable_walk.wgsl",
            "beams qtable2002 per pixel",
            &entries,
            &[Some(instance(size_of::<LightWalk>()))],
        )?;
        Ok(QtablePass {
            ray_end: RayEndPass::new(gpu)?,
            planes,
            walk,
            upsample: Box::new(UpsamplePipelines::new(
                gpu,
                &entries,
                &[Some(instance(size_of::<LightWalk>()))],
            )?),
        })
    }

    /// Renders `qtable` after checking its table and scene against the device's limits;
    /// the passes' GPU time in milliseconds, together, where the device has timestamps.
    pub fn render(
        &self,
        gpu: &GpuContext,
        qtable: &GpuQtable,
    ) -> Result<(BeamImage, Option<f64>), RenderError> {
        let table = table_texture(gpu, qtable)?;
        let table_view = table.create_view(&Default::default());
        let Some(upsample) = &qtable.upsample else {
            let (image, ms, _) = self.planes_frame(gpu, qtable, &qtable.scene, &table_view)?;
            return Ok((image, ms));
        };
        let mut reduced = qtable.scene.clone();
        let (w, h) = upsample.reduced;
        reduced.uniform.size_steps_lights[..2].copy_from_slice(&[w, h]);
        let (low, low_ms, low_end) = self.planes_frame(gpu, qtable, &reduced, &table_view)?;
        let samples = upsample.walked.texture(gpu)?;
        let samples_view = samples.create_view(&Default::default());
        let low_view = low.radiance.create_view(&Default::default());
        let low_end_view = low_end.create_view(&Default::default());
        // With glTF meshes the pixels walked at full size read their ray's end from the
        // frame's own, traced for every pixel first: tracing it through the meshes' BVH
        // in the invocation that walks the planes came out short of light on lavapipe
        // (presumably its silent loop budget, `models/gpu_loops.rs`). Without meshes
        // they trace it themselves, and the frame takes no ray-end pass of its own.
        let ray_ends = if !qtable.scene.triangles.is_empty() {
            RayEnds::Traced(&self.ray_end)
        } else {
            RayEnds::Given(&low_end)
        };
        let walks = &upsample.walked.lights;
        let instances = (!walks.is_empty()).then(|| {
            gpu.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("beams qtable2002 walks"),
                    contents: bytemuck::cast_slice(walks),
                    usage: wgpu::BufferUsages::VERTEX,
                })
        });
        let mut frame = PlanesFrame::begin(
            gpu,
            ray_ends,
            &self.upsample.interpolate,
            "beams qtable2002 upsample",
            &qtable.scene,
            bytemuck::bytes_of(&qtable.uniform),
            &[
                wgpu::BindingResource::TextureView(&table_view),
                wgpu::BindingResource::TextureView(&samples_view),
                wgpu::BindingResource::TextureView(&low_view),
                wgpu::BindingResource::TextureView(&low_end_view),
            ],
        )?;
        let [width, height, ..] = qtable.scene.uniform.size_steps_lights;
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let marks = texture_2d(
            &gpu.device,
            "beams qtable2002 marks",
            (width, height),
            MARK_FORMAT,
            usage,
        );
        let marks_view = marks.create_view(&Default::default());
        frame.draw_with_depth(Some(&marks_view), |pass| {
            pass.draw(0..3, 0..1);
            if let Some(instances) = &instances {
                pass.set_pipeline(&self.upsample.walk);
                pass.set_vertex_buffer(0, instances.slice(..));
                pass.draw(0..6, 0..walks.len() as u32);
            }
        });
        let (image, ms) = frame.finish(gpu)?;
        Ok((image, low_ms.zip(ms).map(|(a, b)| a + b)))
    }

    /// The planes of `qtable` over `scene` (its own size): the image, the passes' GPU
    /// time and the ray ends.
    fn planes_frame(
        &self,
        gpu: &GpuContext,
        qtable: &GpuQtable,
        scene: &GpuScene,
        table_view: &wgpu::TextureView,
    ) -> Result<(BeamImage, Option<f64>, wgpu::Texture), RenderError> {
        let device = &gpu.device;
        let (pipeline, instances, count, samples) = match &qtable.planes {
            QtablePlanes::Raster(planes) => (
                &self.planes,
                bytemuck::cast_slice(planes),
                planes.len(),
                None,
            ),
            QtablePlanes::PerPixel(walks) => (
                &self.walk,
                bytemuck::cast_slice(&walks.lights),
                walks.lights.len(),
                Some(walks.texture(gpu)?.create_view(&Default::default())),
            ),
        };
        let mut own = vec![wgpu::BindingResource::TextureView(table_view)];
        own.extend(samples.as_ref().map(wgpu::BindingResource::TextureView));
        let mut frame = PlanesFrame::begin(
            gpu,
            RayEnds::Traced(&self.ray_end),
            pipeline,
            "beams qtable2002",
            scene,
            bytemuck::bytes_of(&qtable.uniform),
            &own,
        )?;
        let instances = (count > 0).then(|| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("beams qtable2002 planes"),
                contents: instances,
                usage: wgpu::BufferUsages::VERTEX,
            })
        });
        frame.draw(|pass| {
            if let Some(instances) = &instances {
                pass.set_vertex_buffer(0, instances.slice(..));
                pass.draw(0..6, 0..count as u32);
            }
        });
        let ray_end = frame.ray_end().clone();
        let (image, ms) = frame.finish(gpu)?;
        Ok((image, ms, ray_end))
    }
}

/// The q table as an `Rgba32Float` texture, u across and v down; an error where the
/// device cannot hold it.
fn table_texture(gpu: &GpuContext, qtable: &GpuQtable) -> Result<wgpu::Texture, RenderError> {
    let device = &gpu.device;
    let [nu, nv, ..] = qtable.uniform.nodes;
    let side = device.limits().max_texture_dimension_2d;
    if nu > side || nv > side {
        return Err(RenderError::BeamsTooLarge(format!(
            "the q table's {nu}x{nv} nodes exceed the device's largest texture side, {side} \
             (lower table_u or table_v)"
        )));
    }
    Ok(device.create_texture_with_data(
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some("beams q table"),
            size: wgpu::Extent3d {
                width: nu,
                height: nv,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(&qtable.table),
    ))
}
