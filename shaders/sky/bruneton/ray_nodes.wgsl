// The trapezoid nodes along the ray of a row of S, the texels of equal (r, mu): the GPU
// twin of `Builder::ray_nodes` (atmosphere-core `bruneton/view_integrals.rs`) and of
// `bruneton/node_placement.rs`. By default nodes crowd quadratically where the air is
// densest (the start of climbing rays, the end of rays that meet the ground); with
// `density_nodes` they lie at equal steps of half distance, half the share of light that
// meets matter (1 - exp(-optical depth)), found by a fine march of FINE_PER_NODE points
// per node. The transmittance from the ray's start
// comes from a running trapezoid of the densities, as on the CPU.

#import sky/bruneton/tables.wgsl

// `FINE_PER_NODE` of `node_placement.rs`.
const FINE_PER_NODE: u32 = 4u;

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

// Distance of node i of n along `ray` by the crowding rule (`crowded_distance`).
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

// Where a node at distance t lies: q = rho^2 there and its radius.
fn q_at(ray: Ray, t: f32) -> f32 {
    return clamp(ray.q + t * (t + 2.0 * ray.r_mu), 0.0, horizon_sq());
}

// Extinction per metre at the middle channel at distance t (`density_distances`'s
// `extinction`).
fn extinction_at(ray: Ray, t: f32) -> f32 {
    let q = q_at(ray, t);
    return optical_depth(density_at(q / (radius_of_q(q) + atmosphere.bottom_radius_m))).y;
}

// A fine point of the density placement: distance, optical depth from the start,
// extinction there.
struct Fine {
    t: f32,
    depth: f32,
    extinction: f32,
}

// The nodes' march: n intervals, the running column and the last node's densities, the
// distances of the previous, current and next node, and for the density placement the
// fine points j and j + 1 and the share of light that meets matter along the whole ray.
struct Nodes {
    n: u32,
    column: vec3<f32>,
    previous: vec3<f32>,
    t_previous: f32,
    t: f32,
    t_next: f32,
    j: u32,
    lower: Fine,
    upper: Fine,
    depth: f32,
}

fn fine_point(ray: Ray, j: u32, n: u32, before: Fine) -> Fine {
    let t = node_distance(ray, j, FINE_PER_NODE * n);
    let e = extinction_at(ray, t);
    return Fine(t, before.depth + 0.5 * (t - before.t) * (before.extinction + e), e);
}

// `interacted` of `node_placement.rs`: 1 - exp(-tau).
fn interacted(tau: f32) -> f32 {
    if tau < 1e-3 {
        return tau * (1.0 - 0.5 * tau);
    }
    return 1.0 - exp(-tau);
}

// m(t) of `density_distances` at a fine point, `depth` the interacted share of the ray.
fn measure(ray: Ray, f: Fine, depth: f32) -> f32 {
    let by_distance = f.t / ray.length;
    if depth > 0.0 {
        return by_distance + interacted(f.depth) / depth;
    }
    return 2.0 * by_distance;
}

// Distance of node k of the density placement; k never decreases between calls.
fn density_distance(ray: Ray, k: u32, nodes: ptr<function, Nodes>) -> f32 {
    let n = (*nodes).n;
    if k == 0u || ray.length <= 0.0 {
        return 0.0;
    }
    if k >= n {
        return ray.length;
    }
    let goal = 2.0 * f32(k) / f32(n);
    let count = FINE_PER_NODE * n;
    while (*nodes).j + 1u < count && measure(ray, (*nodes).upper, (*nodes).depth) < goal {
        (*nodes).j += 1u;
        (*nodes).lower = (*nodes).upper;
        (*nodes).upper = fine_point(ray, (*nodes).j + 1u, n, (*nodes).lower);
    }
    let lower = (*nodes).lower;
    let upper = (*nodes).upper;
    let m0 = measure(ray, lower, (*nodes).depth);
    let m1 = measure(ray, upper, (*nodes).depth);
    var w = 0.0;
    if m1 > m0 {
        w = clamp((goal - m0) / (m1 - m0), 0.0, 1.0);
    }
    return lower.t + w * (upper.t - lower.t);
}

fn next_distance(ray: Ray, k: u32, nodes: ptr<function, Nodes>) -> f32 {
    if bruneton.density_nodes == 1u {
        return density_distance(ray, k, nodes);
    }
    return node_distance(ray, min(k, (*nodes).n), (*nodes).n);
}

// The march's start for n intervals: for the density placement a first fine march for
// the ray's optical depth.
fn start_nodes(ray: Ray, n: u32) -> Nodes {
    var nodes: Nodes;
    nodes.n = n;
    nodes.column = vec3<f32>(0.0);
    nodes.previous = vec3<f32>(0.0);
    if bruneton.density_nodes == 1u {
        let first = Fine(0.0, 0.0, extinction_at(ray, 0.0));
        var f = first;
        for (var j = 1u; j <= FINE_PER_NODE * n; j++) {
            f = fine_point(ray, j, n, f);
        }
        nodes.depth = interacted(f.depth);
        nodes.j = 0u;
        nodes.lower = first;
        nodes.upper = fine_point(ray, 1u, n, first);
    }
    nodes.t = 0.0;
    nodes.t_previous = 0.0;
    nodes.t_next = next_distance(ray, 1u, &nodes);
    return nodes;
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

// Node i (called for i = 0, 1, ..., n in turn), which advances the march.
fn ray_node(ray: Ray, i: u32, nodes: ptr<function, Nodes>) -> Node {
    if i > 0u {
        (*nodes).t_previous = (*nodes).t;
        (*nodes).t = (*nodes).t_next;
        (*nodes).t_next = next_distance(ray, i + 1u, nodes);
    }
    var node: Node;
    node.t = (*nodes).t;
    node.q = q_at(ray, node.t);
    node.r = radius_of_q(node.q);
    node.densities = density_at(node.q / (node.r + atmosphere.bottom_radius_m));
    if i > 0u {
        (*nodes).column += 0.5 * (node.t - (*nodes).t_previous) * ((*nodes).previous + node.densities);
    }
    (*nodes).previous = node.densities;
    let w = 0.5 * ((*nodes).t_next - (*nodes).t_previous);
    node.weighted_transmittance = w * exp(-optical_depth((*nodes).column));
    return node;
}

// The sun's zenith cosine at `node` for a sun at mu_s seen at nu from the ray's start.
fn node_sun_cosine(ray: Ray, node: Node, mu_s: f32, nu: f32) -> f32 {
    return clamp((mu_s * ray.r + nu * node.t) / node.r, -1.0, 1.0);
}
