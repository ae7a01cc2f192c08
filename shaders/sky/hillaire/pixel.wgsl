// Entry passes: the hillaire model per pixel, `main`, `tables_only` and `from_space`
// (render-wgpu's `sky/hillaire/`). CPU twin: atmosphere-core's `models/hillaire/mod.rs`
// (`Hillaire::radiance`), with the look-ups of its tables (`SkyView::lookup`,
// `AerialPerspective::lookup`, `GroundIrradiance::lookup`). Paper: Hillaire 2020, sections
// 5.3-5.4 (sky-view LUT, aerial-perspective volume) and section 5 (the view march). For
// the view segment of each pixel (`view_segment`, camera-relative):
// - camera inside the atmosphere, ray to space: the sky-view LUT (bilinear), the
//   transmittance from the table;
// - camera inside, ray to the ground or to the frame's surface within the volume's
//   range: the aerial-perspective volume (bilinear in direction, linear in depth), which
//   gives the transmittance too;
// - otherwise (ground or surface beyond the range, camera in space from where the ray
//   enters the atmosphere): the view march per pixel;
// - ground: albedo / pi (T_sun max(mu_s, 0) + E_sky(mu_s)) times the transmittance; a
//   surface: `add_surface` with `hillaire_surface_irradiance`; the sea: `add_sea`
//   (`common/sea_surface.wgsl`) with the sky along the mirror direction marched;
// - the limb-darkened sun disk times the transmittance where the ray reaches space;
// - with light shafts, less the single scattering the terrain's shadow takes out
//   (`shafts_loss`, `sky/hillaire/shafts.wgsl`; `models/hillaire/shafts.rs`), and, when
//   the cloud's sun map shades the air, what the cloud takes out beyond it, read per
//   pixel (`pixel_cloud_air_loss`, `common/surface.wgsl`; `clouds/layer/air_shadow.rs`).
// Writes spectral radiance (W m^-2 sr^-1 nm^-1) at the three channels to the HDR target,
// clamped to the largest finite f16. The transmittance table, the sky view and the volume
// are read through the texture unit's linear filter where the device filters Rgba32Float
// (`FILTERED_TABLES`; render-wgpu's `sky/table_sampling.rs`), else texel by texel with the
// interpolation written out: the same weights from the same coordinates.

#import sky/hillaire/march.wgsl
#import sky/hillaire/directions.wgsl
#import common/frame_params.wgsl
#import common/surface.wgsl
#import common/sea_surface.wgsl
#import common/table_sampling.wgsl
#import common/surface_columns.wgsl
#import sky/hillaire/shafts.wgsl

@group(0) @binding(5) var ground_irradiance: texture_2d<f32>;
@group(0) @binding(6) var sky_view: texture_2d<f32>;
@group(0) @binding(7) var aerial_radiance: texture_3d<f32>;
@group(0) @binding(8) var aerial_transmittance: texture_3d<f32>;
@group(0) @binding(11) var hdr: texture_storage_2d<rgba16float, write>;

// The fractional texel position of a grid position, for a filtered read: the two rows
// are neighbours in storage, in either order.
fn grid_texel(p: GridPosition) -> vec2<f32> {
    let row = f32(p.row0) + p.row_weight * (f32(p.row1) - f32(p.row0));
    return vec2<f32>(f32(p.column) + p.column_weight, row);
}

// `SkyView::lookup` at a grid position.
fn sky_view_lookup(p: GridPosition) -> vec3<f32> {
    if FILTERED_TABLES {
        return sample_2d(sky_view, grid_texel(p));
    }
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
// (radiance 0, transmittance 1) and the first slice, or between two slices. Written
// without branches (a software rasteriser would run both under a mask): within the
// first slice the lower end is the camera's values.
fn aerial_lookup(p: GridPosition, depth_m: f32) -> ViewMarch {
    let slices = textureDimensions(aerial_radiance).z;
    let f = clamp(depth_m / hillaire.aerial_range_m, 0.0, 1.0) * f32(slices);
    let first = f <= 1.0;
    if FILTERED_TABLES {
        // One trilinear read per volume: between slices k and k + 1 at f - 1; within the
        // first slice, slice 0 itself, blended with the camera's values by hand.
        let at = vec3<f32>(grid_texel(p), clamp(f - 1.0, 0.0, f32(slices - 1u)));
        let radiance = sample_3d(aerial_radiance, at);
        let transmittance = sample_3d(aerial_transmittance, at);
        var m: ViewMarch;
        m.radiance = select(radiance, f * radiance, first);
        m.throughput = select(transmittance, 1.0 + f * (transmittance - 1.0), first);
        return m;
    }
    let k = select(min(u32(max(f - 1.0, 0.0)), slices - 2u), 0u, first);
    let a = select(f - 1.0 - f32(k), f, first);
    let k_high = select(k + 1u, 0u, first);
    let r0 = select(slice_lookup(aerial_radiance, p, k), vec3<f32>(0.0), first);
    let t0 = select(slice_lookup(aerial_transmittance, p, k), vec3<f32>(1.0), first);
    var m: ViewMarch;
    m.radiance = r0 + a * (slice_lookup(aerial_radiance, p, k_high) - r0);
    m.throughput = t0 + a * (slice_lookup(aerial_transmittance, p, k_high) - t0);
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

// `Medium::sun_transmittance` on the ground (`ground_columns`: the same value as the
// bilinear read of `sun_transmittance`).
fn ground_sun_transmittance(mu_s: f32) -> vec3<f32> {
    if mu_s < 0.0 {
        return vec3<f32>(0.0);
    }
    return exp(-optical_depth(read_ground_columns(transmittance_columns, min(mu_s, 1.0))));
}

// `Hillaire::ground_light`: light leaving the ground per unit solar irradiance with the
// sun at zenith cosine mu_s.
fn ground_light(mu_s: f32) -> vec3<f32> {
    var sky = vec3<f32>(0.0);
    if hillaire.multiple_on != 0u {
        sky = ground_irradiance_lookup(mu_s);
    }
    let direct = ground_sun_transmittance(mu_s) * max(mu_s, 0.0);
    return atmosphere.ground_albedo / PI * (direct + sky);
}

// `view_angles`: zenith angle and azimuth from the sun's vertical plane of `direction`
// at the camera, from the direction's components in the view's frame by atan2 of a sine
// and a cosine (accurate in f32 where the cosine is near +-1, unlike acos).
fn view_angles(direction: vec3<f32>) -> vec2<f32> {
    let along = dot(direction, hillaire.view_sun_side.xyz);
    let across = dot(direction, hillaire.view_across.xyz);
    let theta = atan2(length(vec2<f32>(along, across)), dot(direction, hillaire.view_up.xyz));
    return vec2<f32>(theta, atan2(abs(across), along));
}

// `Hillaire::radiance` for the view ray with unit `direction` from the camera. `tables`
// and `march` say which of the two ways of finding the light along a ray the frame may
// need (the planner knows; each entry point fixes them, so that a software rasteriser,
// which runs every branch for every pixel under a mask, does not pay for the other).
// The ray ends on an object at `object_m` (0: none): read from the volume, or marched,
// to the object, as on the CPU.
fn hillaire_radiance(px: vec2<u32>, direction: vec3<f32>, object_m: f32, tables: bool, march: bool) -> Radiance {
    let s = view_segment(direction, object_m);
    var out = radiance_of_empty(s, direction);
    if !s.hit {
        return out;
    }
    let sun = frame.sun_direction.xyz;
    let nu = dot(direction, sun);
    let inside = frame.camera_height.y < 0.5;
    var m: ViewMarch;
    let to_space = s.end == END_SPACE;
    let use_tables = inside && (to_space || s.length <= hillaire.aerial_range_m);
    if tables && use_tables {
        // `Hillaire::read_tables`, on the grid of the view's radius, on the half of the
        // whole ray.
        let angles = view_angles(direction);
        let grid = select(textureDimensions(aerial_radiance).xy, textureDimensions(sky_view),
            to_space);
        let p = grid_position(grid, hillaire.view_theta_h, angles.x, angles.y, s.on_ground);
        if !to_space {
            m = aerial_lookup(p, s.length);
        } else {
            m.radiance = sky_view_lookup(p);
            let mu = clamp(s.r_mu / frame.camera_m.w, -1.0, 1.0);
            m.throughput = exp(-optical_depth(read_table_columns(transmittance_columns, s.q, mu)));
        }
    } else if march {
        m = march_run(view_ray(s.q, s.r_mu, s.start_dot_sun, nu), s.length,
            hillaire.march_samples);
    }
    m.radiance -= shafts_loss(s, direction, nu) + pixel_cloud_air_loss(px);
    m = with_ground(m, s, nu);
    out.radiance = max(m.radiance * atmosphere.solar_irradiance.xyz, vec3<f32>(0.0));
    out.transmittance = clamp(m.throughput, vec3<f32>(0.0), vec3<f32>(1.0));
    return out;
}

// `m`, the light along segment `s` at cosine `nu` to the sun, with the Lambertian ground
// at its end where it ends on the ground.
fn with_ground(m_in: ViewMarch, s: Segment, nu: f32) -> ViewMarch {
    var m = m_in;
    if s.end == END_GROUND {
        let mu_g = clamp((s.start_dot_sun + s.length * nu) / atmosphere.bottom_radius_m, -1.0, 1.0);
        m.radiance += m.throughput * ground_light(mu_g);
    }
    return m;
}

// The sky's radiance along the sea's mirror ray (`common/sea_surface.wgsl`): marched from
// the sea point (the sky view and the volume hold the camera's rays only), less its
// shafts as for the camera's rays.
fn hillaire_mirror_sky(direction: vec3<f32>, s: Segment) -> vec3<f32> {
    let nu = dot(direction, frame.sun_direction.xyz);
    var m = march_run(view_ray(s.q, s.r_mu, s.start_dot_sun, nu), s.length,
        hillaire.march_samples);
    m.radiance -= shafts_loss(s, direction, nu);
    m = with_ground(m, s, nu);
    return max(m.radiance * atmosphere.solar_irradiance.xyz, vec3<f32>(0.0));
}

// `Hillaire::surface_irradiance`: the transmitted sun from the transmittance LUT and the
// ground's sky irradiance E_sky at the element's mu_s (tabulated on the ground only)
// times the share of the ground's vertical optical depth above the element.
fn hillaire_surface_irradiance(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let e = surface_element(point, normal);
    let t = element_sun_transmittance(e, transmittance_columns);
    var sky = vec3<f32>(0.0);
    if hillaire.multiple_on != 0u {
        sky = ground_irradiance_lookup(e.mu_s) * vertical_depth_share_above(transmittance_columns, e.q);
    }
    return element_irradiance(e, t, atmosphere.solar_irradiance.xyz * sky);
}

// The pass for a frame with rays of both kinds: a camera in the atmosphere seeing ground
// beyond the aerial-perspective volume, or a surface.
@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    shade(id.xy, true, true);
}

// The pass for a camera in the atmosphere whose every ray reads the tables.
@compute @workgroup_size(8, 8)
fn tables_only(@builtin(global_invocation_id) id: vec3<u32>) {
    shade(id.xy, true, false);
}

// The pass for a camera above the atmosphere: every ray is marched.
@compute @workgroup_size(8, 8)
fn from_space(@builtin(global_invocation_id) id: vec3<u32>) {
    shade(id.xy, false, true);
}

// Pixel `px`: the radiance and the sun disk into the HDR target.
fn shade(px: vec2<u32>, tables: bool, march: bool) {
    if any(px >= frame.size_px.xy) {
        return;
    }
    let direction = pixel_direction(px);
    let surface = frame_surface(px);
    var r = hillaire_radiance(px, direction, surface.distance, tables, march);
    if surface.present {
        let irradiance = hillaire_surface_irradiance(r.end, surface.normal);
        if SEA && surface.water && march {
            let mirror = sea_mirror(r.end, direction, surface.normal);
            let sky = hillaire_mirror_sky(mirror, mirror_segment(r.end, mirror));
            let sun = sea_sun(r.end, hillaire_surface_irradiance(r.end, frame.sun_direction.xyz),
                hillaire_surface_irradiance(r.end, across_normal(r.end)));
            r = add_sea(r, surface, direction, irradiance, sky, sun);
        } else {
            r = add_surface(r, surface, irradiance);
        }
    }
    textureStore(hdr, px, hdr_pixel(direction, r));
}
