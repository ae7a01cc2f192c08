// Entry pass: the oneil model per pixel, `main` (render-wgpu's `sky/oneil.rs`). CPU twin:
// atmosphere-core's `models/oneil.rs` (`Oneil::radiance`). Paper: O'Neil 2004,
// "Real-time atmospheric scattering": `samples` equal sample rays along the view segment;
// at the centre of each, the sun's lookup in the optical-depth table
// (`sky/oneil/optical_depth_table.wgsl`) gives the densities (0 in the planet's shadow:
// the sample is skipped) and the sun's columns; the columns back to the camera are the
// difference of two lookups, sample point and camera in the same direction, reversed when
// the point is above the camera (a camera in space stands at the entry point). With light
// shafts, each sample's single scattering times the sun's visibility past the terrain
// (`shafts/terrain/shadow_map.wgsl`). The
// ground's Lambertian reflection of the transmitted sun; the frame around it (surface, sun
// disk, HDR target) is `common/shade_pixel.wgsl`. Ozone is not in the table, so not in
// the optical depths, as on the CPU. Writes spectral radiance (W m^-2 sr^-1 nm^-1).
//
// Angles from the local vertical are atan2(|p x v|, p . v), accurate at every angle in
// f32 (acos of a cosine loses half the digits near 0 and 180 deg); along the view ray
// |p x direction| is the ray's distance from the planet's centre, a constant.

#import common/atmosphere_params.wgsl
#import common/frame_params.wgsl
#import common/phase.wgsl
#import common/surface.wgsl
#import common/table_sampling.wgsl
#import common/shade_pixel.wgsl
#import shafts/terrain/shadow_map.wgsl

struct OneilParams {
    samples: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(2) var<uniform> oneil: OneilParams;
@group(0) @binding(3) var optical_depth_table: texture_2d<f32>;
// The terrain's shadow map for light shafts (docs/shafts.md).
@group(0) @binding(4) var shadow_tops: texture_2d<f32>;
@group(0) @binding(5) var<uniform> shadow_map: ShadowMapParams;
@group(0) @binding(6) var hdr: texture_storage_2d<rgba16float, write>;

// `OpticalDepthTable::lookup`: the four channels (Rayleigh density, Rayleigh column,
// Mie density, Mie column) at `altitude_m` for a ray `angle` radians from the vertical,
// interpolated bilinearly between nodes: one filtered read where the device filters
// Rgba32Float, else four texel reads (`common/table_sampling.wgsl`).
fn table_lookup(altitude_m: f32, angle: f32) -> vec4<f32> {
    let size = textureDimensions(optical_depth_table);
    let thickness = atmosphere.top_radius_m - atmosphere.bottom_radius_m;
    let x = clamp(altitude_m / thickness, 0.0, 1.0) * f32(size.x - 1u);
    let y = clamp(angle / PI, 0.0, 1.0) * f32(size.y - 1u);
    if FILTERED_TABLES {
        return sample_2d_rgba(optical_depth_table, vec2<f32>(x, y));
    }
    let i = min(vec2<u32>(vec2<f32>(x, y)), size - 2u);
    let f = vec2<f32>(x, y) - vec2<f32>(i);
    let a = textureLoad(optical_depth_table, i, 0);
    let b = textureLoad(optical_depth_table, i + vec2<u32>(1u, 0u), 0);
    let c = textureLoad(optical_depth_table, i + vec2<u32>(0u, 1u), 0);
    let d = textureLoad(optical_depth_table, i + vec2<u32>(1u, 1u), 0);
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

// Optical depth per channel of the columns (Rayleigh, Mie), m.
fn depth(column: vec2<f32>) -> vec3<f32> {
    return column.x * atmosphere.rayleigh_extinction_per_m.xyz
        + column.y * atmosphere.mie_extinction_per_m.xyz;
}

// `Oneil::radiance` for the view ray with unit `direction` from the camera and its
// segment `s` in the atmosphere (`common/shade_pixel.wgsl`).
fn model_radiance(direction: vec3<f32>, s: Segment, empty: Radiance) -> Radiance {
    var out = empty;
    let sun = frame.sun_direction.xyz;
    let nu = dot(direction, sun);
    let phase_r = rayleigh_phase(nu);
    let phase_m = mie_phase(nu);
    // The ray's distance from the centre, |p x direction| at every point p of it.
    let impact = length(cross(s.start, direction));
    let sun_cross = cross(s.start, sun);
    let direction_cross = cross(direction, sun);
    let camera_altitude = altitude_from_q(s.q);
    let camera_angle = atan2(impact, s.r_mu);
    let camera_forward = table_lookup(camera_altitude, camera_angle);
    let camera_back = table_lookup(camera_altitude, PI - camera_angle);

    let n = oneil.samples;
    let ds = s.length / f32(n);
    for (var k = 0u; k <= n; k++) {
        // Samples 0..n-1 at the centres of the sample rays; k = n is the end of the ray,
        // for the transmittance.
        let t = select((f32(k) + 0.5) * ds, s.length, k == n);
        let q = q_along(s, t);
        let altitude = altitude_from_q(q);
        let angle = atan2(impact, s.r_mu + t);
        // Columns from the camera to the point by two lookups ("reverse the ray direction
        // for both lookups when the target vertex is higher than the camera").
        var view: vec4<f32>;
        if q <= s.q {
            view = table_lookup(altitude, PI - angle) - camera_back;
        } else {
            view = camera_forward - table_lookup(altitude, angle);
        }
        let to_camera = max(view.yw, vec2<f32>(0.0));
        if k == n {
            out.transmittance = exp(-depth(to_camera));
            break;
        }
        let sun_angle = atan2(length(sun_cross + t * direction_cross), s.start_dot_sun + t * nu);
        let light = table_lookup(altitude, sun_angle);
        if light.x <= 0.0 && light.z <= 0.0 {
            continue; // in the planet's shadow
        }
        var visible = 1.0;
        if shadow_map.size.y != 0u {
            let position = s.start + t * direction;
            visible = shadow_map_visible(shadow_tops, shadow_map, atmosphere.bottom_radius_m, position, altitude);
        }
        let j = atmosphere.rayleigh_scattering_per_m.xyz * (light.x * phase_r * visible)
            + atmosphere.mie_scattering_per_m.xyz * (light.z * phase_m * visible);
        out.radiance += ds * j * atmosphere.solar_irradiance.xyz
            * exp(-depth(light.yw + to_camera));
    }
    if s.end == END_GROUND {
        let end = s.start + s.length * direction;
        let cos_sun = (s.start_dot_sun + s.length * nu) / atmosphere.bottom_radius_m;
        if cos_sun > 0.0 {
            let light = table_lookup(0.0, atan2(length(cross(end, sun)), dot(end, sun)));
            out.radiance += sunlit_ground(out.transmittance, min(cos_sun, 1.0), exp(-depth(light.yw)));
        }
    }
    return out;
}

// `Oneil::surface_irradiance`: the transmitted sun only, its columns from the table at
// the element's height and sun angle, none where the planet hides the sun's centre.
fn model_surface_irradiance(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let e = surface_element(point, normal);
    var t = vec3<f32>(0.0);
    if e.sun_cosine > 0.0 && !planet_hides_sun(e) {
        let sun = frame.sun_direction.xyz;
        let altitude = e.r - atmosphere.bottom_radius_m;
        let light = table_lookup(altitude, atan2(length(cross(point, sun)), dot(point, sun)));
        t = exp(-depth(light.yw));
    }
    return element_irradiance(e, t, vec3<f32>(0.0));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    shade_pixel(id.xy);
}
