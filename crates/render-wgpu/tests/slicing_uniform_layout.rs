//! `SlicingUniform` (render-wgpu's `clouds/volume/slicing_uniform.rs`) has the size and
//! member offsets of `SlicingParams` in `shaders/clouds/volume/bindings.wgsl`, as naga
//! lays it out in both slice passes.

use render_wgpu::clouds::volume::slicing_uniform::SlicingUniform;
use render_wgpu::gpu::shaders;

#[test]
fn the_slicing_uniform_matches_its_wgsl_layout() {
    let rust = [
        ("view_proj", std::mem::offset_of!(SlicingUniform, view_proj)),
        ("light_u", std::mem::offset_of!(SlicingUniform, light_u)),
        ("light_v", std::mem::offset_of!(SlicingUniform, light_v)),
        (
            "light_size",
            std::mem::offset_of!(SlicingUniform, light_size),
        ),
        ("half", std::mem::offset_of!(SlicingUniform, half)),
        ("light_dir", std::mem::offset_of!(SlicingUniform, light_dir)),
        ("sun", std::mem::offset_of!(SlicingUniform, sun)),
        (
            "irradiance",
            std::mem::offset_of!(SlicingUniform, irradiance),
        ),
        (
            "box_origin",
            std::mem::offset_of!(SlicingUniform, box_origin),
        ),
        ("dims", std::mem::offset_of!(SlicingUniform, dims)),
        ("misc", std::mem::offset_of!(SlicingUniform, misc)),
    ];
    for shader in [
        "clouds/volume/eye_slice.wgsl",
        "clouds/volume/light_slice.wgsl",
    ] {
        let source = shaders::composed(shader).unwrap();
        let module = naga::front::wgsl::parse_str(&source).unwrap();
        let (span, members) = module
            .types
            .iter()
            .find_map(|(_, ty)| match (&ty.name, &ty.inner) {
                (Some(n), naga::TypeInner::Struct { members, span }) if n == "SlicingParams" => {
                    Some((*span as usize, members.clone()))
                }
                _ => None,
            })
            .unwrap_or_else(|| panic!("no SlicingParams in {shader}"));
        assert_eq!(span, size_of::<SlicingUniform>(), "{shader}");
        let wgsl: Vec<(String, usize)> = members
            .iter()
            .map(|m| (m.name.clone().unwrap(), m.offset as usize))
            .collect();
        let rust: Vec<(String, usize)> = rust.iter().map(|&(n, o)| (n.to_string(), o)).collect();
        assert_eq!(wgsl, rust, "{shader}");
    }
}
