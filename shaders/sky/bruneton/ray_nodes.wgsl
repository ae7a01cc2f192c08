// The trapezoid nodes along the ray of a row of S, the texels of equal (r, mu): the GPU
// twin of `Builder::ray_nodes` (atmosphere-core `bruneton/precompute.rs`). Nodes crowd
// quadratically where the air is densest (the start of climbing rays, the end of rays
// that meet the ground); the transmittance from the ray's start comes from a running
// trapezoid of the densities, as on the CPU.

#import sky/bruneton/tables.wgsl

// A row's ray: its start (q, r, r mu), whether it meets the ground, its length.
struct Ray {
    q: f32,
    r: f32,
    r_mu: f32,
    ground: bool,
    length: f32,
}

fn row_ray(t: Texel) -> Ray {
    let r_mu = t.r * t.mu;
    return Ray(t.q, t.r, r_mu, t.ground, ray_length(t.q, r_mu, t.ground));
}

// Distance of node i of n along `ray`.
fn node_distance(ray: Ray, i: u32, n: u32) -> f32 {
    let u = f32(i) / f32(n);
    if ray.r_mu >= 0.0 {
        return ray.length * u * u;
    }
    if ray.ground {
        return ray.length * (1.0 - (1.0 - u) * (1.0 - u));
    }
    return ray.length * u;
}

// One node: where it is, its densities, and its trapezoid weight times the
// transmittance from the ray's start.
struct Node {
    t: f32,
    q: f32,
    r: f32,
    densities: vec3<f32>,
    weighted_transmittance: vec3<f32>,
}

// Node i of n, given the running column up to node i - 1 and that node's densities
// (`column`, `previous`), which it updates.
fn ray_node(ray: Ray, i: u32, n: u32, column: ptr<function, vec3<f32>>, previous: ptr<function, vec3<f32>>) -> Node {
    var node: Node;
    node.t = node_distance(ray, i, n);
    node.q = clamp(ray.q + node.t * (node.t + 2.0 * ray.r_mu), 0.0, horizon_sq());
    node.r = radius_of_q(node.q);
    node.densities = density_at(node.q / (node.r + atmosphere.bottom_radius_m));
    if i > 0u {
        *column += 0.5 * (node.t - node_distance(ray, i - 1u, n)) * (*previous + node.densities);
    }
    *previous = node.densities;
    let w = 0.5 * (node_distance(ray, min(i + 1u, n), n) - node_distance(ray, max(i, 1u) - 1u, n));
    node.weighted_transmittance = w * exp(-optical_depth(*column));
    return node;
}

// The sun's zenith cosine at `node` for a sun at mu_s seen at nu from the ray's start.
fn node_sun_cosine(ray: Ray, node: Node, mu_s: f32, nu: f32) -> f32 {
    return clamp((mu_s * ray.r + nu * node.t) / node.r, -1.0, 1.0);
}
