// Delta E, the ground irradiance of the previous order's sky radiance (Bruneton and
// Neyret 2008, section 4, Eq. 8 and Algorithm 4.1 line 7): the GPU twin of `Builder::irradiance_of`
// (atmosphere-core `bruneton/precompute.rs`): composite 8-point Gauss-Legendre over the
// zenith angle of the upper hemisphere, the midpoint rule over azimuths in [0, pi]
// counted twice. One invocation per texel of E.

#import sky/bruneton/previous_order.wgsl

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= bruneton.irradiance_texels {
        return;
    }
    let texel_e = irradiance_texel(id.x);
    let q = texel_e.x;
    let r = texel_e.y;
    let mu_s = texel_e.z;
    let sin_s = safe_sqrt(1.0 - mu_s * mu_s);
    let panels = bruneton.sphere_panels;
    let phis = bruneton.sphere_azimuths;
    let phi_step = PI / f32(phis);
    var e = vec3<f32>(0.0);
    for (var k = 0u; k < 8u * panels; k++) {
        let theta = theta_node(0.0, 0.5 * PI, panels, k);
        let st = sin(theta.x);
        let ct = cos(theta.x);
        for (var i = 0u; i < phis; i++) {
            let nu = st * cos(phi_step * (f32(i) + 0.5)) * sin_s + ct * mu_s;
            let l = previous_radiance(q, r, ct, mu_s, nu, false);
            e += (theta.y * 2.0 * phi_step * st * ct) * l;
        }
    }
    store_write(bruneton.delta_e_offset + id.x, vec4<f32>(e, 0.0));
}
