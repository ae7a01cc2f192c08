// Single scattering of the Bruneton model (Bruneton and Neyret 2008, Eq. 5 with a point
// sun): Rayleigh and Mie without their phase functions, per unit solar irradiance, by
// the trapezoid rule on the nodes of `sky/bruneton/ray_nodes.wgsl`. The GPU twin of
// `Builder::single_scattering`. One workgroup per row (r, mu) of S, one invocation per
// texel (mu_s, nu) of the row; Mie is left out when pruned.

#import sky/bruneton/ray_nodes.wgsl

@compute @workgroup_size(256)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let size = bruneton.size;
    if lid >= size.z * size.w {
        return;
    }
    let ir = group.x % size.x;
    let imu = group.x / size.x;
    let imus = lid % size.z;
    let inu = lid / size.z;
    let tx = texel(ir, imu, imus, inu);
    let ray = row_ray(tx);
    let n = bruneton.flags.x;
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
    store[bruneton.offsets_a.y + index] = vec4<f32>(rayleigh * atmosphere.rayleigh_scattering_per_m.xyz, 0.0);
    if bruneton.flags.y == 1u {
        store[bruneton.offsets_a.z + index] = vec4<f32>(mie * atmosphere.mie_scattering_per_m.xyz, 0.0);
    }
}
