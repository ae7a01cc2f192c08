// The finished scattering tables S from the store into the 3D textures the per-pixel
// pass reads: S(r, mu, mu_s, nu) at texel (x = nu * mu_s_size + mu_s, y = mu, z = r),
// Rgba32Float (the f32 of the CPU's `Table4`, so no rounding is added). Three textures:
// single Rayleigh and single Mie without phase functions, orders two and up. Also the
// irradiance table E into a 2D texture (x = mu_s, y = r), which the pass reads faster
// than the store (a CPU adapter reads a storage buffer at a computed index lane by lane).

#import sky/bruneton/tables.wgsl

@group(0) @binding(6) var single_rayleigh: texture_storage_3d<rgba32float, write>;
@group(0) @binding(7) var single_mie: texture_storage_3d<rgba32float, write>;
@group(0) @binding(8) var multiple: texture_storage_3d<rgba32float, write>;
@group(0) @binding(9) var irradiance: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = flat_index(id);
    if index < bruneton.irradiance_mu_s_size * bruneton.irradiance_r_size {
        let at_e = vec2<u32>(index % bruneton.irradiance_mu_s_size, index / bruneton.irradiance_mu_s_size);
        textureStore(irradiance, at_e, vec4<f32>(store_read(bruneton.irradiance_offset + index).xyz, 1.0));
    }
    if index >= bruneton.scattering_texels {
        return;
    }
    let c = texel_coords(index);
    let at = texture_texel(c.r, c.mu, c.mu_s, c.nu);
    textureStore(single_rayleigh, at, vec4<f32>(store_read(bruneton.single_rayleigh_offset + index).xyz, 1.0));
    textureStore(multiple, at, vec4<f32>(store_read(bruneton.multiple_offset + index).xyz, 1.0));
    if bruneton.mie_on == 1u {
        textureStore(single_mie, at, vec4<f32>(store_read(bruneton.single_mie_offset + index).xyz, 1.0));
    }
}
