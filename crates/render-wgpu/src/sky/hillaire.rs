//! The hillaire model (Hillaire 2020) on the GPU: its tables in compute shaders named like
//! their CPU twins in atmosphere-core's `hillaire/`, and the per-pixel pass of
//! `shaders/sky/hillaire/pixel.wgsl`. The CPU model is the specification; the steps and the inputs
//! each table depends on are those of `Hillaire::update`:
//! - `transmittance`: the columns of `sky/transmittance_table.wgsl` (the CPU's shared table
//!   holds columns; transmittance is exp(-tau) of the interpolated columns on both
//!   sides), rebuilt when the columns' inputs change;
//! - `multiple_scattering` (Psi_ms) when extinction, scattering or the ground's albedo
//!   change; `ground_irradiance` (E_sky) when those or the Mie phase function change;
//!   neither for single scattering (`max_orders = 1`);
//! - `sky_view` when the view (camera radius to the millimetre, sun zenith cosine:
//!   `view_cache::view_key`), the Mie phase function or the Psi_ms inputs change; not for
//!   a camera above the atmosphere, whose rays are marched;
//! - `aerial_perspective` likewise, and only when some pixel may see the ground within
//!   the volume's range (`ground_in_view`);
//! - `hillaire`: the pass, every frame. It reads the transmittance table, the sky view
//!   and the volume through the texture unit's filter where the device can
//!   (`table_sampling`): one read per look-up instead of 4 (8 for the volume's trilinear
//!   one).

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::table_inputs::Inputs;
use atmosphere_core::models::hillaire::directions::horizon_zenith;
use atmosphere_core::models::hillaire::view_cache::view_key;
use atmosphere_core::models::hillaire::{
    HillaireSettings, MULTIPLE_SCATTERING_INPUTS, VIEW_INPUTS,
};
use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use crate::frame::Frame;
use crate::frame::atmosphere_uniform::check_wavelengths;
use crate::frame::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use crate::frame::ground_in_view::ground_within;
use crate::frame::plan::{FramePlan, StepKind};
use crate::frame::surface_buffer::SurfaceBuffer;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::{
    ComputePipeline, PixelPipeline, storage_texture_entry, texel_groups, texture_entry,
    uniform_buffer, uniform_entry,
};
use crate::gpu::readback::read_texture;
use crate::sky::model_pass::{ModelPass, PassIo, StandaloneInputs};
use crate::sky::table_sampling::TableSampling;
use crate::sky::transmittance::{TABLE_FORMAT, TableOutput, TransmittancePass};

/// WGSL `HillaireParams`, 112 bytes: the view of the per-view tables, the settings'
/// sample counts, and the camera's frame for the pass's view angles.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct HillaireUniform {
    pub view_r: f32,
    pub view_q: f32,
    pub view_mu_s: f32,
    pub aerial_range_m: f32,
    pub ms_sqrt_directions: u32,
    pub ms_samples: u32,
    pub sky_view_samples: u32,
    pub ap_samples_per_slice: u32,
    pub march_samples: u32,
    pub ground_zenith_panels: u32,
    pub ground_azimuths: u32,
    pub multiple_on: u32,
    pub view_theta_h: f32,
    pub pad0: f32,
    pub pad1: f32,
    pub pad2: f32,
    pub view_up: [f32; 4],
    pub view_sun_side: [f32; 4],
    pub view_across: [f32; 4],
}

/// A count as the shaders' u32, or an error naming it.
fn count(name: &str, n: usize) -> Result<u32, RenderError> {
    u32::try_from(n).map_err(|_| RenderError::Unsupported(format!("hillaire {name} = {n}")))
}

impl HillaireUniform {
    /// The settings for a view (camera radius, sun zenith cosine: `view_key`) of
    /// `atmosphere`, with the camera's zenith `up` and the sun's direction.
    pub fn new(
        settings: &HillaireSettings,
        atmosphere: &Atmosphere,
        view: (f64, f64),
        (up, sun): (DVec3, DVec3),
        multiple_on: bool,
    ) -> Result<HillaireUniform, RenderError> {
        let bottom = atmosphere.bottom_radius_m;
        let (r, mu_s) = view;
        let sun_side = (sun - up * sun.dot(up))
            .try_normalize()
            .unwrap_or_else(|| up.any_orthonormal_vector());
        let v4 = |v: DVec3| [v.x as f32, v.y as f32, v.z as f32, 0.0];
        Ok(HillaireUniform {
            view_r: r as f32,
            view_q: ((r - bottom) * (r + bottom)) as f32,
            view_mu_s: mu_s as f32,
            aerial_range_m: settings.aerial_range_m as f32,
            ms_sqrt_directions: count("ms_directions", settings.multiple_scattering_directions)?
                .isqrt(),
            ms_samples: count("ms_samples", settings.multiple_scattering_samples)?,
            sky_view_samples: count("sky_view_samples", settings.sky_view_samples)?,
            ap_samples_per_slice: count("ap_samples_per_slice", settings.aerial_samples_per_slice)?,
            march_samples: count("march_samples", settings.march_samples)?,
            ground_zenith_panels: count("ground_zenith_panels", settings.ground_zenith_panels)?,
            ground_azimuths: count("ground_azimuths", settings.ground_azimuths)?,
            multiple_on: u32::from(multiple_on),
            view_theta_h: horizon_zenith(r, bottom) as f32,
            pad0: 0.0,
            pad1: 0.0,
            pad2: 0.0,
            view_up: v4(up),
            view_sun_side: v4(sun_side),
            view_across: v4(up.cross(sun_side)),
        })
    }
}

/// The model's tables, by step name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Table {
    Transmittance,
    MultipleScattering,
    GroundIrradiance,
    SkyView,
    AerialPerspective,
}

impl Table {
    const ALL: [Table; 5] = [
        Table::Transmittance,
        Table::MultipleScattering,
        Table::GroundIrradiance,
        Table::SkyView,
        Table::AerialPerspective,
    ];

    /// The step's name in the plan.
    pub fn name(self) -> &'static str {
        match self {
            Table::Transmittance => "transmittance",
            Table::MultipleScattering => "multiple_scattering",
            Table::GroundIrradiance => "ground_irradiance",
            Table::SkyView => "sky_view",
            Table::AerialPerspective => "aerial_perspective",
        }
    }

    /// The atmosphere's inputs it depends on (`Hillaire::update`).
    fn inputs(self) -> Inputs {
        match self {
            Table::Transmittance => Inputs::COLUMNS,
            Table::MultipleScattering => MULTIPLE_SCATTERING_INPUTS,
            Table::GroundIrradiance | Table::SkyView | Table::AerialPerspective => VIEW_INPUTS,
        }
    }

    /// Whether it depends on the view and on whether orders two and up are on.
    fn per_view(self) -> bool {
        matches!(self, Table::SkyView | Table::AerialPerspective)
    }
}

/// What a table was built from.
#[derive(Clone, Debug, PartialEq)]
struct Source {
    atmosphere: Atmosphere,
    view: (f64, f64),
    multiple_on: bool,
}

impl Source {
    /// Whether `table` built from `self` is out of date for `new`.
    fn stale_for(&self, table: Table, new: &Source) -> bool {
        Inputs::changed(&self.atmosphere, &new.atmosphere).intersects(table.inputs())
            || (table.per_view() && (self.view != new.view || self.multiple_on != new.multiple_on))
    }
}

/// A texture for a table, written by one shader and read by the next.
fn table_texture(
    gpu: &GpuContext,
    label: &str,
    dimension: wgpu::TextureDimension,
    size: (usize, usize, usize),
) -> Result<wgpu::Texture, RenderError> {
    let limits = gpu.device.limits();
    let largest = match dimension {
        wgpu::TextureDimension::D3 => limits.max_texture_dimension_3d,
        _ => limits.max_texture_dimension_2d,
    };
    let side = |n: usize| {
        u32::try_from(n)
            .ok()
            .filter(|&n| n <= largest)
            .ok_or_else(|| {
                RenderError::Unsupported(format!(
                    "hillaire {label} of {size:?} texels (this GPU's largest side is {largest})"
                ))
            })
    };
    Ok(gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: side(size.0)?,
            height: side(size.1)?,
            depth_or_array_layers: side(size.2)?,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension,
        format: TABLE_FORMAT,
        usage: wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    }))
}

/// The tables of one `HillaireSettings`, and what each was last built from.
#[derive(Debug)]
struct Tables {
    settings: HillaireSettings,
    transmittance: TransmittancePass,
    multiple_scattering: wgpu::Texture,
    ground_irradiance: wgpu::Texture,
    sky_view: wgpu::Texture,
    aerial_radiance: wgpu::Texture,
    aerial_transmittance: wgpu::Texture,
    built: [Option<Source>; 5],
}

impl Tables {
    fn new(gpu: &GpuContext, settings: HillaireSettings) -> Result<Tables, RenderError> {
        use wgpu::TextureDimension::{D2, D3};
        let (tw, th) = settings.transmittance_size;
        let (mw, mh) = settings.multiple_scattering_size;
        let (sw, sh) = settings.sky_view_size;
        let (aw, ah, slices) = settings.aerial_size;
        Ok(Tables {
            settings,
            transmittance: TransmittancePass::with(
                gpu,
                TableOutput::Columns,
                count("transmittance_width", tw)?,
                count("transmittance_height", th)?,
            )?,
            multiple_scattering: table_texture(gpu, "Psi_ms", D2, (mw, mh, 1))?,
            ground_irradiance: table_texture(gpu, "E_sky", D2, (settings.ground_size, 1, 1))?,
            sky_view: table_texture(gpu, "sky view", D2, (sw, sh, 1))?,
            aerial_radiance: table_texture(gpu, "aerial radiance", D3, (aw, ah, slices))?,
            aerial_transmittance: table_texture(gpu, "aerial transmittance", D3, (aw, ah, slices))?,
            built: Default::default(),
        })
    }

    fn texture(&self, table: Table) -> &wgpu::Texture {
        match table {
            Table::Transmittance => self.transmittance.texture(),
            Table::MultipleScattering => &self.multiple_scattering,
            Table::GroundIrradiance => &self.ground_irradiance,
            Table::SkyView => &self.sky_view,
            Table::AerialPerspective => &self.aerial_radiance,
        }
    }
}

/// The model's pipelines and uniform, made once; the tables, remade when their sizes
/// change.
#[derive(Debug)]
pub struct HillairePass {
    multiple_scattering: ComputePipeline,
    ground_irradiance: ComputePipeline,
    sky_view: ComputePipeline,
    aerial_perspective: ComputePipeline,
    /// The pass's entry points by the rays a frame may have: `main` (read from the
    /// tables or marched), `tables_only`, `from_space` (all marched).
    pass: [PixelPipeline; 3],
    params: wgpu::Buffer,
    tables: Option<Tables>,
    /// The atmosphere of the frame being planned, in the GPU's layout, and what the
    /// tables it builds are built from.
    atmosphere: AtmosphereUniform,
    pending: Option<Source>,
    /// The entry point of `pass` the frame being planned uses.
    variant: usize,
    /// How the pass reads its tables.
    sampling: TableSampling,
}

impl HillairePass {
    pub fn new(gpu: &GpuContext) -> Result<HillairePass, GpuError> {
        use wgpu::TextureViewDimension::{D2, D3};
        let sampling = TableSampling::new(gpu);
        // Bindings 0-4 of every hillaire shader: atmosphere, frame (read by the pass
        // only), `HillaireParams`, the transmittance table and Psi_ms; and the table
        // sampler. The tables that are read may be sampled.
        let common = |fifth: wgpu::BindGroupLayoutEntry| {
            vec![
                uniform_entry(0, size_of::<AtmosphereUniform>()),
                uniform_entry(1, size_of::<FrameUniform>()),
                uniform_entry(2, size_of::<HillaireUniform>()),
                sampling.texture_entry(3, D2),
                fifth,
                sampling.sampler_entry(),
            ]
        };
        let psi = sampling.texture_entry(4, D2);
        let with = |extra: &[wgpu::BindGroupLayoutEntry]| {
            let mut entries = common(psi);
            entries.extend_from_slice(extra);
            entries
        };
        let constants = [sampling.constant()];
        let pipeline = |shader: &str, label: &'static str, entries: &[_]| {
            ComputePipeline::with_constants(gpu, shader, "main", label, entries, &constants)
        };
        Ok(HillairePass {
            multiple_scattering: pipeline(
                "sky/hillaire/multiple_scattering.wgsl",
                "the hillaire Psi_ms table",
                &common(storage_texture_entry(4, TABLE_FORMAT, D2)),
            )?,
            ground_irradiance: pipeline(
                "sky/hillaire/ground.wgsl",
                "the hillaire ground irradiance table",
                &with(&[storage_texture_entry(5, TABLE_FORMAT, D2)]),
            )?,
            sky_view: pipeline(
                "sky/hillaire/sky_view.wgsl",
                "the hillaire sky-view table",
                &with(&[storage_texture_entry(5, TABLE_FORMAT, D2)]),
            )?,
            aerial_perspective: pipeline(
                "sky/hillaire/aerial_perspective.wgsl",
                "the hillaire aerial-perspective volume",
                &with(&[
                    storage_texture_entry(5, TABLE_FORMAT, D3),
                    storage_texture_entry(6, TABLE_FORMAT, D3),
                ]),
            )?,
            pass: {
                let surface_entries = SurfaceBuffer::layout_entries();
                let entries = with(&[
                    texture_entry(5, D2),
                    sampling.texture_entry(6, D2),
                    sampling.texture_entry(7, D3),
                    sampling.texture_entry(8, D3),
                    storage_texture_entry(9, HDR_FORMAT, D2),
                    surface_entries[0],
                    surface_entries[1],
                ]);
                let variant = |entry| {
                    PixelPipeline::with_constants(
                        gpu,
                        "sky/hillaire/pixel.wgsl",
                        entry,
                        "the hillaire pass",
                        &entries,
                        &constants,
                    )
                };
                [
                    variant("main")?,
                    variant("tables_only")?,
                    variant("from_space")?,
                ]
            },
            params: uniform_buffer(&gpu.device, "hillaire", size_of::<HillaireUniform>()),
            tables: None,
            atmosphere: AtmosphereUniform::default(),
            pending: None,
            variant: 0,
            sampling,
        })
    }

    /// Builds the tables `frame` needs, as its plan says, without rendering it (to have
    /// them ready before a first frame, or to read them back); returns that plan, less
    /// the pass.
    pub fn build_tables(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
    ) -> Result<FramePlan, RenderError> {
        frame.validate()?;
        let mut plan = FramePlan::default();
        self.plan(gpu, frame, &mut plan)?;
        plan.steps.retain(|s| s.kind == StepKind::TableBuild);
        let inputs = StandaloneInputs::new(gpu, &self.atmosphere, frame);
        let io = inputs.io();
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        for step in &plan.steps {
            self.encode(step.name, gpu, &io, &mut encoder, None);
        }
        gpu.queue.submit([encoder.finish()]);
        Ok(plan)
    }

    /// A table's texels as last built, row-major (a volume's slices one after another;
    /// the volume's radiance: [`HillairePass::read_aerial_transmittance`] has the rest).
    pub fn read_table(&self, gpu: &GpuContext, table: Table) -> Result<Vec<[f32; 4]>, RenderError> {
        self.read(gpu, |t| t.texture(table))
    }

    /// The aerial-perspective volume's transmittance, laid out as its radiance.
    pub fn read_aerial_transmittance(
        &self,
        gpu: &GpuContext,
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        self.read(gpu, |t| &t.aerial_transmittance)
    }

    fn read(
        &self,
        gpu: &GpuContext,
        texture: impl Fn(&Tables) -> &wgpu::Texture,
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        let tables = self
            .tables
            .as_ref()
            .ok_or_else(|| RenderError::Frame("no hillaire frame has been planned".into()))?;
        let bytes = read_texture(gpu, texture(tables), size_of::<[f32; 4]>() as u32)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }
}

impl ModelPass for HillairePass {
    fn plan(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
        plan: &mut FramePlan,
    ) -> Result<(), RenderError> {
        check_wavelengths(&frame.settings.wavelengths_nm)?;
        let settings = HillaireSettings::from_options(&frame.settings.options)?;
        let a = &frame.atmosphere;
        self.atmosphere = AtmosphereUniform::new(a, RGB_WAVELENGTHS_NM)?;
        let multiple_on = frame.settings.max_orders != Some(1);
        let camera = frame.camera_position_m;
        let r = camera.length();
        let (up, sun) = (camera / r, frame.sun_direction.normalize());
        let view = view_key(a, r, sun.dot(up));
        let params = HillaireUniform::new(&settings, a, view, (up, sun), multiple_on)?;
        if self.tables.as_ref().is_none_or(|t| t.settings != settings) {
            self.tables = Some(Tables::new(gpu, settings)?);
        }
        let Some(tables) = self.tables.as_ref() else {
            unreachable!("made above");
        };
        let source = Source {
            atmosphere: a.clone(),
            view,
            multiple_on,
        };
        let stale = |table: Table| {
            tables.built[table as usize]
                .as_ref()
                .is_none_or(|old| old.stale_for(table, &source))
        };
        let inside = r <= a.top_radius_m;
        plan.build_if("transmittance", stale(Table::Transmittance));
        for table in [Table::MultipleScattering, Table::GroundIrradiance] {
            if multiple_on {
                plan.build_if(table.name(), stale(table));
            } else {
                plan.skip(table.name(), "single scattering");
            }
        }
        if inside {
            plan.build_if("sky_view", stale(Table::SkyView));
        } else {
            plan.skip("sky_view", "camera above the atmosphere");
        }
        // A surface counts as ground in view, near and far: it may end any ray at any
        // distance, read from the volume within its range and marched beyond.
        if !inside {
            plan.skip("aerial_perspective", "camera above the atmosphere");
        } else if plan.surface || ground_within(frame, settings.aerial_range_m) {
            plan.build_if("aerial_perspective", stale(Table::AerialPerspective));
        } else {
            plan.skip("aerial_perspective", "no ground in view");
        }
        // Rays to the ground beyond the volume are marched; none when the horizon is
        // nearer than the volume's range or no ground is in view.
        let horizon_m = ((r - a.bottom_radius_m) * (r + a.bottom_radius_m)).sqrt();
        let far_ground = plan.surface
            || horizon_m > settings.aerial_range_m * (1.0 - 1e-3)
                && ground_within(frame, f64::INFINITY);
        self.variant = match (inside, far_ground) {
            (true, true) => 0,
            (true, false) => 1,
            (false, _) => 2,
        };
        plan.run("hillaire", StepKind::Pass);
        self.pending = Some(source);
        gpu.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        Ok(())
    }

    fn encode(
        &mut self,
        step: &'static str,
        gpu: &GpuContext,
        io: &PassIo<'_>,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let Some(tables) = self.tables.as_mut() else {
            unreachable!("plan makes the tables before any step");
        };
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let transmittance = view(tables.transmittance.texture());
        let psi = view(&tables.multiple_scattering);
        // Bindings 0-3, `extra` from 4 on, the table sampler, and for the per-pixel pass
        // the frame's `surface` at 30 and 31.
        let run = |pipeline: &ComputePipeline,
                   encoder: &mut wgpu::CommandEncoder,
                   extra: &[wgpu::BindingResource<'_>],
                   surface: Option<&[wgpu::TextureView; 2]>,
                   groups: [u32; 3],
                   timestamps| {
            let mut resources = vec![
                io.atmosphere.as_entire_binding(),
                io.frame.as_entire_binding(),
                self.params.as_entire_binding(),
                wgpu::BindingResource::TextureView(&transmittance),
            ];
            resources.extend_from_slice(extra);
            let bind_group = self.sampling.bind_group(gpu, pipeline, &resources, surface);
            pipeline.dispatch(encoder, step, &bind_group, groups, timestamps);
        };
        let tiles = |t: &wgpu::Texture| texel_groups(t);
        let psi_view = wgpu::BindingResource::TextureView(&psi);
        let built = match step {
            "transmittance" => {
                tables
                    .transmittance
                    .encode(gpu, &self.atmosphere, encoder, timestamps);
                Some(Table::Transmittance)
            }
            "multiple_scattering" => {
                let t = &tables.multiple_scattering;
                run(
                    &self.multiple_scattering,
                    encoder,
                    &[psi_view],
                    None,
                    [t.width(), t.height(), 1],
                    timestamps,
                );
                Some(Table::MultipleScattering)
            }
            "ground_irradiance" => {
                let t = &tables.ground_irradiance;
                let out = view(t);
                run(
                    &self.ground_irradiance,
                    encoder,
                    &[psi_view, wgpu::BindingResource::TextureView(&out)],
                    None,
                    [t.width(), 1, 1],
                    timestamps,
                );
                Some(Table::GroundIrradiance)
            }
            "sky_view" => {
                let out = view(&tables.sky_view);
                run(
                    &self.sky_view,
                    encoder,
                    &[psi_view, wgpu::BindingResource::TextureView(&out)],
                    None,
                    tiles(&tables.sky_view),
                    timestamps,
                );
                Some(Table::SkyView)
            }
            "aerial_perspective" => {
                let (radiance, transmittance) = (
                    view(&tables.aerial_radiance),
                    view(&tables.aerial_transmittance),
                );
                run(
                    &self.aerial_perspective,
                    encoder,
                    &[
                        psi_view,
                        wgpu::BindingResource::TextureView(&radiance),
                        wgpu::BindingResource::TextureView(&transmittance),
                    ],
                    None,
                    tiles(&tables.aerial_radiance),
                    timestamps,
                );
                Some(Table::AerialPerspective)
            }
            "hillaire" => {
                let views = [
                    &tables.ground_irradiance,
                    &tables.sky_view,
                    &tables.aerial_radiance,
                    &tables.aerial_transmittance,
                ]
                .map(view);
                let hdr = view(io.hdr);
                let mut extra = vec![psi_view];
                extra.extend(views.iter().map(wgpu::BindingResource::TextureView));
                extra.push(wgpu::BindingResource::TextureView(&hdr));
                run(
                    self.pass[self.variant].variant(io.has_surface),
                    encoder,
                    &extra,
                    Some(io.surface),
                    tiles(io.hdr),
                    timestamps,
                );
                None
            }
            other => unreachable!("the hillaire plan has no step {other}"),
        };
        if let Some(table) = built {
            tables.built[table as usize] = self.pending.clone();
        }
    }

    fn table_bytes(&self) -> u64 {
        self.tables.as_ref().map_or(0, |t| {
            Table::ALL
                .iter()
                .map(|&table| t.texture(table))
                .chain([&t.aerial_transmittance])
                .map(|texture| {
                    u64::from(texture.width())
                        * u64::from(texture.height())
                        * u64::from(texture.depth_or_array_layers())
                        * 16
                })
                .sum()
        })
    }
}
