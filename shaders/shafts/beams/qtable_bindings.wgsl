// Library: the bindings of the q(u, v) table pass beside the scene's (`bindings.wgsl`,
// group 0), laid out as render-wgpu's `shafts/beams/qtable_pass.rs` packs them.

struct QtableParams {
    // x: the plane interval dt, m; y: 1 where each sample is weighted by g at it
    // (`weighted_samples`); z: the most samples of an interval (1 + `max_subplanes`);
    // w: 1 where each ray counts its own sub-planes (`subplanes_per_ray`).
    interval_m: vec4<f32>,
    // The ranges the table's nodes span evenly: asinh(u / dt) (xy) and ln v (zw).
    ranges: vec4<f32>,
    // Nodes along u and along v.
    nodes: vec4<u32>,
    // A reduced walk's upsampling (`qtable_upsample.wgsl`): the taps' largest spread of
    // radiance (x, a share of the brightest) and of ray ends (y, of the nearest); z: 1
    // where the frame's own ray ends are given (the scene has glTF meshes).
    upsample: vec4<f32>,
}

@group(1) @binding(0) var<uniform> qtable: QtableParams;
// Where each pixel's ray ends, m (`ray_end.wgsl`).
@group(1) @binding(1) var ray_end: texture_2d<f32>;
// q(u, v) at the three wavelengths (rgb), m^-2 sr^-1: u across, v down.
@group(1) @binding(2) var q_table: texture_2d<f32>;
