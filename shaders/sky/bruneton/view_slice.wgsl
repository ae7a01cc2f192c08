// The view slice of the bruneton pass for a camera inside the atmosphere: every view ray
// starts at the camera's radius r and sun cosine mu_s, so the part of the quadrilinear
// interpolation of S (`Table4::lookup`) over r and mu_s is the same for every pixel.
// Done once per frame here for every (mu, nu) node of the three scattering textures:
// texel (k * nu_size + inu, imu) = S_k(r, mu_imu, mu_s, nu_inu) interpolated in r and mu_s
// (k: 0 single Rayleigh, 1 single Mie, 2 multiple). The pass then interpolates in mu and
// nu, reading 4 texels per table instead of 16; the interpolation is the same, in
// another order.

#import sky/bruneton/lookup.wgsl
#import common/frame_params.wgsl

@group(0) @binding(9) var view_slice: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= 3u * bruneton.nu_size || id.y >= bruneton.mu_size {
        return;
    }
    let k = id.x / bruneton.nu_size;
    let inu = id.x % bruneton.nu_size;
    // As `bruneton_radiance` finds r and mu_s for a camera inside the atmosphere.
    let q = frame.camera_height.x;
    let r = radius_of_q(q);
    let mu_s = clamp(dot(frame.camera_m.xyz, frame.sun_direction.xyz) / r, -1.0, 1.0);
    let p = table_position(q, r, 0.0, mu_s, 0.0, false);
    var value = vec3<f32>(0.0);
    switch k {
        case 0u: {
            value = texture_row(single_rayleigh, p, id.y, inu);
        }
        case 1u: {
            if bruneton.mie_on == 1u {
                value = texture_row(single_mie, p, id.y, inu);
            }
        }
        default: {
            value = texture_row(multiple, p, id.y, inu);
        }
    }
    textureStore(view_slice, id.xy, vec4<f32>(value, 1.0));
}
