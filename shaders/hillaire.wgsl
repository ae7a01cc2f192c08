// Hillaire 2020 per pixel: the GPU twin of `Hillaire::radiance` in atmosphere-core's
// `hillaire/mod.rs`, with the look-ups of its tables (`SkyView::lookup`,
// `AerialPerspective::lookup`, `GroundIrradiance::lookup`). For the view segment of each
// pixel (`view_segment`, camera-relative):
// - camera inside the atmosphere, ray to space: the sky-view LUT (bilinear), the
//   transmittance from the table;
// - camera inside, ray to the ground within the volume's range: the aerial-perspective
//   volume (bilinear in direction, linear in depth), which gives the transmittance too;
// - otherwise (ground beyond the range, camera in space from where the ray enters the
//   atmosphere): the view march per pixel;
// - ground: albedo / pi (T_sun max(mu_s, 0) + E_sky(mu_s)) times the transmittance;
// - the limb-darkened sun disk times the transmittance where the ray reaches space.
// Writes spectral radiance (W m^-2 sr^-1 nm^-1) at the three channels to the HDR target,
// clamped to the largest finite f16.

#import hillaire_march.wgsl
#import hillaire_directions.wgsl
#import frame_params.wgsl

@group(0) @binding(5) var ground_irradiance: texture_2d<f32>;
@group(0) @binding(6) var sky_view: texture_2d<f32>;
@group(0) @binding(7) var aerial_radiance: texture_3d<f32>;
@group(0) @binding(8) var aerial_transmittance: texture_3d<f32>;
@group(0) @binding(9) var hdr: texture_storage_2d<rgba16float, write>;

// The largest finite f16.
const F16_MAX: f32 = 65504.0;

// `SkyView::lookup` at a grid position.
fn sky_view_lookup(p: GridPosition) -> vec3<f32> {
    let a = p.column_weight;
    let c00 = textureLoad(sky_view, vec2<u32>(p.column, p.row0), 0).xyz;
    let c10 = textureLoad(sky_view, vec2<u32>(p.column + 1u, p.row0), 0).xyz;
    let c01 = textureLoad(sky_view, vec2<u32>(p.column, p.row1), 0).xyz;
    let c11 = textureLoad(sky_view, vec2<u32>(p.column + 1u, p.row1), 0).xyz;
    let low = c00 + a * (c10 - c00);
    let high = c01 + a * (c11 - c01);
    return low + p.row_weight * (high - low);
}

// Bilinear read of slice k of a volume at a grid position (`LatLong::interpolate`).
fn slice_lookup(volume: texture_3d<f32>, p: GridPosition, k: u32) -> vec3<f32> {
    let a = p.column_weight;
    let c00 = textureLoad(volume, vec3<u32>(p.column, p.row0, k), 0).xyz;
    let c10 = textureLoad(volume, vec3<u32>(p.column + 1u, p.row0, k), 0).xyz;
    let c01 = textureLoad(volume, vec3<u32>(p.column, p.row1, k), 0).xyz;
    let c11 = textureLoad(volume, vec3<u32>(p.column + 1u, p.row1, k), 0).xyz;
    let low = c00 + a * (c10 - c00);
    let high = c01 + a * (c11 - c01);
    return low + p.row_weight * (high - low);
}

// `AerialPerspective::lookup` to depth `depth_m` at a grid position: between the camera
// (radiance 0, transmittance 1) and the first slice, or between two slices.
fn aerial_lookup(p: GridPosition, depth_m: f32) -> ViewMarch {
    let slices = textureDimensions(aerial_radiance).z;
    let f = clamp(depth_m / hillaire.aerial_range_m, 0.0, 1.0) * f32(slices);
    var m: ViewMarch;
    if f <= 1.0 {
        m.radiance = f * slice_lookup(aerial_radiance, p, 0u);
        m.throughput = 1.0 + f * (slice_lookup(aerial_transmittance, p, 0u) - 1.0);
        return m;
    }
    let k = min(u32(f - 1.0), slices - 2u);
    let a = f - 1.0 - f32(k);
    let r0 = slice_lookup(aerial_radiance, p, k);
    let t0 = slice_lookup(aerial_transmittance, p, k);
    m.radiance = r0 + a * (slice_lookup(aerial_radiance, p, k + 1u) - r0);
    m.throughput = t0 + a * (slice_lookup(aerial_transmittance, p, k + 1u) - t0);
    return m;
}

// `GroundIrradiance::lookup`: E_sky / E_sun at sun cosine mu_s, geometric interpolation
// between positive values, linear where one is zero.
fn ground_irradiance_lookup(mu_s: f32) -> vec3<f32> {
    let n = textureDimensions(ground_irradiance).x;
    let m = clamp(mu_s, -1.0, 1.0);
    let x = sign(m) * sqrt(abs(m));
    let f = (x + 1.0) * 0.5 * f32(n - 1u);
    let i = min(u32(f), n - 2u);
    let a = f - f32(i);
    let lo = textureLoad(ground_irradiance, vec2<u32>(i, 0u), 0).xyz;
    let hi = textureLoad(ground_irradiance, vec2<u32>(i + 1u, 0u), 0).xyz;
    let geometric = lo * pow(hi / max(lo, vec3<f32>(1e-30)), vec3<f32>(a));
    return select(lo + a * (hi - lo), geometric, lo > vec3<f32>(0.0) & hi > vec3<f32>(0.0));
}

// `Hillaire::ground_light`: light leaving the ground per unit solar irradiance with the
// sun at zenith cosine mu_s.
fn ground_light(mu_s: f32) -> vec3<f32> {
    var sky = vec3<f32>(0.0);
    if hillaire.multiple_on != 0u {
        sky = ground_irradiance_lookup(mu_s);
    }
    let direct = sun_transmittance(0.0, mu_s) * max(mu_s, 0.0);
    return atmosphere.ground_albedo / PI * (direct + sky);
}

struct Radiance {
    radiance: vec3<f32>,
    transmittance: vec3<f32>,
    // False when the ray ends on the ground.
    reaches_space: bool,
}

// `Hillaire::radiance` for the view ray with unit `direction` from the camera.
fn hillaire_radiance(direction: vec3<f32>) -> Radiance {
    var out = Radiance(vec3<f32>(0.0), vec3<f32>(1.0), true);
    let s = view_segment(direction);
    if !s.hit {
        return out;
    }
    let sun = frame.sun_direction.xyz;
    let nu = dot(direction, sun);
    let inside = frame.camera_height.y < 0.5;
    var m: ViewMarch;
    if inside && (!s.on_ground || s.length <= hillaire.aerial_range_m) {
        // `Hillaire::read_tables`, on the grid of the view's radius.
        let up = frame.camera_m.xyz / frame.camera_m.w;
        let angles = view_angles(up, direction, sun);
        let theta_h = horizon_zenith(hillaire.view_q, hillaire.view_r);
        if s.on_ground {
            let p = grid_position(textureDimensions(aerial_radiance).xy, theta_h, angles.x,
                angles.y, true);
            m = aerial_lookup(p, s.length);
        } else {
            let p = grid_position(textureDimensions(sky_view), theta_h, angles.x, angles.y,
                false);
            m.radiance = sky_view_lookup(p);
            let mu = clamp(s.r_mu / frame.camera_m.w, -1.0, 1.0);
            m.throughput = exp(-optical_depth(table_columns(transmittance_columns, s.q, mu)));
        }
    } else {
        m = march_run(view_ray(s.q, s.r_mu, s.start_dot_sun, nu), s.length,
            hillaire.march_samples);
    }
    if s.on_ground {
        let mu_g = clamp((s.start_dot_sun + s.length * nu) / atmosphere.bottom_radius_m, -1.0, 1.0);
        m.radiance += m.throughput * ground_light(mu_g);
    }
    out.radiance = max(m.radiance * atmosphere.solar_irradiance.xyz, vec3<f32>(0.0));
    out.transmittance = clamp(m.throughput, vec3<f32>(0.0), vec3<f32>(1.0));
    out.reaches_space = !s.on_ground;
    return out;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let direction = pixel_direction(id.xy);
    let r = hillaire_radiance(direction);
    var radiance = r.radiance;
    if r.reaches_space {
        radiance += frame_sun_disk(direction, r.transmittance);
    }
    textureStore(hdr, id.xy, vec4<f32>(min(radiance, vec3<f32>(F16_MAX)), 1.0));
}
