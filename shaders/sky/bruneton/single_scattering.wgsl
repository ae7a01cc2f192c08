// Single scattering of the Bruneton model (Bruneton and Neyret 2008, section 4, Eq. 5 with a point
// sun): Rayleigh and Mie without their phase functions, per unit solar irradiance, by
// the trapezoid rule on the nodes of `sky/bruneton/ray_nodes.wgsl`. The GPU twin of
// `Builder::single_scattering`. One invocation per texel of S (a flat dispatch); Mie is
// left out when pruned.

#import sky/bruneton/ray_nodes.wgsl

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = flat_index(id);
    if index >= bruneton.scattering_texels {
        return;
    }
    let tx = texel_of_index(index);
    let ray = row_ray(tx);
    let n = bruneton.view_samples;
    var nodes = start_nodes(ray, n);
    var rayleigh = vec3<f32>(0.0);
    var mie = vec3<f32>(0.0);
    for (var i = 0u; i <= n; i++) {
        let node = ray_node(ray, i, &nodes);
        if node.densities.x == 0.0 && node.densities.y == 0.0 {
            continue;
        }
        let sun = sun_transmittance(node.q, node.r, node_sun_cosine(ray, node, tx.mu_s, tx.nu));
        let c = node.weighted_transmittance * sun;
        rayleigh += c * node.densities.x;
        mie += c * node.densities.y;
    }
    store_write(bruneton.single_rayleigh_offset + index, vec4<f32>(rayleigh * atmosphere.rayleigh_scattering_per_m.xyz, 0.0));
    if bruneton.mie_on == 1u {
        store_write(bruneton.single_mie_offset + index, vec4<f32>(mie * atmosphere.mie_scattering_per_m.xyz, 0.0));
    }
}
