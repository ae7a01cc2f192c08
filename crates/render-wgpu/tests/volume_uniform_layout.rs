//! `VolumeUniform` and `VolumesUniform` (render-wgpu's `precipitation/volume_uniform.rs`)
//! have the size and member offsets of `VolumeParams` and `VolumesParams` in
//! `shaders/precipitation/volume_params.wgsl`, as naga lays them out in the volumes pass.

use render_wgpu::gpu::shaders;
use render_wgpu::precipitation::volume_uniform::{VolumeUniform, VolumesUniform};

const PASS: &str = "precipitation/volumes_composite.wgsl";

/// Size and member offsets (by name) of WGSL struct `name` in the volumes pass.
fn wgsl_layout(name: &str) -> (usize, Vec<(String, usize)>) {
    let source = shaders::composed(PASS).unwrap();
    let module = naga::front::wgsl::parse_str(&source).unwrap();
    module
        .types
        .iter()
        .find_map(|(_, ty)| match (&ty.name, &ty.inner) {
            (Some(n), naga::TypeInner::Struct { members, span }) if n == name => Some((
                *span as usize,
                members
                    .iter()
                    .map(|m| (m.name.clone().unwrap(), m.offset as usize))
                    .collect(),
            )),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no struct {name} in {PASS}"))
}

#[test]
fn the_volume_uniforms_match_their_wgsl_layouts() {
    use std::mem::offset_of;
    let volume = [
        ("kind", offset_of!(VolumeUniform, kind)),
        ("axis", offset_of!(VolumeUniform, axis)),
        ("place", offset_of!(VolumeUniform, place)),
        ("bin_deg", offset_of!(VolumeUniform, bin_deg)),
        ("extinction", offset_of!(VolumeUniform, extinction)),
        ("sun_irradiance", offset_of!(VolumeUniform, sun_irradiance)),
        ("sky_radiance", offset_of!(VolumeUniform, sky_radiance)),
        ("probes", offset_of!(VolumeUniform, probes)),
        ("lobes", offset_of!(VolumeUniform, lobes)),
    ];
    let volumes = [
        ("count", offset_of!(VolumesUniform, count)),
        ("reduction", offset_of!(VolumesUniform, reduction)),
        ("volumes", offset_of!(VolumesUniform, volumes)),
    ];
    for (name, size, rust) in [
        ("VolumeParams", size_of::<VolumeUniform>(), &volume[..]),
        ("VolumesParams", size_of::<VolumesUniform>(), &volumes[..]),
    ] {
        let (span, wgsl) = wgsl_layout(name);
        assert_eq!(span, size, "size of {name}");
        let rust: Vec<(String, usize)> = rust.iter().map(|&(n, o)| (n.to_string(), o)).collect();
        assert_eq!(wgsl, rust, "{name}");
    }
}
