// Entry pass: the terrain, `vertex_main` and `fragment_main` (render-wgpu's
// `terrain/pass.rs`): the chunks of the cube-sphere quadtree drawn into the surface buffer
// that every model's pixel pass reads (`common/surface.wgsl`): per pixel the outward
// normal and the distance from the camera along the pixel's ray, and the albedo from the
// Earth's colour map, or the water's albedo where the interpolated height of the height
// field is below 0 (the refined coastline, `sea_colour.rs`). CPU twin: none in
// atmosphere-core (the meshes are built by render-wgpu's `terrain/`); the projection is
// `Frame::pixel_ray`'s. No paper.
//
// Camera-relative: a vertex is its chunk's offset `origin - camera` (f64 on the CPU,
// rounded to f32) plus its f32 offset from the origin, so positions near the camera are
// small and exact to a fraction of a millimetre. The projection is that of
// `pixel_direction` (common/frame_params.wgsl) with reversed depth and an infinite far plane:
// clip = (x / half_width, y / half_height, near, d) for camera-axis coordinates (x, y)
// and depth d along the forward axis, so depth = near / d falls from 1 at the near plane
// to 0 at infinity, and f32 depth keeps its relative precision at every distance.

struct TerrainParams {
    // The camera's right, up and forward axes in planet axes; right and up divided by
    // half the image's extent at unit distance.
    right: vec4<f32>,
    up: vec4<f32>,
    forward: vec4<f32>,
    // x: the near plane's distance, m.
    near: vec4<f32>,
    // rgb: the water's albedo.
    sea_albedo: vec4<f32>,
}

struct Chunk {
    // xyz: the chunk's origin minus the camera, m.
    offset: vec4<f32>,
    // xyz: the chunk's origin, planet-centred, m (for latitude and longitude).
    origin: vec4<f32>,
}

@group(0) @binding(0) var<uniform> terrain: TerrainParams;
@group(0) @binding(1) var<storage, read> chunks: array<Chunk>;
@group(0) @binding(2) var colour_map: texture_2d<f32>;
@group(0) @binding(3) var colour_sampler: sampler;

const TAU: f32 = 6.28318530717959;
const PI: f32 = 3.14159265358979;

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    // Camera-relative position, m.
    @location(0) relative: vec3<f32>,
    // Planet-centred position, m (rounded to about 0.5 m).
    @location(1) planet: vec3<f32>,
    @location(2) normal: vec3<f32>,
    // The height field's height, m (below 0: water).
    @location(3) height: f32,
}

@vertex
fn vertex_main(
    @builtin(instance_index) chunk: u32,
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) height: f32,
) -> VertexOut {
    let c = chunks[chunk];
    let relative = c.offset.xyz + position;
    var out: VertexOut;
    out.clip = vec4<f32>(dot(relative, terrain.right.xyz), dot(relative, terrain.up.xyz),
        terrain.near.x, dot(relative, terrain.forward.xyz));
    out.relative = relative;
    out.planet = c.origin.xyz + position;
    out.normal = normal;
    out.height = height;
    return out;
}

struct SurfaceOut {
    @location(0) geometry: vec4<f32>,
    @location(1) albedo: vec4<f32>,
}

// The colour map's coordinates of a planet-centred point (`geo_grid.rs`): u from 180 deg
// west eastwards, v from the north pole.
fn map_uv(p: vec3<f32>) -> vec2<f32> {
    let lon = atan2(p.y, p.x);
    let lat = atan2(p.z, length(p.xy));
    return vec2<f32>((lon + PI) / TAU, (0.5 * PI - lat) / PI);
}

// A screen derivative of u across the map's seam at 180 deg, where u wraps from 1 to 0.
fn unwrap_derivative(d: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(d.x - round(d.x), d.y);
}

@fragment
fn fragment_main(in: VertexOut) -> SurfaceOut {
    let uv = map_uv(in.planet);
    let colour = textureSampleGrad(colour_map, colour_sampler, uv,
        unwrap_derivative(dpdx(uv)), unwrap_derivative(dpdy(uv)));
    var out: SurfaceOut;
    out.geometry = vec4<f32>(normalize(in.normal), length(in.relative));
    out.albedo = vec4<f32>(select(colour.rgb, terrain.sea_albedo.rgb, in.height < 0.0), 1.0);
    return out;
}
