// Library: the bindings of the virtual planes pass beside the scene's
// (`bindings.wgsl`, group 0), laid out as render-wgpu's `shafts/beams/planes_pass.rs`
// packs them.

struct PlanesParams {
    // Planes, lattice points on a side, lights, 0.
    planes_lattice_lights: vec4<u32>,
    // x: the spacing of the planes along the view direction, m.
    spacing_m: vec4<f32>,
}

@group(1) @binding(0) var<uniform> planes: PlanesParams;
// Where each pixel's ray ends, m (`ray_end.wgsl`).
@group(1) @binding(1) var ray_end: texture_2d<f32>;
