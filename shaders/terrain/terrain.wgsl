// Entry pass: the terrain, `vertex_main` and `fragment_main` (render-wgpu's
// `terrain/pass.rs`): the chunks of the cube-sphere quadtree drawn into the surface buffer
// that every model's pixel pass reads (`common/surface.wgsl`): per pixel the outward
// normal and the distance from the camera along the pixel's ray, and the albedo from the
// Earth's colour map (alpha 1), or the water body's albedo and alpha 0, the sea
// (`common/sea_surface.wgsl`), where the interpolated height of the height field is
// below 0 (the refined coastline, `sea_colour.rs`); the land's colour gets rock on steep
// slopes and snow above the season's snow line (`land_albedo`). CPU twins: the meshes
// are built by render-wgpu's `terrain/`; the projection is `Frame::pixel_ray`'s; the
// land's colour is atmosphere-core's `geo/land_cover.rs`; the normal map's sample and
// fade are `terrain/normal_map.rs`'s, its morph towards the parent's map
// `terrain/detail_morph.rs`'s. No paper but Strugar 2009's morph (below).
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
    // x: the near plane's distance, m; y: where a morph begins, as a fraction of its end
    // (`geomorph.rs`'s MORPH_START); z: pixels per radian (the normal maps' fade).
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
    // xyz: the chunk's origin, planet-centred, m (for latitude and longitude); w: a
    // normal-map texel's side, m.
    origin: vec4<f32>,
    // x, y: where the chunk's own and its coarser neighbours' morphs end, m (0: none);
    // z: the edges bordering a coarser chunk as bits (1 << Edge: u min, u max, v min,
    // v max); w: cells along a side.
    morph: vec4<f32>,
}

@group(0) @binding(0) var<uniform> terrain: TerrainParams;
@group(0) @binding(1) var<storage, read> chunks: array<Chunk>;
@group(0) @binding(2) var colour_map: texture_2d<f32>;
@group(0) @binding(3) var colour_sampler: sampler;
// The drawn chunk's normal map (`normal_map.rs`): xyz the refined relief's normal at
// twice the mesh's resolution, clamped bilinear.
@group(1) @binding(0) var normal_map: texture_2d<f32>;
@group(1) @binding(1) var normal_sampler: sampler;
// The parent's normal map over the drawn chunk (`detail_morph.rs`): texel (a, b) is the
// chunk's mesh cell (a - 1, b - 1), one texel beyond the chunk on every side.
@group(1) @binding(2) var parent_map: texture_2d<f32>;

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
    // The chunk coordinate (i, j) / cells of the vertex, for the normal map.
    @location(4) chunk_uv: vec2<f32>,
    // A normal-map texel's side, m.
    @location(5) @interpolate(flat) texel: f32,
    // The chunk's own morph factor, by which its map blends towards the parent's.
    @location(6) detail_morph: f32,
}

// Geomorphing (render-wgpu's `terrain/geomorph.rs`, `morph_factor`, `morph_role` and
// `normal_factor`; Strugar 2009): the factors of vertex `index` of chunk `c`, `relative`
// to the camera, by which it moves towards its morph target (x) and its normal towards
// the target's, the parent's (y): the coarser neighbour's factor for the even vertices of
// an edge bordering one, its own otherwise, but no move for the parent's other vertices
// (whose normals still morph); and the chunk's own factor at the vertex, the normal
// map's (z, `detail_morph::detail_factor`).
fn morph_factors(c: Chunk, index: u32, relative: vec3<f32>) -> vec3<f32> {
    let cells = u32(c.morph.w);
    let i = index % (cells + 1u);
    let j = index / (cells + 1u);
    let mask = u32(c.morph.z);
    let on_coarser = (i == 0u && (mask & 1u) != 0u) || (i == cells && (mask & 2u) != 0u)
        || (j == 0u && (mask & 4u) != 0u) || (j == cells && (mask & 8u) != 0u);
    let odd = (i % 2u) == 1u || (j % 2u) == 1u;
    let edge = on_coarser && !odd;
    let end = select(c.morph.x, c.morph.y, edge);
    let start = terrain.near.y;
    let distance = length(relative);
    let m = clamp((distance / end - start) / (1.0 - start), 0.0, 1.0);
    let normal_m = select(0.0, m, end > 0.0);
    let own = clamp((distance / c.morph.x - start) / (1.0 - start), 0.0, 1.0);
    let detail_m = select(0.0, own, c.morph.x > 0.0);
    return vec3<f32>(select(0.0, normal_m, odd || edge), normal_m, detail_m);
}

@vertex
fn vertex_main(
    @builtin(instance_index) chunk: u32,
    @builtin(vertex_index) index: u32,
    @location(0) own_position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) own_height: f32,
    // The morph target relative to the vertex.
    @location(3) morph_offset: vec3<f32>,
    @location(4) target_height: f32,
    // The parent's normal at the morph target (`geomorph.rs`'s `normal_pair`).
    @location(5) target_normal: vec3<f32>,
) -> VertexOut {
    let c = chunks[chunk];
    let factors = morph_factors(c, index, c.offset.xyz + own_position);
    let m = factors.x;
    let position = own_position + m * morph_offset;
    let height = mix(own_height, target_height, m);
    let relative = c.offset.xyz + position;
    var out: VertexOut;
    out.clip = vec4<f32>(dot(relative, terrain.right.xyz), dot(relative, terrain.up.xyz),
        terrain.near.x, dot(relative, terrain.forward.xyz));
    out.relative = relative;
    out.planet = c.origin.xyz + position;
    out.normal = normalize(mix(normal, target_normal, factors.y));
    out.height = height;
    let cells = u32(c.morph.w);
    out.chunk_uv = vec2<f32>(f32(index % (cells + 1u)), f32(index / (cells + 1u))) / c.morph.w;
    out.texel = c.origin.w;
    out.detail_morph = factors.z;
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
    // The normal map, blended towards the parent's over the chunk by the chunk's morph
    // factor `m` (`detail_morph::morphed_detail`), where its texels (the parent's at
    // m = 1, `morphed_texel_m`) cover 2 pixels or more, the mesh's normal where they
    // cover 1 or less (`normal_map::detail_weight`, `shading_normal`).
    let distance = length(in.relative);
    let m = in.detail_morph;
    let texel = in.texel * (1.0 + m);
    let weight = clamp(texel * terrain.near.z / distance - 1.0, 0.0, 1.0);
    let mesh = normalize(in.normal);
    let own = normalize(textureSample(normal_map, normal_sampler, in.chunk_uv).xyz);
    let side = f32(textureDimensions(parent_map).x);
    let parent_uv = (in.chunk_uv * (side - 2.0) + 1.0) / side;
    let parent = normalize(textureSample(parent_map, normal_sampler, parent_uv).xyz);
    let map = normalize(mix(own, parent, m));
    let normal = normalize(mesh + (map - mesh) * weight);
    var out: SurfaceOut;
    out.geometry = vec4<f32>(normal, distance);
    let water = in.height < 0.0;
    let land = land_albedo(colour.rgb, in.planet, in.height, normal);
    out.albedo = select(vec4<f32>(land, 1.0), vec4<f32>(terrain.sea_albedo.rgb, 0.0), water);
    return out;
}
