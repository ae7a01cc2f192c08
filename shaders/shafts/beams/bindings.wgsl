// Library: the bindings of the beams march pass and their types, laid out byte for byte
// as render-wgpu's `shafts/beams/gpu_scene.rs` packs them (every struct 16-byte
// aligned). Conventions, once for the folder: the scene frame is glTF's (right-handed,
// y up) with the camera at the origin, in metres; radiance in W m^-2 sr^-1 nm^-1 at
// three wavelengths (xyz: 680, 550, 440 nm), the light's intensity in W sr^-1 nm^-1
// (a parallel light's irradiance in W m^-2 nm^-1).

struct BeamsParams {
    // xyz the camera's right vector, w tan(half the vertical view) times the aspect.
    camera_right: vec4<f32>,
    // xyz up, w tan(half the vertical view).
    camera_up: vec4<f32>,
    // xyz forward, w where the medium has extinguished the light, m.
    camera_forward: vec4<f32>,
    scattering_per_m: vec4<f32>,
    extinction_per_m: vec4<f32>,
    // Row k: a light map texel's red, green, blue weights at wavelength k.
    channel_weights: array<vec4<f32>, 3>,
    // Width, height, steps, lights.
    size_steps_lights: vec4<u32>,
    // Primitives, BVH nodes, phase kind, phase table rows.
    counts: vec4<u32>,
    // x: the phase function's asymmetry g.
    phase: vec4<f32>,
}

struct BeamLight {
    // xyz position relative to the camera, w radius (m).
    position: vec4<f32>,
    frame_x: vec4<f32>,
    frame_y: vec4<f32>,
    frame_z: vec4<f32>,
    // A spot: cos and tan of the cone, falloff exponent; parallel: half sides, has them.
    beam: vec4<f32>,
    emission: vec4<f32>,
    // 0 point, 1 spot, 2 parallel.
    kind: u32,
    map_offset: u32,
    map_width: u32,
    map_height: u32,
    first_view: u32,
    view_count: u32,
    pad0: u32,
    pad1: u32,
}

struct ShadowView {
    // xyz apex or centre, w tan of half the view (perspective).
    origin: vec4<f32>,
    frame_x: vec4<f32>,
    frame_y: vec4<f32>,
    frame_z: vec4<f32>,
    // Orthographic half sides.
    half: vec4<f32>,
    // 0 perspective, 1 orthographic.
    kind: u32,
    size: u32,
    offset: u32,
    pad: u32,
}

struct Primitive {
    a: vec4<f32>,
    b: vec4<f32>,
    c: vec4<f32>,
    // 0 sphere, 1 box, 2 quad, 3 plane.
    kind: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

struct BvhNode {
    min: vec3<f32>,
    first: u32,
    max: vec3<f32>,
    count: u32,
}

@group(0) @binding(0) var<uniform> params: BeamsParams;
@group(0) @binding(1) var<storage, read> lights: array<BeamLight>;
@group(0) @binding(2) var<storage, read> light_texels: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> shadow_views: array<ShadowView>;
@group(0) @binding(4) var<storage, read> shadow_depths: array<f32>;
@group(0) @binding(5) var<storage, read> primitives: array<Primitive>;
@group(0) @binding(6) var<storage, read> bvh_nodes: array<BvhNode>;
// Three corners per triangle (xyz).
@group(0) @binding(7) var<storage, read> triangles: array<vec4<f32>>;
// (angle in degrees, value in sr^-1) per row of a tabulated phase function.
@group(0) @binding(8) var<storage, read> phase_table: array<vec2<f32>>;
// Radiance at the three wavelengths (xyz), w = 1.
@group(0) @binding(9) var radiance_out: texture_storage_2d<rgba32float, write>;

// The camera ray's unit direction through the pixel centre `pixel` (framebuffer
// coordinates) of the image of `params.size_steps_lights.xy` pixels.
fn pixel_direction(pixel: vec2<f32>) -> vec3<f32> {
    let size = vec2<f32>(params.size_steps_lights.xy);
    let sx = (2.0 * pixel.x / size.x - 1.0) * params.camera_right.w;
    let sy = (1.0 - 2.0 * pixel.y / size.y) * params.camera_up.w;
    return normalize(params.camera_forward.xyz + params.camera_right.xyz * sx
        + params.camera_up.xyz * sy);
}
