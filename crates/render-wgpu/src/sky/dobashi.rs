//! The dobashi model on the GPU: the pre-integrated segment tables of the sampling planes
//! and of the sample spheres (seed 000 sections 5.2-5.3) built by
//! `shaders/sky/dobashi/tables.wgsl` (the GPU twins of atmosphere-core's
//! `dobashi::PlaneTables` and `dobashi::SphereTables`), g_l (the `columns` of the
//! transmittance pass), the ambient term's table (`shaders/sky/dobashi/ambient.wgsl`,
//! `AmbientTable::build`) and the per-pixel pass (`shaders/sky/dobashi/pixel.wgsl`,
//! `Dobashi::radiance`). Each table is rebuilt only when what it depends on changed.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::table_inputs::Inputs;
use atmosphere_core::models::dobashi::sphere_tables::sphere_heights;
use atmosphere_core::models::dobashi::{AmbientTable, DobashiSettings, PlaneTables};
use bytemuck::{Pod, Zeroable};

use crate::frame::Frame;
use crate::frame::atmosphere_uniform::check_wavelengths;
use crate::frame::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use crate::frame::plan::{FramePlan, StepKind};
use crate::frame::surface_buffer::SurfaceBuffer;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::{
    ComputePipeline, PixelPipeline, read_only_storage_buffer_entry, storage_texture_entry,
    texel_groups, texture_2d, uniform_buffer, uniform_entry,
};
use crate::gpu::readback::read_texture;
use crate::sky::model_pass::{ModelPass, PassIo};
use crate::sky::table_sampling::TableSampling;
use crate::sky::transmittance::{TABLE_FORMAT, TableOutput, TransmittancePass};

/// Panels of 5-point Gauss-Legendre per plane segment (at most Delta_t, 8.8 km for the
/// earth at the defaults).
pub const PLANE_PANELS: u32 = 16;
/// Panels per sphere segment (up to the 1,750 km chord of the earth's top sphere).
pub const SPHERE_PANELS: u32 = 256;

/// WGSL `DobashiTableParams`, 16 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct DobashiTableUniform {
    pub interval_m: f32,
    pub plane_panels: u32,
    pub sphere_panels: u32,
    pub pad0: u32,
}

/// The interval Delta_t of `settings` for `atmosphere`: the interval rule of section
/// 4.2.1 with the paper's I_max = 1 always reaches Delta_max (dI_r + dI_m <= 1 - dg_v <
/// 1; `PlaneTables::build`), the horizontal view from the ground over `planes`. A lower
/// `table_max` would need the tables at every step before choosing; the GPU refuses it.
pub fn plane_interval_m(
    atmosphere: &Atmosphere,
    settings: &DobashiSettings,
) -> Result<f64, RenderError> {
    if settings.table_max < 1.0 {
        return Err(RenderError::Unsupported(format!(
            "dobashi: table_max={} (the GPU builds the tables at the interval of table_max=1)",
            settings.table_max
        )));
    }
    let (bottom, top) = (atmosphere.bottom_radius_m, atmosphere.top_radius_m);
    Ok(((top - bottom) * (top + bottom)).sqrt() / settings.planes as f64)
}

/// The rows of the sphere tables for the shader (`sphere_rows`): per sphere and kind of
/// segment (down, chord, up), q0 = r^2 - bottom^2 of the sphere, q of the end sphere
/// minus q0, and the shortest and longest segment (`SphereTables::length_range`), or a
/// negative longest where the kind does not exist. The per-pixel pass reads the spheres'
/// q0 and steps from them too.
pub fn sphere_rows(atmosphere: &Atmosphere, spheres: usize) -> Vec<[f32; 4]> {
    let bottom = atmosphere.bottom_radius_m;
    let heights = sphere_heights(atmosphere, spheres);
    let q = |k: usize| heights[k] * (heights[k] + 2.0 * bottom);
    let radius = |k: usize| bottom + heights[k];
    let chord = |k: usize, other: usize| {
        let (r, o) = (radius(k), radius(other));
        ((r - o).abs() * (r + o)).sqrt()
    };
    let row = |q0: f64, dq: f64, d_min: f64, d_max: f64| {
        [q0 as f32, dq as f32, d_min as f32, d_max as f32]
    };
    let mut rows = Vec::with_capacity(3 * spheres);
    for k in 0..spheres {
        let missing = row(q(k), 0.0, 0.0, -1.0);
        if k > 0 {
            rows.push(row(
                q(k),
                q(k - 1) - q(k),
                radius(k) - radius(k - 1),
                chord(k, k - 1),
            ));
            rows.push(row(q(k), 0.0, 0.0, 2.0 * chord(k, k - 1)));
        } else {
            rows.extend([missing, missing]);
        }
        if k + 1 < spheres {
            rows.push(row(
                q(k),
                q(k + 1) - q(k),
                radius(k + 1) - radius(k),
                chord(k, k + 1),
            ));
        } else {
            rows.push(missing);
        }
    }
    rows
}

/// dI_r, dI_m, dg_v as three `Rgba32Float` textures (rgb = the three channels).
#[derive(Debug)]
pub struct SegmentTextures {
    pub scatter_r: wgpu::Texture,
    pub scatter_m: wgpu::Texture,
    pub transmittance: wgpu::Texture,
}

impl SegmentTextures {
    fn new(gpu: &GpuContext, label: &str, width: u32, height: u32) -> SegmentTextures {
        let texture = |what: &str| {
            texture_2d(
                &gpu.device,
                &format!("dobashi {label} {what}"),
                (width, height),
                TABLE_FORMAT,
                wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
            )
        };
        SegmentTextures {
            scatter_r: texture("dI_r"),
            scatter_m: texture("dI_m"),
            transmittance: texture("dg_v"),
        }
    }

    /// The three textures in binding order.
    pub fn all(&self) -> [&wgpu::Texture; 3] {
        [&self.scatter_r, &self.scatter_m, &self.transmittance]
    }

    /// Bytes held.
    pub fn bytes(&self) -> u64 {
        let t = &self.scatter_r;
        3 * u64::from(t.width()) * u64::from(t.height()) * 16
    }

    /// The texels of each texture, row-major, waiting for the GPU.
    pub fn read_back(&self, gpu: &GpuContext) -> Result<[Vec<[f32; 4]>; 3], GpuError> {
        let read = |t: &wgpu::Texture| -> Result<Vec<[f32; 4]>, GpuError> {
            Ok(bytemuck::pod_collect_to_vec(&read_texture(gpu, t, 16)?))
        };
        Ok([
            read(&self.scatter_r)?,
            read(&self.scatter_m)?,
            read(&self.transmittance)?,
        ])
    }
}

/// The plane and sphere tables of one size, their pipelines and inputs.
#[derive(Debug)]
pub struct DobashiTables {
    planes_pipeline: ComputePipeline,
    spheres_pipeline: ComputePipeline,
    params: wgpu::Buffer,
    rows: wgpu::Buffer,
    /// table_angles x table_heights (`PlaneTables`).
    pub planes: SegmentTextures,
    /// sphere_table_angles x 3 spheres (`SphereTables`).
    pub spheres: SegmentTextures,
}

impl DobashiTables {
    /// Pipelines and unbuilt tables of the sizes of `settings`.
    pub fn new(gpu: &GpuContext, settings: &DobashiSettings) -> Result<DobashiTables, GpuError> {
        use wgpu::TextureViewDimension::D2;
        let rows = 3 * settings.spheres;
        let entries = [
            uniform_entry(0, size_of::<AtmosphereUniform>()),
            uniform_entry(1, size_of::<DobashiTableUniform>()),
            read_only_storage_buffer_entry(2, 16 * rows),
            storage_texture_entry(3, TABLE_FORMAT, D2),
            storage_texture_entry(4, TABLE_FORMAT, D2),
            storage_texture_entry(5, TABLE_FORMAT, D2),
        ];
        let pipeline = |entry, label| {
            ComputePipeline::new(gpu, "sky/dobashi/tables.wgsl", entry, label, &entries)
        };
        Ok(DobashiTables {
            planes_pipeline: pipeline("planes", "the dobashi plane tables")?,
            spheres_pipeline: pipeline("spheres", "the dobashi sphere tables")?,
            params: uniform_buffer(
                &gpu.device,
                "dobashi tables",
                size_of::<DobashiTableUniform>(),
            ),
            rows: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("dobashi sphere rows"),
                size: (16 * rows) as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            planes: SegmentTextures::new(
                gpu,
                "planes",
                settings.table_angles as u32,
                settings.table_heights as u32,
            ),
            spheres: SegmentTextures::new(
                gpu,
                "spheres",
                settings.sphere_table_angles as u32,
                rows as u32,
            ),
        })
    }

    /// Whether these tables have the sizes of `settings`.
    pub fn fits(&self, settings: &DobashiSettings) -> bool {
        let (p, s) = (&self.planes.scatter_r, &self.spheres.scatter_r);
        (p.width(), p.height(), s.width(), s.height())
            == (
                settings.table_angles as u32,
                settings.table_heights as u32,
                settings.sphere_table_angles as u32,
                3 * settings.spheres as u32,
            )
    }

    /// Uploads the interval and the sphere rows of `atmosphere` (whose uniform is in the
    /// buffer `atmosphere_buffer`) and records the build of the plane tables (`spheres`
    /// false) or of the sphere tables.
    #[allow(clippy::too_many_arguments)]
    pub fn encode(
        &self,
        gpu: &GpuContext,
        atmosphere_buffer: &wgpu::Buffer,
        interval_m: f64,
        rows: &[[f32; 4]],
        spheres: bool,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let params = DobashiTableUniform {
            interval_m: interval_m as f32,
            plane_panels: PLANE_PANELS,
            sphere_panels: SPHERE_PANELS,
            pad0: 0,
        };
        gpu.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        gpu.queue
            .write_buffer(&self.rows, 0, bytemuck::cast_slice(rows));
        let (pipeline, textures, label) = if spheres {
            (
                &self.spheres_pipeline,
                &self.spheres,
                "dobashi sphere tables",
            )
        } else {
            (&self.planes_pipeline, &self.planes, "dobashi plane tables")
        };
        let views = textures.all().map(|t| t.create_view(&Default::default()));
        let bind_group = pipeline.bind_group(
            gpu,
            &[
                atmosphere_buffer.as_entire_binding(),
                self.params.as_entire_binding(),
                self.rows.as_entire_binding(),
                wgpu::BindingResource::TextureView(&views[0]),
                wgpu::BindingResource::TextureView(&views[1]),
                wgpu::BindingResource::TextureView(&views[2]),
            ],
        );
        let t = &textures.scatter_r;
        let groups = texel_groups(t);
        pipeline.dispatch(encoder, label, &bind_group, groups, timestamps);
    }

    /// Bytes held by the tables.
    pub fn bytes(&self) -> u64 {
        self.planes.bytes() + self.spheres.bytes()
    }

    /// The sphere rows as last uploaded.
    pub fn rows(&self) -> &wgpu::Buffer {
        &self.rows
    }
}

/// WGSL `DobashiParams`, 32 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct DobashiUniform {
    pub interval_m: f32,
    pub use_spheres: u32,
    pub ambient_on: u32,
    /// 0: all orders.
    pub max_orders: u32,
    pub ambient_directions: u32,
    pub spheres: u32,
    pub pad0: u32,
    pub pad1: u32,
}

/// Whether a camera at `camera_radius_m` renders with sample spheres
/// (`Tracer::uses_spheres`): above the atmosphere, and needing more than `max_planes`
/// planes of `interval_m` to cover what it sees.
pub fn uses_spheres(
    atmosphere: &Atmosphere,
    settings: &DobashiSettings,
    interval_m: f64,
    camera_radius_m: f64,
) -> bool {
    let (bottom, top) = (atmosphere.bottom_radius_m, atmosphere.top_radius_m);
    let r = camera_radius_m.max(bottom);
    let t_max = ((r - bottom) * (r + bottom)).sqrt() + ((top - bottom) * (top + bottom)).sqrt();
    let t_min = (r - top).max(0.0);
    r > top && (t_max - t_min) / interval_m + 1.0 > settings.max_planes as f64
}

/// The settings the plane and sphere tables depend on.
fn table_key(s: &DobashiSettings) -> [usize; 5] {
    [
        s.planes,
        s.spheres,
        s.table_heights,
        s.table_angles,
        s.sphere_table_angles,
    ]
}

/// The settings the ambient table depends on besides the tables'.
fn ambient_key(s: &DobashiSettings) -> [usize; 2] {
    [s.ambient_directions, s.ambient_sun_angles]
}

/// The g_l table and the atmosphere it was built from.
#[derive(Debug)]
struct GlTable {
    pass: TransmittancePass,
    built_from: Option<Atmosphere>,
}

/// What the ambient table was built from: the atmosphere, the table settings, the
/// ambient settings and the orders.
type AmbientKey = (Atmosphere, [usize; 5], [usize; 2], Option<u32>);

/// Pipelines and uniforms, made once; tables remade when their sizes change.
#[derive(Debug)]
pub struct DobashiPass {
    pass_pipeline: PixelPipeline,
    ambient_pipeline: ComputePipeline,
    params: wgpu::Buffer,
    /// psi per sun cosine, `ambient_sun_angles` x 1 texels (made by `plan`).
    ambient: Option<wgpu::Texture>,
    /// The unit ambient radiance the ambient build's rays see: 2 x 1 texels of ones.
    unit_ambient: wgpu::Texture,
    ambient_from: Option<AmbientKey>,
    g_l: Option<GlTable>,
    tables: Option<DobashiTables>,
    tables_from: Option<(Atmosphere, [usize; 5])>,
    /// The frame being planned.
    atmosphere: AtmosphereUniform,
    atmosphere_value: Option<Atmosphere>,
    settings: DobashiSettings,
    max_orders: Option<u32>,
    interval_m: f64,
    rows: Vec<[f32; 4]>,
    /// How the ambient table and the pass read the tables.
    sampling: TableSampling,
}

impl DobashiPass {
    pub fn new(gpu: &GpuContext) -> Result<DobashiPass, GpuError> {
        use wgpu::TextureViewDimension::D2;
        // g_l and the six segment tables may be sampled (`table_sampling`).
        let sampling = TableSampling::new(gpu);
        let mut entries = vec![
            uniform_entry(0, size_of::<AtmosphereUniform>()),
            uniform_entry(1, size_of::<FrameUniform>()),
            uniform_entry(2, size_of::<DobashiUniform>()),
            sampling.sampler_entry(),
        ];
        entries.extend((3..10).map(|b| sampling.texture_entry(b, D2)));
        entries.push(read_only_storage_buffer_entry(10, 16));
        // The ambient table read at 11 (by the build, a table of ones), and at 12 what
        // each writes.
        entries.push(sampling.texture_entry(11, D2));
        let constants = [sampling.constant()];
        let mut ambient_entries = entries.clone();
        ambient_entries.push(storage_texture_entry(12, TABLE_FORMAT, D2));
        let ambient_pipeline = ComputePipeline::with_constants(
            gpu,
            "sky/dobashi/ambient.wgsl",
            "main",
            "the dobashi ambient table",
            &ambient_entries,
            &constants,
        )?;
        entries.push(storage_texture_entry(12, HDR_FORMAT, D2));
        entries.extend(SurfaceBuffer::layout_entries());
        let pass_pipeline = PixelPipeline::with_constants(
            gpu,
            "sky/dobashi/pixel.wgsl",
            "main",
            "the dobashi pass",
            &entries,
            &constants,
        )?;
        Ok(DobashiPass {
            pass_pipeline,
            ambient_pipeline,
            params: uniform_buffer(&gpu.device, "dobashi", size_of::<DobashiUniform>()),
            ambient: None,
            unit_ambient: unit_ambient_texture(gpu),
            ambient_from: None,
            g_l: None,
            tables: None,
            tables_from: None,
            atmosphere: AtmosphereUniform::default(),
            atmosphere_value: None,
            settings: DobashiSettings::default(),
            max_orders: None,
            interval_m: 0.0,
            rows: Vec::new(),
            sampling,
        })
    }

    /// The resources of the ambient build (`hdr` none) and the per-pixel pass from
    /// binding 0 to 12 and the table sampler: at 11 the ambient table they read (the
    /// unit table for the build), at 12 what they write (the ambient table, the HDR
    /// target); the pass's frame surface at 30 and 31.
    fn bind_group(
        &self,
        gpu: &GpuContext,
        pipeline: &ComputePipeline,
        io: &PassIo<'_>,
        hdr: Option<&wgpu::TextureView>,
    ) -> wgpu::BindGroup {
        let (Some(g_l), Some(tables), Some(ambient)) = (
            self.g_l.as_ref(),
            self.tables.as_ref(),
            self.ambient.as_ref(),
        ) else {
            unreachable!("plan makes every table before any step");
        };
        let mut views = vec![g_l.pass.texture().create_view(&Default::default())];
        for t in tables.planes.all().into_iter().chain(tables.spheres.all()) {
            views.push(t.create_view(&Default::default()));
        }
        let ambient = ambient.create_view(&Default::default());
        let unit_ambient = self.unit_ambient.create_view(&Default::default());
        // The build reads the unit table and writes the ambient table; the pass reads
        // the ambient table and writes the HDR target.
        let (ambient_in, out) = match hdr {
            Some(hdr) => (&ambient, hdr),
            None => (&unit_ambient, &ambient),
        };
        let mut resources = vec![
            io.atmosphere.as_entire_binding(),
            io.frame.as_entire_binding(),
            self.params.as_entire_binding(),
        ];
        resources.extend(views.iter().map(wgpu::BindingResource::TextureView));
        resources.push(tables.rows().as_entire_binding());
        resources.push(wgpu::BindingResource::TextureView(ambient_in));
        resources.push(wgpu::BindingResource::TextureView(out));
        let surface = hdr.map(|_| io.surface);
        self.sampling.bind_group(gpu, pipeline, &resources, surface)
    }
}

/// A table of ones in the ambient table's place: psi = 1 at every sun angle.
fn unit_ambient_texture(gpu: &GpuContext) -> wgpu::Texture {
    let texture = texture_2d(
        &gpu.device,
        "dobashi unit ambient",
        (2, 1),
        TABLE_FORMAT,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    gpu.queue.write_texture(
        texture.as_image_copy(),
        bytemuck::cast_slice(&[[1.0f32; 4]; 2]),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(32),
            rows_per_image: None,
        },
        texture.size(),
    );
    texture
}

/// The ambient table's texture of `sun_angles` x 1 texels, or why this GPU cannot hold it.
fn ambient_texture(gpu: &GpuContext, sun_angles: usize) -> Result<wgpu::Texture, RenderError> {
    let largest = gpu.device.limits().max_texture_dimension_2d;
    let width = u32::try_from(sun_angles)
        .ok()
        .filter(|&n| n <= largest)
        .ok_or_else(|| {
            RenderError::Unsupported(format!(
                "dobashi ambient_sun_angles = {sun_angles} (this GPU's largest texture side is {largest})"
            ))
        })?;
    Ok(texture_2d(
        &gpu.device,
        "dobashi ambient",
        (width, 1),
        TABLE_FORMAT,
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
    ))
}

impl ModelPass for DobashiPass {
    fn plan(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
        plan: &mut FramePlan,
    ) -> Result<(), RenderError> {
        check_wavelengths(&frame.settings.wavelengths_nm)?;
        let settings = DobashiSettings::from_options(&frame.settings.options)?;
        let atmosphere = &frame.atmosphere;
        let interval_m = plane_interval_m(atmosphere, &settings)?;
        let max_orders = frame.settings.max_orders;
        self.atmosphere = AtmosphereUniform::new(atmosphere, RGB_WAVELENGTHS_NM)?;

        let gl_size = (
            settings.sun_table_angles as u32,
            settings.sun_table_heights as u32,
        );
        if self
            .g_l
            .as_ref()
            .is_none_or(|t| (t.pass.texture().width(), t.pass.texture().height()) != gl_size)
        {
            self.g_l = Some(GlTable {
                pass: TransmittancePass::with(gpu, TableOutput::Columns, gl_size.0, gl_size.1)?,
                built_from: None,
            });
        }
        let changed =
            |old: &Atmosphere, inputs: Inputs| Inputs::changed(old, atmosphere).intersects(inputs);
        let gl_stale = self.g_l.as_ref().is_none_or(|t| {
            t.built_from
                .as_ref()
                .is_none_or(|old| changed(old, Inputs::COLUMNS))
        });

        let key = table_key(&settings);
        if self.tables.as_ref().is_none_or(|t| !t.fits(&settings)) {
            self.tables = Some(DobashiTables::new(gpu, &settings)?);
            self.tables_from = None;
        }
        let tables_stale = self
            .tables_from
            .as_ref()
            .is_none_or(|(old, old_key)| *old_key != key || changed(old, PlaneTables::INPUTS));

        let ambient_on = max_orders != Some(1);
        if self
            .ambient
            .as_ref()
            .is_none_or(|t| t.width() as usize != settings.ambient_sun_angles)
        {
            self.ambient = Some(ambient_texture(gpu, settings.ambient_sun_angles)?);
            self.ambient_from = None;
        }
        let ambient_settings = ambient_key(&settings);
        let ambient_stale = ambient_on
            && (gl_stale
                || tables_stale
                || self
                    .ambient_from
                    .as_ref()
                    .is_none_or(|(old, k, a, orders)| {
                        (*k, *a, *orders) != (key, ambient_settings, max_orders)
                            || changed(old, AmbientTable::INPUTS)
                    }));

        self.settings = settings;
        self.max_orders = max_orders;
        self.interval_m = interval_m;
        self.atmosphere_value = Some(atmosphere.clone());
        if tables_stale {
            self.rows = sphere_rows(atmosphere, settings.spheres);
        }
        plan.build_if("g_l", gl_stale);
        plan.build_if("plane_tables", tables_stale);
        plan.build_if("sphere_tables", tables_stale);
        if ambient_on {
            plan.build_if("ambient", ambient_stale);
        } else {
            plan.skip("ambient", "single scattering (max_orders = 1)");
        }
        plan.run("dobashi", StepKind::Pass);

        let params = DobashiUniform {
            interval_m: interval_m as f32,
            use_spheres: u32::from(uses_spheres(
                atmosphere,
                &settings,
                interval_m,
                frame.camera_position_m.length(),
            )),
            ambient_on: u32::from(ambient_on),
            max_orders: max_orders.unwrap_or(0),
            ambient_directions: settings.ambient_directions as u32,
            spheres: settings.spheres as u32,
            pad0: 0,
            pad1: 0,
        };
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
        let (Some(g_l), Some(tables), Some(atmosphere)) = (
            self.g_l.as_mut(),
            self.tables.as_ref(),
            self.atmosphere_value.as_ref(),
        ) else {
            unreachable!("plan makes every table before any step");
        };
        match step {
            "g_l" => {
                g_l.pass.encode(gpu, &self.atmosphere, encoder, timestamps);
                g_l.built_from = Some(atmosphere.clone());
            }
            "plane_tables" | "sphere_tables" => {
                let spheres = step == "sphere_tables";
                tables.encode(
                    gpu,
                    io.atmosphere,
                    self.interval_m,
                    &self.rows,
                    spheres,
                    encoder,
                    timestamps,
                );
                if spheres {
                    self.tables_from = Some((atmosphere.clone(), table_key(&self.settings)));
                }
            }
            "ambient" => {
                let bind_group = self.bind_group(gpu, &self.ambient_pipeline, io, None);
                let groups = [(self.settings.ambient_sun_angles as u32).div_ceil(8), 1, 1];
                self.ambient_pipeline.dispatch(
                    encoder,
                    "dobashi ambient",
                    &bind_group,
                    groups,
                    timestamps,
                );
                self.ambient_from = Some((
                    atmosphere.clone(),
                    table_key(&self.settings),
                    ambient_key(&self.settings),
                    self.max_orders,
                ));
            }
            "dobashi" => {
                let hdr = io.hdr.create_view(&Default::default());
                let pipeline = self.pass_pipeline.variant(io.has_surface);
                let bind_group = self.bind_group(gpu, pipeline, io, Some(&hdr));
                let groups = texel_groups(io.hdr);
                pipeline.dispatch(encoder, "dobashi", &bind_group, groups, timestamps);
            }
            other => unreachable!("the dobashi plan has no step {other}"),
        }
    }

    fn table_bytes(&self) -> u64 {
        let g_l = self.g_l.as_ref().map_or(0, |t| {
            let texture = t.pass.texture();
            u64::from(texture.width()) * u64::from(texture.height()) * 16
        });
        g_l + self.tables.as_ref().map_or(0, DobashiTables::bytes)
            + self
                .ambient
                .as_ref()
                .map_or(0, |t| 16 * u64::from(t.width()))
    }
}
