// Library: the solar disk with limb darkening. CPU twin: atmosphere-core's
// `optics/sun_disk.rs`. Paper: Hestroffer and Magnan 1998, I(mu) / I(1) = mu^alpha(lambda).

// Radiance of the disk seen along `direction`, per channel, before the atmosphere:
// `centre` is the radiance at the disk's centre and `exponent` alpha, per channel;
// zero outside the disk. The angle from the centre is taken from the cross product,
// which keeps its accuracy where the cosine is within rounding of 1.
fn sun_disk_radiance(direction: vec3<f32>, sun: vec3<f32>, angular_radius: f32,
                     centre: vec3<f32>, exponent: vec3<f32>) -> vec3<f32> {
    let angle = atan2(length(cross(direction, sun)), dot(direction, sun));
    let x = angle / angular_radius;
    if x >= 1.0 {
        return vec3<f32>(0.0);
    }
    return centre * pow(vec3<f32>(sqrt(max(1.0 - x * x, 1e-20))), exponent);
}
