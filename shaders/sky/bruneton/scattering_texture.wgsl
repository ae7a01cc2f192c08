// The finished scattering tables S from the store into the 3D textures the per-pixel
// pass reads: S(r, mu, mu_s, nu) at texel (x = nu * mu_s_size + mu_s, y = mu, z = r),
// Rgba32Float (the f32 of the CPU's `Table4`, so no rounding is added). Three textures:
// single Rayleigh and single Mie without phase functions, orders two and up. Also the
// irradiance table E into a 2D texture (x = mu_s, y = r): lavapipe reads a storage
// buffer at a computed index lane by lane, several times slower than a texel read.

#import sky/bruneton/tables.wgsl

@group(0) @binding(6) var single_rayleigh: texture_storage_3d<rgba32float, write>;
@group(0) @binding(7) var single_mie: texture_storage_3d<rgba32float, write>;
@group(0) @binding(8) var multiple: texture_storage_3d<rgba32float, write>;
@group(0) @binding(9) var irradiance: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let n_e = bruneton.irradiance_size;
    if id.x < n_e.x * n_e.y {
        let at_e = vec2<u32>(id.x % n_e.x, id.x / n_e.x);
        textureStore(irradiance, at_e, vec4<f32>(store[bruneton.offsets_b.w + id.x].xyz, 1.0));
    }
    if id.x >= bruneton.offsets_c.z {
        return;
    }
    let size = bruneton.size;
    let imus = id.x % size.z;
    let rest = id.x / size.z;
    let ir = rest % size.x;
    let imu = (rest / size.x) % size.y;
    let inu = rest / (size.x * size.y);
    let at = vec3<u32>(inu * size.z + imus, imu, ir);
    textureStore(single_rayleigh, at, vec4<f32>(store[bruneton.offsets_a.y + id.x].xyz, 1.0));
    textureStore(multiple, at, vec4<f32>(store[bruneton.offsets_a.w + id.x].xyz, 1.0));
    if bruneton.flags.y == 1u {
        textureStore(single_mie, at, vec4<f32>(store[bruneton.offsets_a.z + id.x].xyz, 1.0));
    }
}
