// Entry pass: a frame's cloud composited with its sky model (render-wgpu's
// `clouds/frame_pass.rs`). Per pixel, per channel, as atmosphere-core's
// `clouds/layer/composite.rs` specifies (Riley et al. 2004, section 5: the atmosphere
// in front of and behind the volume),
//     L = L_front + T_front L_cloud + T_cloud (L_full - L_front),
// with L_full the model's pixel (its surface and sun disk included), L_front the model's
// second run ended where the ray enters the cloud, L_cloud and T_cloud the march
// (`clouds/frame_march.wgsl`), and T_front the atmosphere's transmittance from the
// camera to the cloud's entry, exp(-tau) of the columns integrated by the midpoint rule
// over FRONT_STEPS steps. Pixels without cloud (T_cloud = 1) keep L_full exactly.

#import common/frame_params.wgsl

const FRONT_STEPS: u32 = 32u;

@group(0) @binding(2) var full_image: texture_2d<f32>;
@group(0) @binding(3) var front_image: texture_2d<f32>;
// rgb: the cloud's radiance; a: its transmittance.
@group(0) @binding(4) var cloud_image: texture_2d<f32>;
// w: the cloud's entry distance, m (0: the camera is inside it, or no cloud).
@group(0) @binding(5) var cloud_front: texture_2d<f32>;
@group(0) @binding(6) var hdr: texture_storage_2d<rgba16float, write>;
// y: 1 when the model's second run wrote `front_image`, 0 when the camera is inside the
// layer and it did not run (no air in front of the cloud; x is the march's).
@group(0) @binding(7) var<uniform> composite_flags: vec4<u32>;

// Transmittance of the atmosphere from the camera to `distance_m` along `direction`.
fn front_transmittance(direction: vec3<f32>, distance_m: f32) -> vec3<f32> {
    let s = view_segment(direction, distance_m);
    if !s.hit {
        return vec3<f32>(1.0);
    }
    let dt = s.length / f32(FRONT_STEPS);
    var column = vec3<f32>(0.0);
    for (var k = 0u; k < FRONT_STEPS; k++) {
        column += dt * densities(altitude_from_q(q_along(s, (f32(k) + 0.5) * dt)));
    }
    return exp(-optical_depth(column));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let full = textureLoad(full_image, id.xy, 0).rgb;
    let cloud = textureLoad(cloud_image, id.xy, 0);
    var out = full;
    if cloud.a < 1.0 {
        let entry_m = textureLoad(cloud_front, id.xy, 0).w;
        var front = vec3<f32>(0.0);
        var t_front = vec3<f32>(1.0);
        if entry_m > 0.0 && composite_flags.y == 1u {
            front = textureLoad(front_image, id.xy, 0).rgb;
            t_front = front_transmittance(pixel_direction(id.xy), entry_m);
        }
        out = front + t_front * cloud.rgb + cloud.a * max(full - front, vec3<f32>(0.0));
    }
    textureStore(hdr, id.xy, vec4<f32>(min(out, vec3<f32>(F16_MAX)), 1.0));
}
