//! How each step other than the loop over orders (`orders.rs`) records its dispatch.

use crate::frame::surface_buffer::{ALBEDO_BINDING, GEOMETRY_BINDING};
use crate::gpu::context::GpuContext;
use crate::gpu::pipeline::{ComputePipeline, texel_groups};
use crate::sky::bruneton::bindings::bind_group;
use crate::sky::bruneton::pipelines::{Pipelines, SHADOW_MAP_BINDING, SHADOW_TOPS_BINDING};
use crate::sky::bruneton::store::{DENSITY_SAMPLES, StoreTable};
use crate::sky::bruneton::tables::Tables;
use crate::sky::bruneton::workgroups::{FLAT, flat_groups};
use crate::sky::model_pass::PassIo;
use crate::sky::table_sampling::TableSampling;

type Timestamps<'t> = Option<wgpu::ComputePassTimestampWrites<'t>>;

/// What a step records with: the frame's inputs, the tables and the pipelines.
#[derive(Debug)]
pub struct StepEncoder<'a> {
    pub gpu: &'a GpuContext,
    pub io: &'a PassIo<'a>,
    pub tables: &'a Tables,
    pub pipelines: &'a Pipelines,
    pub sampling: &'a TableSampling,
}

impl StepEncoder<'_> {
    /// The bind group of `pipeline` whose own resources are the three scattering
    /// textures then `own`, with `elsewhere` (binding, resource) pairs.
    fn scattering_bind_group(
        &self,
        pipeline: &ComputePipeline,
        own: &[&wgpu::TextureView],
        elsewhere: &[(u32, wgpu::BindingResource<'_>)],
    ) -> wgpu::BindGroup {
        let t = self.tables;
        let views = t.scattering_views();
        let extra: Vec<_> = views
            .iter()
            .chain(own.iter().copied())
            .map(wgpu::BindingResource::TextureView)
            .collect();
        bind_group(self.gpu, self.io, t, pipeline, &t.params, &extra, elsewhere)
    }

    /// One dispatch of `groups` workgroups of `pipeline` with the shared bindings alone.
    fn shared_only(
        &self,
        pipeline: &ComputePipeline,
        label: &str,
        groups: [u32; 3],
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Timestamps<'_>,
    ) {
        let t = self.tables;
        let bind_group = bind_group(self.gpu, self.io, t, pipeline, &t.params, &[], &[]);
        pipeline.dispatch(encoder, label, &bind_group, groups, timestamps);
    }

    /// The density table into the store, then copied into its texture.
    pub fn density(&self, encoder: &mut wgpu::CommandEncoder, timestamps: Timestamps<'_>) {
        let t = self.tables;
        let groups = [DENSITY_SAMPLES.div_ceil(FLAT), 1, 1];
        self.shared_only(
            &self.pipelines.density,
            "density",
            groups,
            encoder,
            timestamps,
        );
        let (offset, _) = t.layout.range(StoreTable::Density);
        encoder.copy_buffer_to_texture(
            wgpu::TexelCopyBufferInfo {
                buffer: &t.store,
                layout: wgpu::TexelCopyBufferLayout {
                    offset,
                    bytes_per_row: Some(DENSITY_SAMPLES * 16),
                    rows_per_image: None,
                },
            },
            t.density.as_image_copy(),
            Tables::density_extent(),
        );
    }

    /// Single scattering: one invocation per texel of S.
    pub fn single_scattering(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Timestamps<'_>,
    ) {
        let texels = self.tables.settings.scattering_size.texels() as u32;
        let single = &self.pipelines.single;
        let groups = flat_groups(texels);
        self.shared_only(single, "single scattering", groups, encoder, timestamps);
    }

    /// S into the three 3D textures and E into its 2D texture.
    pub fn scattering_texture(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Timestamps<'_>,
    ) {
        let t = self.tables;
        let irradiance = t.irradiance.create_view(&Default::default());
        let texture = &self.pipelines.texture;
        let bind_group = self.scattering_bind_group(texture, &[&irradiance], &[]);
        let (e_mu_s, e_r) = t.settings.irradiance_size;
        let texels = (t.settings.scattering_size.texels() as u32).max((e_mu_s * e_r) as u32);
        let groups = flat_groups(texels);
        texture.dispatch(
            encoder,
            "scattering texture",
            &bind_group,
            groups,
            timestamps,
        );
    }

    /// S at the camera's r and mu_s for every (mu, nu) node.
    pub fn view_slice(&self, encoder: &mut wgpu::CommandEncoder, timestamps: Timestamps<'_>) {
        let slice = self.tables.view_slice.create_view(&Default::default());
        let pipeline = &self.pipelines.view_slice;
        let bind_group = self.scattering_bind_group(pipeline, &[&slice], &[]);
        let groups = texel_groups(&self.tables.view_slice);
        pipeline.dispatch(encoder, "view slice", &bind_group, groups, timestamps);
    }

    /// The per-pixel pass, for a camera `inside` the atmosphere (after the view slice) or
    /// above it.
    pub fn render(
        &self,
        inside: bool,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Timestamps<'_>,
    ) {
        let (t, io) = (self.tables, self.io);
        let hdr = io.hdr.create_view(&Default::default());
        let slice = t.view_slice.create_view(&Default::default());
        let irradiance = t.irradiance.create_view(&Default::default());
        let p = self.pipelines;
        let render =
            if inside { &p.render_inside } else { &p.render }.variant(io.has_surface, io.has_sea);
        let [geometry, albedo] = io.surface;
        let shadow = io.shadow.view();
        let [map, map_params] = io.sun_map.bindings();
        let surface = [
            (
                GEOMETRY_BINDING,
                wgpu::BindingResource::TextureView(geometry),
            ),
            (ALBEDO_BINDING, wgpu::BindingResource::TextureView(albedo)),
            map,
            map_params,
            self.sampling.sampler_binding(),
            (
                SHADOW_TOPS_BINDING,
                wgpu::BindingResource::TextureView(&shadow),
            ),
            (SHADOW_MAP_BINDING, io.shadow.params().as_entire_binding()),
        ];
        let bind_group = self.scattering_bind_group(render, &[&hdr, &slice, &irradiance], &surface);
        let groups = texel_groups(io.hdr);
        render.dispatch(encoder, "bruneton", &bind_group, groups, timestamps);
    }
}
