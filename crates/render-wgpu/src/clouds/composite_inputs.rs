//! What the composite of a frame's cloud with its sky model binds besides the cloud
//! (`shaders/clouds/composite_pixel.wgsl`): the frame's atmosphere and frame uniforms,
//! the model's pixels (L_full), its second run in front of the cloud (every pixel's, or
//! the reduced rays' with their entries and transmittance), the composite's flags and the
//! HDR target it writes. The composite pass (`frame_pass.rs`) and the spheres' upsample
//! that composites (`spheres/frame_spheres.rs`) bind them alike.

use crate::frame::atmosphere_uniform::AtmosphereUniform;
use crate::frame::uniform::FrameUniform;
use crate::gpu::formats::HDR_FORMAT;
use crate::gpu::pipeline::{storage_texture_entry, texture_entry, uniform_entry};

/// Bindings of `composite_pixel.wgsl`: the atmosphere and frame uniforms (0, 1), the
/// model's pixels (2), its run in front (3), the HDR target (6), the flags (7), the
/// reduced run's entries (8) and transmittance (9).
const BINDINGS: [u32; 8] = [0, 1, 2, 3, 6, 7, 8, 9];

/// The views and buffers of one frame's composite.
#[derive(Debug)]
pub struct CompositeInputs {
    atmosphere: wgpu::Buffer,
    frame: wgpu::Buffer,
    flags: wgpu::Buffer,
    /// The model's pixels, its run in front, the HDR target, the reduced run's entries and
    /// transmittance (the run in front's geometry where it takes every pixel: unread).
    views: [wgpu::TextureView; 5],
}

/// The textures a composite reads and writes, as [`CompositeInputs`] binds them.
#[derive(Clone, Copy, Debug)]
pub struct CompositeTextures<'a> {
    pub full: &'a wgpu::Texture,
    pub front: &'a wgpu::Texture,
    pub hdr: &'a wgpu::Texture,
    pub entries: &'a wgpu::Texture,
    pub transmittance: &'a wgpu::Texture,
}

impl CompositeInputs {
    /// The inputs of `textures` with the frame's `uniforms` (atmosphere, frame) and the
    /// composite's `flags`.
    pub fn new(
        (atmosphere, frame): (&wgpu::Buffer, &wgpu::Buffer),
        flags: &wgpu::Buffer,
        textures: CompositeTextures<'_>,
    ) -> CompositeInputs {
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        CompositeInputs {
            atmosphere: atmosphere.clone(),
            frame: frame.clone(),
            flags: flags.clone(),
            views: [
                view(textures.full),
                view(textures.front),
                view(textures.hdr),
                view(textures.entries),
                view(textures.transmittance),
            ],
        }
    }

    /// The layout entries of the composite's bindings.
    pub fn layout_entries() -> [wgpu::BindGroupLayoutEntry; 8] {
        use wgpu::TextureViewDimension::D2;
        let [
            atmosphere,
            frame,
            full,
            front,
            hdr,
            flags,
            entries,
            transmittance,
        ] = BINDINGS;
        [
            uniform_entry(atmosphere, size_of::<AtmosphereUniform>()),
            uniform_entry(frame, size_of::<FrameUniform>()),
            texture_entry(full, D2),
            texture_entry(front, D2),
            storage_texture_entry(hdr, HDR_FORMAT, D2),
            uniform_entry(flags, 16),
            texture_entry(entries, D2),
            texture_entry(transmittance, D2),
        ]
    }

    /// The (binding, resource) pairs of a bind group.
    pub fn bindings(&self) -> [(u32, wgpu::BindingResource<'_>); 8] {
        let [
            atmosphere,
            frame,
            full,
            front,
            hdr,
            flags,
            entries,
            transmittance,
        ] = BINDINGS;
        let [
            full_view,
            front_view,
            hdr_view,
            entries_view,
            transmittance_view,
        ] = &self.views;
        let texture = wgpu::BindingResource::TextureView;
        [
            (atmosphere, self.atmosphere.as_entire_binding()),
            (frame, self.frame.as_entire_binding()),
            (full, texture(full_view)),
            (front, texture(front_view)),
            (hdr, texture(hdr_view)),
            (flags, self.flags.as_entire_binding()),
            (entries, texture(entries_view)),
            (transmittance, texture(transmittance_view)),
        ]
    }
}
