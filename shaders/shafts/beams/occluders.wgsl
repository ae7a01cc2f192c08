// Library: where a ray meets the scene's occluders. CPU twins: atmosphere-core's
// `beams/occluder.rs` (analytic primitives), `beams/triangle.rs` (Moller and Trumbore
// 1997), `beams/bvh.rs` (the hierarchy, traversed with a fixed stack) and
// `beams/occluders.rs` (the nearest surface; the infinite planes a shadow map cannot
// hold). A miss is MISS; hits lie strictly between t_min and t_max.

#import shafts/beams/bindings.wgsl

const MISS: f32 = -1.0;
// The nearest a shadow ray's blocker may be to its start, m (`SHADOW_RAY_START_M`).
const SHADOW_RAY_START_M: f32 = 1e-7;
// The traversal stack (`bvh.rs`'s `STACK_DEPTH`).
const STACK_DEPTH: u32 = 64u;

fn within(t: f32, t_min: f32, t_max: f32) -> f32 {
    return select(MISS, t, t > t_min && t < t_max);
}

// The nearer of two candidate hits that lies within (t_min, t_max), as
// `within(a).or_else(|| within(b))`.
fn first_within(a: f32, b: f32, t_min: f32, t_max: f32) -> f32 {
    let first = within(a, t_min, t_max);
    return select(within(b, t_min, t_max), first, first != MISS);
}

fn sphere_hit(p: Primitive, o: vec3<f32>, d: vec3<f32>, t_min: f32, t_max: f32) -> f32 {
    let radius = p.a.w;
    let oc = o - p.a.xyz;
    let b = dot(oc, d);
    let distance = length(oc);
    let c = (distance - radius) * (distance + radius);
    let disc = b * b - c;
    if disc < 0.0 {
        return MISS;
    }
    let root = sqrt(disc);
    let far = -b + root;
    let near = select(-b - root, c / far, far != 0.0);
    return first_within(min(near, far), max(near, far), t_min, t_max);
}

fn box_hit(p: Primitive, o: vec3<f32>, d: vec3<f32>, t_min: f32, t_max: f32) -> f32 {
    let inv = 1.0 / d;
    let a = (p.a.xyz - o) * inv;
    let b = (p.b.xyz - o) * inv;
    let lo = min(a, b);
    let hi = max(a, b);
    let enter = max(max(lo.x, lo.y), lo.z);
    let exit = min(min(hi.x, hi.y), hi.z);
    if enter > exit {
        return MISS;
    }
    return first_within(enter, exit, t_min, t_max);
}

fn quad_hit(p: Primitive, o: vec3<f32>, d: vec3<f32>, t_min: f32, t_max: f32) -> f32 {
    let eu = p.b.xyz;
    let ev = p.c.xyz;
    let normal = cross(eu, ev);
    let denom = dot(normal, d);
    if denom == 0.0 {
        return MISS;
    }
    let t = dot(normal, p.a.xyz - o) / denom;
    let q = o + d * t - p.a.xyz;
    let uu = dot(eu, eu);
    let uv = dot(eu, ev);
    let vv = dot(ev, ev);
    let pu = dot(q, eu);
    let pv = dot(q, ev);
    let det = uu * vv - uv * uv;
    let s = (pu * vv - pv * uv) / det;
    let r = (pv * uu - pu * uv) / det;
    if s >= 0.0 && s <= 1.0 && r >= 0.0 && r <= 1.0 {
        return within(t, t_min, t_max);
    }
    return MISS;
}

fn plane_hit(p: Primitive, o: vec3<f32>, d: vec3<f32>, t_min: f32, t_max: f32) -> f32 {
    let denom = dot(p.b.xyz, d);
    if denom == 0.0 {
        return MISS;
    }
    return within(dot(p.b.xyz, p.a.xyz - o) / denom, t_min, t_max);
}

fn primitive_hit(p: Primitive, o: vec3<f32>, d: vec3<f32>, t_min: f32, t_max: f32) -> f32 {
    switch p.kind {
        case 0u: {
            return sphere_hit(p, o, d, t_min, t_max);
        }
        case 1u: {
            return box_hit(p, o, d, t_min, t_max);
        }
        case 2u: {
            return quad_hit(p, o, d, t_min, t_max);
        }
        default: {
            return plane_hit(p, o, d, t_min, t_max);
        }
    }
}

// Moller and Trumbore 1997 (`Triangle::hit`).
fn triangle_hit(index: u32, o: vec3<f32>, d: vec3<f32>, t_min: f32, t_max: f32) -> f32 {
    let a = triangles[3u * index].xyz;
    let e1 = triangles[3u * index + 1u].xyz - a;
    let e2 = triangles[3u * index + 2u].xyz - a;
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det == 0.0 {
        return MISS;
    }
    let inv = 1.0 / det;
    let s = o - a;
    let u = dot(s, p) * inv;
    if u < 0.0 || u > 1.0 {
        return MISS;
    }
    let q = cross(s, e1);
    let v = dot(d, q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return MISS;
    }
    return within(dot(e2, q) * inv, t_min, t_max);
}

fn box_overlaps(node: BvhNode, o: vec3<f32>, inv: vec3<f32>, t_min: f32, t_max: f32) -> bool {
    let a = (node.min - o) * inv;
    let b = (node.max - o) * inv;
    let lo = min(a, b);
    let hi = max(a, b);
    let enter = max(max(max(lo.x, lo.y), lo.z), t_min);
    let exit = min(min(min(hi.x, hi.y), hi.z), t_max);
    return enter <= exit;
}

// The nearest triangle hit (`Bvh::hit` without `any_hit`).
fn bvh_hit(o: vec3<f32>, d: vec3<f32>, t_min: f32, t_max: f32) -> f32 {
    if params.counts.y == 0u {
        return MISS;
    }
    let inv = 1.0 / d;
    var nearest = t_max;
    var found = MISS;
    var stack: array<u32, STACK_DEPTH>;
    stack[0] = 0u;
    var top = 1u;
    while top > 0u {
        top -= 1u;
        let node = bvh_nodes[stack[top]];
        if !box_overlaps(node, o, inv, t_min, nearest) {
            continue;
        }
        if node.count > 0u {
            for (var i = node.first; i < node.first + node.count; i++) {
                let t = triangle_hit(i, o, d, t_min, nearest);
                if t != MISS {
                    nearest = t;
                    found = t;
                }
            }
        } else if top + 2u <= STACK_DEPTH {
            stack[top] = node.first;
            stack[top + 1u] = node.first + 1u;
            top += 2u;
        }
    }
    return found;
}

// The distance to the first surface along the ray within t_max (`Occluders::nearest`).
fn nearest_occluder(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> f32 {
    var nearest = bvh_hit(o, d, 0.0, t_max);
    for (var i = 0u; i < params.counts.x; i++) {
        let limit = select(t_max, nearest, nearest != MISS);
        let t = primitive_hit(primitives[i], o, d, 0.0, limit);
        if t != MISS {
            nearest = t;
        }
    }
    return nearest;
}

// Whether an infinite plane lies between `point` and `distance` along `d`
// (`Occluders::planes_block`).
fn planes_block(point: vec3<f32>, d: vec3<f32>, distance: f32) -> bool {
    for (var i = 0u; i < params.counts.x; i++) {
        let p = primitives[i];
        if p.kind == 3u && plane_hit(p, point, d, SHADOW_RAY_START_M, distance) != MISS {
            return true;
        }
    }
    return false;
}
