// Entry pass: where each pixel's ray ends, `main` (render-wgpu's
// `shafts/beams/planes_pass.rs`): at the first occluder or where the medium has
// extinguished the light, as the march's ray ends (`march.wgsl`). The virtual planes
// read it as a rasteriser reads a depth buffer. CPU twin: atmosphere-core's
// `InScattering::ray_end_m`.

#import shafts/beams/bindings.wgsl
#import shafts/beams/occluders.wgsl

@group(0) @binding(10) var ray_end_out: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = params.size_steps_lights.xy;
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let sx = (2.0 * (f32(id.x) + 0.5) / f32(size.x) - 1.0) * params.camera_right.w;
    let sy = (1.0 - 2.0 * (f32(id.y) + 0.5) / f32(size.y)) * params.camera_up.w;
    let dir = normalize(params.camera_forward.xyz + params.camera_right.xyz * sx
        + params.camera_up.xyz * sy);
    let limit = params.camera_forward.w;
    let hit = nearest_occluder(vec3<f32>(0.0), dir, limit);
    textureStore(ray_end_out, vec2<i32>(id.xy), vec4<f32>(select(limit, hit, hit != MISS), 0.0, 0.0, 1.0));
}
