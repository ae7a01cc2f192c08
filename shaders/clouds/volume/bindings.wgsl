// Half-angle slicing of a voxel cloud (Riley et al. 2004 sections 4.2 and 5, after
// Kniss et al. 2002): the parameters and bindings every slice pass shares. Positions are
// relative to the camera, in metres. Layout checked against
// render-wgpu/src/clouds/volume/slicing_uniform.rs.

struct SlicingParams {
    // World (relative to the camera) to the eye buffer's clip space.
    view_proj: mat4x4<f32>,
    // The light buffer's axes e_u, e_v and the coordinates of its lowest corner.
    light_u: vec4<f32>,
    light_v: vec4<f32>,
    // Its extent along e_u and e_v, m; its side, texels; the light's path between slices, m.
    light_size: vec4<f32>,
    // The slices' normal h; h . x of slice 0.
    half: vec4<f32>,
    // The direction the light travels, l = -sun; the slices' spacing along h, m.
    light_dir: vec4<f32>,
    // Towards the sun; the albedo.
    sun: vec4<f32>,
    // The sun's irradiance at 680, 550, 440 nm; the extinction at density 1, m^-1.
    irradiance: vec4<f32>,
    // The box's lowest corner; the voxel's side, m.
    box_origin: vec4<f32>,
    // The grid's sides; the light's method (0 riley, 1 octaves).
    dims: vec4<u32>,
    // xi, the octaves, 1 when the eye composites front to back.
    misc: vec4<f32>,
}

@group(0) @binding(0) var<uniform> volume: SlicingParams;
// The densities, R32Float, read texel by texel.
@group(0) @binding(1) var density: texture_3d<f32>;
// A_n at ANGLES angles per row for each wavelength, then F_n (layer_inputs.rs's layout).
@group(0) @binding(2) var<storage, read> orders: array<f32>;
// The light buffer the pass reads: (I at 680, 550, 440 nm, tau).
@group(0) @binding(3) var light_in: texture_2d<f32>;

const PI: f32 = 3.14159265358979;
const ANGLES: u32 = 1024u;
const ORDERS: u32 = 26u;
const WAVES: u32 = 3u;

struct SliceVertex {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
}
