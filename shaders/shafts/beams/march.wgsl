// Entry pass: the per-pixel ray march with shadow maps, `main` (render-wgpu's
// `shafts/beams/march_pass.rs`). CPU twin: atmosphere-core's `beams/methods/march.rs`
// with `beams/in_scattering.rs` (`InScattering::add_at`). Per pixel: the ray through
// the pixel's centre ends at the first occluder or where the medium has extinguished
// the light; `steps` samples at the midpoints of equal pieces of it each add, per light,
// the integrand of Dobashi et al. 2002 Eq. 2-3 (Dobashi, Yamamoto and Nishita 2000
// Eq. 1, second term):
//   sigma_s F(alpha) I H exp(-sigma_t (s + t)) / s^2,
// H read from the light's shadow map; the sum times the step is the radiance.

#import shafts/beams/bindings.wgsl
#import shafts/beams/occluders.wgsl
#import shafts/beams/lights.wgsl
#import shafts/beams/shadow_maps.wgsl
#import shafts/beams/phase.wgsl

// The light of `light` scattered toward the camera per metre at `point`, distance `t`
// along `dir`.
fn in_scattering(light: BeamLight, point: vec3<f32>, t: f32, dir: vec3<f32>) -> vec3<f32> {
    let path = light_path(light, point);
    if !path.inside {
        return vec3<f32>(0.0);
    }
    let seen = shadow_visibility(light, point, path.to_light, path.distance_m);
    if seen <= 0.0 {
        return vec3<f32>(0.0);
    }
    let weight = beams_phase(dot(path.to_light, dir)) * path.factor * seen;
    let rgb = light_map_rgb(light, path.uv, path.wrap_u);
    let transmission = vec3<f32>(
        dot(params.channel_weights[0].xyz, rgb),
        dot(params.channel_weights[1].xyz, rgb),
        dot(params.channel_weights[2].xyz, rgb),
    );
    let extinction = params.extinction_per_m.xyz;
    return params.scattering_per_m.xyz * light.emission.xyz * weight * transmission
        * exp(-extinction * (path.distance_m + t));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = params.size_steps_lights.xy;
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let sx = (2.0 * (f32(id.x) + 0.5) / f32(size.x) - 1.0) * params.camera_right.w;
    let sy = (1.0 - 2.0 * (f32(id.y) + 0.5) / f32(size.y)) * params.camera_up.w;
    let dir = normalize(params.camera_forward.xyz + params.camera_right.xyz * sx
        + params.camera_up.xyz * sy);
    let limit = params.camera_forward.w;
    let hit = nearest_occluder(vec3<f32>(0.0), dir, limit);
    let t_end = select(limit, hit, hit != MISS);
    let steps = params.size_steps_lights.z;
    let step = t_end / f32(steps);
    // Light by light, each read once (the sum is the CPU's in another order).
    var sum = vec3<f32>(0.0);
    for (var l = 0u; l < params.size_steps_lights.w; l++) {
        let light = lights[l];
        for (var i = 0u; i < steps; i++) {
            let t = (f32(i) + 0.5) * step;
            sum += in_scattering(light, dir * t, t, dir);
        }
    }
    textureStore(radiance_out, vec2<i32>(id.xy), vec4<f32>(sum * step, 1.0));
}
