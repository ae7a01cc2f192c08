// Library: the way from a point of the medium to a light and the light it brings:
// Dobashi, Yamamoto and Nishita 2000 Eq. 3 (a point light's I(theta, phi) / r^2, the
// parallel light's I_0), the light maps of their section 5.1 and Appendix A, a spot's
// cone and cos^n falloff. CPU twins: atmosphere-core's `beams/light.rs` (`path_from`)
// and `beams/light_map.rs` (`sample`: bilinear, clamped or wrapped in u).

#import shafts/beams/bindings.wgsl

const TAU: f32 = 6.28318530717959;
const PI_BEAMS: f32 = 3.14159265358979;

struct LightPath {
    // Whether the point is inside the beam; nothing else is set where it is not.
    inside: bool,
    to_light: vec3<f32>,
    distance_m: f32,
    // 1 / r^2 times a spot's falloff (`LightPath::factor`).
    factor: f32,
    // A spot's cos^n falloff; 1 for the other lights.
    profile: f32,
    // Where the light map is read: u across, v down.
    uv: vec2<f32>,
    wrap_u: bool,
}

fn light_frame_local(light: BeamLight, v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(v, light.frame_x.xyz), dot(v, light.frame_y.xyz), dot(v, light.frame_z.xyz));
}

fn light_path(light: BeamLight, point: vec3<f32>) -> LightPath {
    var path: LightPath;
    path.inside = false;
    path.wrap_u = false;
    if light.kind == 2u {
        // Parallel: from its plane along frame z.
        let local = light_frame_local(light, point - light.position.xyz);
        if local.z < 0.0 {
            return path;
        }
        path.to_light = -light.frame_z.xyz;
        path.distance_m = max(local.z, 0.0);
        path.factor = 1.0;
        path.profile = 1.0;
        path.uv = vec2<f32>(0.5, 0.5);
        if light.beam.z > 0.0 {
            let half = light.beam.xy;
            if abs(local.x) > half.x || abs(local.y) > half.y {
                return path;
            }
            path.uv = vec2<f32>(0.5 + 0.5 * local.x / half.x, 0.5 - 0.5 * local.y / half.y);
        }
        path.inside = true;
        return path;
    }
    let offset = light.position.xyz - point;
    let r = length(offset);
    path.to_light = select(vec3<f32>(0.0, 1.0, 0.0), offset / r, r > 0.0);
    path.distance_m = r;
    let inverse_square = 1.0 / (max(r, light.position.w) * max(r, light.position.w));
    let d = light_frame_local(light, -path.to_light);
    if light.kind == 0u {
        // acos(d.z) of the CPU, by atan2: as accurate near the axis as elsewhere in f32.
        let theta = atan2(length(d.xy), d.z);
        var phi = atan2(d.y, d.x);
        phi = select(phi, phi + TAU, phi < 0.0);
        path.factor = inverse_square;
        path.profile = 1.0;
        path.uv = vec2<f32>(phi / TAU, theta / PI_BEAMS);
        path.wrap_u = true;
        path.inside = true;
        return path;
    }
    // Spot.
    let cos_cone = light.beam.x;
    let tan_cone = light.beam.y;
    if d.z < cos_cone || d.z <= 0.0 {
        return path;
    }
    path.profile = pow(d.z, light.beam.z);
    path.factor = inverse_square * path.profile;
    path.uv = vec2<f32>(0.5 + 0.5 * d.x / (d.z * tan_cone), 0.5 - 0.5 * d.y / (d.z * tan_cone));
    path.inside = true;
    return path;
}

fn map_texel(light: BeamLight, row: u32, column: u32) -> vec3<f32> {
    return light_texels[light.map_offset + row * light.map_width + column].xyz;
}

// The light map's linear RGB at `uv`, bilinear between texel centres (`LightMap::sample`);
// white where the light has no map.
fn light_map_rgb(light: BeamLight, uv: vec2<f32>, wrap_u: bool) -> vec3<f32> {
    if light.map_width == 0u {
        return vec3<f32>(1.0);
    }
    let w = f32(light.map_width);
    let h = f32(light.map_height);
    let x = uv.x * w - 0.5;
    let y = clamp(uv.y * h - 0.5, 0.0, h - 1.0);
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    var c0: u32;
    var c1: u32;
    if wrap_u {
        c0 = min(u32(x0 - w * floor(x0 / w)), light.map_width - 1u);
        c1 = min(u32((x0 + 1.0) - w * floor((x0 + 1.0) / w)), light.map_width - 1u);
    } else {
        c0 = u32(clamp(x0, 0.0, w - 1.0));
        c1 = u32(clamp(x0 + 1.0, 0.0, w - 1.0));
    }
    let r0 = u32(y0);
    let r1 = min(r0 + 1u, light.map_height - 1u);
    let top = map_texel(light, r0, c0) * (1.0 - fx) + map_texel(light, r0, c1) * fx;
    let bottom = map_texel(light, r1, c0) * (1.0 - fx) + map_texel(light, r1, c1) * fx;
    return top * (1.0 - fy) + bottom * fy;
}
