//! The bruneton model on the GPU (Bruneton and Neyret 2008, seed 004): every table of
//! atmosphere-core's `bruneton` built in compute shaders as the CPU builds it, and the
//! per-pixel pass of `shaders/bruneton.wgsl`.
//!
//! Tables, in the order of the plan (step names; the shaders are `bruneton_*.wgsl`):
//! - `transmittance`: the columns of matter T(r, mu) (`transmittance_table.wgsl`,
//!   `columns`), the CPU's `TransmittanceTable`; and `sun_transmittance`, the same table
//!   as transmittances (entry point `main`), the CPU's `Builder::sun_transmittances`.
//! - `density`: the 8192-sample density table (`DensityTable`), copied into a 1D texture
//!   for the shaders' reads (lavapipe reads storage buffers lane by lane).
//! - `single_scattering`: Rayleigh and Mie without phase functions (paper Eq. 5).
//! - `scattering_orders`: Algorithm 4.1's loop: per order Delta J (moments per (r, mu_s),
//!   then every texel), Delta E, Delta S, their sums, the GPU's decision whether the order
//!   is added and whether the loop goes on (`bruneton_orders.wgsl`), S += Delta S and E
//!   += Delta E. Every order up to the limit is recorded; those after the loop's end
//!   dispatch no workgroups (indirect dispatch sizes written by the GPU), so nothing is
//!   read back.
//! - `scattering_texture`: S into three `Rgba32Float` 3D textures (single Rayleigh,
//!   single Mie, orders two and up) at (x = nu * mu_s_size + mu_s, y = mu, z = r), and E
//!   into a 2D texture (x = mu_s, y = r) for the pass's ground term.
//!
//! Passes, each frame: for a camera inside the atmosphere, `view_slice`
//! (`bruneton_view_slice.wgsl`): S interpolated at the camera's r and mu_s for every
//! (mu, nu) node, which the pass's `inside` entry point interpolates in mu and nu (4
//! texel reads per table and pixel instead of 16); then `bruneton`.
//!
//! Tables being built live in one storage buffer (the store), indexed as the CPU's, so a
//! table read back compares texel by texel. Rebuilds follow the CPU's `update`: the
//! columns and densities on [`Inputs::COLUMNS`], single scattering on
//! [`Inputs::EXTINCTION`], the orders also on the ground albedo and the Mie phase function
//! (unless Mie is pruned); the sun rebuilds nothing. Mie work is left out when
//! `Spectra::needs_mie` says so.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::bruneton::BrunetonSettings;
use atmosphere_core::bruneton::parameterization::ScatteringSize;
use atmosphere_core::bruneton::precompute::DeltaM;
use atmosphere_core::reference::Spectra;
use atmosphere_core::table_inputs::Inputs;
use bytemuck::{Pod, Zeroable};

use crate::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use crate::device::GpuContext;
use crate::error::{GpuError, RenderError};
use crate::frame::Frame;
use crate::frame_plan::{FramePlan, StepKind};
use crate::frame_uniform::FrameUniform;
use crate::model_pass::{ModelPass, PassIo};
use crate::nishita_pass::{HDR_FORMAT, check_wavelengths};
use crate::pipeline::{
    ComputePipeline, storage_buffer_entry, storage_texture_entry, texel_groups, texture_entry,
    uniform_buffer, uniform_entry,
};
use crate::readback::{map_and_read, read_texture};
use crate::transmittance_pass::{TableOutput, TransmittancePass};

/// Texels of a row of S (mu_s x nu) at most: the workgroup of the row shaders
/// (`ROW_TEXELS` of `bruneton_scattering.wgsl`).
pub const ROW_TEXELS: usize = 256;
/// The most orders the GPU loop records (`OrderState::shares` holds 64).
pub const MAX_ORDERS: u32 = 63;
/// Samples of the density table (`DensityTable::SAMPLES`).
const DENSITY_SAMPLES: u32 = 8192;
/// Workgroups of the partial sums (`SUM_GROUPS` of `bruneton_orders.wgsl`).
const SUM_GROUPS: u32 = 256;
/// The binding of the density table's texture (`bruneton_tables.wgsl`).
const DENSITY_BINDING: u32 = 12;
/// Invocations of the flat shaders' workgroups.
const FLAT: u32 = 64;

/// WGSL `BrunetonParams`, 128 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BrunetonUniform {
    pub size: [u32; 4],
    pub irradiance_size: [u32; 4],
    pub flags: [u32; 4],
    pub offsets_a: [u32; 4],
    pub offsets_b: [u32; 4],
    pub offsets_c: [u32; 4],
    pub delta_m: [f32; 4],
    pub density: [f32; 4],
}

/// WGSL `OrderState` (`bruneton_orders.wgsl`), 496 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct OrderState {
    pub totals: [f32; 4],
    pub previous_added: [f32; 4],
    pub order: u32,
    pub running: u32,
    pub last_order: u32,
    pub has_previous: u32,
    pub args: [[u32; 4]; 6],
    pub full: [[u32; 4]; 6],
    pub shares: [f32; 64],
}

/// The tables of the store, in its order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StoreTable {
    Density,
    SingleRayleigh,
    SingleMie,
    Multiple,
    DeltaS,
    DeltaJ,
    DeltaE,
    Irradiance,
    Moments,
    Partials,
}

/// Offsets and lengths (vec4 texels) of the store's tables.
#[derive(Clone, Copy, Debug, PartialEq)]
struct StoreLayout {
    offsets: [u32; 10],
    lengths: [u32; 10],
}

impl StoreLayout {
    fn new(s: ScatteringSize, irradiance: usize) -> StoreLayout {
        let n = s.texels() as u32;
        let e = irradiance as u32;
        let lengths = [
            DENSITY_SAMPLES,
            n,
            n,
            n,
            n,
            n,
            e,
            e,
            (7 * s.r * s.mu_s) as u32,
            SUM_GROUPS,
        ];
        let mut offsets = [0; 10];
        for k in 1..10 {
            offsets[k] = offsets[k - 1] + lengths[k - 1];
        }
        StoreLayout { offsets, lengths }
    }

    fn bytes(&self) -> u64 {
        u64::from(self.offsets[9] + self.lengths[9]) * 16
    }

    fn range(&self, table: StoreTable) -> (u64, u64) {
        let k = table as usize;
        (
            u64::from(self.offsets[k]) * 16,
            u64::from(self.lengths[k]) * 16,
        )
    }
}

/// What each table was last built from.
#[derive(Debug, Default)]
struct Built {
    columns: Option<Atmosphere>,
    sun: Option<Atmosphere>,
    single: Option<Atmosphere>,
    /// With whether Mie was computed.
    orders: Option<(Atmosphere, bool)>,
}

/// The tables of one set of sizes.
#[derive(Debug)]
struct Tables {
    settings: BrunetonSettings,
    max_orders: u32,
    layout: StoreLayout,
    columns: TransmittancePass,
    transmittance: TransmittancePass,
    store: wgpu::Buffer,
    state: wgpu::Buffer,
    /// The parameters of order 2 (`flags.z` = 1) and of every other step.
    params_first: wgpu::Buffer,
    params: wgpu::Buffer,
    /// Single Rayleigh, single Mie, multiple.
    textures: [wgpu::Texture; 3],
    /// E, copied from the store with S for the pass's reads.
    irradiance: wgpu::Texture,
    /// The density table, copied from the store for the shaders' reads.
    density: wgpu::Texture,
    /// Delta J as a 3D texture like S's, written with the store's copy, read by Delta S.
    delta_j: wgpu::Texture,
    /// S of the three textures at the camera's r and mu_s per (mu, nu) node, side by
    /// side (`bruneton_view_slice.wgsl`).
    view_slice: wgpu::Texture,
    built: Built,
}

/// The pipelines of every step.
#[derive(Debug)]
struct Pipelines {
    density: ComputePipeline,
    single: ComputePipeline,
    moments: ComputePipeline,
    scattering_density: ComputePipeline,
    irradiance: ComputePipeline,
    scattering: ComputePipeline,
    sum_single: ComputePipeline,
    sum_order: ComputePipeline,
    decide: ComputePipeline,
    accumulate: ComputePipeline,
    texture: ComputePipeline,
    view_slice: ComputePipeline,
    /// The pass for a camera above the atmosphere, and for one inside (after the view
    /// slice).
    render: ComputePipeline,
    render_inside: ComputePipeline,
}

/// The steps' pipelines and the tables; see the module documentation.
#[derive(Debug)]
pub struct BrunetonPass {
    pipelines: Pipelines,
    tables: Option<Tables>,
    uniform: BrunetonUniform,
    atmosphere: AtmosphereUniform,
    /// The frame's atmosphere and whether Mie is computed, while its steps are encoded.
    pending: Option<(Atmosphere, bool)>,
    /// Whether the frame's camera is inside the atmosphere (the view slice and the
    /// `inside` pass).
    inside: bool,
}

/// Bindings 0-5 and 12 of every bruneton shader: atmosphere, frame, parameters, the
/// columns table, the store, the transmittance table; the density table's texture.
fn common_entries(store_bytes: usize) -> Vec<wgpu::BindGroupLayoutEntry> {
    use wgpu::TextureViewDimension::{D1, D2};
    vec![
        texture_entry(DENSITY_BINDING, D1),
        uniform_entry(0, size_of::<AtmosphereUniform>()),
        uniform_entry(1, size_of::<FrameUniform>()),
        uniform_entry(2, size_of::<BrunetonUniform>()),
        texture_entry(3, D2),
        storage_buffer_entry(4, store_bytes),
        texture_entry(5, D2),
    ]
}

impl BrunetonPass {
    pub fn new(gpu: &GpuContext) -> Result<BrunetonPass, GpuError> {
        use wgpu::TextureViewDimension::{D2, D3};
        let common = common_entries(16);
        let with = |extra: &[wgpu::BindGroupLayoutEntry]| {
            let mut entries = common.clone();
            entries.extend_from_slice(extra);
            entries
        };
        let make = |shader, entry, label, entries: &[wgpu::BindGroupLayoutEntry]| {
            ComputePipeline::new(gpu, shader, entry, label, entries)
        };
        let order_entries = with(&[storage_buffer_entry(6, size_of::<OrderState>())]);
        let delta_j_out = with(&[storage_texture_entry(
            6,
            wgpu::TextureFormat::Rgba32Float,
            D3,
        )]);
        let delta_j_in = with(&[texture_entry(6, D3)]);
        let texture_entries = with(&[
            storage_texture_entry(6, wgpu::TextureFormat::Rgba32Float, D3),
            storage_texture_entry(7, wgpu::TextureFormat::Rgba32Float, D3),
            storage_texture_entry(8, wgpu::TextureFormat::Rgba32Float, D3),
            storage_texture_entry(9, wgpu::TextureFormat::Rgba32Float, D2),
        ]);
        let view_slice_entries = with(&[
            texture_entry(6, D3),
            texture_entry(7, D3),
            texture_entry(8, D3),
            storage_texture_entry(9, wgpu::TextureFormat::Rgba32Float, D2),
        ]);
        let render_entries = with(&[
            texture_entry(6, D3),
            texture_entry(7, D3),
            texture_entry(8, D3),
            storage_texture_entry(9, HDR_FORMAT, D2),
            texture_entry(10, D2),
            texture_entry(11, D2),
        ]);
        let pipelines = Pipelines {
            density: make("bruneton_density.wgsl", "main", "bruneton density", &common)?,
            single: make(
                "bruneton_single_scattering.wgsl",
                "main",
                "bruneton single scattering",
                &common,
            )?,
            moments: make(
                "bruneton_scattering_density.wgsl",
                "moments",
                "bruneton Delta J moments",
                &common,
            )?,
            scattering_density: make(
                "bruneton_scattering_density.wgsl",
                "main",
                "bruneton Delta J",
                &delta_j_out,
            )?,
            irradiance: make(
                "bruneton_irradiance.wgsl",
                "main",
                "bruneton Delta E",
                &common,
            )?,
            scattering: make(
                "bruneton_scattering.wgsl",
                "main",
                "bruneton Delta S",
                &delta_j_in,
            )?,
            sum_single: make(
                "bruneton_orders.wgsl",
                "sum_single",
                "bruneton sums",
                &common,
            )?,
            sum_order: make(
                "bruneton_orders.wgsl",
                "sum_order",
                "bruneton sums",
                &common,
            )?,
            decide: make(
                "bruneton_orders.wgsl",
                "decide",
                "bruneton order decision",
                &order_entries,
            )?,
            accumulate: make(
                "bruneton_orders.wgsl",
                "accumulate",
                "bruneton accumulation",
                &common,
            )?,
            texture: make(
                "bruneton_scattering_texture.wgsl",
                "main",
                "bruneton scattering texture",
                &texture_entries,
            )?,
            view_slice: make(
                "bruneton_view_slice.wgsl",
                "main",
                "bruneton view slice",
                &view_slice_entries,
            )?,
            render: make(
                "bruneton.wgsl",
                "main",
                "the bruneton pass",
                &render_entries,
            )?,
            render_inside: make(
                "bruneton.wgsl",
                "inside",
                "the bruneton pass",
                &render_entries,
            )?,
        };
        Ok(BrunetonPass {
            pipelines,
            tables: None,
            uniform: BrunetonUniform::default(),
            atmosphere: AtmosphereUniform::default(),
            pending: None,
            inside: false,
        })
    }

    /// The tables and their parameters for `settings`, or why the GPU cannot hold them.
    fn make_tables(
        gpu: &GpuContext,
        settings: &BrunetonSettings,
        max_orders: u32,
    ) -> Result<Tables, RenderError> {
        let s = settings.scattering_size;
        if s.mu_s * s.nu > ROW_TEXELS {
            return Err(RenderError::Unsupported(format!(
                "bruneton mu_s x nu = {} texels per row (the GPU's row workgroup holds {ROW_TEXELS})",
                s.mu_s * s.nu
            )));
        }
        if max_orders > MAX_ORDERS {
            return Err(RenderError::Unsupported(format!(
                "{max_orders} scattering orders (the GPU records at most {MAX_ORDERS})"
            )));
        }
        let (e_mu_s, e_r) = settings.irradiance_size;
        let layout = StoreLayout::new(s, e_mu_s * e_r);
        let limits = gpu.device.limits();
        let groups = (s.texels() as u64).div_ceil(u64::from(FLAT));
        if layout.bytes() > limits.max_storage_buffer_binding_size
            || groups > u64::from(limits.max_compute_workgroups_per_dimension)
            || (s.r * s.mu) as u64 > u64::from(limits.max_compute_workgroups_per_dimension)
        {
            return Err(RenderError::Unsupported(format!(
                "bruneton tables of {s:?}: {} bytes of tables being built, more than the device's \
                 storage buffer or workgroup limits allow",
                layout.bytes()
            )));
        }
        let device = &gpu.device;
        let (t_width, t_height) = (
            settings.transmittance_size.0 as u32,
            settings.transmittance_size.1 as u32,
        );
        let texture = |label| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: (s.nu * s.mu_s) as u32,
                    height: s.mu as u32,
                    depth_or_array_layers: s.r as u32,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D3,
                format: wgpu::TextureFormat::Rgba32Float,
                usage: wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        };
        Ok(Tables {
            settings: settings.clone(),
            max_orders,
            layout,
            columns: TransmittancePass::with(gpu, TableOutput::Columns, t_width, t_height)?,
            transmittance: TransmittancePass::with(
                gpu,
                TableOutput::Transmittance,
                t_width,
                t_height,
            )?,
            store: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("bruneton store"),
                size: layout.bytes(),
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_SRC
                    | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            state: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("bruneton order state"),
                size: size_of::<OrderState>() as u64,
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::INDIRECT
                    | wgpu::BufferUsages::COPY_SRC
                    | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            params_first: uniform_buffer(device, "bruneton order 2", size_of::<BrunetonUniform>()),
            params: uniform_buffer(device, "bruneton", size_of::<BrunetonUniform>()),
            density: device.create_texture(&wgpu::TextureDescriptor {
                label: Some("bruneton densities"),
                size: wgpu::Extent3d {
                    width: DENSITY_SAMPLES,
                    height: 1,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D1,
                format: wgpu::TextureFormat::Rgba32Float,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            }),
            delta_j: texture("bruneton Delta J"),
            irradiance: device.create_texture(&wgpu::TextureDescriptor {
                label: Some("bruneton irradiance"),
                size: wgpu::Extent3d {
                    width: e_mu_s as u32,
                    height: e_r as u32,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba32Float,
                usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            }),
            view_slice: device.create_texture(&wgpu::TextureDescriptor {
                label: Some("bruneton view slice"),
                size: wgpu::Extent3d {
                    width: 3 * s.nu as u32,
                    height: s.mu as u32,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba32Float,
                usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            }),
            textures: [
                texture("bruneton single Rayleigh"),
                texture("bruneton single Mie"),
                texture("bruneton multiple scattering"),
            ],
            built: Built::default(),
        })
    }

    /// The parameters of the shaders for `tables` and an atmosphere.
    fn uniform(tables: &Tables, atmosphere: &Atmosphere, mie: bool) -> BrunetonUniform {
        let st = &tables.settings;
        let s = st.scattering_size;
        let o = &tables.layout.offsets;
        let l = &tables.layout.lengths;
        let delta_m = if mie {
            let d = DeltaM::new(&atmosphere.mie.phase);
            [d.forward_fraction, d.chi1, d.chi2]
        } else {
            [0.0; 3]
        };
        let u = |x: usize| x as u32;
        BrunetonUniform {
            size: [u(s.r), u(s.mu), u(s.mu_s), u(s.nu)],
            irradiance_size: [
                u(st.irradiance_size.0),
                u(st.irradiance_size.1),
                u(st.sphere_samples.0.div_ceil(16).max(1)),
                u((st.sphere_samples.1 / 2).max(1)),
            ],
            flags: [u(st.view_samples), u32::from(mie), 0, tables.max_orders],
            offsets_a: [o[0], o[1], o[2], o[3]],
            offsets_b: [o[4], o[5], o[6], o[7]],
            offsets_c: [o[8], o[9], l[1], l[6]],
            delta_m: [
                delta_m[0] as f32,
                delta_m[1] as f32,
                delta_m[2] as f32,
                st.order_threshold as f32,
            ],
            density: [
                (atmosphere.thickness_m() / f64::from(DENSITY_SAMPLES - 1)) as f32,
                0.0,
                0.0,
                0.0,
            ],
        }
    }

    /// The loop's state before its first decision: dispatch sizes of every order's steps.
    fn initial_state(&self, tables: &Tables) -> OrderState {
        let s = tables.settings.scattering_size;
        let n = s.texels() as u32;
        let e = tables.layout.lengths[6];
        let groups = |x: u32| [x, 1, 1, 0];
        let full = [
            groups(((s.r * s.mu_s) as u32).div_ceil(FLAT)),
            groups(n.div_ceil(FLAT)),
            groups(e.div_ceil(FLAT)),
            groups(n.div_ceil(FLAT)),
            groups(SUM_GROUPS),
            groups(n.max(e).div_ceil(FLAT)),
        ];
        OrderState {
            totals: [0.0; 4],
            previous_added: [0.0; 4],
            order: 1,
            running: 1,
            last_order: 1,
            has_previous: 0,
            args: full,
            full,
            shares: [0.0; 64],
        }
    }

    fn tables(&self) -> Result<&Tables, RenderError> {
        self.tables
            .as_ref()
            .ok_or_else(|| RenderError::Frame("the bruneton tables are not built yet".into()))
    }

    /// A table of the store as last built, vec4 per texel (rgb = the three channels), in
    /// the CPU's order (`ScatteringSize::index`, `IrradianceMapping::index`).
    pub fn read_table(
        &self,
        gpu: &GpuContext,
        table: StoreTable,
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        let tables = self.tables()?;
        let (offset, size) = tables.layout.range(table);
        let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("bruneton read-back"),
            size,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&tables.store, offset, &buffer, 0, size);
        gpu.queue.submit([encoder.finish()]);
        Ok(bytemuck::pod_collect_to_vec(&map_and_read(gpu, &buffer)?))
    }

    /// Scattering texture `k` (0 single Rayleigh, 1 single Mie, 2 orders two and up),
    /// texels in x, y, z order.
    pub fn read_scattering_texture(
        &self,
        gpu: &GpuContext,
        k: usize,
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        let bytes = read_texture(gpu, &self.tables()?.textures[k], 16)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    /// The state of the last loop over orders: the highest order added and each order's
    /// share.
    pub fn read_orders(&self, gpu: &GpuContext) -> Result<OrderState, RenderError> {
        let tables = self.tables()?;
        let size = size_of::<OrderState>() as u64;
        let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("bruneton order read-back"),
            size,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&tables.state, 0, &buffer, 0, size);
        gpu.queue.submit([encoder.finish()]);
        Ok(bytemuck::pod_read_unaligned(&map_and_read(gpu, &buffer)?))
    }

    /// Plans `frame` and builds the tables its plan lists, without rendering; returns
    /// the plan (for tests of the tables).
    pub fn build_tables(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
    ) -> Result<FramePlan, RenderError> {
        let mut plan = FramePlan::default();
        self.plan(gpu, frame, &mut plan)?;
        let inputs = StandaloneInputs::new(gpu, &self.atmosphere, frame);
        let io = inputs.io();
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        for step in plan.steps.iter().filter(|s| s.kind == StepKind::TableBuild) {
            self.encode(step.name, gpu, &io, &mut encoder, None);
        }
        gpu.queue.submit([encoder.finish()]);
        gpu.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(GpuError::from)?;
        Ok(plan)
    }

    /// The bind group of `pipeline`: bindings 0-5 with `params`, 12, then `extra` from
    /// binding 6 on.
    fn bind_group(
        &self,
        gpu: &GpuContext,
        io: &PassIo<'_>,
        pipeline: &ComputePipeline,
        params: &wgpu::Buffer,
        extra: &[wgpu::BindingResource<'_>],
    ) -> wgpu::BindGroup {
        let tables = self.tables.as_ref().expect("plan makes the tables");
        let columns = tables.columns.texture().create_view(&Default::default());
        let transmittance = tables
            .transmittance
            .texture()
            .create_view(&Default::default());
        let density = tables.density.create_view(&Default::default());
        let mut resources = vec![
            (0, io.atmosphere.as_entire_binding()),
            (1, io.frame.as_entire_binding()),
            (2, params.as_entire_binding()),
            (3, wgpu::BindingResource::TextureView(&columns)),
            (4, tables.store.as_entire_binding()),
            (5, wgpu::BindingResource::TextureView(&transmittance)),
            (
                DENSITY_BINDING,
                wgpu::BindingResource::TextureView(&density),
            ),
        ];
        resources.extend((6..).zip(extra.iter().cloned()));
        pipeline.bind_group_numbered(gpu, &resources)
    }

    /// The dispatches of the loop over orders (Algorithm 4.1), in order, after clearing
    /// S's multiple part and E: each with its step's name and the order it belongs to (1
    /// for the sums of single scattering).
    fn order_dispatches(
        &self,
        gpu: &GpuContext,
        io: &PassIo<'_>,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Vec<OrderDispatch<'_>> {
        let tables = self.tables.as_ref().expect("plan makes the tables");
        let p = &self.pipelines;
        for table in [StoreTable::Multiple, StoreTable::Irradiance] {
            let (offset, size) = tables.layout.range(table);
            encoder.clear_buffer(&tables.store, offset, Some(size));
        }
        let state = [tables.state.as_entire_binding()];
        let delta_j = tables.delta_j.create_view(&Default::default());
        let extra = |pipeline: &ComputePipeline| -> Vec<wgpu::BindingResource<'_>> {
            if std::ptr::eq(pipeline, &p.scattering_density)
                || std::ptr::eq(pipeline, &p.scattering)
            {
                vec![wgpu::BindingResource::TextureView(&delta_j)]
            } else {
                Vec::new()
            }
        };
        let first =
            |pipeline| self.bind_group(gpu, io, pipeline, &tables.params_first, &extra(pipeline));
        let later = |pipeline| self.bind_group(gpu, io, pipeline, &tables.params, &extra(pipeline));
        let ordered = |pipeline| self.bind_group(gpu, io, pipeline, &tables.params, &state);
        let steps = [
            ("moments", &p.moments),
            ("scattering_density", &p.scattering_density),
            ("irradiance", &p.irradiance),
            ("scattering", &p.scattering),
        ];
        let groups: Vec<_> = steps
            .iter()
            .map(|(name, pipeline)| (*name, *pipeline, first(pipeline), later(pipeline)))
            .collect();
        // The state is bound to `decide` only: the other steps are dispatched from it.
        let sum_single = later(&p.sum_single);
        let sum_order = later(&p.sum_order);
        let decide = ordered(&p.decide);
        let accumulate = later(&p.accumulate);
        let args = |k: u64| 48 + 16 * k;
        let mut out = vec![
            OrderDispatch {
                name: "sum_single",
                order: 1,
                pipeline: &p.sum_single.pipeline,
                bind_group: sum_single,
                size: DispatchSize::Direct(SUM_GROUPS),
            },
            OrderDispatch {
                name: "decide",
                order: 1,
                pipeline: &p.decide.pipeline,
                bind_group: decide.clone(),
                size: DispatchSize::Direct(1),
            },
        ];
        for order in 2..=tables.max_orders {
            for (k, (name, pipeline, first_group, later_group)) in groups.iter().enumerate() {
                out.push(OrderDispatch {
                    name,
                    order,
                    pipeline: &pipeline.pipeline,
                    bind_group: if order == 2 { first_group } else { later_group }.clone(),
                    size: DispatchSize::Indirect(&tables.state, args(k as u64)),
                });
            }
            out.push(OrderDispatch {
                name: "sum_order",
                order,
                pipeline: &p.sum_order.pipeline,
                bind_group: sum_order.clone(),
                size: DispatchSize::Indirect(&tables.state, args(4)),
            });
            out.push(OrderDispatch {
                name: "decide",
                order,
                pipeline: &p.decide.pipeline,
                bind_group: decide.clone(),
                size: DispatchSize::Direct(1),
            });
            out.push(OrderDispatch {
                name: "accumulate",
                order,
                pipeline: &p.accumulate.pipeline,
                bind_group: accumulate.clone(),
                size: DispatchSize::Indirect(&tables.state, args(5)),
            });
        }
        out
    }

    /// Records the loop over orders (Algorithm 4.1) into one compute pass.
    fn encode_orders(
        &self,
        gpu: &GpuContext,
        io: &PassIo<'_>,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let dispatches = self.order_dispatches(gpu, io, encoder);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("bruneton scattering orders"),
            timestamp_writes: timestamps,
        });
        for d in &dispatches {
            d.record(&mut pass);
        }
    }

    /// Builds every table of `frame` (as if never built) one dispatch at a time, waiting
    /// for the GPU after each, and returns each step's wall-clock time in ms: the table
    /// steps by name, and the loop over orders per dispatch (`scattering_orders
    /// order 3 scattering`). For profiling the build: a CPU adapter such as lavapipe
    /// times its dispatches unreliably with timestamp queries.
    pub fn profile_build(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
    ) -> Result<Vec<(String, f64)>, RenderError> {
        if let Some(t) = self.tables.as_mut() {
            t.built = Built::default();
        }
        let mut plan = FramePlan::default();
        self.plan(gpu, frame, &mut plan)?;
        let inputs = StandaloneInputs::new(gpu, &self.atmosphere, frame);
        let io = inputs.io();
        let wait = || -> Result<(), RenderError> {
            gpu.device
                .poll(wgpu::PollType::wait_indefinitely())
                .map_err(GpuError::from)?;
            Ok(())
        };
        let mut times = Vec::new();
        wait()?;
        for step in plan.steps.iter().filter(|s| s.kind == StepKind::TableBuild) {
            if step.name != "scattering_orders" {
                let start = std::time::Instant::now();
                let mut encoder = gpu.device.create_command_encoder(&Default::default());
                self.encode(step.name, gpu, &io, &mut encoder, None);
                gpu.queue.submit([encoder.finish()]);
                wait()?;
                times.push((step.name.to_string(), start.elapsed().as_secs_f64() * 1e3));
                continue;
            }
            let mut encoder = gpu.device.create_command_encoder(&Default::default());
            let dispatches = self.order_dispatches(gpu, &io, &mut encoder);
            gpu.queue.submit([encoder.finish()]);
            wait()?;
            for d in &dispatches {
                let start = std::time::Instant::now();
                let mut encoder = gpu.device.create_command_encoder(&Default::default());
                {
                    let mut pass = encoder.begin_compute_pass(&Default::default());
                    d.record(&mut pass);
                }
                gpu.queue.submit([encoder.finish()]);
                wait()?;
                times.push((
                    format!("scattering_orders order {} {}", d.order, d.name),
                    start.elapsed().as_secs_f64() * 1e3,
                ));
            }
            drop(dispatches);
            let (atmosphere, mie) = self.pending.clone().expect("planned above");
            self.tables.as_mut().expect("planned above").built.orders = Some((atmosphere, mie));
        }
        Ok(times)
    }
}

/// A dispatch's size: workgroups along x, or the indirect arguments at an offset of a
/// buffer.
#[derive(Debug)]
enum DispatchSize<'a> {
    Direct(u32),
    Indirect(&'a wgpu::Buffer, u64),
}

/// One dispatch of the loop over orders.
#[derive(Debug)]
struct OrderDispatch<'a> {
    name: &'static str,
    order: u32,
    pipeline: &'a wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
    size: DispatchSize<'a>,
}

impl OrderDispatch<'_> {
    fn record(&self, pass: &mut wgpu::ComputePass<'_>) {
        pass.set_pipeline(self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        match self.size {
            DispatchSize::Direct(x) => pass.dispatch_workgroups(x, 1, 1),
            DispatchSize::Indirect(buffer, offset) => {
                pass.dispatch_workgroups_indirect(buffer, offset)
            }
        }
    }
}

/// What the table steps read when they run outside a `Renderer` frame (tests and
/// profiling): the uniforms of `frame` and a 1x1 HDR target, which they do not touch.
struct StandaloneInputs {
    atmosphere: wgpu::Buffer,
    frame: wgpu::Buffer,
    hdr: wgpu::Texture,
}

impl StandaloneInputs {
    fn new(gpu: &GpuContext, atmosphere: &AtmosphereUniform, frame: &Frame) -> Self {
        let inputs = StandaloneInputs {
            atmosphere: uniform_buffer(&gpu.device, "atmosphere", size_of::<AtmosphereUniform>()),
            frame: uniform_buffer(&gpu.device, "frame", size_of::<FrameUniform>()),
            hdr: gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some("unused"),
                size: wgpu::Extent3d::default(),
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: HDR_FORMAT,
                usage: wgpu::TextureUsages::STORAGE_BINDING,
                view_formats: &[],
            }),
        };
        gpu.queue
            .write_buffer(&inputs.atmosphere, 0, bytemuck::bytes_of(atmosphere));
        let frame_uniform = FrameUniform::new(frame, RGB_WAVELENGTHS_NM);
        gpu.queue
            .write_buffer(&inputs.frame, 0, bytemuck::bytes_of(&frame_uniform));
        inputs
    }

    fn io(&self) -> PassIo<'_> {
        PassIo {
            atmosphere: &self.atmosphere,
            frame: &self.frame,
            hdr: &self.hdr,
        }
    }
}

impl ModelPass for BrunetonPass {
    fn plan(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
        plan: &mut FramePlan,
    ) -> Result<(), RenderError> {
        check_wavelengths(&frame.settings.wavelengths_nm)?;
        let settings = BrunetonSettings::from_options(&frame.settings.options)?;
        let max_orders = frame.settings.max_orders.unwrap_or(settings.order_limit);
        self.atmosphere = AtmosphereUniform::new(&frame.atmosphere, RGB_WAVELENGTHS_NM)?;
        let same = self
            .tables
            .as_ref()
            .is_some_and(|t| t.settings == settings && t.max_orders == max_orders);
        if !same {
            self.tables = Some(Self::make_tables(gpu, &settings, max_orders)?);
        }
        let mie = Spectra::new(&frame.atmosphere, RGB_WAVELENGTHS_NM.as_slice())
            .needs_mie(frame.settings.prune);
        let tables = self.tables.as_ref().expect("made above");
        let atmosphere = &frame.atmosphere;
        let stale = |old: &Option<Atmosphere>, inputs| {
            old.as_ref()
                .is_none_or(|old| Inputs::changed(old, atmosphere).intersects(inputs))
        };
        let columns = stale(&tables.built.columns, Inputs::COLUMNS);
        let sun = stale(&tables.built.sun, Inputs::EXTINCTION);
        let single = stale(&tables.built.single, Inputs::EXTINCTION);
        let orders = single
            || tables.built.orders.as_ref().is_none_or(|(old, old_mie)| {
                let changed = Inputs::changed(old, atmosphere);
                changed.intersects(Inputs::GROUND_ALBEDO)
                    || (changed.intersects(Inputs::MIE_PHASE) && *old_mie)
            });
        plan.build_if("transmittance", columns);
        plan.build_if("density", columns);
        plan.build_if("sun_transmittance", sun);
        plan.build_if("single_scattering", single);
        plan.build_if("scattering_orders", orders);
        plan.build_if("scattering_texture", single || orders);
        let r = frame.camera_position_m.length();
        self.inside = r <= atmosphere.top_radius_m;
        if self.inside {
            plan.run("view_slice", StepKind::Pass);
        }
        plan.run("bruneton", StepKind::Pass);
        // Mie pruning as built (a frame that rebuilds nothing renders what was built).
        let mie = if orders {
            mie
        } else {
            tables.built.orders.as_ref().is_some_and(|(_, m)| *m)
        };
        self.uniform = Self::uniform(tables, atmosphere, mie);
        let mut first = self.uniform;
        first.flags[2] = 1;
        gpu.queue
            .write_buffer(&tables.params, 0, bytemuck::bytes_of(&self.uniform));
        gpu.queue
            .write_buffer(&tables.params_first, 0, bytemuck::bytes_of(&first));
        if orders {
            let state = self.initial_state(tables);
            gpu.queue
                .write_buffer(&tables.state, 0, bytemuck::bytes_of(&state));
        }
        self.pending = Some((atmosphere.clone(), mie));
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
        let Some((atmosphere, mie)) = self.pending.clone() else {
            unreachable!("plan comes before encode");
        };
        let tables = self.tables.as_ref().expect("plan makes the tables");
        let s = tables.settings.scattering_size;
        let n = s.texels() as u32;
        let p = &self.pipelines;
        let simple =
            |pipeline: &ComputePipeline, label, x, encoder: &mut wgpu::CommandEncoder, ts| {
                let bind_group = self.bind_group(gpu, io, pipeline, &tables.params, &[]);
                pipeline.dispatch(encoder, label, &bind_group, [x, 1, 1], ts);
            };
        match step {
            "transmittance" => tables
                .columns
                .encode(gpu, &self.atmosphere, encoder, timestamps),
            "sun_transmittance" => {
                tables
                    .transmittance
                    .encode(gpu, &self.atmosphere, encoder, timestamps);
            }
            "density" => {
                simple(
                    &p.density,
                    "density",
                    DENSITY_SAMPLES.div_ceil(FLAT),
                    encoder,
                    timestamps,
                );
                let (offset, _) = tables.layout.range(StoreTable::Density);
                encoder.copy_buffer_to_texture(
                    wgpu::TexelCopyBufferInfo {
                        buffer: &tables.store,
                        layout: wgpu::TexelCopyBufferLayout {
                            offset,
                            bytes_per_row: Some(DENSITY_SAMPLES * 16),
                            rows_per_image: None,
                        },
                    },
                    tables.density.as_image_copy(),
                    wgpu::Extent3d {
                        width: DENSITY_SAMPLES,
                        height: 1,
                        depth_or_array_layers: 1,
                    },
                );
            }
            "single_scattering" => simple(
                &p.single,
                "single scattering",
                (s.r * s.mu) as u32,
                encoder,
                timestamps,
            ),
            "scattering_orders" => self.encode_orders(gpu, io, encoder, timestamps),
            "scattering_texture" => {
                let views = tables
                    .textures
                    .each_ref()
                    .map(|t| t.create_view(&Default::default()));
                let irradiance = tables.irradiance.create_view(&Default::default());
                let mut extra: Vec<wgpu::BindingResource<'_>> = views
                    .iter()
                    .map(wgpu::BindingResource::TextureView)
                    .collect();
                extra.push(wgpu::BindingResource::TextureView(&irradiance));
                let bind_group = self.bind_group(gpu, io, &p.texture, &tables.params, &extra);
                let (e_mu_s, e_r) = tables.settings.irradiance_size;
                let texels = n.max((e_mu_s * e_r) as u32);
                p.texture.dispatch(
                    encoder,
                    "scattering texture",
                    &bind_group,
                    [texels.div_ceil(FLAT), 1, 1],
                    timestamps,
                );
            }
            "view_slice" => {
                let views = tables
                    .textures
                    .each_ref()
                    .map(|t| t.create_view(&Default::default()));
                let slice = tables.view_slice.create_view(&Default::default());
                let mut extra: Vec<wgpu::BindingResource<'_>> = views
                    .iter()
                    .map(wgpu::BindingResource::TextureView)
                    .collect();
                extra.push(wgpu::BindingResource::TextureView(&slice));
                let bind_group = self.bind_group(gpu, io, &p.view_slice, &tables.params, &extra);
                let groups = texel_groups(&tables.view_slice);
                p.view_slice
                    .dispatch(encoder, "view slice", &bind_group, groups, timestamps);
            }
            "bruneton" => {
                let views = tables
                    .textures
                    .each_ref()
                    .map(|t| t.create_view(&Default::default()));
                let hdr = io.hdr.create_view(&Default::default());
                let slice = tables.view_slice.create_view(&Default::default());
                let mut extra: Vec<wgpu::BindingResource<'_>> = views
                    .iter()
                    .map(wgpu::BindingResource::TextureView)
                    .collect();
                let irradiance = tables.irradiance.create_view(&Default::default());
                extra.push(wgpu::BindingResource::TextureView(&hdr));
                extra.push(wgpu::BindingResource::TextureView(&slice));
                extra.push(wgpu::BindingResource::TextureView(&irradiance));
                let render = if self.inside {
                    &p.render_inside
                } else {
                    &p.render
                };
                let bind_group = self.bind_group(gpu, io, render, &tables.params, &extra);
                let groups = texel_groups(io.hdr);
                render.dispatch(encoder, "bruneton", &bind_group, groups, timestamps);
            }
            other => unreachable!("the bruneton plan has no step {other}"),
        }
        let built = &mut self.tables.as_mut().expect("plan makes the tables").built;
        match step {
            "transmittance" => built.columns = Some(atmosphere),
            "sun_transmittance" => built.sun = Some(atmosphere),
            "single_scattering" => built.single = Some(atmosphere),
            "scattering_orders" => built.orders = Some((atmosphere, mie)),
            _ => {}
        }
    }

    fn table_bytes(&self) -> u64 {
        self.tables.as_ref().map_or(0, |t| {
            let s = t.settings.scattering_size;
            let (e_mu_s, e_r) = t.settings.irradiance_size;
            let (w, h) = t.settings.transmittance_size;
            t.layout.bytes()
                + 3 * 16 * s.texels() as u64
                + 2 * 16 * (w * h) as u64
                + 3 * 16 * (s.nu * s.mu) as u64
                + 16 * (e_mu_s * e_r) as u64
        })
    }
}
