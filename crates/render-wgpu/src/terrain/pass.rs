//! The terrain pass: the Earth's relief drawn into the frame's surface buffer
//! (`surface_buffer.rs`), which every model's pixel pass then lights and sees through
//! its atmosphere (`shaders/common/surface.wgsl`). The shader is `shaders/terrain/terrain.wgsl`.
//!
//! Each frame: the quadtree's chunks for the camera ([`select_chunks`], screen-space
//! error), those whose bounding sphere meets the view pyramid ([`Frustum`]), their meshes
//! and normal maps (built on first use and kept while drawn, `chunk_cache.rs`; a changed
//! exaggeration rebuilds them), and one draw per chunk with its `origin - camera` offset computed in
//! f64 and its morph ends (`geomorph.rs`). Offline (`TerrainOptions::wait_for_chunks`)
//! the frame builds every missing mesh in parallel before drawing, so its image depends
//! on nothing but the frame; interactive, the chunks are chosen and the meshes built off
//! the render thread (`chunk_selector.rs`, `chunk_worker.rs`) and covered until they
//! arrive (`chunk_cover.rs`). Depth is reversed with an infinite far plane and a near plane at half the
//! camera's height above the terrain below it, so 1 m and 1e8 m need nothing special.
//! Albedo comes from the colour map (decoded from sRGB, mip-mapped in linear light),
//! taken as the albedo at the three wavelengths: the Blue Marble is a true-colour
//! picture, not a measured albedo, which docs/terrain.md discusses; rock on steep slopes
//! and snow above the season's snow line replace it (atmosphere-core's
//! `geo::land_cover`), and the sea is marked for the model passes' specular water.

use std::collections::HashMap;
use std::sync::Arc;

use atmosphere_core::geo::land_cover::{
    ROCK_ALBEDO, ROCK_SLOPE_COS, SNOW_ALBEDO, SNOW_BAND_M, SnowLine,
};
use glam::DVec3;
use rayon::prelude::*;

use crate::frame::surface_buffer::SurfaceBuffer;
use crate::frame::{Frame, TerrainOptions};
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{buffer, ordered_bind_group, texture_2d, uniform_buffer};
use crate::terrain::chunk_cache::{ChunkCache, buffer_with};
use crate::terrain::chunk_cover::cover;
use crate::terrain::chunk_key::ChunkKey;
use crate::terrain::chunk_mesh::ChunkMesh;
use crate::terrain::chunk_selector::{
    ChunkSelector, Elevation, Selection, SelectionRequest, root_chunks,
};
use crate::terrain::chunk_worker::ChunkWorker;
use crate::terrain::colour_texture::upload_colour;
use crate::terrain::earth_data::{COLOUR_FILE, EarthData};
use crate::terrain::frustum::Frustum;
use crate::terrain::geomorph::{MORPH_START, MorphEnds};
use crate::terrain::height_field::HeightField;
use crate::terrain::lod::{LodSettings, LodView, SelectedChunk, select_chunks};
use crate::terrain::map_error::MapError;
use crate::terrain::normal_map::texel_size_m;
use crate::terrain::normal_texture::NormalTextures;
use crate::terrain::refined_heights::RefinedHeights;
use crate::terrain::sea_colour::open_sea_albedo;
use crate::terrain::stitching::stitched_indices;
use crate::terrain::surface::TerrainSurface;
use crate::terrain::terrain_pipeline::{
    ChunkUniform, DEPTH_FORMAT, TerrainUniform, terrain_pipeline,
};

/// The smallest near plane, m.
const MIN_NEAR_M: f64 = 0.05;

/// How the chosen chunks of the last prepared frame stand.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ChunkProgress {
    /// Chunks the level of detail chose.
    pub chosen: usize,
    /// Chosen chunks without a mesh yet, drawn as a cover (`chunk_cover.rs`).
    pub covered: usize,
    /// Meshes the worker is building.
    pub building: usize,
    /// Whether a choice of chunks is being made off the render thread
    /// (`chunk_selector.rs`); the frame drew the newest finished one.
    pub selecting: bool,
    /// The render thread's time in [`TerrainPass::prepare`], microseconds.
    pub prepare_us: u64,
}

/// One chunk of this frame: its key and which edges border a coarser chunk.
#[derive(Clone, Copy, Debug)]
struct Draw {
    key: ChunkKey,
    coarser: [bool; 4],
}

/// The terrain's maps, pipeline and chunk cache; see the module documentation.
#[derive(Debug)]
pub struct TerrainPass {
    surface: Arc<TerrainSurface<Arc<RefinedHeights>>>,
    lod: LodSettings,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    normal_textures: NormalTextures,
    params: wgpu::Buffer,
    colour: wgpu::TextureView,
    sampler: wgpu::Sampler,
    chunks: ChunkCache,
    worker: ChunkWorker,
    selector: ChunkSelector,
    progress: ChunkProgress,
    /// Index buffers by coarser-edge pattern (the same for every chunk).
    indices: HashMap<[bool; 4], (wgpu::Buffer, u32)>,
    chunk_buffer: wgpu::Buffer,
    /// The depth buffer at the last prepared frame's size (1 x 1 before the first).
    depth: wgpu::Texture,
    draws: Vec<Draw>,
    /// Whether a chunk drawn this frame holds sea.
    water_in_view: bool,
    frame_number: u64,
    /// The water's albedo, linear.
    sea_albedo: [f64; 3],
}

/// A reversed-depth buffer of `width` x `height` pixels.
fn depth_buffer(gpu: &GpuContext, width: u32, height: u32) -> wgpu::Texture {
    texture_2d(
        &gpu.device,
        "terrain depth",
        (width, height),
        DEPTH_FORMAT,
        wgpu::TextureUsages::RENDER_ATTACHMENT,
    )
}

impl TerrainPass {
    /// Loads the Earth's maps from `earth` onto a planet of `radius_m` and compiles the
    /// pass.
    pub fn new(
        gpu: &GpuContext,
        radius_m: f64,
        earth: &EarthData,
    ) -> Result<TerrainPass, RenderError> {
        let heights = earth.refined_heights()?;
        let colours = earth.colours()?;
        let sea_albedo = open_sea_albedo(&colours, &heights.data, heights.mask.as_ref());
        let device = &gpu.device;
        let largest = device.limits().max_texture_dimension_2d;
        if colours.width > largest as usize {
            return Err(MapError::Format {
                path: earth.path_of(COLOUR_FILE),
                found: format!(
                    "{} x {}, wider than this GPU's largest texture ({largest} texels)",
                    colours.width, colours.height
                ),
                expected: "a colour map that fits one texture",
            }
            .into());
        }
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let colour = upload_colour(gpu, &colours);
        let normal_textures = NormalTextures::new(device);
        let (layout, pipeline) = terrain_pipeline(device, &normal_textures.layout)?;
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("colour map"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        let params = uniform_buffer(device, "terrain", size_of::<TerrainUniform>());
        let chunk_buffer = chunk_buffer(gpu, 1);
        if let Some(source) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Validation {
                what: "the terrain pipeline",
                source,
            }
            .into());
        }
        let lod = LodSettings::for_spacing(radius_m, heights.sample_spacing_rad());
        Ok(TerrainPass {
            surface: Arc::new(TerrainSurface::new(Arc::new(heights), radius_m)),
            lod,
            pipeline,
            layout,
            normal_textures,
            params,
            colour,
            sampler,
            chunks: ChunkCache::default(),
            worker: ChunkWorker::default(),
            selector: ChunkSelector::default(),
            progress: ChunkProgress::default(),
            indices: HashMap::new(),
            chunk_buffer,
            depth: depth_buffer(gpu, 1, 1),
            draws: Vec::new(),
            water_in_view: false,
            frame_number: 0,
            sea_albedo,
        })
    }

    /// Chooses, builds and uploads the chunks `frame` sees with `options`; returns how
    /// many it will draw (0: no terrain in view, the pass can be skipped). With
    /// `options.wait_for_chunks` off, the chunks are chosen off the render thread
    /// (`chunk_selector.rs`; the newest finished choice is drawn, the six roots before the
    /// first), and chunk meshes not yet built are asked of the worker and covered
    /// meanwhile (`chunk_cover.rs`): only the six roots are ever built here.
    pub fn prepare(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
        options: &TerrainOptions,
    ) -> Result<usize, RenderError> {
        let start = std::time::Instant::now();
        let drawn = self.prepare_chunks(gpu, frame, options);
        self.progress.prepare_us = start.elapsed().as_micros() as u64;
        drawn
    }

    fn prepare_chunks(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
        options: &TerrainOptions,
    ) -> Result<usize, RenderError> {
        self.frame_number += 1;
        let radius_m = frame.atmosphere.bottom_radius_m;
        if self.surface.exaggeration != options.exaggeration || self.surface.radius_m != radius_m {
            self.surface = Arc::new(TerrainSurface {
                exaggeration: options.exaggeration,
                radius_m,
                ..(*self.surface).clone()
            });
            self.lod =
                LodSettings::for_spacing(radius_m, self.surface.heights.sample_spacing_rad());
            self.chunks.clear();
            self.worker.reset();
            self.selector.reset();
        }
        let camera = frame.camera_position_m;
        let surface = &self.surface;
        let ground_m = surface.elevation_m(camera.normalize());
        let altitude_m = camera.length() - radius_m;
        if altitude_m < ground_m {
            return Err(RenderError::Frame(format!(
                "the camera at {altitude_m:.0} m is not above the terrain: the ground there is \
                 at {ground_m:.0} m (with exaggeration {}); raise it to at least {:.0} m",
                options.exaggeration,
                ground_m + 1.0
            )));
        }
        let view = LodView::new(
            camera,
            f64::from(frame.height),
            frame.vertical_fov_deg.to_radians(),
        );
        let (selected, draws) = if options.wait_for_chunks {
            let selected = select_chunks(&self.lod, &view, |d| surface.elevation_m(d))
                .map_err(|e| RenderError::Frame(e.to_string()))?;
            self.build_in_place(gpu, &selected);
            (selected.clone(), selected)
        } else {
            let surface = Arc::clone(surface);
            let elevation: Elevation = Arc::new(move |d| surface.elevation_m(d));
            self.selector
                .update(SelectionRequest {
                    settings: self.lod,
                    view,
                    elevation,
                })
                .map_err(|e| RenderError::Frame(e.to_string()))?;
            let selection = self
                .selector
                .latest()
                .unwrap_or_else(|| Arc::new(Selection::roots(view)));
            self.build_off_thread(gpu, &selection.build_order);
            let draws = cover(&selection.chunks, |k| self.chunks.contains(k));
            (selection.chunks.clone(), draws)
        };
        self.progress = ChunkProgress {
            chosen: selected.len(),
            covered: selected
                .iter()
                .filter(|c| !self.chunks.contains(c.key))
                .count(),
            building: self.worker.pending(),
            selecting: self.selector.is_selecting(),
            prepare_us: 0,
        };

        let [right, up, forward] = frame.axes();
        let (half_w, half_h) = frame.half_extent();
        let frustum = Frustum::new(camera, [right, up, forward], half_w, half_h);
        let lowest_ray_m = frustum.lowest_radius_m();
        let with_w = |c: [f64; 3], w: f64| [c[0] as f32, c[1] as f32, c[2] as f32, w as f32];
        self.draws.clear();
        self.water_in_view = false;
        let mut uniforms = Vec::new();
        for chunk in &draws {
            self.chunks.touch(chunk.key, self.frame_number);
            let gpu_chunk = self.chunks.get(chunk.key).expect("built or covered above");
            let (centre, radius) = gpu_chunk.bounds;
            let below_every_ray = gpu_chunk.max_radius_m + 1.0 < lowest_ray_m;
            if below_every_ray || !frustum.sees_sphere(centre, radius) {
                continue;
            }
            self.water_in_view |= gpu_chunk.has_water;
            self.draws.push(Draw {
                key: chunk.key,
                coarser: chunk.coarser,
            });
            let ends = MorphEnds::of_level(&self.lod, &view, chunk.key.level);
            let mask = (0..4)
                .filter(|&e| chunk.coarser[e])
                .map(|e| 1 << e)
                .sum::<u32>();
            uniforms.push(ChunkUniform {
                offset: v4(gpu_chunk.origin_m - camera),
                origin: with_w(
                    gpu_chunk.origin_m.to_array(),
                    texel_size_m(radius_m, self.lod.cells, chunk.key.level),
                ),
                morph: [
                    ends.own_m as f32,
                    ends.edge_m as f32,
                    mask as f32,
                    self.lod.cells as f32,
                ],
            });
        }
        self.chunks.evict(self.frame_number);
        for draw in &self.draws {
            self.indices.entry(draw.coarser).or_insert_with(|| {
                let indices = stitched_indices(self.lod.cells, draw.coarser);
                let count = indices.len() as u32;
                (
                    buffer_with(gpu, "terrain indices", &indices, wgpu::BufferUsages::INDEX),
                    count,
                )
            });
        }
        if uniforms.is_empty() {
            return Ok(0);
        }
        let needed = (uniforms.len() * size_of::<ChunkUniform>()) as u64;
        if self.chunk_buffer.size() < needed {
            self.chunk_buffer = chunk_buffer(gpu, uniforms.len().next_power_of_two());
        }
        gpu.queue
            .write_buffer(&self.chunk_buffer, 0, bytemuck::cast_slice(&uniforms));
        let clearance = altitude_m - ground_m;
        let sea = self.sea_albedo.map(|c| c as f32);
        // The season: the sun's declination, its planet-fixed direction's latitude.
        let declination = frame.sun_direction.normalize().z.clamp(-1.0, 1.0).asin();
        let line = SnowLine::for_declination(declination);
        let params = TerrainUniform {
            right: v4(right / half_w),
            up: v4(up / half_h),
            forward: v4(forward),
            near: [
                near_plane_m(clearance) as f32,
                MORPH_START as f32,
                view.pixels_per_radian as f32,
                0.0,
            ],
            sea_albedo: [sea[0], sea[1], sea[2], 1.0],
            snow_line: [
                line.at_equator_m as f32,
                line.drop_to_pole_m as f32,
                line.shift_rad as f32,
                SNOW_BAND_M as f32,
            ],
            rock: with_w(ROCK_ALBEDO, ROCK_SLOPE_COS[0]),
            snow: with_w(SNOW_ALBEDO, ROCK_SLOPE_COS[1]),
        };
        gpu.write_uniform(&self.params, &params);
        self.ensure_depth(gpu, frame.width, frame.height);
        Ok(self.draws.len())
    }

    /// Builds the chosen chunks not in the cache, in parallel, and uploads them.
    fn build_in_place(&mut self, gpu: &GpuContext, selected: &[SelectedChunk]) {
        let missing: Vec<&SelectedChunk> = selected
            .iter()
            .filter(|c| !self.chunks.contains(c.key))
            .collect();
        let surface = &self.surface;
        let cells = self.lod.cells;
        let built: Vec<ChunkMesh> = missing
            .par_iter()
            .map(|chunk| ChunkMesh::build(surface, chunk, cells))
            .collect();
        for mesh in &built {
            self.chunks
                .insert(gpu, &self.normal_textures, mesh, self.frame_number);
        }
    }

    /// Uploads the worker's finished meshes, builds the six roots here if missing (the
    /// cover of last resort), and asks the worker for the chosen chunks still missing in
    /// `build_order` (coarsest first, then nearest).
    fn build_off_thread(&mut self, gpu: &GpuContext, build_order: &[SelectedChunk]) {
        for mesh in self.worker.finished() {
            if !self.chunks.contains(mesh.key) {
                self.chunks
                    .insert(gpu, &self.normal_textures, &mesh, self.frame_number);
            }
        }
        self.build_in_place(gpu, &root_chunks());
        for chunk in build_order {
            if self.chunks.contains(chunk.key) || self.worker.is_building(chunk.key) {
                continue;
            }
            if !self.worker.request(&self.surface, *chunk, self.lod.cells) {
                break;
            }
        }
    }

    /// How the last prepared frame's chunks stood.
    pub fn progress(&self) -> ChunkProgress {
        self.progress
    }

    fn ensure_depth(&mut self, gpu: &GpuContext, width: u32, height: u32) {
        if (self.depth.width(), self.depth.height()) != (width, height) {
            self.depth = depth_buffer(gpu, width, height);
        }
    }

    /// Draws the chunks the last [`TerrainPass::prepare`] chose into `surface` (cleared
    /// to "no surface" first).
    pub fn encode(
        &self,
        gpu: &GpuContext,
        surface: &SurfaceBuffer,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let depth = &self.depth;
        let bind_group = ordered_bind_group(
            &gpu.device,
            Some("terrain"),
            &self.layout,
            &[
                self.params.as_entire_binding(),
                self.chunk_buffer.as_entire_binding(),
                wgpu::BindingResource::TextureView(&self.colour),
                wgpu::BindingResource::Sampler(&self.sampler),
            ],
        );
        let [geometry, albedo] = surface.views();
        let colour = |view| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })
        };
        let depth_view = depth.create_view(&Default::default());
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("terrain"),
            color_attachments: &[colour(&geometry), colour(&albedo)],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: timestamps,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        for (instance, draw) in self.draws.iter().enumerate() {
            let chunk = self.chunks.get(draw.key).expect("drawn chunks are cached");
            let (indices, count) = &self.indices[&draw.coarser];
            pass.set_bind_group(1, &chunk.normal_map, &[]);
            pass.set_vertex_buffer(0, chunk.vertices.slice(..));
            pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
            let instance = instance as u32;
            pass.draw_indexed(0..*count, 0, instance..instance + 1);
        }
    }

    /// Whether the last prepared frame draws sea: the model passes then run their
    /// variant with the sea's reflection (`shaders/common/sea_surface.wgsl`).
    pub fn water_in_view(&self) -> bool {
        self.water_in_view
    }

    /// The drawn terrain's elevation above the reference sphere in a unit direction, m,
    /// with the last frame's exaggeration: what the camera must stay above.
    pub fn elevation_m(&self, direction: DVec3) -> f64 {
        self.surface.elevation_m(direction)
    }

    /// The drawn surface: the relief whose shadow the light shafts show.
    pub fn surface(&self) -> &TerrainSurface<Arc<RefinedHeights>> {
        &self.surface
    }
}

/// The near plane for a camera `clearance_m` above the terrain below it: half of it, so
/// nothing in front of the camera is cut, and at least [`MIN_NEAR_M`].
pub fn near_plane_m(clearance_m: f64) -> f64 {
    (0.5 * clearance_m).max(MIN_NEAR_M)
}

fn v4(v: DVec3) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, 0.0]
}

fn chunk_buffer(gpu: &GpuContext, chunks: usize) -> wgpu::Buffer {
    let size = (chunks.max(1) * size_of::<ChunkUniform>()) as u64;
    let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
    buffer(&gpu.device, "terrain chunks", size, usage)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_near_plane_is_half_the_clearance_and_never_zero() {
        assert_eq!(near_plane_m(1000.0), 500.0);
        assert_eq!(near_plane_m(0.02), MIN_NEAR_M);
        assert_eq!(near_plane_m(-30.0), MIN_NEAR_M);
    }
}
