// Library: the surface a frame's rays end on, per pixel, drawn by the terrain pass or
// given by the caller (render-wgpu's `frame/surface_buffer.rs` binds it at 30 and 31), and
// the surface element the models light. Every model's pixel pass ends its rays there
// (`view_segment`'s object) and adds the surface's Lambertian reflection T a / pi E(x, n)
// with the model's own irradiance E. CPU twin: atmosphere-core's
// `optics/surface_lighting.rs` (`SurfaceElement`, `radiance_with_surface`). No paper: the
// papers light only the ground sphere, the case n = up.

#import common/atmosphere_params.wgsl
#import common/frame_params.wgsl
#import common/ground_ray.wgsl
#import common/phase.wgsl
#import clouds/sun_map_params.wgsl

// xyz: outward unit normal; w: distance from the camera along the pixel's ray, m
// (0: no surface in this pixel).
@group(0) @binding(30) var surface_geometry: texture_2d<f32>;
// rgb: albedo (linear); a: 1 for a Lambertian surface, 0 for the sea
// (`common/sea_surface.wgsl`), whose rgb is then the water body's albedo.
@group(0) @binding(31) var surface_albedo: texture_2d<f32>;
// x: the sun's transmittance through the cloud layer at each pixel's surface
// (`clouds/sun_map_pixels.wgsl`), read where the sun map's flag (counts.w) is 1; y, z, w:
// the single scattering per unit solar irradiance that the cloud's shadow takes out of
// the air below its base (`clouds/air_shadow.wgsl`), read where the map shades the air;
// the map's parameters at 33 (`clouds/sun_map_params.wgsl`).
@group(0) @binding(32) var surface_cloud_sun: texture_2d<f32>;

// This pixel's cloud transmittance, set by `frame_surface`: the surface elements the
// pass lights lie on the pixel's surface (the ground sphere of a pixel without one is
// not shaded).
var<private> pixel_cloud_sun: f32 = 1.0;

// Whether the pipeline reads a surface at all (`PixelPipeline`): its variant without one
// has every branch of the surface compiled out, as a software rasteriser runs both sides
// of every branch.
override SURFACE: bool = true;

struct Surface {
    present: bool,
    // Distance from the camera, m; 0 when absent (`view_segment`'s "no object").
    distance: f32,
    normal: vec3<f32>,
    albedo: vec3<f32>,
    // Whether the surface is the sea.
    water: bool,
}

// The surface in pixel `px`; none at all, without reading, in the pipeline variant for
// frames without a surface.
fn frame_surface(px: vec2<u32>) -> Surface {
    var out: Surface;
    out.present = false;
    out.distance = 0.0;
    if !SURFACE {
        return out;
    }
    let geometry = textureLoad(surface_geometry, px, 0);
    out.present = geometry.w > 0.0;
    out.distance = max(geometry.w, 0.0);
    out.normal = geometry.xyz;
    let albedo = textureLoad(surface_albedo, px, 0);
    out.albedo = albedo.rgb;
    out.water = albedo.a < 0.5;
    if out.present && sun_map_params.counts.w == 1u {
        pixel_cloud_sun = textureLoad(surface_cloud_sun, px, 0).x;
    }
    return out;
}

// The single scattering that the cloud layer's shadow takes out of pixel `px`'s view
// segment below the layer's base beyond the terrain's shadow, per unit solar irradiance
// (`clouds/air_shadow.wgsl`; CPU twin `AirShadow::cloud_single`): every model subtracts
// it times its solar irradiance beside its own terrain shafts; 0 unless the frame's sun
// map shades the air.
fn pixel_cloud_air_loss(px: vec2<u32>) -> vec3<f32> {
    if !cloud_shafts_on() {
        return vec3<f32>(0.0);
    }
    return textureLoad(surface_cloud_sun, px, 0).yzw;
}

// `radiance` less the cloud's shadow in pixel `px`'s air (`pixel_cloud_air_loss`), at
// least 0 (`CloudAirShadow::radiance`).
fn without_cloud_air_shadow(px: vec2<u32>, radiance: vec3<f32>) -> vec3<f32> {
    let lost = pixel_cloud_air_loss(px) * atmosphere.solar_irradiance.xyz;
    return max(radiance - lost, vec3<f32>(0.0));
}

// A surface element in the variables the models look up (`SurfaceElement::new`).
struct SurfaceElement {
    r: f32,
    // r^2 - bottom^2, the accurate variable of the tables (`common/frame_params.wgsl`).
    q: f32,
    mu_s: f32,
    sun_cosine: f32,
    sky_view_factor: f32,
    // The sun's transmittance through the cloud layer at the pixel's surface (1 without).
    cloud_sun: f32,
}

// The element at planet-centred `point` with outward unit `normal`; a point above the
// atmosphere is lit as at its top.
fn surface_element(point: vec3<f32>, normal: vec3<f32>) -> SurfaceElement {
    let sun = frame.sun_direction.xyz;
    let r = length(point);
    let up = point / r;
    var e: SurfaceElement;
    let bottom = atmosphere.bottom_radius_m;
    e.r = clamp(r, bottom, atmosphere.top_radius_m);
    e.q = (e.r - bottom) * (e.r + bottom);
    e.mu_s = clamp(dot(up, sun), -1.0, 1.0);
    e.sun_cosine = max(dot(normal, sun), 0.0);
    e.sky_view_factor = 0.5 * (1.0 + clamp(dot(normal, up), -1.0, 1.0));
    e.cloud_sun = pixel_cloud_sun;
    return e;
}

// Whether the planet hides the sun's centre from the element (`ray_hits_ground` towards
// the sun).
fn planet_hides_sun(e: SurfaceElement) -> bool {
    return hits_ground(e.q, e.r * e.mu_s);
}

// E_sun T_sun T_cloud max(n . s, 0) + E_sky (1 + n . up) / 2 (`SurfaceElement::irradiance`,
// the cloud's T_cloud by `clouds/layer/shadowed_surface.rs`).
fn element_irradiance(e: SurfaceElement, sun_transmittance: vec3<f32>, sky: vec3<f32>) -> vec3<f32> {
    return atmosphere.solar_irradiance.xyz * sun_transmittance * e.sun_cosine * e.cloud_sun
        + sky * e.sky_view_factor;
}

// `r` with the surface's reflection added for the model's `irradiance` at its end
// (`radiance_with_surface`); the surface hides the sun disk.
fn add_surface(r: Radiance, surface: Surface, irradiance: vec3<f32>) -> Radiance {
    var out = r;
    out.radiance += r.transmittance * surface.albedo / PI * irradiance;
    out.reaches_space = false;
    return out;
}

// The ground's Lambertian reflection of the sun, seen through the view ray's
// `transmittance`: the sun at cosine `sun_cosine` from the vertical, transmitted by
// `sun_transmittance` (Dobashi, Yamamoto and Nishita 2002, Eq. 11).
fn sunlit_ground(transmittance: vec3<f32>, sun_cosine: f32, sun_transmittance: vec3<f32>) -> vec3<f32> {
    return transmittance * atmosphere.ground_albedo / PI * atmosphere.solar_irradiance.xyz
        * sun_cosine * sun_transmittance;
}
