// Entry pass: the nishita model per pixel, `main` (render-wgpu's `sky/nishita.rs`). CPU
// twin: atmosphere-core's `models/nishita.rs`. Paper: Nishita et al. 1993, as Dobashi,
// Yamamoto and Nishita 2002 (section 5, Eq. 11 and 12) write it: single scattering
// integrated along each view ray with N equal sub-segments, one sample at each midpoint
// (Eq. 12); the sun's optical depth from the table g_l (the `columns` of
// `sky/transmittance_table.wgsl`); the ground's Lambertian reflection of the transmitted
// sun (Eq. 11); with light shafts, each sample's single scattering times the sun's
// visibility past the terrain (`shafts/terrain/shadow_map.wgsl`). The frame around it (surface, sun disk, HDR target) is
// `common/shade_pixel.wgsl`. Writes spectral radiance (W m^-2 sr^-1 nm^-1) at the three
// wavelengths of the uniform.

#import common/atmosphere_params.wgsl
#import common/frame_params.wgsl
#import common/transmittance_lookup.wgsl
#import common/phase.wgsl
#import common/surface.wgsl
#import common/shade_pixel.wgsl
#import shafts/terrain/shadow_map.wgsl

struct NishitaParams {
    view_samples: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(2) var<uniform> nishita: NishitaParams;
@group(0) @binding(3) var g_l: texture_2d<f32>;
// The terrain's shadow map for light shafts (docs/shafts.md).
@group(0) @binding(4) var shadow_tops: texture_2d<f32>;
@group(0) @binding(5) var<uniform> shadow_map: ShadowMapParams;
@group(0) @binding(6) var hdr: texture_storage_2d<rgba16float, write>;

// `Nishita::radiance` for the view ray with unit `direction` from the camera and its
// segment `s` in the atmosphere (`common/shade_pixel.wgsl`).
fn model_radiance(direction: vec3<f32>, s: Segment, empty: Radiance) -> Radiance {
    var out = empty;
    let sun = frame.sun_direction.xyz;
    let bottom = atmosphere.bottom_radius_m;
    let n = nishita.view_samples;
    let dt = s.length / f32(n);
    let nu = dot(direction, sun);
    let phase_r = rayleigh_phase(nu);
    let phase_m = mie_phase(nu);
    var view_column = vec3<f32>(0.0);
    for (var k = 0u; k < n; k++) {
        let t = (f32(k) + 0.5) * dt;
        let q = q_along(s, t);
        let rho = densities(altitude_from_q(q));
        let to_sample = view_column + 0.5 * dt * rho;
        view_column += dt * rho;
        let radius = sqrt(bottom * bottom + q);
        let mu_sun = clamp((s.start_dot_sun + t * nu) / radius, -1.0, 1.0);
        // The sun's centre behind the planet: g_l = 0 (`sun_column`).
        if mu_sun < 0.0 && (radius * mu_sun) * (radius * mu_sun) - q >= 0.0 {
            continue;
        }
        var visible = 1.0;
        if shadow_map.size.y != 0u {
            let position = s.start + t * direction;
            visible = shadow_map_visible(shadow_tops, shadow_map, bottom, position, q / (radius + bottom));
        }
        let sun_column = table_columns(g_l, q, mu_sun);
        let tau = optical_depth(to_sample) + optical_depth(sun_column);
        let j = atmosphere.rayleigh_scattering_per_m.xyz * (rho.x * phase_r * visible)
            + atmosphere.mie_scattering_per_m.xyz * (rho.y * phase_m * visible);
        out.radiance += dt * exp(-tau) * j * atmosphere.solar_irradiance.xyz;
    }
    out.transmittance = exp(-optical_depth(view_column));
    if s.end == END_GROUND {
        let cos_g = (s.start_dot_sun + s.length * nu) / bottom;
        if cos_g > 0.0 {
            let sun_column = table_columns(g_l, 0.0, min(cos_g, 1.0));
            out.radiance += sunlit_ground(out.transmittance, cos_g, exp(-optical_depth(sun_column)));
        }
    }
    return out;
}

// `Nishita::surface_irradiance`: the transmitted sun only.
fn model_surface_irradiance(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let e = surface_element(point, normal);
    var t = vec3<f32>(0.0);
    if e.sun_cosine > 0.0 && !planet_hides_sun(e) {
        t = exp(-optical_depth(table_columns(g_l, e.q, e.mu_s)));
    }
    return element_irradiance(e, t, vec3<f32>(0.0));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    shade_pixel(id.xy);
}
