//! The dobashi model's pipelines, its plan (which tables a frame rebuilds) and the
//! encoding of its steps.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::dobashi::{AmbientTable, DobashiSettings, PlaneTables};
use bytemuck::{Pod, Zeroable};

use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::{
    ComputePipeline, read_only_storage_buffer_entry, storage_texture_entry, texture_entry,
    uniform_buffer, uniform_entry,
};
use crate::shafts::terrain::uniform::ShadowMapUniform;
use crate::sky::columns_table::ColumnsTable;
use crate::sky::dobashi::ambient::{
    AmbientKey, ambient_key, ambient_texture, unit_ambient_texture,
};
use crate::sky::dobashi::step::DobashiStep;
use crate::sky::dobashi::tables::{DobashiTables, plane_interval_m, sphere_rows, table_key};
use crate::sky::model_pass::{ModelPass, StepContext, frame_atmosphere};
use crate::sky::pixel_pass::{PixelPass, PixelShader};
use crate::sky::steps::SkyPlan;
use crate::sky::table_sampling::TableSampling;
use crate::sky::transmittance::TABLE_FORMAT;

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

/// What the segment tables were built from: the atmosphere and the table settings.
type TablesKey = (Atmosphere, [usize; 5]);

/// The size of g_l for `settings`: sun angles by heights.
fn gl_size(settings: &DobashiSettings) -> (u32, u32) {
    (
        settings.sun_table_angles as u32,
        settings.sun_table_heights as u32,
    )
}

/// Pipelines and uniforms, made once; tables remade when their sizes change.
#[derive(Debug)]
pub struct DobashiPass {
    pass: PixelPass,
    ambient_pipeline: ComputePipeline,
    params: wgpu::Buffer,
    /// psi per sun cosine, `ambient_sun_angles` x 1 texels.
    ambient: wgpu::Texture,
    /// The unit ambient radiance the ambient build's rays see: 2 x 1 texels of ones.
    unit_ambient: wgpu::Texture,
    /// What the ambient table was built from, and what its planned build is for.
    ambient_from: Option<AmbientKey>,
    ambient_pending: Option<AmbientKey>,
    g_l: ColumnsTable,
    tables: DobashiTables,
    /// What the segment tables were built from, and what their planned build is for.
    tables_from: Option<TablesKey>,
    tables_pending: Option<TablesKey>,
    /// The frame being planned.
    atmosphere: AtmosphereUniform,
    settings: DobashiSettings,
    interval_m: f64,
    rows: Vec<[f32; 4]>,
    /// How the ambient build reads the tables.
    sampling: TableSampling,
}

impl DobashiPass {
    /// The pipelines and unbuilt tables of the default settings' sizes.
    pub fn new(gpu: &GpuContext) -> Result<DobashiPass, RenderError> {
        use wgpu::TextureViewDimension::D2;
        // g_l and the six segment tables may be sampled (`table_sampling`); the ambient
        // table is read at 11 (by the build, a table of ones).
        let sampling = TableSampling::new(gpu);
        let mut tables: Vec<_> = (3..10).map(|b| sampling.texture_entry(b, D2)).collect();
        tables.push(read_only_storage_buffer_entry(10, 16));
        tables.push(sampling.texture_entry(11, D2));
        let mut ambient_entries = vec![
            uniform_entry(0, size_of::<AtmosphereUniform>()),
            uniform_entry(1, size_of::<FrameUniform>()),
            uniform_entry(2, size_of::<DobashiUniform>()),
            sampling.sampler_entry(),
            storage_texture_entry(12, TABLE_FORMAT, D2),
        ];
        ambient_entries.extend_from_slice(&tables);
        let ambient_pipeline = ComputePipeline::with_constants(
            gpu,
            "sky/dobashi/ambient.wgsl",
            "main",
            "the dobashi ambient table",
            &ambient_entries,
            &[sampling.constant()],
        )?;
        // The pass also reads the terrain's shadow map for light shafts at 12 and 13.
        let mut pass_tables = tables.clone();
        pass_tables.push(texture_entry(12, D2));
        pass_tables.push(uniform_entry(13, size_of::<ShadowMapUniform>()));
        let pass = PixelPass::new(
            gpu,
            PixelShader {
                path: "sky/dobashi/pixel.wgsl",
                entry: "main",
                label: "the dobashi pass",
                params_size: size_of::<DobashiUniform>(),
                tables: &pass_tables,
                sampling: Some(&sampling),
            },
        )?;
        let settings = DobashiSettings::default();
        Ok(DobashiPass {
            pass,
            ambient_pipeline,
            params: uniform_buffer(&gpu.device, "dobashi", size_of::<DobashiUniform>()),
            ambient: ambient_texture(gpu, settings.ambient_sun_angles)?,
            unit_ambient: unit_ambient_texture(gpu),
            ambient_from: None,
            ambient_pending: None,
            g_l: ColumnsTable::new(gpu, gl_size(&settings))?,
            tables: DobashiTables::new(gpu, &settings)?,
            tables_from: None,
            tables_pending: None,
            atmosphere: AtmosphereUniform::default(),
            settings,
            interval_m: 0.0,
            rows: Vec::new(),
            sampling,
        })
    }

    /// Bindings 3 to 11 of the ambient build and of the pass: g_l, the six segment
    /// tables and the sphere rows (in `views`, from [`DobashiPass::table_views`]), and at
    /// 11 the ambient table they read, `ambient_in`.
    fn inputs<'a>(
        &'a self,
        views: &'a [wgpu::TextureView],
        ambient_in: &'a wgpu::TextureView,
    ) -> Vec<wgpu::BindingResource<'a>> {
        let mut resources: Vec<_> = views
            .iter()
            .map(wgpu::BindingResource::TextureView)
            .collect();
        resources.push(self.tables.rows().as_entire_binding());
        resources.push(wgpu::BindingResource::TextureView(ambient_in));
        resources
    }

    /// Views of g_l and of the six segment tables, in binding order.
    fn table_views(&self) -> Vec<wgpu::TextureView> {
        let segments = self.tables.planes.all().into_iter();
        [self.g_l.texture()]
            .into_iter()
            .chain(segments.chain(self.tables.spheres.all()))
            .map(|t| t.create_view(&Default::default()))
            .collect()
    }

    /// Records the ambient build: it reads the unit table and writes the ambient table
    /// at binding 12.
    fn encode_ambient(&self, cx: StepContext<'_>) {
        let io = cx.io;
        let views = self.table_views();
        let unit = self.unit_ambient.create_view(&Default::default());
        let out = self.ambient.create_view(&Default::default());
        let mut resources = vec![
            io.atmosphere.as_entire_binding(),
            io.frame.as_entire_binding(),
            self.params.as_entire_binding(),
        ];
        resources.extend(self.inputs(&views, &unit));
        resources.push(wgpu::BindingResource::TextureView(&out));
        let pipeline = &self.ambient_pipeline;
        let bind_group = self.sampling.bind_group(cx.gpu, pipeline, &resources);
        // One workgroup per sun angle (`shaders/sky/dobashi/ambient.wgsl`).
        let groups = [self.settings.ambient_sun_angles as u32, 1, 1];
        let label = "dobashi ambient";
        pipeline.dispatch(cx.encoder, label, &bind_group, groups, cx.timestamps);
    }
}

impl ModelPass for DobashiPass {
    type Step = DobashiStep;

    fn plan(&mut self, plan: &mut SkyPlan<'_, DobashiStep>) -> Result<(), RenderError> {
        let (gpu, frame) = (plan.gpu, plan.frame);
        self.atmosphere = frame_atmosphere(frame)?;
        let settings = DobashiSettings::from_options(&frame.settings.options)?;
        let atmosphere = &frame.atmosphere;
        let interval_m = plane_interval_m(atmosphere, &settings)?;
        let max_orders = frame.settings.max_orders;

        self.g_l.fit(gpu, gl_size(&settings))?;
        let gl_stale = self.g_l.plan(atmosphere);

        let key = table_key(&settings);
        if !self.tables.fits(&settings) {
            self.tables = DobashiTables::new(gpu, &settings)?;
            self.tables_from = None;
        }
        let tables_stale = self.tables_from.as_ref().is_none_or(|(old, old_key)| {
            *old_key != key || PlaneTables::INPUTS.stale(Some(old), atmosphere)
        });

        let ambient_on = max_orders != Some(1);
        if self.ambient.width() as usize != settings.ambient_sun_angles {
            self.ambient = ambient_texture(gpu, settings.ambient_sun_angles)?;
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
                            || AmbientTable::INPUTS.stale(Some(old), atmosphere)
                    }));

        self.settings = settings;
        self.interval_m = interval_m;
        self.tables_pending = tables_stale.then(|| (atmosphere.clone(), key));
        self.ambient_pending =
            ambient_stale.then(|| (atmosphere.clone(), key, ambient_settings, max_orders));
        if tables_stale {
            self.rows = sphere_rows(atmosphere, settings.spheres);
        }
        plan.build_if(DobashiStep::GL, gl_stale);
        plan.build_if(DobashiStep::PlaneTables, tables_stale);
        plan.build_if(DobashiStep::SphereTables, tables_stale);
        if ambient_on {
            plan.build_if(DobashiStep::Ambient, ambient_stale);
        } else {
            plan.skip(DobashiStep::Ambient, "single scattering (max_orders = 1)");
        }
        plan.run(DobashiStep::Pass);

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
        gpu.write_uniform(&self.params, &params);
        Ok(())
    }

    fn encode(&mut self, step: DobashiStep, cx: StepContext<'_>) {
        match step {
            DobashiStep::GL => self.g_l.encode(&self.atmosphere, cx),
            DobashiStep::PlaneTables | DobashiStep::SphereTables => {
                let spheres = step == DobashiStep::SphereTables;
                self.tables.encode(
                    cx.gpu,
                    cx.io.atmosphere,
                    self.interval_m,
                    &self.rows,
                    spheres,
                    cx.encoder,
                    cx.timestamps,
                );
                if spheres && let Some(key) = self.tables_pending.take() {
                    self.tables_from = Some(key);
                }
            }
            DobashiStep::Ambient => {
                self.encode_ambient(cx);
                if let Some(key) = self.ambient_pending.take() {
                    self.ambient_from = Some(key);
                }
            }
            DobashiStep::Pass => {
                let views = self.table_views();
                let ambient = self.ambient.create_view(&Default::default());
                let shadow = cx.io.shadow.view();
                let mut tables = self.inputs(&views, &ambient);
                tables.push(wgpu::BindingResource::TextureView(&shadow));
                tables.push(cx.io.shadow.params().as_entire_binding());
                self.pass.encode(cx, &self.params, &tables);
            }
        }
    }

    fn table_bytes(&self) -> u64 {
        self.g_l.bytes() + self.tables.bytes() + 16 * u64::from(self.ambient.width())
    }
}
