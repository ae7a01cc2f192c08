//! The bruneton model behind the [`ModelPass`] trait: the frame's plan (which tables its
//! atmosphere makes stale, which share of a progressive build it records) and the
//! recording of each step.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::presets::earth;
use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::models::bruneton::BrunetonSettings;

use crate::frame::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::sky::bruneton::encode::StepEncoder;
use crate::sky::bruneton::order_state::OrderState;
use crate::sky::bruneton::orders::encode_orders;
use crate::sky::bruneton::pipelines::Pipelines;
use crate::sky::bruneton::progressive::{Recording, Share};
use crate::sky::bruneton::step::BrunetonStep;
use crate::sky::bruneton::tables::Tables;
use crate::sky::bruneton::uniform::BrunetonUniform;
use crate::sky::model_pass::{ModelPass, StepContext, frame_atmosphere};
use crate::sky::steps::SkyPlan;
use crate::sky::table_sampling::TableSampling;

/// What the last plan decided for the frame whose steps are encoded.
#[derive(Debug)]
pub(super) struct PlannedFrame {
    /// The frame's atmosphere, as the tables are built from it.
    pub atmosphere: Atmosphere,
    /// The same as the shaders read it.
    pub atmosphere_uniform: AtmosphereUniform,
    /// Whether Mie is computed (`Spectra::needs_mie`), or was in the tables as built.
    pub mie: bool,
    /// The part of the loop over orders recorded, when the plan lists it.
    pub recording: Recording,
    /// Whether the camera is inside the atmosphere (the view slice and the `inside`
    /// pass).
    pub inside: bool,
}

/// The steps' pipelines and the tables; see the module documentation of
/// [`crate::sky::bruneton`].
#[derive(Debug)]
pub struct BrunetonPass {
    pub(super) pipelines: Pipelines,
    /// How the pass reads its tables.
    pub(super) sampling: TableSampling,
    /// The tables at the last plan's sizes (the defaults' before the first plan).
    pub(super) tables: Tables,
    /// What the last plan decided (an Earth frame before the first plan).
    pub(super) frame: PlannedFrame,
    /// Whether the loop over orders is spread over frames ([`ModelPass::set_progressive`]).
    progressive: bool,
    /// The most bytes one binding of the store covers (`store_chunks.rs`).
    store_binding_bytes: u64,
}

impl BrunetonPass {
    /// The pass with its tables at the default settings' sizes, none built yet.
    pub fn new(gpu: &GpuContext) -> Result<BrunetonPass, RenderError> {
        let limit = gpu.device.limits().max_storage_buffer_binding_size;
        BrunetonPass::with_store_binding(gpu, limit)
    }

    /// The pass with the store of the tables it plans bound in ranges of at most
    /// `binding_bytes` (the device's largest storage buffer binding where that is less),
    /// so that a test may split small tables over several bindings; the default settings'
    /// tables, made now and unbuilt, are bound as [`BrunetonPass::new`] binds them.
    pub fn with_store_binding(
        gpu: &GpuContext,
        binding_bytes: u64,
    ) -> Result<BrunetonPass, RenderError> {
        let limit = gpu.device.limits().max_storage_buffer_binding_size;
        // The pass may sample the columns table, the view slice and E.
        let sampling = TableSampling::new(gpu);
        let settings = BrunetonSettings::default();
        let atmosphere = earth();
        Ok(BrunetonPass {
            pipelines: Pipelines::new(gpu, &sampling)?,
            sampling,
            tables: Tables::new(gpu, &settings, settings.order_limit, limit)?,
            frame: PlannedFrame {
                atmosphere_uniform: AtmosphereUniform::new(&atmosphere, RGB_WAVELENGTHS_NM)?,
                atmosphere,
                mie: true,
                recording: Recording::All,
                inside: true,
            },
            progressive: false,
            store_binding_bytes: binding_bytes,
        })
    }
}

impl ModelPass for BrunetonPass {
    type Step = BrunetonStep;

    fn plan(&mut self, plan: &mut SkyPlan<'_, BrunetonStep>) -> Result<(), RenderError> {
        let (gpu, frame) = (plan.gpu, plan.frame);
        let atmosphere_uniform = frame_atmosphere(frame)?;
        let settings = BrunetonSettings::from_options(&frame.settings.options)?;
        let max_orders = frame.settings.max_orders.unwrap_or(settings.order_limit);
        let binding_bytes = self.store_binding_bytes;
        if self.tables.settings != settings
            || self.tables.max_orders != max_orders
            || self.tables.binding_bytes != binding_bytes
        {
            self.tables = Tables::new(gpu, &settings, max_orders, binding_bytes)?;
        }
        let tables = &mut self.tables;
        let atmosphere = &frame.atmosphere;
        let stale = tables.built.stale(atmosphere, tables.settings.sun_disk);
        // The loop over orders starts again when its inputs changed, and a progressive
        // build under way is done in one go once progressive building is off.
        let orders = stale.orders || (tables.next.is_some() && !self.progressive);
        // Before an order after the second, whether the GPU has ended the loop (a read of
        // its state, the last frame's work done): the orders after it would add nothing.
        let ask = !orders && tables.next.is_some_and(|n| n.part == 0 && n.order > 2);
        let ended = ask && tables.read_state(gpu)?.running == 0;
        if orders || ended {
            tables.next = None;
        }
        let recording = match (self.progressive, orders) {
            (false, true) => Some(Recording::All),
            (true, true) => Some(Recording::Share(Share::FIRST)),
            (_, false) => tables.next.map(Recording::Share),
        };
        let (slices, max_orders) = (tables.slices, tables.max_orders);
        let refresh = recording.is_some_and(|r| r.ends_order(slices));
        plan.build_if(BrunetonStep::Transmittance, stale.columns);
        plan.build_if(BrunetonStep::Density, stale.columns);
        plan.build_if(BrunetonStep::SunTransmittance, stale.sun);
        plan.build_if(BrunetonStep::SingleScattering, stale.single);
        plan.build_if(BrunetonStep::ScatteringOrders, recording.is_some());
        plan.build_if(BrunetonStep::ScatteringTexture, refresh);
        let inside = frame.camera_position_m.length() <= atmosphere.top_radius_m;
        if inside {
            plan.run(BrunetonStep::ViewSlice);
        }
        plan.run(BrunetonStep::Render);
        plan.set_building(match recording {
            Some(Recording::Share(s)) if s.after(slices, max_orders).is_some() => {
                Some(s.describe(slices, max_orders))
            }
            _ => None,
        });
        // Mie pruning as built (a frame that rebuilds nothing renders what was built).
        let mie = if orders {
            Spectra::new(atmosphere, RGB_WAVELENGTHS_NM.as_slice()).needs_mie(frame.settings.prune)
        } else {
            tables.built.mie()
        };
        let uniform = BrunetonUniform::new(
            &tables.settings,
            &tables.layout,
            &tables.chunks,
            max_orders,
            atmosphere,
            mie,
        );
        tables.write_params(gpu, &uniform);
        if orders {
            let irradiance_texels = uniform.irradiance_texels;
            let state = OrderState::initial(tables.settings.scattering_size, irradiance_texels);
            gpu.write_uniform(&tables.state, &state);
        }
        self.frame = PlannedFrame {
            atmosphere: atmosphere.clone(),
            atmosphere_uniform,
            mie,
            recording: recording.unwrap_or(Recording::All),
            inside,
        };
        Ok(())
    }

    /// Records `step` of the last plan into `cx`, and notes what the tables it builds were
    /// built from.
    fn encode(&mut self, step: BrunetonStep, cx: StepContext<'_>) {
        let StepContext {
            gpu,
            io,
            encoder,
            timestamps,
        } = cx;
        let (tables, frame) = (&mut self.tables, &self.frame);
        let steps = StepEncoder {
            gpu,
            io,
            tables,
            pipelines: &self.pipelines,
            sampling: &self.sampling,
        };
        let atmosphere = &frame.atmosphere_uniform;
        match step {
            BrunetonStep::Transmittance => {
                tables.columns.encode(gpu, atmosphere, encoder, timestamps)
            }
            BrunetonStep::SunTransmittance => tables
                .transmittance
                .encode(gpu, atmosphere, encoder, timestamps),
            BrunetonStep::Density => steps.density(encoder, timestamps),
            BrunetonStep::SingleScattering => steps.single_scattering(encoder, timestamps),
            BrunetonStep::ScatteringOrders => encode_orders(
                gpu,
                io,
                tables,
                &self.pipelines,
                frame.recording,
                encoder,
                timestamps,
            ),
            BrunetonStep::ScatteringTexture => steps.scattering_texture(encoder, timestamps),
            BrunetonStep::ViewSlice => steps.view_slice(encoder, timestamps),
            BrunetonStep::Render => steps.render(frame.inside, encoder, timestamps),
        }
        let built = &mut tables.built;
        let atmosphere = || Some(frame.atmosphere.clone());
        match step {
            BrunetonStep::Transmittance => built.columns = atmosphere(),
            BrunetonStep::SunTransmittance => built.sun = atmosphere(),
            BrunetonStep::SingleScattering => built.single = atmosphere(),
            BrunetonStep::ScatteringOrders => {
                if frame.recording.starts() {
                    built.orders = Some((frame.atmosphere.clone(), frame.mie));
                }
                tables.next = frame.recording.next(tables.slices, tables.max_orders);
            }
            BrunetonStep::Density
            | BrunetonStep::ScatteringTexture
            | BrunetonStep::ViewSlice
            | BrunetonStep::Render => {}
        }
    }

    /// On: the loop over orders spreads over frames: the first frame builds every table
    /// up to single scattering (S's multiple part zero), each later one a share of an
    /// order ([`Share`]: Delta J and Delta E, then each Delta S slice, the last with the
    /// order's accumulation), the scattering textures refreshed after each order, until
    /// the order limit or the GPU's end of the loop. Off: the whole build in one frame;
    /// a build under way is finished at the next frame.
    fn set_progressive(&mut self, on: bool) {
        self.progressive = on;
    }

    fn table_bytes(&self) -> u64 {
        self.tables.bytes()
    }
}
