// Delta S of an order: T Delta J integrated along every texel's ray (Bruneton and Neyret
// 2008, Eq. 7 and Algorithm 4.1 line 8) by the trapezoid rule on the nodes of
// `bruneton_ray_nodes.wgsl`: the GPU twin of `Builder::scattering_of` (atmosphere-core
// `bruneton/precompute.rs`). One workgroup per row (r, mu) of S, one invocation per
// texel (mu_s, nu) of the row, as the CPU shares work: at each node Delta J is first
// interpolated in (r, mu) for every (mu_s, nu) texel of the row (the plane, in workgroup
// memory), then in mu_s and nu for each texel.

#import bruneton_ray_nodes.wgsl

// The most texels per row (mu_s x nu): the workgroup's size.
const ROW_TEXELS: u32 = 256u;

var<workgroup> plane: array<vec3<f32>, ROW_TEXELS>;

@compute @workgroup_size(256)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let size = bruneton.size;
    let in_row = lid < size.z * size.w;
    let ir = group.x % size.x;
    let imu = group.x / size.x;
    // This invocation's texel (mu_s, nu), and the plane entry it fills.
    let imus = lid % size.z;
    let inu = min(lid / size.z, size.w - 1u);
    let tx = texel(ir, imu, imus, inu);
    let ray = row_ray(tx);
    let nu_axis = axis(u_nu(tx.nu), size.w);
    let delta_j = bruneton.offsets_b.y;
    let n = bruneton.flags.x;
    var column = vec3<f32>(0.0);
    var previous = vec3<f32>(0.0);
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i <= n; i++) {
        let node = ray_node(ray, i, n, &column, &previous);
        let p = table_position(node.q, node.r, ray.r_mu + node.t, 0.0, 0.0, ray.ground);
        workgroupBarrier();
        if in_row {
            let a = delta_j + table_index(p.r.i, p.mu.i, imus, inu);
            let b = delta_j + table_index(p.r.i, p.mu.i + 1u, imus, inu);
            let wr = p.r.w;
            let wm = p.mu.w;
            plane[lid] = (1.0 - wr) * (1.0 - wm) * store[a].xyz + wr * (1.0 - wm) * store[a + size.z].xyz
                + (1.0 - wr) * wm * store[b].xyz + wr * wm * store[b + size.z].xyz;
        }
        workgroupBarrier();
        if in_row {
            let s = axis(u_mu_s(node_sun_cosine(ray, node, tx.mu_s, tx.nu)), size.z);
            let lo = nu_axis.i * size.z + s.i;
            let hi = lo + size.z;
            let a = mix(plane[lo], plane[lo + 1u], s.w);
            let b = mix(plane[hi], plane[hi + 1u], s.w);
            sum += node.weighted_transmittance * mix(a, b, nu_axis.w);
        }
    }
    if in_row {
        store[bruneton.offsets_b.x + table_index(ir, imu, imus, inu)] = vec4<f32>(sum, 0.0);
    }
}
