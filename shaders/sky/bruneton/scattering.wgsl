// Delta S of an order: T Delta J integrated along every texel's ray (Bruneton and Neyret
// 2008, section 4, Eq. 7 and Algorithm 4.1 line 8) by the trapezoid rule on the nodes of
// `sky/bruneton/ray_nodes.wgsl`: the GPU twin of `Builder::scattering_of` (atmosphere-core
// `bruneton/precompute.rs`). One invocation per texel. At each node Delta J is
// interpolated in (r, mu), then in mu_s and nu, as the CPU does. The CPU computes the
// (r, mu) interpolation once per row for all (mu_s, nu) texels (its plane); here each
// texel computes the four plane entries it reads, from Delta J's 3D texture: sharing
// them in workgroup memory took a storage buffer read, a workgroup store, four
// workgroup reads and two barriers per node, and lavapipe does each of those memory
// accesses lane by lane (docs/rendering.md, "Cost").

#import sky/bruneton/ray_nodes.wgsl

@group(0) @binding(6) var delta_j: texture_3d<f32>;
// x: the first texel of this dispatch. An order's Delta S is dispatched in slices of
// texels (`SLICE_TEXELS` of render-wgpu's `sky/bruneton/workgroups.rs`), so that a
// progressive build can spread it over frames.
@group(0) @binding(7) var<uniform> slice: vec4<u32>;

// Delta J of nu slice `inu` at mu_s texel `imus` interpolated in (r, mu) at `p`: the
// CPU's plane entry (`scattering_of`), corner weights and order as there.
fn plane_entry(p: Position, imus: u32, inu: u32) -> vec3<f32> {
    let at = texture_texel(p.r.i, p.mu.i, imus, inu);
    let wr = p.r.w;
    let wm = p.mu.w;
    return (1.0 - wr) * (1.0 - wm) * textureLoad(delta_j, at, 0).xyz
        + wr * (1.0 - wm) * textureLoad(delta_j, at + vec3<u32>(0u, 0u, 1u), 0).xyz
        + (1.0 - wr) * wm * textureLoad(delta_j, at + vec3<u32>(0u, 1u, 0u), 0).xyz
        + wr * wm * textureLoad(delta_j, at + vec3<u32>(0u, 1u, 1u), 0).xyz;
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = slice.x + id.x;
    if index >= bruneton.scattering_texels {
        return;
    }
    let tx = texel_of_index(index);
    let ray = row_ray(tx);
    let u = u_nu(tx.nu);
    let nu_texel = axis(u, bruneton.nu_size);
    let n = bruneton.view_samples;
    var nodes = start_nodes(ray, n);
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i <= n; i++) {
        let node = ray_node(ray, i, &nodes);
        let p = table_position(node.q, node.r, ray.r_mu + node.t, 0.0, 0.0, ray.ground);
        let mu_s_t = node_sun_cosine(ray, node, tx.mu_s, tx.nu);
        let s = axis(u_mu_s(mu_s_t), bruneton.mu_s_size);
        // The node's mu and mu_s move the nu weight along the ray with `nu_edge` (they
        // bound nu) and the texels too with `nu_by_azimuth` (they turn the ray's nu
        // into another azimuth); else both are the texel's own.
        let mu_t = clamp((ray.r_mu + node.t) / node.r, -1.0, 1.0);
        var nu_at = nu_texel;
        if bruneton.nu_by_azimuth == 1u {
            nu_at = axis(azimuth_unit(mu_t, mu_s_t, tx.nu), bruneton.nu_size);
        } else {
            nu_at.w = nu_edge_weight(nu_texel, u, mu_t, mu_s_t);
        }
        let wnu = nu_at.w;
        let geometric = geometric_pair(s.i);
        let a = along_mu_s(plane_entry(p, s.i, nu_at.i), plane_entry(p, s.i + 1u, nu_at.i), s.w, geometric);
        let b = along_mu_s(plane_entry(p, s.i, nu_at.i + 1u), plane_entry(p, s.i + 1u, nu_at.i + 1u), s.w, geometric);
        sum += node.weighted_transmittance * mix(a, b, wnu);
    }
    store_write(bruneton.delta_s_offset + index, vec4<f32>(sum, 0.0));
}
