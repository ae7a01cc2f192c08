// Single scattering of the Bruneton model (Bruneton and Neyret 2008, section 4, Eq. 5 with a point
// sun): Rayleigh and Mie without their phase functions, per unit solar irradiance, by
// the trapezoid rule on the nodes of `sky/bruneton/ray_nodes.wgsl`. The GPU twin of
// `Builder::single_scattering`. One workgroup per row (r, mu) of S, one invocation per
// texel (mu_s, nu) of the row; Mie is left out when pruned.

#import sky/bruneton/ray_nodes.wgsl

@compute @workgroup_size(256)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    if lid >= bruneton.mu_s_size * bruneton.nu_size {
        return;
    }
    let ir = group.x % bruneton.r_size;
    let imu = group.x / bruneton.r_size;
    let imus = lid % bruneton.mu_s_size;
    let inu = lid / bruneton.mu_s_size;
    let tx = texel(ir, imu, imus, inu);
    let ray = row_ray(tx);
    let n = bruneton.view_samples;
    var column = vec3<f32>(0.0);
    var previous = vec3<f32>(0.0);
    var rayleigh = vec3<f32>(0.0);
    var mie = vec3<f32>(0.0);
    for (var i = 0u; i <= n; i++) {
        let node = ray_node(ray, i, n, &column, &previous);
        if node.densities.x == 0.0 && node.densities.y == 0.0 {
            continue;
        }
        let sun = sun_transmittance(node.q, node.r, node_sun_cosine(ray, node, tx.mu_s, tx.nu));
        let c = node.weighted_transmittance * sun;
        rayleigh += c * node.densities.x;
        mie += c * node.densities.y;
    }
    let index = table_index(ir, imu, imus, inu);
    store[bruneton.single_rayleigh_offset + index] = vec4<f32>(rayleigh * atmosphere.rayleigh_scattering_per_m.xyz, 0.0);
    if bruneton.mie_on == 1u {
        store[bruneton.single_mie_offset + index] = vec4<f32>(mie * atmosphere.mie_scattering_per_m.xyz, 0.0);
    }
}
