// Library: the body of the per-pixel pass of the nishita, oneil, riley and dobashi models
// (each model's `sky/<model>/pixel.wgsl` has the `@compute main` that calls
// `shade_pixel`). CPU twin: atmosphere-core's `optics/surface_lighting.rs`
// (`radiance_with_surface`): the model's radiance along the pixel's view ray, ended on
// the frame's surface where it has one, plus that surface's Lambertian reflection, or on
// the sea the water's light (`common/sea_surface.wgsl`, twin `optics/sea_surface.rs`);
// then the transmitted sun disk where the ray reaches space (`hdr_pixel`). No paper: the
// frame's bookkeeping around each model's equations.
//
// The importing pass defines what differs per model:
// - `fn model_radiance(direction: vec3<f32>, s: Segment, empty: Radiance) -> Radiance`:
//   the model's answer for the view ray with unit `direction` from the camera whose
//   segment `s` inside the atmosphere is not empty (`view_segment`, ended on the frame's
//   surface where it has one), given `empty`, the answer before any light is added;
// - `fn model_surface_irradiance(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32>`: the
//   model's irradiance E(x, n) on a surface element (`SkyModel::surface_irradiance`);
// - `hdr`: the HDR target, a `texture_storage_2d<rgba16float, write>`.
// So this file is validated only inside those passes (`shader_validation.rs` validates
// every entry pass).

#import common/frame_params.wgsl
#import common/surface.wgsl
#import common/sea_surface.wgsl

// Pixel `px`: the model's radiance, the surface's reflection and the sun disk into the
// HDR target, clamped to the largest finite f16.
fn shade_pixel(px: vec2<u32>) {
    if any(px >= frame.size_px.xy) {
        return;
    }
    let direction = pixel_direction(px);
    let surface = frame_surface(px);
    let s = view_segment(direction, surface.distance);
    var r = radiance_of_empty(s, direction);
    if s.hit {
        r = model_radiance(direction, s, r);
        r.radiance = without_cloud_air_shadow(px, r.radiance);
    }
    if surface.present {
        let irradiance = model_surface_irradiance(r.end, surface.normal);
        if SEA && surface.water {
            r = shade_sea(r, surface, direction, irradiance);
        } else {
            r = add_surface(r, surface, irradiance);
        }
    }
    textureStore(hdr, px, hdr_pixel(direction, r));
}

// `r` ending on the sea `surface` with the model's `irradiance` there: the water's light
// from the model's sky along the mirror direction and its sun (`add_sea`).
fn shade_sea(r: Radiance, surface: Surface, direction: vec3<f32>, irradiance: vec3<f32>) -> Radiance {
    let mirror = sea_mirror(r.end, direction, surface.normal);
    let m = mirror_segment(r.end, mirror);
    let sky = model_radiance(mirror, m, radiance_of_empty(m, mirror)).radiance;
    let sun = sea_sun(r.end, model_surface_irradiance(r.end, frame.sun_direction.xyz),
        model_surface_irradiance(r.end, across_normal(r.end)));
    return add_sea(r, surface, direction, irradiance, sky, sun);
}
