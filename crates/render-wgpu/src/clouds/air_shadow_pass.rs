//! The cloud layer's shadow in the air below its base, per pixel, for every sky model
//! (`shaders/clouds/air_shadow.wgsl`; CPU twin: atmosphere-core's
//! `clouds/layer/air_shadow.rs`): run after the sun map's fill in frames whose map shades
//! the air ([`crate::frame::plan::FramePlan::cloud_shafts`]), it writes each pixel's
//! single scattering that the cloud takes out beyond the terrain's shadow beside the
//! surface's cloud transmittance into the map's per-pixel image, which every model's
//! pixel pass reads and subtracts. It marches through a columns table of its own,
//! rebuilt when the atmosphere's columns change; at a resolution divisor above 1 (the
//! layer settings' `air_shadow_divisor`) one ray per block of pixels first, whose taps of the same span the
//! full pass reads (atmosphere-core's `clouds/layer/air_shadow_upsample.rs`), listing the
//! pixels without such taps for a pass of their own to march ([`PixelList`]). The map is
//! read here rather than inside the pixel passes, which crashed lavapipe (Mesa 22.3.6)
//! with it (docs/clouds.md, "Cloud shadows in the air").

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::clouds::layer::air_shadow::CloudAirShadow;
use atmosphere_core::clouds::layer::upsample::reduced_size;

use crate::clouds::sun_map_pass::PixelInputs;
use crate::clouds::sun_map_texture::{
    PIXELS_FORMAT, PIXELS_OUT_BINDING, SUN_MAP_BINDING, SUN_MAP_PARAMS_BINDING, SunMapTexture,
    SunMapUniform,
};
use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::surface_buffer::GEOMETRY_BINDING;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{
    ComputePipeline, split_timestamps, storage_texture_entry, texel_groups, texture_2d,
    texture_entry, uniform_entry,
};
use crate::gpu::pixel_list::PixelList;
use crate::shafts::terrain::uniform::ShadowMapUniform;
use crate::sky::columns_table::ColumnsTable;
use crate::sky::table_sampling::TableSampling;

/// The columns table's binding (that of `sky/hillaire/bindings.wgsl`, whose march the
/// shader runs).
const COLUMNS_BINDING: u32 = 3;
/// The reduced march's image, written and read.
const REDUCED_OUT_BINDING: u32 = 36;
const REDUCED_IN_BINDING: u32 = 37;
/// The surface's cloud transmittance per pixel, as `sun_map_pixels.wgsl` wrote it.
const SURFACE_SUN_BINDING: u32 = 38;
/// The pixels the full pass lists for the listed march, and that march's dispatch.
const LIST_BINDING: u32 = 39;
const LIST_DISPATCH_BINDING: u32 = 40;

/// The full pass in four variants (with the frame's surface and without, the buffer
/// unread; from the reduced march's taps or not), the reduced march and the listed
/// pixels' march in two each, the reduced march's image (1 x 1 until a frame is reduced)
/// and the list of pixels to march (made for the first frame's size), the image of the surface's cloud transmittance the
/// full pass copies (1 x 1 until a frame has a surface) and the columns table.
#[derive(Debug)]
pub struct AirShadowPass {
    /// Indexed by `2 surface + upsample`.
    full: [ComputePipeline; 4],
    /// Indexed by `surface`.
    reduced: [ComputePipeline; 2],
    /// Indexed by `surface`.
    listed: [ComputePipeline; 2],
    image: wgpu::Texture,
    list: Option<PixelList>,
    surface_sun: wgpu::Texture,
    sampling: TableSampling,
    columns: ColumnsTable,
}

/// An image of the per-pixel image's format of `size`, written by one pass and read by
/// the next.
fn pass_image(gpu: &GpuContext, label: &str, size: (u32, u32)) -> wgpu::Texture {
    texture_2d(
        &gpu.device,
        label,
        size,
        PIXELS_FORMAT,
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
    )
}

const REDUCED_LABEL: &str = "cloud shadow in the air, reduced";
const SURFACE_SUN_LABEL: &str = "cloud shadow in the air, the surface's sun";

impl AirShadowPass {
    /// Compiles every variant; the table, of [`CloudAirShadow::TABLE_SIZE`], unbuilt.
    pub fn new(gpu: &GpuContext) -> Result<AirShadowPass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let sampling = TableSampling::new(gpu);
        let shared = [
            uniform_entry(0, size_of::<AtmosphereUniform>()),
            uniform_entry(1, size_of::<FrameUniform>()),
            sampling.texture_entry(COLUMNS_BINDING, D2),
            texture_entry(9, D2),
            uniform_entry(10, size_of::<ShadowMapUniform>()),
            texture_entry(GEOMETRY_BINDING, D2),
            uniform_entry(SUN_MAP_PARAMS_BINDING, size_of::<SunMapUniform>()),
            texture_entry(SUN_MAP_BINDING, D2),
            sampling.sampler_entry(),
        ];
        let full_entries: Vec<_> = shared
            .iter()
            .cloned()
            .chain([
                storage_texture_entry(PIXELS_OUT_BINDING, PIXELS_FORMAT, D2),
                texture_entry(REDUCED_IN_BINDING, D2),
                texture_entry(SURFACE_SUN_BINDING, D2),
                PixelList::list_entry(LIST_BINDING),
                PixelList::dispatch_entry(LIST_DISPATCH_BINDING),
            ])
            .collect();
        let listed_entries: Vec<_> = shared
            .iter()
            .cloned()
            .chain([
                storage_texture_entry(PIXELS_OUT_BINDING, PIXELS_FORMAT, D2),
                texture_entry(SURFACE_SUN_BINDING, D2),
                PixelList::list_entry(LIST_BINDING),
            ])
            .collect();
        let reduced_entries: Vec<_> = shared
            .iter()
            .cloned()
            .chain([storage_texture_entry(
                REDUCED_OUT_BINDING,
                PIXELS_FORMAT,
                D2,
            )])
            .collect();
        let flag = |on: bool| f64::from(u8::from(on));
        let full = |surface: bool, upsample: bool| {
            ComputePipeline::with_constants(
                gpu,
                "clouds/air_shadow.wgsl",
                "main",
                "cloud shadow in the air",
                &full_entries,
                &[
                    ("SURFACE", flag(surface)),
                    ("UPSAMPLE", flag(upsample)),
                    sampling.constant(),
                ],
            )
        };
        let reduced = |surface: bool| {
            ComputePipeline::with_constants(
                gpu,
                "clouds/air_shadow.wgsl",
                "reduced",
                "cloud shadow in the air, reduced",
                &reduced_entries,
                &[("SURFACE", flag(surface)), sampling.constant()],
            )
        };
        let listed = |surface: bool| {
            ComputePipeline::with_constants(
                gpu,
                "clouds/air_shadow.wgsl",
                "listed",
                "cloud shadow in the air, listed pixels",
                &listed_entries,
                &[("SURFACE", flag(surface)), sampling.constant()],
            )
        };
        let (width, height) = CloudAirShadow::TABLE_SIZE;
        Ok(AirShadowPass {
            full: [
                full(false, false)?,
                full(false, true)?,
                full(true, false)?,
                full(true, true)?,
            ],
            reduced: [reduced(false)?, reduced(true)?],
            listed: [listed(false)?, listed(true)?],
            image: pass_image(gpu, REDUCED_LABEL, (1, 1)),
            list: None,
            surface_sun: pass_image(gpu, SURFACE_SUN_LABEL, (1, 1)),
            columns: ColumnsTable::new(gpu, (width as u32, height as u32))?,
            sampling,
        })
    }

    /// The image the sun map's per-pixel read writes the surface's cloud transmittance
    /// to in a frame of `size` with a surface, which the full pass copies into the
    /// per-pixel image beside the loss (computed there instead, the read crashed
    /// lavapipe, Mesa 22.3.6).
    pub fn surface_sun_target(&mut self, gpu: &GpuContext, size: (u32, u32)) -> &wgpu::Texture {
        if (self.surface_sun.width(), self.surface_sun.height()) != size {
            self.surface_sun = pass_image(gpu, SURFACE_SUN_LABEL, size);
        }
        &self.surface_sun
    }

    /// Plans the table's build for a frame of `atmosphere` when its columns changed.
    pub fn plan(&mut self, atmosphere: &Atmosphere) {
        self.columns.plan(atmosphere);
    }

    /// Records the table's planned build, from the frame's atmosphere, then the
    /// pass over every pixel of the frame of `inputs` into `map`'s per-pixel image (after
    /// the map's fill), from a reduced march of one ray per `divisor` x `divisor` pixels
    /// when `divisor` is above 1 (then the pixels without taps of their span marched by a
    /// pass of their own); `timestamps` open the first pass and close the last.
    pub fn encode(
        &mut self,
        gpu: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        inputs: PixelInputs<'_>,
        (map, divisor): (&SunMapTexture, u32),
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        self.columns.build_planned(gpu, encoder)?;
        let frame = (map.pixels().width(), map.pixels().height());
        let upsample = divisor > 1;
        let low = if upsample {
            reduced_size(frame.0, frame.1, divisor)
        } else {
            (1, 1)
        };
        if (self.image.width(), self.image.height()) != low {
            self.image = pass_image(gpu, REDUCED_LABEL, low);
        }
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (out, image) = (view(map.pixels()), view(&self.image));
        let surface_sun = view(&self.surface_sun);
        let columns = view(self.columns.texture());
        let shadow = inputs.shadow.view();
        let shared = [
            (0, inputs.atmosphere.as_entire_binding()),
            (1, inputs.frame.as_entire_binding()),
            (
                COLUMNS_BINDING,
                wgpu::BindingResource::TextureView(&columns),
            ),
            (9, wgpu::BindingResource::TextureView(&shadow)),
            (10, inputs.shadow.params().as_entire_binding()),
            (
                GEOMETRY_BINDING,
                wgpu::BindingResource::TextureView(inputs.geometry),
            ),
            (SUN_MAP_PARAMS_BINDING, map.params().as_entire_binding()),
            map.map_binding(),
            self.sampling.sampler_binding(),
        ];
        let surface = usize::from(inputs.has_surface);
        let list_size = if upsample { frame } else { (1, 1) };
        let kept = match self.list.take() {
            Some(kept) if kept.size == list_size => {
                kept.reset(gpu);
                kept
            }
            _ => PixelList::new(gpu, "cloud shadow in the air", list_size).map_err(|e| {
                RenderError::Frame(format!(
                    "the cloud's shadow in the air at a reduced resolution: {e}; use the \
                     offline cloud quality (air_shadow_divisor 1) or a smaller frame"
                ))
            })?,
        };
        let PixelList { list, dispatch, .. } = self.list.insert(kept);
        // The first pass opens the step's timing and the last closes it.
        let (mut first, last) = match upsample {
            true => split_timestamps(timestamps),
            false => (timestamps, None),
        };
        let target = [
            (PIXELS_OUT_BINDING, wgpu::BindingResource::TextureView(&out)),
            (
                SURFACE_SUN_BINDING,
                wgpu::BindingResource::TextureView(&surface_sun),
            ),
            (LIST_BINDING, list.as_entire_binding()),
        ];
        if upsample {
            let pipeline = &self.reduced[surface];
            let reduced = [(
                REDUCED_OUT_BINDING,
                wgpu::BindingResource::TextureView(&image),
            )];
            let bind_group = pipeline.bind_group_numbered(gpu, &[&shared[..], &reduced].concat());
            pipeline.dispatch(
                encoder,
                "cloud shadow in the air, reduced",
                &bind_group,
                texel_groups(&self.image),
                first.take(),
            );
        }
        let pipeline = &self.full[2 * surface + usize::from(upsample)];
        let taps = [
            (
                REDUCED_IN_BINDING,
                wgpu::BindingResource::TextureView(&image),
            ),
            (LIST_DISPATCH_BINDING, dispatch.as_entire_binding()),
        ];
        let bind_group = pipeline.bind_group_numbered(gpu, &[&shared[..], &target, &taps].concat());
        pipeline.dispatch(
            encoder,
            "cloud shadow in the air",
            &bind_group,
            texel_groups(map.pixels()),
            first.take(),
        );
        if upsample {
            let pipeline = &self.listed[surface];
            let bind_group = pipeline.bind_group_numbered(gpu, &[&shared[..], &target].concat());
            pipeline.dispatch_indirect(
                encoder,
                "cloud shadow in the air, listed pixels",
                &bind_group,
                dispatch,
                last,
            );
        }
        Ok(())
    }
}
