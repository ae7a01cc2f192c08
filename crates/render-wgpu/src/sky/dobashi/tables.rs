//! The dobashi model's segment tables on the GPU: dI_r, dI_m and dg_v per segment of the
//! sampling planes and of the sample spheres (Dobashi, Yamamoto and Nishita 2002,
//! sections 5.2-5.3), and the interval and sphere rows they are built for.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::dobashi::DobashiSettings;
use atmosphere_core::models::dobashi::sphere_tables::sphere_heights;
use bytemuck::{Pod, Zeroable};

use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{
    ComputePipeline, buffer, read_only_storage_buffer_entry, storage_texture_entry, texel_groups,
    uniform_buffer, uniform_entry,
};
use crate::gpu::readback::read_texture;
use crate::sky::transmittance::{TABLE_FORMAT, table_texture};

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
        let texture =
            |what: &str| table_texture(gpu, &format!("dobashi {label} {what}"), (width, height));
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
            rows: buffer(
                &gpu.device,
                "dobashi sphere rows",
                (16 * rows) as u64,
                wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            ),
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
        gpu.write_uniform(&self.params, &params);
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

/// The settings the plane and sphere tables depend on.
pub fn table_key(s: &DobashiSettings) -> [usize; 5] {
    [
        s.planes,
        s.spheres,
        s.table_heights,
        s.table_angles,
        s.sphere_table_angles,
    ]
}
