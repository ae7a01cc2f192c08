// Library: where a line meets a sphere about the planet's centre, in the form that
// keeps its accuracy in f32 (the smaller root from the larger by their product; CPU
// twin: atmosphere-core's `clouds/spheres/shells.rs`, `roots`). Used by the cloud
// spheres (`clouds/spheres/shade.wgsl`) and the rays of the run in front of them
// (`clouds/front_rays.wgsl`).

// The two distances (near, far) where the line through a point at radius r with
// direction cosine mu meets the sphere of `radius`; x > y when it misses (`roots`).
fn sphere_roots(r: f32, mu: f32, radius: f32) -> vec2<f32> {
    let b = r * mu;
    let c = (r - radius) * (r + radius);
    let disc = b * b - c;
    if disc < 0.0 {
        return vec2<f32>(1.0, -1.0);
    }
    var s = 1.0;
    if b < 0.0 {
        s = -1.0;
    }
    let q = -(b + s * sqrt(disc));
    if q == 0.0 {
        return vec2<f32>(0.0);
    }
    let other = c / q;
    return vec2<f32>(min(q, other), max(q, other));
}
