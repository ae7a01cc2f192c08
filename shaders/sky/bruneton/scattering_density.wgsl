// Delta J of the next order, the light scattered at each point and direction by the
// previous order's radiance (Bruneton and Neyret 2008, section 4, Eq. 7 and Algorithm 4.1 line 6):
// the GPU twin of `Builder::scattering_density` (atmosphere-core
// `bruneton/precompute.rs`), which is its specification.
//
// Entry point `moments`: for each (r, mu_s) of S, the angular moments of the incoming
// radiance (L0, Fx, Fz, Mxx, Myy, Mzz, Mxz per channel) over the sphere, by composite
// 8-point Gauss-Legendre in the zenith angle on each side of the horizon and the
// midpoint rule over azimuths in [0, pi] counted twice (the field is symmetric about the
// sun's vertical plane). Entry point `main`: Delta J at every texel from the moments:
// Rayleigh exactly (its phase function is quadratic in the direction), Mie by the
// delta-M approximation with three Legendre terms, whose forward peak takes the incoming
// radiance along the view, or, with `mie_directions`, by a quadrature about the view
// (`sky/bruneton/mie_quadrature.wgsl`).

#import sky/bruneton/mie_quadrature.wgsl

// Delta J also as a 3D texture, texel (x = nu * mu_s_size + mu_s, y = mu, z = r), for
// Delta S to read (`sky/bruneton/scattering.wgsl`).
@group(0) @binding(6) var delta_j_out: texture_storage_3d<rgba32float, write>;

// The moments of pair (ir, imus) start at this store index.
fn moments_base(ir: u32, imus: u32) -> u32 {
    return bruneton.moments_offset + 7u * (ir + bruneton.r_size * imus);
}

@compute @workgroup_size(64)
fn moments(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= bruneton.r_size * bruneton.mu_s_size {
        return;
    }
    let ir = id.x % bruneton.r_size;
    let imus = id.x / bruneton.r_size;
    let tx = texel(ir, 0u, imus, 0u);
    let sin_s = safe_sqrt(1.0 - tx.mu_s * tx.mu_s);
    let theta_h = acos(horizon_mu_of(tx.q, tx.r));
    let panels = bruneton.sphere_panels;
    let phis = bruneton.sphere_azimuths;
    let phi_step = PI / f32(phis);
    var m: array<vec3<f32>, 7>;
    for (var j = 0u; j < 7u; j++) {
        m[j] = vec3<f32>(0.0);
    }
    for (var side = 0u; side < 2u; side++) {
        let a = select(0.0, theta_h, side == 1u);
        let b = select(theta_h, PI, side == 1u);
        for (var k = 0u; k < 8u * panels; k++) {
            let theta = theta_node(a, b, panels, k);
            let st = sin(theta.x);
            let ct = cos(theta.x);
            let ground = hits_ground(tx.q, tx.r * ct);
            for (var i = 0u; i < phis; i++) {
                let phi = phi_step * (f32(i) + 0.5);
                let wx = st * cos(phi);
                let wy = st * sin(phi);
                let wz = ct;
                let nu = wx * sin_s + wz * tx.mu_s;
                let l = (theta.y * 2.0 * phi_step * st) * incoming(tx.q, tx.r, ct, tx.mu_s, nu, ground);
                m[0] += l;
                m[1] += l * wx;
                m[2] += l * wz;
                m[3] += l * (wx * wx);
                m[4] += l * (wy * wy);
                m[5] += l * (wz * wz);
                m[6] += l * (wx * wz);
            }
        }
    }
    let base = moments_base(ir, imus);
    for (var j = 0u; j < 7u; j++) {
        store_write(base + j, vec4<f32>(m[j], 0.0));
    }
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = flat_index(id);
    if index >= bruneton.scattering_texels {
        return;
    }
    let c = texel_coords(index);
    let tx = texel(c.r, c.mu, c.mu_s, c.nu);
    let sin_s = safe_sqrt(1.0 - tx.mu_s * tx.mu_s);
    let vx = select(0.0, (tx.nu - tx.mu * tx.mu_s) / sin_s, sin_s > 1e-9);
    let vy = safe_sqrt(1.0 - tx.mu * tx.mu - vx * vx);
    let vz = tx.mu;
    let base = moments_base(c.r, c.mu_s);
    let l0 = store_read(base).xyz;
    let fx = store_read(base + 1u).xyz;
    let fz = store_read(base + 2u).xyz;
    let q = store_read(base + 3u).xyz * (vx * vx) + store_read(base + 4u).xyz * (vy * vy)
        + store_read(base + 5u).xyz * (vz * vz) + store_read(base + 6u).xyz * (2.0 * vx * vz);
    let rho = density_at(tx.q / (tx.r + atmosphere.bottom_radius_m));
    var j = atmosphere.rayleigh_scattering_per_m.xyz * (rho.x * 3.0 / (16.0 * PI)) * (l0 + q);
    if bruneton.mie_on == 1u && bruneton.mie_directions > 0u {
        let j_m = mie_by_quadrature(tx.q, tx.r, tx.mu_s, sin_s, vec3<f32>(vx, vy, vz));
        j += atmosphere.mie_scattering_per_m.xyz * rho.y * max(j_m, vec3<f32>(0.0));
    } else if bruneton.mie_on == 1u {
        let l_v = incoming(tx.q, tx.r, tx.mu, tx.mu_s, tx.nu, tx.ground);
        let p1 = vx * fx + vz * fz;
        let p2 = 0.5 * (3.0 * q - l0);
        let f = bruneton.mie_forward_fraction;
        let j_m = f * l_v + (1.0 - f) / (4.0 * PI) * (l0 + 3.0 * bruneton.mie_chi1 * p1 + 5.0 * bruneton.mie_chi2 * p2);
        j += atmosphere.mie_scattering_per_m.xyz * rho.y * max(j_m, vec3<f32>(0.0));
    }
    let value = vec4<f32>(max(j, vec3<f32>(0.0)), 0.0);
    store_write(bruneton.delta_j_offset + index, value);
    textureStore(delta_j_out, texture_texel(c.r, c.mu, c.mu_s, c.nu), value);
}
