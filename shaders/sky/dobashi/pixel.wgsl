// Entry pass: the dobashi model per pixel, `main` (render-wgpu's `sky/dobashi/`). CPU
// twin: atmosphere-core's `models/dobashi/mod.rs` (`Dobashi::radiance`,
// `Dobashi::surface_irradiance`). Paper: Dobashi, Yamamoto and Nishita 2002, sections
// 5.2-5.3: Eq. 12 along the pixel's ray through the sampling planes, or the sample spheres
// for a camera far out (`sky/dobashi/trace.wgsl`), with the ambient term, ending on the
// frame's surface where it has one (lit by the transmitted sun and the ambient sky); with
// light shafts, each segment's single scattering times the sun's visibility past the
// terrain at its plane (`shafts/terrain/shadow_map.wgsl`; section 4.2.2's H). The
// frame around it (surface, sun disk, HDR target) is `common/shade_pixel.wgsl`. Writes
// spectral radiance (W m^-2 sr^-1 nm^-1).

#import sky/dobashi/trace.wgsl
#import common/surface.wgsl
#import common/surface_columns.wgsl
#import common/shade_pixel.wgsl
#import shafts/terrain/shadow_map.wgsl

// The terrain's shadow map for light shafts (docs/shafts.md).
@group(0) @binding(12) var shadow_tops: texture_2d<f32>;
@group(0) @binding(13) var<uniform> shadow_map: ShadowMapParams;
@group(0) @binding(14) var hdr: texture_storage_2d<rgba16float, write>;

// `Accumulator::visible_at`: the sun's visibility past the terrain at the planet-centred
// `position` of altitude `altitude` (1 without shafts).
fn terrain_visible(position: vec3<f32>, altitude: f32) -> f32 {
    if shadow_map.size.y == 0u {
        return 1.0;
    }
    return shadow_map_visible(shadow_tops, shadow_map, atmosphere.bottom_radius_m, position, altitude);
}

// `Dobashi::radiance` for the view ray with unit `direction` from the camera and its
// segment `s` in the atmosphere (`common/shade_pixel.wgsl`): Eq. 12 per unit solar
// irradiance, times it.
fn model_radiance(direction: vec3<f32>, s: Segment, empty: Radiance) -> Radiance {
    var r = empty;
    // Sample spheres for a camera far out only: the sea's mirror ray starts inside
    // (`t_enter` 0) and crosses the planes, as `Tracer::uses_spheres` says for its origin.
    let spheres = dobashi.use_spheres != 0u && s.t_enter > 0.0;
    let terms = trace(make_ray(s, direction, frame.sun_direction.xyz), spheres);
    r.radiance = atmosphere.solar_irradiance.xyz * (terms.single + terms.ambient);
    r.transmittance = terms.transmittance;
    return r;
}

// `Dobashi::surface_irradiance` (`Tracer::element_light`): the transmitted sun g_l
// (Eq. 11) and the ambient sky, pi psi on a horizontal element, psi at the element's sun
// angle, times the share of the ground's vertical optical depth above the element.
fn model_surface_irradiance(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let e = surface_element(point, normal);
    var t = vec3<f32>(0.0);
    if e.sun_cosine > 0.0 {
        t = sunlight_at(e.q, e.mu_s);
    }
    let share = vertical_depth_share_above(g_l, e.q);
    let sky = PI * ambient_at(e.mu_s) * share * atmosphere.solar_irradiance.xyz;
    return element_irradiance(e, t, sky);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    shade_pixel(id.xy);
}
