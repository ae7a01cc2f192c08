// Library: the parameters of the cloud layer's sun map (render-wgpu's
// `clouds/sun_map_texture.rs`, whose layout the naga test checks) at binding 33, read by
// its fill and per-pixel passes, the layer's march, the cloud's shadow in the air
// (`clouds/air_shadow.wgsl`) and, for its flags, by every model's pixel pass
// (`common/surface.wgsl`).

// WGSL `SunMapParams` (Rust `SunMapUniform`).
struct SunMapParams {
    // The grid's axes (planet-fixed, unit); w of the first: the cell's side on the base
    // sphere, m.
    east_cell: vec4<f32>,
    north: vec4<f32>,
    up: vec4<f32>,
    // Unit vector towards the sun (xyz).
    sun: vec4<f32>,
    // Radii of the layer's base and top, m; z: 1 when the map shades the air under the
    // base (`clouds/air_shadow.wgsl`), else 0; w unused.
    radii: vec4<f32>,
    // Cells per side, levels, march steps per texel, 1 when the frame has the map.
    counts: vec4<u32>,
}

@group(0) @binding(33) var<uniform> sun_map_params: SunMapParams;

// Whether the frame's sun map shades the air under the layer's base (radii.z): the
// pixel passes then read the cloud's shadow in the air per pixel
// (`clouds/air_shadow.wgsl`).
fn cloud_shafts_on() -> bool {
    return sun_map_params.counts.w == 1u && sun_map_params.radii.z > 0.5;
}
