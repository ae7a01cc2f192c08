//! The cloud layer's sun map on the GPU (atmosphere-core's `clouds/layer/sun_map.rs`):
//! its optical depths in an `R32Float` texture, level k in rows k n to k n + n - 1, its
//! parameters in a uniform, and the map's transmittance at each pixel's surface (and,
//! beside it, the cloud's shadow in the air, `air_shadow_pass.rs`)
//! (`shaders/clouds/sun_map_pixels.wgsl`), which every model's pixel pass binds at 32
//! with the parameters at 33 (`shaders/common/surface.wgsl`) and multiplies its
//! surface's sun by. A frame without the map binds small textures with the flag off.

use atmosphere_core::clouds::layer::sun_map::SunMapResolution;
use atmosphere_core::shafts::GnomonicGrid;
use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::{texture_2d, texture_entry, uniform_buffer, uniform_entry};

/// The texture's format: one optical depth per texel.
pub const SUN_MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;
/// The per-pixel image's format: the transmittance at the pixel's surface, then the
/// single scattering per unit solar irradiance that the cloud's shadow takes out of the
/// air.
pub const PIXELS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// The bindings, in the model's pixel passes, of the per-pixel transmittance and of the
/// parameters; in the per-pixel pass, of the per-pixel output and of the map.
pub const PIXELS_BINDING: u32 = 32;
pub const SUN_MAP_PARAMS_BINDING: u32 = 33;
pub const PIXELS_OUT_BINDING: u32 = 34;
pub const SUN_MAP_BINDING: u32 = 35;

/// WGSL `SunMapParams`, 96 bytes; `counts[3] = 0` for a frame without the map.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct SunMapUniform {
    /// The grid's east axis; w: the cell's side on the base sphere, m.
    pub east_cell: [f32; 4],
    pub north: [f32; 4],
    /// The grid's centre direction.
    pub up: [f32; 4],
    /// Unit vector towards the sun.
    pub sun: [f32; 4],
    /// Radii of the layer's base and top, m; 1 when the map shades the air under the
    /// base (`air_shadow_pass.rs`), else 0; 0.
    pub radii: [f32; 4],
    /// Cells per side, levels, march steps per texel, 1.
    pub counts: [u32; 4],
}

impl SunMapUniform {
    /// The parameters of the map over `grid` (on the base sphere) for the unit `sun`,
    /// with the layer's `top_radius_m`.
    pub fn new(
        grid: &GnomonicGrid,
        sun: DVec3,
        top_radius_m: f64,
        resolution: &SunMapResolution,
    ) -> SunMapUniform {
        let v = |d: DVec3, w: f64| [d.x as f32, d.y as f32, d.z as f32, w as f32];
        SunMapUniform {
            east_cell: v(grid.east, grid.cell_m),
            north: v(grid.north, 0.0),
            up: v(grid.up, 0.0),
            sun: v(sun, 0.0),
            radii: [grid.radius_m as f32, top_radius_m as f32, 0.0, 0.0],
            counts: [
                grid.size as u32,
                resolution.levels as u32,
                resolution.steps as u32,
                1,
            ],
        }
    }

    /// These parameters with the flag that the map shades the air under the layer's
    /// base (`on`) or not.
    pub fn shading_air(self, on: bool) -> SunMapUniform {
        let mut params = self;
        params.radii[2] = if on { 1.0 } else { 0.0 };
        params
    }
}

/// The map's texture, parameters and per-pixel transmittance.
#[derive(Clone, Debug)]
pub struct SunMapTexture {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    pixels: wgpu::Texture,
    pixels_view: wgpu::TextureView,
    params: wgpu::Buffer,
    /// The same parameters with the cloud's shadow in the air off
    /// ([`SunMapTexture::without_air_shadow`]).
    params_without_air: wgpu::Buffer,
}

impl SunMapTexture {
    /// The placeholder of frames without the map.
    pub fn new(gpu: &GpuContext) -> SunMapTexture {
        let pixels = map_texture(gpu, "cloud sun map pixels", (1, 1), PIXELS_FORMAT);
        let params = uniform_buffer(&gpu.device, "cloud sun map", size_of::<SunMapUniform>());
        gpu.write_uniform(&params, &SunMapUniform::default());
        let size = size_of::<SunMapUniform>();
        let params_without_air = uniform_buffer(&gpu.device, "cloud sun map, no air", size);
        gpu.write_uniform(&params_without_air, &SunMapUniform::default());
        let texture = map_texture(gpu, "cloud sun map", (2, 2), SUN_MAP_FORMAT);
        SunMapTexture {
            params_without_air,
            view: texture.create_view(&Default::default()),
            texture,
            pixels_view: pixels.create_view(&Default::default()),
            pixels,
            params,
        }
    }

    /// Writes `params` (`None`: the frames that follow have no map) and makes the
    /// textures their sizes, the per-pixel one `pixels` (width, height); an error names a
    /// map taller than the device's textures.
    pub fn set(
        &mut self,
        gpu: &GpuContext,
        params: Option<&SunMapUniform>,
        pixels: (u32, u32),
    ) -> Result<(), RenderError> {
        let Some(params) = params else {
            gpu.write_uniform(&self.params, &SunMapUniform::default());
            gpu.write_uniform(&self.params_without_air, &SunMapUniform::default());
            return Ok(());
        };
        let [n, levels, _, _] = params.counts;
        let size = (n, n * levels);
        let limit = gpu.device.limits().max_texture_dimension_2d;
        if size.1 > limit {
            return Err(RenderError::Frame(format!(
                "cloud sun map: {n} cells x {levels} levels need a texture {} texels tall, \
                 over this GPU's {limit}",
                size.1
            )));
        }
        if (self.texture.width(), self.texture.height()) != size {
            self.texture = map_texture(gpu, "cloud sun map", size, SUN_MAP_FORMAT);
            self.view = self.texture.create_view(&Default::default());
        }
        if (self.pixels.width(), self.pixels.height()) != pixels {
            self.pixels = map_texture(gpu, "cloud sun map pixels", pixels, PIXELS_FORMAT);
            self.pixels_view = self.pixels.create_view(&Default::default());
        }
        gpu.write_uniform(&self.params, params);
        gpu.write_uniform(&self.params_without_air, &params.shading_air(false));
        Ok(())
    }

    /// The same map for the model's second run in front of the cloud (`cloud_front`)
    /// when the camera is above the layer: every ray enters the cloud before it reaches
    /// the air below the base, so the cloud's shadow in the air lies behind the cloud,
    /// where the composite dims it with the rest of the light behind
    /// (`clouds/layer/composite.rs`), and the run in front takes none of it.
    pub fn without_air_shadow(&self) -> SunMapTexture {
        SunMapTexture {
            params: self.params_without_air.clone(),
            ..self.clone()
        }
    }

    /// The map (the fill pass writes it; tests read it back).
    pub fn texture(&self) -> &wgpu::Texture {
        &self.texture
    }

    /// The per-pixel transmittance (the per-pixel pass writes it).
    pub fn pixels(&self) -> &wgpu::Texture {
        &self.pixels
    }

    /// The parameters' buffer.
    pub fn params(&self) -> &wgpu::Buffer {
        &self.params
    }

    /// The layout entries of bindings 32 and 33 of the models' pixel passes.
    pub fn layout_entries() -> [wgpu::BindGroupLayoutEntry; 2] {
        [
            texture_entry(PIXELS_BINDING, wgpu::TextureViewDimension::D2),
            uniform_entry(SUN_MAP_PARAMS_BINDING, size_of::<SunMapUniform>()),
        ]
    }

    /// The resources of bindings 32 and 33 of the models' pixel passes.
    pub fn bindings(&self) -> [(u32, wgpu::BindingResource<'_>); 2] {
        [
            (
                PIXELS_BINDING,
                wgpu::BindingResource::TextureView(&self.pixels_view),
            ),
            (SUN_MAP_PARAMS_BINDING, self.params.as_entire_binding()),
        ]
    }
}

impl SunMapTexture {
    /// The map itself at 35 (the shadow in the air reads it).
    pub fn map_binding(&self) -> (u32, wgpu::BindingResource<'_>) {
        (
            SUN_MAP_BINDING,
            wgpu::BindingResource::TextureView(&self.view),
        )
    }
}

fn map_texture(
    gpu: &GpuContext,
    label: &str,
    size: (u32, u32),
    format: wgpu::TextureFormat,
) -> wgpu::Texture {
    texture_2d(
        &gpu.device,
        label,
        size,
        format,
        wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
    )
}
