// Library: the atmosphere's transmittance from a frame's camera to where a ray enters the
// cloud, exp(-tau) of the columns integrated by the midpoint rule over FRONT_STEPS steps
// (the composite's T_front, `clouds/frame_composite.wgsl`, and its reduced rays',
// `clouds/front_rays.wgsl`; CPU: the model's own transmittance).

#import common/frame_params.wgsl

const FRONT_STEPS: u32 = 32u;

// Transmittance of the atmosphere from the camera to `distance_m` along `direction`.
fn front_transmittance(direction: vec3<f32>, distance_m: f32) -> vec3<f32> {
    let s = view_segment(direction, distance_m);
    if !s.hit {
        return vec3<f32>(1.0);
    }
    let dt = s.length / f32(FRONT_STEPS);
    var column = vec3<f32>(0.0);
    for (var k = 0u; k < FRONT_STEPS; k++) {
        column += dt * densities(altitude_from_q(q_along(s, (f32(k) + 0.5) * dt)));
    }
    return exp(-optical_depth(column));
}
