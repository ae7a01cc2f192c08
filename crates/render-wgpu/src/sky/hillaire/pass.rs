//! The hillaire model's pipelines, its plan (which tables a frame rebuilds, as the CPU's
//! `Hillaire::update` decides) and the encoding of its steps.

use atmosphere_core::models::hillaire::HillaireSettings;
use atmosphere_core::models::hillaire::view_cache::view_key;

use crate::frame::Frame;
use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::ground_in_view::ground_within;
use crate::frame::plan::FramePlan;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::{
    ComputePipeline, storage_texture_entry, texel_groups, texture_entry, uniform_buffer,
    uniform_entry,
};
use crate::gpu::readback::read_texture;
use crate::shafts::terrain::uniform::ShadowMapUniform;
use crate::sky::hillaire::step::HillaireStep;
use crate::sky::hillaire::tables::{Source, Table, Tables};
use crate::sky::hillaire::uniform::HillaireUniform;
use crate::sky::model_pass::{ModelPass, StepContext, frame_atmosphere};
use crate::sky::pixel_pass::{PixelPass, PixelShader};
use crate::sky::sky_pass::build_tables;
use crate::sky::steps::SkyPlan;
use crate::sky::table_sampling::TableSampling;
use crate::sky::transmittance::TABLE_FORMAT;

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
    pass: [PixelPass; 3],
    params: wgpu::Buffer,
    tables: Tables,
    /// The atmosphere of the frame being planned, in the GPU's layout, and what the
    /// tables it builds are built from.
    atmosphere: AtmosphereUniform,
    pending: Option<Source>,
    /// The entry point of `pass` the frame being planned uses.
    variant: usize,
    /// How the table builds read their tables.
    sampling: TableSampling,
}

impl HillairePass {
    /// The pipelines and unbuilt tables of the default settings' sizes.
    pub fn new(gpu: &GpuContext) -> Result<HillairePass, RenderError> {
        use wgpu::TextureViewDimension::{D2, D3};
        let sampling = TableSampling::new(gpu);
        // Bindings 0-4 of every hillaire table build: atmosphere, frame (unused),
        // `HillaireParams`, the transmittance table and Psi_ms; and the table sampler.
        // The tables that are read may be sampled.
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
        let pass_tables = [
            sampling.texture_entry(3, D2),
            psi,
            texture_entry(5, D2),
            sampling.texture_entry(6, D2),
            sampling.texture_entry(7, D3),
            sampling.texture_entry(8, D3),
            // The terrain's shadow map for light shafts (`sky/hillaire/shafts.wgsl`).
            texture_entry(9, D2),
            uniform_entry(10, size_of::<ShadowMapUniform>()),
        ];
        let pass = |entry| {
            PixelPass::new(
                gpu,
                PixelShader {
                    path: "sky/hillaire/pixel.wgsl",
                    entry,
                    label: "the hillaire pass",
                    params_size: size_of::<HillaireUniform>(),
                    tables: &pass_tables,
                    sampling: Some(&sampling),
                },
            )
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
            pass: [pass("main")?, pass("tables_only")?, pass("from_space")?],
            params: uniform_buffer(&gpu.device, "hillaire", size_of::<HillaireUniform>()),
            tables: Tables::new(gpu, HillaireSettings::default())?,
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
        build_tables(self, gpu, frame)
    }

    /// A table's texels as last built, row-major (a volume's slices one after another;
    /// the volume's radiance: [`HillairePass::read_aerial_transmittance`] has the rest).
    pub fn read_table(&self, gpu: &GpuContext, table: Table) -> Result<Vec<[f32; 4]>, RenderError> {
        read_texels(gpu, self.tables.texture(table))
    }

    /// The aerial-perspective volume's transmittance, laid out as its radiance.
    pub fn read_aerial_transmittance(
        &self,
        gpu: &GpuContext,
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        read_texels(gpu, &self.tables.aerial_transmittance)
    }

    /// Records the build of `table` (bindings 0-4 as in [`HillairePass::new`], the
    /// table's outputs after them).
    fn encode_table(&self, table: Table, cx: StepContext<'_>) {
        let tables = &self.tables;
        let (pipeline, outputs, groups) = match table {
            Table::Transmittance => {
                let columns = &tables.transmittance;
                columns.encode(cx.gpu, &self.atmosphere, cx.encoder, cx.timestamps);
                return;
            }
            Table::MultipleScattering => {
                // Psi_ms is written at binding 4, where the others read it.
                let t = &tables.multiple_scattering;
                (
                    &self.multiple_scattering,
                    vec![],
                    [
                        t.width(),
                        tables.settings.multiple_scattering_size.1 as u32,
                        1,
                    ],
                )
            }
            Table::GroundIrradiance => {
                let t = &tables.ground_irradiance;
                (&self.ground_irradiance, vec![t], [t.width(), 1, 1])
            }
            Table::SkyView => (
                &self.sky_view,
                vec![&tables.sky_view],
                texel_groups(&tables.sky_view),
            ),
            Table::AerialPerspective => (
                &self.aerial_perspective,
                vec![&tables.aerial_radiance, &tables.aerial_transmittance],
                texel_groups(&tables.aerial_radiance),
            ),
        };
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let inputs = [tables.transmittance.texture(), &tables.multiple_scattering].map(view);
        let outputs: Vec<_> = outputs.into_iter().map(view).collect();
        let mut resources = vec![
            cx.io.atmosphere.as_entire_binding(),
            cx.io.frame.as_entire_binding(),
            self.params.as_entire_binding(),
        ];
        resources.extend(
            inputs
                .iter()
                .chain(&outputs)
                .map(wgpu::BindingResource::TextureView),
        );
        let bind_group = self.sampling.bind_group(cx.gpu, pipeline, &resources);
        pipeline.dispatch(cx.encoder, table.name(), &bind_group, groups, cx.timestamps);
    }
}

/// The texels of `texture`, row-major, waiting for the GPU.
fn read_texels(gpu: &GpuContext, texture: &wgpu::Texture) -> Result<Vec<[f32; 4]>, RenderError> {
    let bytes = read_texture(gpu, texture, size_of::<[f32; 4]>() as u32)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}

impl ModelPass for HillairePass {
    type Step = HillaireStep;

    fn plan(&mut self, plan: &mut SkyPlan<'_, HillaireStep>) -> Result<(), RenderError> {
        let (gpu, frame) = (plan.gpu, plan.frame);
        self.atmosphere = frame_atmosphere(frame)?;
        let settings = HillaireSettings::from_options(&frame.settings.options)?;
        let a = &frame.atmosphere;
        let multiple_on = frame.settings.max_orders != Some(1);
        let camera = frame.camera_position_m;
        let r = camera.length();
        let (up, sun) = (camera / r, frame.sun_direction.normalize());
        let view = view_key(a, r, sun.dot(up));
        let params = HillaireUniform::new(&settings, a, view, (up, sun), multiple_on)?;
        if self.tables.settings != settings {
            self.tables = Tables::new(gpu, settings)?;
        }
        let source = Source {
            atmosphere: a.clone(),
            view,
            multiple_on,
        };
        let (built, settings) = (&self.tables.built, &self.tables.settings);
        let build_if_stale = |plan: &mut SkyPlan<'_, HillaireStep>, table: Table| {
            let stale = built[table as usize]
                .as_ref()
                .is_none_or(|old| old.stale_for(table, settings, &source));
            plan.build_if(HillaireStep::Table(table), stale);
        };
        let skip = |plan: &mut SkyPlan<'_, HillaireStep>, table, why| {
            plan.skip(HillaireStep::Table(table), why);
        };
        let inside = r <= a.top_radius_m;
        build_if_stale(plan, Table::Transmittance);
        for table in [Table::MultipleScattering, Table::GroundIrradiance] {
            if multiple_on {
                build_if_stale(plan, table);
            } else {
                skip(plan, table, "single scattering");
            }
        }
        if inside {
            build_if_stale(plan, Table::SkyView);
        } else {
            skip(plan, Table::SkyView, "camera above the atmosphere");
        }
        // A surface counts as ground in view, near and far: it may end any ray at any
        // distance, read from the volume within its range and marched beyond.
        if !inside {
            skip(
                plan,
                Table::AerialPerspective,
                "camera above the atmosphere",
            );
        } else if plan.surface() || ground_within(frame, settings.aerial_range_m) {
            build_if_stale(plan, Table::AerialPerspective);
        } else {
            skip(plan, Table::AerialPerspective, "no ground in view");
        }
        // Rays to the ground beyond the volume are marched; none when the horizon is
        // nearer than the volume's range or no ground is in view.
        let horizon_m = ((r - a.bottom_radius_m) * (r + a.bottom_radius_m)).sqrt();
        let far_ground = plan.surface()
            || horizon_m > settings.aerial_range_m * (1.0 - 1e-3)
                && ground_within(frame, f64::INFINITY);
        self.variant = match (inside, far_ground) {
            (true, true) => 0,
            (true, false) => 1,
            (false, _) => 2,
        };
        plan.run(HillaireStep::Pass);
        self.pending = Some(source);
        gpu.write_uniform(&self.params, &params);
        Ok(())
    }

    fn encode(&mut self, step: HillaireStep, cx: StepContext<'_>) {
        match step {
            HillaireStep::Table(table) => {
                self.encode_table(table, cx);
                self.tables.built[table as usize] = self.pending.clone();
            }
            HillaireStep::Pass => {
                let t = &self.tables;
                let views = [
                    t.transmittance.texture(),
                    &t.multiple_scattering,
                    &t.ground_irradiance,
                    &t.sky_view,
                    &t.aerial_radiance,
                    &t.aerial_transmittance,
                ]
                .map(|t| t.create_view(&Default::default()));
                let shadow = cx.io.shadow.view();
                let mut tables: Vec<_> = views
                    .iter()
                    .chain([&shadow])
                    .map(wgpu::BindingResource::TextureView)
                    .collect();
                tables.push(cx.io.shadow.params().as_entire_binding());
                self.pass[self.variant].encode(cx, &self.params, &tables);
            }
        }
    }

    fn table_bytes(&self) -> u64 {
        self.tables.bytes()
    }
}
