// Mie's share of Delta J by a quadrature over the sphere about the view direction with
// the exact phase function (Bruneton and Neyret 2008, section 4: Delta J per texel over
// the sphere), the directions crowded towards the view: psi = pi u^2, u at composite
// 8-point Gauss-Legendre nodes on [0, 1], `mie_directions` of them, by as many
// azimuths; or with `mie_horizon` in the texel's frame, split at the view's and the
// horizon's zenith angles. The GPU twin of `MieQuadrature::integrate` (atmosphere-core
// `bruneton/mie_quadrature.rs`), which is its specification.

#import sky/bruneton/previous_order.wgsl

// Two unit vectors completing the unit vector n to a right-handed orthonormal basis (Duff
// et al. 2017, Listing 3): the CPU's `orthonormal_basis`.
fn orthonormal_basis(n: vec3<f32>) -> mat2x3<f32> {
    let sign = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    return mat2x3<f32>(
        vec3<f32>(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        vec3<f32>(b, sign + n.y * n.y * a, -n.y),
    );
}

// Sum over the nodes of weight x p_M x the previous order's incoming radiance at (q, r)
// with the sun at mu_s, about the unit view direction v (zenith z, sun in the x-z plane).
fn mie_by_quadrature(q: f32, r: f32, mu_s: f32, sin_s: f32, v: vec3<f32>) -> vec3<f32> {
    if bruneton.mie_horizon == 1u {
        return mie_in_horizon_frame(q, r, mu_s, sin_s, v);
    }
    let n = bruneton.mie_directions;
    let panels = max(n / 8u, 1u);
    let azimuth_weight = 2.0 * PI / f32(n);
    let basis = orthonormal_basis(v);
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < 8u * panels; k++) {
        let node = theta_node(0.0, 1.0, panels, k);
        let psi = PI * node.x * node.x;
        let s = sin(psi);
        let c = cos(psi);
        let weight = node.y * 2.0 * PI * node.x * s * azimuth_weight * mie_phase(c);
        for (var j = 0u; j < n; j++) {
            let phi = azimuth_weight * (f32(j) + 0.5);
            let w = v * c + (basis[0] * cos(phi) + basis[1] * sin(phi)) * s;
            let mu_w = clamp(w.z, -1.0, 1.0);
            let nu_w = clamp(w.x * sin_s + w.z * mu_s, -1.0, 1.0);
            sum += weight * incoming(q, r, mu_w, mu_s, nu_w, hits_ground(q, r * mu_w));
        }
    }
    return sum;
}

// `in_horizon_frame`: the zenith angle over the segments between 0, the view's, the
// horizon's and pi, `mie_directions` Gauss-Legendre nodes each; the azimuth about the
// view's, phi_v +- pi x^2, as many nodes of x per side.
fn mie_in_horizon_frame(q: f32, r: f32, mu_s: f32, sin_s: f32, v: vec3<f32>) -> vec3<f32> {
    let n = bruneton.mie_directions;
    let panels = max(n / 8u, 1u);
    let theta_v = acos(clamp(v.z, -1.0, 1.0));
    let theta_h = acos(clamp(horizon_mu_of(q, r), -1.0, 1.0));
    let phi_v = atan2(v.y, v.x);
    let cuts = vec4<f32>(0.0, min(theta_v, theta_h), max(theta_v, theta_h), PI);
    var sum = vec3<f32>(0.0);
    for (var segment = 0u; segment < 3u; segment++) {
        let a = cuts[segment];
        let b = cuts[segment + 1u];
        for (var k = 0u; k < 8u * panels; k++) {
            let node = theta_node(0.0, 1.0, panels, k);
            let theta = a + (b - a) * node.x;
            let st = sin(theta);
            let ct = cos(theta);
            let w_zenith = node.y * (b - a) * st;
            for (var side = 0u; side < 2u; side++) {
                let sign = select(-1.0, 1.0, side == 0u);
                for (var j = 0u; j < 8u * panels; j++) {
                    let x = theta_node(0.0, 1.0, panels, j);
                    let phi = phi_v + sign * PI * x.x * x.x;
                    let w = vec3<f32>(st * cos(phi), st * sin(phi), ct);
                    let weight = w_zenith * x.y * 2.0 * PI * x.x * mie_phase(dot(v, w));
                    let nu_w = clamp(w.x * sin_s + ct * mu_s, -1.0, 1.0);
                    sum += weight * incoming(q, r, ct, mu_s, nu_w, hits_ground(q, r * ct));
                }
            }
        }
    }
    return sum;
}
