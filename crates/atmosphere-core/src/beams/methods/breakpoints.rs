//! Where along a view ray the in-scattered light jumps or peaks, found analytically so
//! that the reference's quadrature places panel edges there instead of hunting for
//! them: the edges of each spot's cone and each parallel beam's rectangle, the shadow
//! boundaries of spheres (a cone from a point light, a cylinder along a parallel one)
//! and of the edges of boxes and quads (the plane through an edge and the light),
//! the closest approach to each point light, where 1 / s^2 peaks, and the lines through
//! the texel centres of each light map, where its bilinear filtering has kinks (planes
//! through a spot's apex, planes across a parallel beam, a point light's cones of
//! constant theta and half-planes of constant phi).

use glam::DVec3;

use crate::beams::light::LightShape;
use crate::beams::occluder::Primitive;
use crate::beams::ray::SceneRay;
use crate::beams::scene::BeamScene;

/// The distances in (0, t_end) along `ray` where the integrand changes abruptly, sorted,
/// with 0 and `t_end`.
pub fn breakpoints(scene: &BeamScene, ray: &SceneRay, t_end: f64) -> Vec<f64> {
    let (o, d) = (ray.origin_m, ray.direction);
    let mut t = vec![0.0, t_end];
    let edges = primitive_edges(scene);
    let spheres: Vec<(DVec3, f64)> = scene
        .occluders
        .primitives
        .iter()
        .filter_map(|p| match *p {
            Primitive::Sphere { center, radius } => Some((center, radius)),
            _ => None,
        })
        .collect();
    for light in &scene.lights {
        if let Some(map) = &light.light_map {
            texel_centre_lines(&light.shape, map.width, map.height, o, d, &mut t);
        }
        for &(a, b) in &edges {
            let toward_light = match &light.shape {
                LightShape::Parallel { frame, .. } => frame.z,
                LightShape::Point { position_m, .. } | LightShape::Spot { position_m, .. } => {
                    a - *position_m
                }
            };
            let n = (b - a).cross(toward_light);
            let rate = n.dot(d);
            if rate != 0.0 {
                t.push(n.dot(a - o) / rate);
            }
        }
        match &light.shape {
            LightShape::Point {
                position_m,
                radius_m,
                ..
            }
            | LightShape::Spot {
                position_m,
                radius_m,
                ..
            } => {
                let w = o - *position_m;
                let closest = -w.dot(d);
                let miss = (w + d * closest).length().max(*radius_m);
                for k in [-8.0, -1.0, 0.0, 1.0, 8.0] {
                    t.push(closest + k * miss);
                }
                if let LightShape::Spot {
                    frame, cos_cone, ..
                } = &light.shape
                {
                    t.extend(cone(o, d, *position_m, frame.z, *cos_cone));
                }
                for &(center, radius) in &spheres {
                    let to_center = center - *position_m;
                    let distance = to_center.length();
                    if distance > radius {
                        let cos = (1.0 - (radius / distance).powi(2)).sqrt();
                        t.extend(cone(o, d, *position_m, to_center / distance, cos));
                    }
                }
            }
            LightShape::Parallel {
                position_m,
                frame,
                half_size_m,
            } => {
                let (start, step) = (frame.local(o - *position_m), frame.local(d));
                let mut crossing = |from: f64, rate: f64, at: f64| {
                    if rate != 0.0 {
                        t.push((at - from) / rate);
                    }
                };
                crossing(start.z, step.z, 0.0);
                if let Some([hx, hy]) = half_size_m {
                    for s in [-1.0, 1.0] {
                        crossing(start.x, step.x, s * hx);
                        crossing(start.y, step.y, s * hy);
                    }
                }
                for &(center, radius) in &spheres {
                    let (w, z) = (o - center, frame.z);
                    let (dp, wp) = (d - z * d.dot(z), w - z * w.dot(z));
                    t.extend(quadratic(
                        dp.dot(dp),
                        2.0 * dp.dot(wp),
                        wp.dot(wp) - radius * radius,
                    ));
                }
            }
        }
    }
    t.retain(|x| x.is_finite() && (0.0..=t_end).contains(x));
    t.sort_by(f64::total_cmp);
    t.dedup();
    t
}

/// The edges of the scene's boxes and quads, whose shadows are bounded by the planes
/// through them and the light.
fn primitive_edges(scene: &BeamScene) -> Vec<(DVec3, DVec3)> {
    let mut edges = Vec::new();
    for p in &scene.occluders.primitives {
        match *p {
            Primitive::Box { min, max } => {
                let corner = |i: usize| {
                    DVec3::new(
                        if i & 1 == 0 { min.x } else { max.x },
                        if i & 2 == 0 { min.y } else { max.y },
                        if i & 4 == 0 { min.z } else { max.z },
                    )
                };
                for i in 0..8 {
                    for bit in [1, 2, 4] {
                        if i & bit == 0 {
                            edges.push((corner(i), corner(i | bit)));
                        }
                    }
                }
            }
            Primitive::Quad {
                corner,
                edge_u,
                edge_v,
            } => {
                let far = corner + edge_u + edge_v;
                edges.extend([
                    (corner, corner + edge_u),
                    (corner, corner + edge_v),
                    (corner + edge_u, far),
                    (corner + edge_v, far),
                ]);
            }
            Primitive::Sphere { .. } | Primitive::Plane { .. } => {}
        }
    }
    edges
}

/// Where the ray crosses the lines of a `width` x `height` light map's texel centres,
/// as the light's shape lays the map out (`light.rs`).
fn texel_centre_lines(
    shape: &LightShape,
    width: usize,
    height: usize,
    o: DVec3,
    d: DVec3,
    t: &mut Vec<f64>,
) {
    let centre = |i: usize, n: usize| 2.0 * (i as f64 + 0.5) / n as f64 - 1.0;
    // The plane through `point` with normal `n`.
    let plane = |n: DVec3, point: DVec3| -> Option<f64> {
        let rate = n.dot(d);
        (rate != 0.0).then(|| n.dot(point - o) / rate)
    };
    match shape {
        LightShape::Spot {
            position_m,
            frame,
            tan_cone,
            ..
        } => {
            for i in 0..width {
                let a = centre(i, width) * tan_cone;
                t.extend(plane(frame.x - frame.z * a, *position_m));
            }
            for j in 0..height {
                let b = -centre(j, height) * tan_cone;
                t.extend(plane(frame.y - frame.z * b, *position_m));
            }
        }
        LightShape::Parallel {
            position_m,
            frame,
            half_size_m: Some([hx, hy]),
        } => {
            for i in 0..width {
                t.extend(plane(
                    frame.x,
                    *position_m + frame.x * (centre(i, width) * hx),
                ));
            }
            for j in 0..height {
                t.extend(plane(
                    frame.y,
                    *position_m - frame.y * (centre(j, height) * hy),
                ));
            }
        }
        LightShape::Parallel { .. } => {}
        LightShape::Point {
            position_m, frame, ..
        } => {
            for i in 0..width {
                let phi = std::f64::consts::PI * (centre(i, width) + 1.0);
                t.extend(plane(
                    frame.y * phi.cos() - frame.x * phi.sin(),
                    *position_m,
                ));
            }
            for j in 0..height {
                let theta = 0.5 * std::f64::consts::PI * (centre(j, height) + 1.0);
                t.extend(cone(o, d, *position_m, frame.z, theta.cos()));
            }
        }
    }
}

/// Where the ray crosses the double cone with apex `apex`, unit axis `axis` and
/// half-angle acos(cos): ((p - apex).axis)^2 = cos^2 |p - apex|^2.
fn cone(o: DVec3, d: DVec3, apex: DVec3, axis: DVec3, cos: f64) -> Vec<f64> {
    let w = o - apex;
    let (da, wa, c2) = (d.dot(axis), w.dot(axis), cos * cos);
    quadratic(
        da * da - c2,
        2.0 * (da * wa - c2 * d.dot(w)),
        wa * wa - c2 * w.dot(w),
    )
}

/// The real roots of a t^2 + b t + c = 0 (one root where a is 0).
fn quadratic(a: f64, b: f64, c: f64) -> Vec<f64> {
    if a == 0.0 {
        return if b != 0.0 { vec![-c / b] } else { vec![] };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return vec![];
    }
    // The root without cancellation first, the other from the product c / a.
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q == 0.0 {
        return vec![0.0];
    }
    vec![q / a, c / q]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadratic_roots_are_exact_for_well_separated_roots() {
        let mut r = quadratic(1.0, -1e8, 1.0);
        r.sort_by(f64::total_cmp);
        assert!((r[0] - 1e-8).abs() < 1e-22 && (r[1] - 1e8).abs() < 1e-6);
        assert!(quadratic(1.0, 0.0, 1.0).is_empty());
        assert_eq!(quadratic(0.0, 2.0, -4.0), vec![2.0]);
    }

    #[test]
    fn ray_crosses_a_cone_at_its_edges() {
        // A 45-degree cone down from (0, 10, 0); a horizontal ray at y = 5 crosses it
        // at x = -5 and x = 5.
        let o = DVec3::new(-20.0, 5.0, 0.0);
        let mut t = cone(
            o,
            DVec3::X,
            DVec3::new(0.0, 10.0, 0.0),
            DVec3::NEG_Y,
            0.5f64.sqrt(),
        );
        t.sort_by(f64::total_cmp);
        assert!(
            (t[0] - 15.0).abs() < 1e-12 && (t[1] - 25.0).abs() < 1e-12,
            "{t:?}"
        );
    }
}
