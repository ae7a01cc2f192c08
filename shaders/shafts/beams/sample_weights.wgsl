// Library: the weight of a sample of a plane interval in its mean of I_l H, g of
// Dobashi et al. 2002 Eq. 3 without sigma_s (the setting `weighted_samples`, not the
// paper's: each sample weighted by g at it instead of all alike). CPU twin:
// atmosphere-core's `beams/methods/qtable2002/sample_weights.rs` (`smooth_factor`).

#import shafts/beams/bindings.wgsl
#import shafts/beams/phase.wgsl

// g at the point `t` along the camera's ray along the unit `dir` for `light`, per
// wavelength (xyz), its attenuation taken relative to a path of `base_m` (negative:
// this sample's own, the interval's first), and the sample's own path length, the
// light's to it plus the camera's distance (w), to pass as `base_m` for the interval's
// later samples.
fn smooth_factor(light: BeamLight, dir: vec3<f32>, t: f32, base_m: f32) -> vec4<f32> {
    let point = dir * t;
    var to_light = -light.frame_z.xyz;
    var distance = max(dot(light.frame_z.xyz, point - light.position.xyz), 0.0);
    var inverse_square = 1.0;
    if light.kind != 2u {
        let offset = light.position.xyz - point;
        let r = length(offset);
        to_light = select(vec3<f32>(0.0, 1.0, 0.0), offset / r, r > 0.0);
        distance = r;
        let reach = max(r, light.position.w);
        inverse_square = 1.0 / (reach * reach);
    }
    let path = distance + t;
    let base = select(base_m, path, base_m < 0.0);
    let angular = beams_phase(dot(to_light, dir)) * inverse_square;
    return vec4<f32>(angular * exp(-params.extinction_per_m.xyz * (path - base)), path);
}
