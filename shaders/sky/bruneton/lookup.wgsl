// Reading the scattering tables S from their 3D textures (written by
// `sky/bruneton/scattering_texture.wgsl`, texel (x = nu * mu_s_size + mu_s, y = mu, z = r)):
// the quadrilinear interpolation of `Table4::lookup`, for the per-pixel pass
// (`sky/bruneton/pixel.wgsl`) and its view slice (`sky/bruneton/view_slice.wgsl`).

#import sky/bruneton/tables.wgsl

@group(0) @binding(6) var single_rayleigh: texture_3d<f32>;
@group(0) @binding(7) var single_mie: texture_3d<f32>;
@group(0) @binding(8) var multiple: texture_3d<f32>;

// Bilinear interpolation over (r, mu_s) of row imu in nu slice `inu` of a scattering
// texture; along mu_s geometric where `geometric_pair` says so (`Table4::at_position`).
fn texture_row(table: texture_3d<f32>, p: Position, imu: u32, inu: u32) -> vec3<f32> {
    let geometric = geometric_pair(p.mu_s.i);
    var out = vec3<f32>(0.0);
    for (var dr = 0u; dr < 2u; dr++) {
        let w_r = select(1.0 - p.r.w, p.r.w, dr == 1u);
        let at = texture_texel(p.r.i + dr, imu, p.mu_s.i, inu);
        let a = textureLoad(table, at, 0).xyz;
        let b = textureLoad(table, at + vec3<u32>(1u, 0u, 0u), 0).xyz;
        out += w_r * along_mu_s(a, b, p.mu_s.w, geometric);
    }
    return out;
}

// Trilinear interpolation over (r, mu, mu_s) in nu slice `inu` of a scattering texture.
fn texture_slice(table: texture_3d<f32>, p: Position, inu: u32) -> vec3<f32> {
    var out = vec3<f32>(0.0);
    for (var dm = 0u; dm < 2u; dm++) {
        let wm = select(1.0 - p.mu.w, p.mu.w, dm == 1u);
        out += wm * texture_row(table, p, p.mu.i + dm, inu);
    }
    return out;
}

// Quadrilinear interpolation of a scattering texture (`Table4::at_position`).
fn texture_lookup(table: texture_3d<f32>, p: Position) -> vec3<f32> {
    let lo = texture_slice(table, p, p.nu.i);
    if p.nu.w == 0.0 {
        return lo;
    }
    return mix(lo, texture_slice(table, p, p.nu.i + 1u), p.nu.w);
}
