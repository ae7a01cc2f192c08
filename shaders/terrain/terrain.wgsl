// Entry pass: the terrain, `vertex_main` and `fragment_main` (render-wgpu's
// `terrain/pass.rs`): the chunks of the cube-sphere quadtree drawn into the surface buffer
// that every model's pixel pass reads (`common/surface.wgsl`): per pixel the outward
// normal and the distance from the camera along the pixel's ray, and the albedo from the
// Earth's colour map (alpha 1), or the water body's albedo and alpha 0, the sea
// (`common/sea_surface.wgsl`), where the interpolated height of the height field is
// below 0 (the refined coastline, `sea_colour.rs`); the land's colour gets rock on steep
// slopes and snow above the season's snow line (`land_albedo`). CPU twins: the meshes
// are built by render-wgpu's `terrain/`; the projection is `Frame::pixel_ray`'s; the
// land's colour is atmosphere-core's `geo/land_cover.rs`. No paper.
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
    // The season's snow line (`land_albedo`): x its height at the thermal equator, m; y
    // its fall to the pole, m; z the thermal equator's latitude, rad; w the band over
    // which snow sets in, m.
    snow_line: vec4<f32>,
    // rgb: rock's albedo; w: the slope cosine where rock sets in.
    rock: vec4<f32>,
    // rgb: snow's albedo; w: the slope cosine past which all is rock.
    snow: vec4<f32>,
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

// The land's albedo from the colour map's `map` at planet-centred `p`, `height` m above
// the sea, with unit `normal` (atmosphere-core's `geo::land_cover::land_albedo`): rock
// where steep, snow above the season's snow line, none at or below sea level.
fn land_albedo(map: vec3<f32>, p: vec3<f32>, height: f32, normal: vec3<f32>) -> vec3<f32> {
    let up = normalize(p);
    let rock = 1.0 - smoothstep(terrain.snow.w, terrain.rock.w, dot(normal, up));
    let latitude = atan2(p.z, length(p.xy));
    let sine = sin(latitude - terrain.snow_line.z);
    let line = terrain.snow_line.x - terrain.snow_line.y * sine * sine;
    let band = 0.5 * terrain.snow_line.w;
    let snow = select(0.0, smoothstep(-band, band, height - line), height > 0.0) * (1.0 - rock);
    let ground = mix(map, terrain.rock.rgb, rock);
    return mix(ground, terrain.snow.rgb, snow);
}

@fragment
fn fragment_main(in: VertexOut) -> SurfaceOut {
    let uv = map_uv(in.planet);
    let colour = textureSampleGrad(colour_map, colour_sampler, uv,
        unwrap_derivative(dpdx(uv)), unwrap_derivative(dpdy(uv)));
    let normal = normalize(in.normal);
    var out: SurfaceOut;
    out.geometry = vec4<f32>(normal, length(in.relative));
    let water = in.height < 0.0;
    let land = land_albedo(colour.rgb, in.planet, in.height, normal);
    out.albedo = select(vec4<f32>(land, 1.0), vec4<f32>(terrain.sea_albedo.rgb, 0.0), water);
    return out;
}
