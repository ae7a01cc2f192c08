// Library: the light one light brings to a point where a plane's fragment crosses the
// view ray, before the method's own factor (Dobashi, Yamamoto and Nishita 2000 sections
// 5.1-5.2; Dobashi et al. 2002 Eq. 10's I_l H): whether the point is in the beam and
// seen by the light (its shadow map), and the light's emission times a spot's cos^n
// falloff, the light map's transmission at the three wavelengths and the visibility.
// The 1 / r^2 is not in it: the virtual planes carry it in xi, the q table in f_l.
// Used by `planes.wgsl` and `qtable.wgsl`. CPU twin: atmosphere-core's `beams/light.rs`
// (`path_from`, `beam`) and `beams/shadow_map.rs`.

#import shafts/beams/bindings.wgsl
#import shafts/beams/occluders.wgsl
#import shafts/beams/lights.wgsl
#import shafts/beams/shadow_maps.wgsl

struct PlaneLight {
    // Whether the point is in the beam and not wholly shadowed; `light` is zero where not.
    lit: bool,
    // Emission x profile x light map transmission x visibility, per wavelength.
    light: vec3<f32>,
}

fn plane_light(light: BeamLight, point: vec3<f32>) -> PlaneLight {
    var out: PlaneLight;
    out.lit = false;
    out.light = vec3<f32>(0.0);
    let path = light_path(light, point);
    if !path.inside {
        return out;
    }
    let seen = shadow_visibility(light, point, path.to_light, path.distance_m);
    if seen <= 0.0 {
        return out;
    }
    let rgb = light_map_rgb(light, path.uv, path.wrap_u);
    let transmission = vec3<f32>(
        dot(params.channel_weights[0].xyz, rgb),
        dot(params.channel_weights[1].xyz, rgb),
        dot(params.channel_weights[2].xyz, rgb),
    );
    out.lit = true;
    out.light = light.emission.xyz * path.profile * transmission * seen;
    return out;
}
