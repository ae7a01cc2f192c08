// Entry pass: the cloud spheres' radiance and transmittance for every pixel (render-wgpu's
// `clouds/spheres/sphere_pass.rs`; CPU twin: atmosphere-core's
// `clouds/spheres/composite.rs`, `spheres_only`, compared pixel by pixel in
// `tests/tests/gpu_cloud_spheres_parity.rs`). Pixel (x, y) of a W x H image looks along
// forward + (2 (x + 0.5) / W - 1) tan(fov / 2) aspect right
//         - (2 (y + 0.5) / H - 1) tan(fov / 2) up, normalised.
// Along a ray the radius falls to its closest approach and rises after it, so the
// shells' first intervals, outermost first, then their second intervals, innermost
// first, are the crossings in order of distance (`shells.rs` sorts them); each is
// composited front to back until the transmittance falls below MIN_TRANSMITTANCE.

#import clouds/spheres/shade.wgsl

// Below this transmittance the crossings behind are left out (`composite.rs`'s
// MIN_TRANSMITTANCE).
const MIN_TRANSMITTANCE: f32 = 1e-4;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = spheres.counts.zw;
    if any(id.xy >= size) {
        return;
    }
    let tan_half = spheres.camera_m.w;
    let aspect = f32(size.x) / f32(size.y);
    let sx = (2.0 * (f32(id.x) + 0.5) / f32(size.x) - 1.0) * tan_half * aspect;
    let sy = (2.0 * (f32(id.y) + 0.5) / f32(size.y) - 1.0) * tan_half;
    let d = normalize(spheres.forward.xyz + sx * spheres.right.xyz - sy * spheres.up.xyz);
    let o = spheres.camera_m.xyz;
    let r = length(o);
    let mu = clamp(dot(o, d) / r, -1.0, 1.0);
    var end = 3.0e38;
    let ground = sphere_roots(r, mu, spheres.radii_m.x);
    if ground.x <= ground.y && ground.x >= 0.0 && mu < 0.0 {
        end = ground.x;
    }
    let m = spheres.counts.x;
    var result = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    for (var half = 0u; half < 2u; half++) {
        for (var n = 0u; n < m; n++) {
            // First intervals from the outermost shell in, then second ones outwards.
            var k = n;
            if half == 0u {
                k = m - 1u - n;
            }
            let inner = spheres.radii_m.y + f32(k) * spheres.radii_m.w;
            let outer_roots = sphere_roots(r, mu, inner + spheres.radii_m.w);
            if outer_roots.x > outer_roots.y {
                continue;
            }
            let inner_roots = sphere_roots(r, mu, inner);
            var t = outer_roots;
            if inner_roots.x <= inner_roots.y {
                if half == 0u {
                    t.y = min(t.y, inner_roots.x);
                } else {
                    t.x = max(t.x, inner_roots.y);
                }
            } else if half == 1u {
                continue;
            }
            let t0 = max(t.x, 0.0);
            let t1 = min(t.y, end);
            if result.a < MIN_TRANSMITTANCE {
                break;
            }
            if t0 < t1 {
                let c = shade_crossing(o, d, k, t0, t1);
                result = vec4<f32>(result.rgb + result.a * c.rgb, result.a * c.a);
            }
        }
    }
    textureStore(sphere_image, id.xy, result);
}
