// The voxel cloud's extinction, the light buffer's bilinear read, and Riley et al.
// 2004's Eq. 25 step and Eq. 26 source (or the octaves): twins of atmosphere-core's
// clouds/volume/grid.rs, cloud.rs, light_buffer.rs and clouds/layer/march.rs.

#import clouds/volume/bindings.wgsl
#import clouds/orders.wgsl

fn voxel(i: u32, j: u32, k: u32) -> f32 {
    return textureLoad(density, vec3<u32>(i, j, k), 0).r;
}

// Extinction at `p`, m^-1: trilinear between voxel centres, clamped to the edge voxels,
// 0 outside the box.
fn extinction(p: vec3<f32>) -> f32 {
    let n = volume.dims.xyz;
    let u = (p - volume.box_origin.xyz) / volume.box_origin.w;
    if any(u < vec3<f32>(0.0)) || any(u > vec3<f32>(n)) {
        return 0.0;
    }
    let c = clamp(u - 0.5, vec3<f32>(0.0), vec3<f32>(n - 1u));
    let i0 = min(vec3<u32>(floor(c)), max(n, vec3<u32>(2u)) - 2u);
    let i1 = min(i0 + 1u, n - 1u);
    let f = c - vec3<f32>(i0);
    let x00 = mix(voxel(i0.x, i0.y, i0.z), voxel(i1.x, i0.y, i0.z), f.x);
    let x10 = mix(voxel(i0.x, i1.y, i0.z), voxel(i1.x, i1.y, i0.z), f.x);
    let x01 = mix(voxel(i0.x, i0.y, i1.z), voxel(i1.x, i0.y, i1.z), f.x);
    let x11 = mix(voxel(i0.x, i1.y, i1.z), voxel(i1.x, i1.y, i1.z), f.x);
    return volume.irradiance.w * mix(mix(x00, x10, f.y), mix(x01, x11, f.y), f.z);
}

// The light buffer at `p`, bilinear, clamped to the edge texels: (I per wavelength, tau).
fn read_light(p: vec3<f32>) -> vec4<f32> {
    let side = u32(volume.light_size.z);
    let texel = volume.light_size.xy / volume.light_size.z;
    let x = (vec2<f32>(dot(p, volume.light_u.xyz), dot(p, volume.light_v.xyz))
        - vec2<f32>(volume.light_u.w, volume.light_v.w)) / texel - 0.5;
    let c = clamp(x, vec2<f32>(0.0), vec2<f32>(f32(side - 1u)));
    let i0 = min(vec2<u32>(floor(c)), vec2<u32>(max(side, 2u) - 2u));
    let i1 = min(i0 + 1u, vec2<u32>(side - 1u));
    let f = c - vec2<f32>(i0);
    let a = mix(textureLoad(light_in, vec2<u32>(i0.x, i0.y), 0), textureLoad(light_in, vec2<u32>(i1.x, i0.y), 0), f.x);
    let b = mix(textureLoad(light_in, vec2<u32>(i0.x, i1.y), 0), textureLoad(light_in, vec2<u32>(i1.x, i1.y), 0), f.x);
    return mix(a, b, f.y);
}

// Eq. 25's factor over a step of optical depth `d` after `walked`, each wavelength.
fn riley_step(walked: f32, d: f32) -> vec3<f32> {
    let albedo = volume.sun.w;
    let m = u32(floor(albedo * walked + 1.0 + d));
    let kept = albedo * forward_fraction(m);
    let t = exp(-d);
    return t + (1.0 - t) * pow(kept, vec3<f32>(d));
}

// J / E_sun towards the eye, sr^-1, from the light buffer's (I, tau) at cosine `nu`.
fn eye_source(light: vec4<f32>, nu: f32) -> vec3<f32> {
    let tau = light.w;
    if volume.dims.w == 0u {
        let n = u32(floor(volume.sun.w * tau)) + 1u;
        return light.xyz * (distribution(n, nu) + volume.misc.x);
    }
    let single = distribution(1u, nu);
    let isotropic = 1.0 / (4.0 * PI);
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < u32(volume.misc.y); i++) {
        let c = pow(0.5, f32(i));
        sum += c * exp(-c * tau) * (c * single + (1.0 - c) * isotropic);
    }
    return sum;
}
