// Library: rays from a point given in the accurate variables of `common/frame_params.wgsl`,
// q = r^2 - bottom^2 and r mu: whether a ray meets the ground, and how far it is. CPU
// twin: atmosphere-core's `optics/geometry.rs` (`ray_hits_ground`, `distance_to_bottom`).
// Paper: the ray-sphere geometry of Bruneton 2017 (`RayIntersectsGround`,
// `DistanceToBottomAtmosphereBoundary`), rewritten in q so that no planet-sized f32
// numbers are subtracted.

#import common/atmosphere_params.wgsl

// Whether the ray from (q, r mu) meets the ground (`ray_hits_ground`).
fn hits_ground(q: f32, r_mu: f32) -> bool {
    return r_mu < 0.0 && r_mu * r_mu - q >= 0.0;
}

// Distance from (q, r mu) to the ground along a ray at or below the horizon, as the near
// root q / (-r mu + root); the discriminant is clamped at 0 so that a tangent ray reaches
// its tangent point.
fn ground_distance(q: f32, r_mu: f32) -> f32 {
    let denom = -r_mu + safe_sqrt(r_mu * r_mu - q);
    return select(0.0, max(q / denom, 0.0), denom > 0.0);
}
