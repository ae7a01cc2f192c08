//! The bruneton model on the GPU (Bruneton and Neyret 2008, seed 004): every table of
//! atmosphere-core's `bruneton` built in compute shaders as the CPU builds it, and the
//! per-pixel pass of `shaders/sky/bruneton/pixel.wgsl`.
//!
//! Tables, in the order of the plan (step names; the shaders are `bruneton_*.wgsl`):
//! - `transmittance`: the columns of matter T(r, mu) (`sky/transmittance_table.wgsl`,
//!   `columns`), the CPU's `TransmittanceTable`; and `sun_transmittance`, the same table
//!   as transmittances (entry point `main`), the CPU's `Builder::sun_transmittances`.
//! - `density`: the 8192-sample density table (`DensityTable`), copied into a 1D texture
//!   for the shaders' reads (lavapipe reads storage buffers lane by lane).
//! - `single_scattering`: Rayleigh and Mie without phase functions (paper Eq. 5).
//! - `scattering_orders`: Algorithm 4.1's loop: per order Delta J (moments per (r, mu_s),
//!   then every texel), Delta E, Delta S, their sums, the GPU's decision whether the order
//!   is added and whether the loop goes on (`sky/bruneton/orders.wgsl`), S += Delta S and E
//!   += Delta E. Every order up to the limit is recorded; those after the loop's end
//!   dispatch no workgroups (indirect dispatch sizes written by the GPU), so nothing is
//!   read back.
//! - `scattering_texture`: S into three `Rgba32Float` 3D textures (single Rayleigh,
//!   single Mie, orders two and up) at (x = nu * mu_s_size + mu_s, y = mu, z = r), and E
//!   into a 2D texture (x = mu_s, y = r) for the pass's ground term.
//!
//! Passes, each frame: for a camera inside the atmosphere, `view_slice`
//! (`sky/bruneton/view_slice.wgsl`): S interpolated at the camera's r and mu_s for every
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
use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::atmosphere::table_inputs::Inputs;
use atmosphere_core::models::bruneton::BrunetonSettings;
use atmosphere_core::models::bruneton::delta_m::DeltaM;
use atmosphere_core::models::bruneton::parameterization::ScatteringSize;
use bytemuck::{Pod, Zeroable};

use crate::frame::Frame;
use crate::frame::atmosphere_uniform::check_wavelengths;
use crate::frame::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use crate::frame::plan::{FramePlan, StepKind};
use crate::frame::surface_buffer::{ALBEDO_BINDING, GEOMETRY_BINDING, SurfaceBuffer};
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::{
    ComputePipeline, PixelPipeline, storage_buffer_entry, storage_texture_entry, texel_groups,
    texture_2d, texture_entry, uniform_buffer, uniform_entry,
};
use crate::gpu::readback::{map_and_read, read_texture};
use crate::sky::model_pass::{ModelPass, PassIo, StandaloneInputs};
use crate::sky::table_sampling::TableSampling;
use crate::sky::transmittance::{TableOutput, TransmittancePass};

/// Texels of a row of S (mu_s x nu) at most: the workgroup of the row shaders
/// (`ROW_TEXELS` of `sky/bruneton/scattering.wgsl`).
pub const ROW_TEXELS: usize = 256;
/// The most orders the GPU loop records (`OrderState::shares` holds 64).
pub const MAX_ORDERS: u32 = 63;
/// Samples of the density table (`DensityTable::SAMPLES`).
const DENSITY_SAMPLES: u32 = 8192;
/// Workgroups of the partial sums (`SUM_GROUPS` of `sky/bruneton/orders.wgsl`).
const SUM_GROUPS: u32 = 256;
/// The binding of the density table's texture (`sky/bruneton/tables.wgsl`).
const DENSITY_BINDING: u32 = 12;
/// Invocations of the flat shaders' workgroups.
const FLAT: u32 = 64;
/// Texels of S per Delta S dispatch at most: an order's Delta S is dispatched in slices of
/// this many texels, so that a progressive build can spread it over frames (a multiple of
/// [`FLAT`]).
pub const SLICE_TEXELS: u32 = 65536;

/// The Delta S slices of an order over `texels` texels of S: how many, and the texels of
/// each (a multiple of [`FLAT`]; the last slice may hold fewer).
fn delta_s_slices(texels: u32) -> (u32, u32) {
    let slices = texels.div_ceil(SLICE_TEXELS);
    (slices, texels.div_ceil(slices).next_multiple_of(FLAT))
}

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

/// WGSL `OrderState` (`sky/bruneton/orders.wgsl`), 496 bytes.
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
    /// The first texel of each Delta S slice (`vec4<u32>`, x), one per uniform offset
    /// alignment.
    slice_starts: wgpu::Buffer,
    /// Bytes between two slices' starts in `slice_starts`.
    slice_stride: u64,
    /// Delta S slices per order.
    slices: u32,
    /// S of the three textures at the camera's r and mu_s per (mu, nu) node, side by
    /// side (`sky/bruneton/view_slice.wgsl`).
    view_slice: wgpu::Texture,
    built: Built,
    /// The share of the loop over orders that the next progressive frame records;
    /// `None` when no progressive build is under way.
    next: Option<Share>,
}

impl Tables {
    /// Views of the three scattering textures (single Rayleigh, single Mie, multiple).
    fn scattering_views(&self) -> [wgpu::TextureView; 3] {
        self.textures
            .each_ref()
            .map(|t| t.create_view(&Default::default()))
    }
}

/// A share of the loop over orders that one progressive frame records: order 1 (after
/// clearing S's multiple part and E, the sums of single scattering and their decision),
/// or part `part` of an order of two or more (0: Delta J's moments, Delta J and Delta E;
/// 1 to `slices`: Delta S slice `part - 1`, the last with the order's sums, decision and
/// accumulation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Share {
    order: u32,
    part: u32,
}

impl Share {
    /// The first share: single scattering's.
    const FIRST: Share = Share { order: 1, part: 0 };

    /// Whether this share ends its order: S and E then hold every order up to it.
    fn ends_order(self, slices: u32) -> bool {
        self.order == 1 || self.part == slices
    }

    /// The share after this one, `None` after the last order's last.
    fn after(self, slices: u32, max_orders: u32) -> Option<Share> {
        if !self.ends_order(slices) {
            Some(Share {
                part: self.part + 1,
                ..self
            })
        } else if self.order < max_orders {
            Some(Share {
                order: self.order + 1,
                part: 0,
            })
        } else {
            None
        }
    }

    /// What the share builds, for [`FramePlan::building`].
    fn describe(self, slices: u32, max_orders: u32) -> String {
        match self.part {
            _ if self.order == 1 => "bruneton: single scattering".to_string(),
            0 => format!(
                "bruneton: order {} of at most {max_orders}, Delta J and Delta E",
                self.order
            ),
            p => format!(
                "bruneton: order {} of at most {max_orders}, Delta S slice {p} of {slices}",
                self.order
            ),
        }
    }
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
    render: PixelPipeline,
    render_inside: PixelPipeline,
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
    /// Whether the loop over orders is spread over frames ([`ModelPass::set_progressive`]).
    progressive: bool,
    /// The share of the loop over orders this frame records; `None`: all of it.
    recording: Option<Share>,
    /// Whether the frame's camera is inside the atmosphere (the view slice and the
    /// `inside` pass).
    inside: bool,
    /// How the pass reads its tables.
    sampling: TableSampling,
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
        let delta_j_in = with(&[texture_entry(6, D3), uniform_entry(7, 16)]);
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
        // The pass may sample the columns table, the view slice and E.
        let sampling = TableSampling::new(gpu);
        let surface_entries = SurfaceBuffer::layout_entries();
        let mut render_entries = with(&[
            texture_entry(6, D3),
            texture_entry(7, D3),
            texture_entry(8, D3),
            storage_texture_entry(9, HDR_FORMAT, D2),
            surface_entries[0],
            surface_entries[1],
            sampling.texture_entry(10, D2),
            sampling.texture_entry(11, D2),
            sampling.sampler_entry(),
        ]);
        for entry in &mut render_entries {
            if entry.binding == 3 {
                *entry = sampling.texture_entry(3, D2);
            }
        }
        let render = |entry| {
            PixelPipeline::with_constants(
                gpu,
                "sky/bruneton/pixel.wgsl",
                entry,
                "the bruneton pass",
                &render_entries,
                &[sampling.constant()],
            )
        };
        let pipelines = Pipelines {
            density: make(
                "sky/bruneton/density.wgsl",
                "main",
                "bruneton density",
                &common,
            )?,
            single: make(
                "sky/bruneton/single_scattering.wgsl",
                "main",
                "bruneton single scattering",
                &common,
            )?,
            moments: make(
                "sky/bruneton/scattering_density.wgsl",
                "moments",
                "bruneton Delta J moments",
                &common,
            )?,
            scattering_density: make(
                "sky/bruneton/scattering_density.wgsl",
                "main",
                "bruneton Delta J",
                &delta_j_out,
            )?,
            irradiance: make(
                "sky/bruneton/irradiance.wgsl",
                "main",
                "bruneton Delta E",
                &common,
            )?,
            scattering: make(
                "sky/bruneton/scattering.wgsl",
                "main",
                "bruneton Delta S",
                &delta_j_in,
            )?,
            sum_single: make(
                "sky/bruneton/orders.wgsl",
                "sum_single",
                "bruneton sums",
                &common,
            )?,
            sum_order: make(
                "sky/bruneton/orders.wgsl",
                "sum_order",
                "bruneton sums",
                &common,
            )?,
            decide: make(
                "sky/bruneton/orders.wgsl",
                "decide",
                "bruneton order decision",
                &order_entries,
            )?,
            accumulate: make(
                "sky/bruneton/orders.wgsl",
                "accumulate",
                "bruneton accumulation",
                &common,
            )?,
            texture: make(
                "sky/bruneton/scattering_texture.wgsl",
                "main",
                "bruneton scattering texture",
                &texture_entries,
            )?,
            view_slice: make(
                "sky/bruneton/view_slice.wgsl",
                "main",
                "bruneton view slice",
                &view_slice_entries,
            )?,
            render: render("main")?,
            render_inside: render("inside")?,
        };
        Ok(BrunetonPass {
            pipelines,
            tables: None,
            uniform: BrunetonUniform::default(),
            atmosphere: AtmosphereUniform::default(),
            pending: None,
            progressive: false,
            recording: None,
            inside: false,
            sampling,
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
        let (slices, slice_texels) = delta_s_slices(s.texels() as u32);
        let slice_stride = u64::from(limits.min_uniform_buffer_offset_alignment).max(16);
        let slice_starts = uniform_buffer(
            device,
            "bruneton Delta S slices",
            (slice_stride * u64::from(slices)) as usize,
        );
        for k in 0..slices {
            gpu.queue.write_buffer(
                &slice_starts,
                slice_stride * u64::from(k),
                bytemuck::bytes_of(&[k * slice_texels, 0, 0, 0]),
            );
        }
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
            irradiance: texture_2d(
                device,
                "bruneton irradiance",
                (e_mu_s as u32, e_r as u32),
                wgpu::TextureFormat::Rgba32Float,
                wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
            ),
            view_slice: texture_2d(
                device,
                "bruneton view slice",
                (3 * s.nu as u32, s.mu as u32),
                wgpu::TextureFormat::Rgba32Float,
                wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
            ),
            textures: [
                texture("bruneton single Rayleigh"),
                texture("bruneton single Mie"),
                texture("bruneton multiple scattering"),
            ],
            slice_starts,
            slice_stride,
            slices,
            built: Built::default(),
            next: None,
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
            groups(delta_s_slices(n).1 / FLAT),
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
    /// binding 6 on, and for the per-pixel pass the frame's `surface` at 30 and 31 and the
    /// table sampler.
    fn bind_group(
        &self,
        gpu: &GpuContext,
        io: &PassIo<'_>,
        pipeline: &ComputePipeline,
        params: &wgpu::Buffer,
        extra: &[wgpu::BindingResource<'_>],
        surface: Option<&[wgpu::TextureView; 2]>,
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
        if let Some([geometry, albedo]) = surface {
            resources.push((
                GEOMETRY_BINDING,
                wgpu::BindingResource::TextureView(geometry),
            ));
            resources.push((ALBEDO_BINDING, wgpu::BindingResource::TextureView(albedo)));
            resources.push(self.sampling.sampler_binding());
        }
        pipeline.bind_group_numbered(gpu, &resources)
    }

    /// The dispatches of the loop over orders (Algorithm 4.1), in order: each with its
    /// step's name and the share of a progressive build it belongs to (order 1 for the
    /// sums of single scattering). The loop starts by clearing S's multiple part and E
    /// ([`BrunetonPass::clear_orders`]).
    fn order_dispatches(&self, gpu: &GpuContext, io: &PassIo<'_>) -> Vec<OrderDispatch<'_>> {
        let tables = self.tables.as_ref().expect("plan makes the tables");
        let p = &self.pipelines;
        let state = [tables.state.as_entire_binding()];
        let delta_j = tables.delta_j.create_view(&Default::default());
        let slice = |k: u32| {
            wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer: &tables.slice_starts,
                offset: tables.slice_stride * u64::from(k),
                size: wgpu::BufferSize::new(16),
            })
        };
        let with_delta_j = [wgpu::BindingResource::TextureView(&delta_j)];
        let bind = |pipeline, params, extra: &[wgpu::BindingResource<'_>]| {
            self.bind_group(gpu, io, pipeline, params, extra, None)
        };
        // Bind groups of order 2 (`params_first`) and of later orders.
        let both = |pipeline, extra: &[wgpu::BindingResource<'_>]| {
            [
                bind(pipeline, &tables.params_first, extra),
                bind(pipeline, &tables.params, extra),
            ]
        };
        let first_steps = [
            ("moments", &p.moments, both(&p.moments, &[])),
            (
                "scattering_density",
                &p.scattering_density,
                both(&p.scattering_density, &with_delta_j),
            ),
            ("irradiance", &p.irradiance, both(&p.irradiance, &[])),
        ];
        let slice_groups: Vec<_> = (0..tables.slices)
            .map(|k| both(&p.scattering, &[with_delta_j[0].clone(), slice(k)]))
            .collect();
        // The state is bound to `decide` only: the other steps are dispatched from it.
        let sum_single = bind(&p.sum_single, &tables.params, &[]);
        let sum_order = bind(&p.sum_order, &tables.params, &[]);
        let decide = bind(&p.decide, &tables.params, &state);
        let accumulate = bind(&p.accumulate, &tables.params, &[]);
        let args = |k: u64| 48 + 16 * k;
        let dispatch = OrderDispatch::new;
        let single = Share::FIRST;
        let mut out = vec![
            dispatch(
                "sum_single",
                single,
                &p.sum_single,
                sum_single,
                DispatchSize::Direct(SUM_GROUPS),
            ),
            dispatch(
                "decide",
                single,
                &p.decide,
                decide.clone(),
                DispatchSize::Direct(1),
            ),
        ];
        for order in 2..=tables.max_orders {
            let later = usize::from(order > 2);
            let part = |part| Share { order, part };
            for (k, (name, pipeline, groups)) in first_steps.iter().enumerate() {
                out.push(dispatch(
                    name,
                    part(0),
                    pipeline,
                    groups[later].clone(),
                    DispatchSize::Indirect(&tables.state, args(k as u64)),
                ));
            }
            for (k, groups) in (1..).zip(&slice_groups) {
                out.push(dispatch(
                    "scattering",
                    part(k),
                    &p.scattering,
                    groups[later].clone(),
                    DispatchSize::Indirect(&tables.state, args(3)),
                ));
            }
            let last = part(tables.slices);
            out.push(dispatch(
                "sum_order",
                last,
                &p.sum_order,
                sum_order.clone(),
                DispatchSize::Indirect(&tables.state, args(4)),
            ));
            out.push(dispatch(
                "decide",
                last,
                &p.decide,
                decide.clone(),
                DispatchSize::Direct(1),
            ));
            out.push(dispatch(
                "accumulate",
                last,
                &p.accumulate,
                accumulate.clone(),
                DispatchSize::Indirect(&tables.state, args(5)),
            ));
        }
        out
    }

    /// Clears S's multiple part and E, where the loop over orders adds its orders.
    fn clear_orders(&self, encoder: &mut wgpu::CommandEncoder) {
        let tables = self.tables.as_ref().expect("plan makes the tables");
        for table in [StoreTable::Multiple, StoreTable::Irradiance] {
            let (offset, size) = tables.layout.range(table);
            encoder.clear_buffer(&tables.store, offset, Some(size));
        }
    }

    /// Records the loop over orders (Algorithm 4.1) into one compute pass: all of it, or
    /// the share of this progressive frame ([`BrunetonPass::recording`]).
    fn encode_orders(
        &self,
        gpu: &GpuContext,
        io: &PassIo<'_>,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        if self.recording.is_none_or(|s| s == Share::FIRST) {
            self.clear_orders(encoder);
        }
        let dispatches = self.order_dispatches(gpu, io);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("bruneton scattering orders"),
            timestamp_writes: timestamps,
        });
        for d in &dispatches {
            if self.recording.is_none_or(|s| s == d.share) {
                d.record(&mut pass);
            }
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
            self.clear_orders(&mut encoder);
            let dispatches = self.order_dispatches(gpu, &io);
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
                    format!("scattering_orders order {} {}", d.share.order, d.name),
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
    /// The share of a progressive build it belongs to.
    share: Share,
    pipeline: &'a wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
    size: DispatchSize<'a>,
}

impl<'a> OrderDispatch<'a> {
    fn new(
        name: &'static str,
        share: Share,
        pipeline: &'a ComputePipeline,
        bind_group: wgpu::BindGroup,
        size: DispatchSize<'a>,
    ) -> Self {
        OrderDispatch {
            name,
            share,
            pipeline: &pipeline.pipeline,
            bind_group,
            size,
        }
    }

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
        // The loop over orders starts again when its inputs changed, and a progressive
        // build under way is done in one go once progressive building is off.
        let orders = single
            || (tables.next.is_some() && !self.progressive)
            || tables.built.orders.as_ref().is_none_or(|(old, old_mie)| {
                let changed = Inputs::changed(old, atmosphere);
                changed.intersects(Inputs::GROUND_ALBEDO)
                    || (changed.intersects(Inputs::MIE_PHASE) && *old_mie)
            });
        // Before an order after the second, whether the GPU has ended the loop (a read of
        // its state, the last frame's work done): the orders after it would add nothing.
        let ask = !orders && tables.next.is_some_and(|n| n.part == 0 && n.order > 2);
        let ended = ask && self.read_orders(gpu)?.running == 0;
        let tables = self.tables.as_mut().expect("made above");
        if orders || ended {
            tables.next = None;
        }
        self.recording = match (self.progressive, orders) {
            (false, _) => None,
            (true, true) => Some(Share::FIRST),
            (true, false) => tables.next,
        };
        let (slices, max_orders) = (tables.slices, tables.max_orders);
        let refresh = orders && self.recording.is_none()
            || self.recording.is_some_and(|s| s.ends_order(slices));
        plan.build_if("transmittance", columns);
        plan.build_if("density", columns);
        plan.build_if("sun_transmittance", sun);
        plan.build_if("single_scattering", single);
        plan.build_if("scattering_orders", orders || self.recording.is_some());
        plan.build_if("scattering_texture", refresh);
        let r = frame.camera_position_m.length();
        self.inside = r <= atmosphere.top_radius_m;
        if self.inside {
            plan.run("view_slice", StepKind::Pass);
        }
        plan.run("bruneton", StepKind::Pass);
        plan.building = self
            .recording
            .filter(|s| s.after(slices, max_orders).is_some())
            .map(|s| s.describe(slices, max_orders));
        let tables = self.tables.as_ref().expect("made above");
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
                let bind_group = self.bind_group(gpu, io, pipeline, &tables.params, &[], None);
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
                let views = tables.scattering_views();
                let irradiance = tables.irradiance.create_view(&Default::default());
                let mut extra: Vec<wgpu::BindingResource<'_>> = views
                    .iter()
                    .map(wgpu::BindingResource::TextureView)
                    .collect();
                extra.push(wgpu::BindingResource::TextureView(&irradiance));
                let bind_group = self.bind_group(gpu, io, &p.texture, &tables.params, &extra, None);
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
                let views = tables.scattering_views();
                let slice = tables.view_slice.create_view(&Default::default());
                let mut extra: Vec<wgpu::BindingResource<'_>> = views
                    .iter()
                    .map(wgpu::BindingResource::TextureView)
                    .collect();
                extra.push(wgpu::BindingResource::TextureView(&slice));
                let bind_group =
                    self.bind_group(gpu, io, &p.view_slice, &tables.params, &extra, None);
                let groups = texel_groups(&tables.view_slice);
                p.view_slice
                    .dispatch(encoder, "view slice", &bind_group, groups, timestamps);
            }
            "bruneton" => {
                let views = tables.scattering_views();
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
                }
                .variant(io.has_surface);
                let bind_group =
                    self.bind_group(gpu, io, render, &tables.params, &extra, Some(io.surface));
                let groups = texel_groups(io.hdr);
                render.dispatch(encoder, "bruneton", &bind_group, groups, timestamps);
            }
            other => unreachable!("the bruneton plan has no step {other}"),
        }
        let tables = self.tables.as_mut().expect("plan makes the tables");
        let built = &mut tables.built;
        match step {
            "transmittance" => built.columns = Some(atmosphere),
            "sun_transmittance" => built.sun = Some(atmosphere),
            "single_scattering" => built.single = Some(atmosphere),
            "scattering_orders" => {
                if self.recording.is_none_or(|s| s == Share::FIRST) {
                    built.orders = Some((atmosphere, mie));
                }
                tables.next = self
                    .recording
                    .and_then(|s| s.after(tables.slices, tables.max_orders));
            }
            _ => {}
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
