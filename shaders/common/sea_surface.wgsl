// Library: the sea as a specular interface, for every model's pixel pass: a view ray
// ending on water adds
//     T [ (1 - F(v . n)) a / pi E(x, n) + F(v . n) L_sky(x, m) + E_sun T_sun(x) G ],
// the water body's Lambertian light through the surface, the model's own sky along the
// mirror direction m from the sea point x, and the sun's glint G of Cox and Munk 1954
// (the isotropic Gaussian of the slopes, mean square slope 0.003 + 5.12e-3 W for wind
// speed W, in `frame.sea.x`) with Smith's masking for it (Walter et al. 2007, Eq. 27). F is the exact Fresnel reflectance of unpolarised light
// into water (Born and Wolf 1999, section 1.5.2), of refractive index `frame.sea.y`.
// The pass finds the model's pieces (its irradiance E on the element, its radiance along
// `mirror_segment`, the sun from `across_normal`'s element) and `add_sea` sums them.
// CPU twin: atmosphere-core's `optics/sea_surface.rs`.

#import common/frame_params.wgsl
#import common/surface.wgsl

// Whether the pipeline draws the sea at all (`PixelPipeline`): its variant for a surface
// without sea has the sea's branch compiled out, as a software rasteriser runs both
// sides of every branch.
override SEA: bool = true;

// The reflectance of unpolarised light meeting water at incidence cosine `c` from air:
// the mean of r_s^2 and r_p^2 (`fresnel_reflectance`).
fn water_fresnel(c_in: f32) -> f32 {
    let n = frame.sea.y;
    let c = clamp(c_in, 0.0, 1.0);
    let cos_t = sqrt(max(1.0 - (1.0 - c * c) / (n * n), 0.0));
    let r_s = (c - n * cos_t) / (c + n * cos_t);
    let r_p = (n * c - cos_t) / (n * c + cos_t);
    return 0.5 * (r_s * r_s + r_p * r_p);
}

// Smith's masking at cosine `c` from the mean normal for mean square slope `sigma2`
// (`smith_masking`, Walter et al. 2007, Eq. 27).
fn smith_masking(c: f32, sigma2: f32) -> f32 {
    if c >= 1.0 {
        return 1.0;
    }
    let a = c / (sqrt(sigma2) * sqrt(1.0 - c * c));
    if a >= 1.6 {
        return 1.0;
    }
    return (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
}

// The glitter factor G towards unit `eye` for the sun along unit `sun` on a sea with unit
// `normal` (`glint_factor`): F(v . h) p(tan beta) G1(v) G1(s) / (4 (n . v) cos^4 beta).
fn glint_factor(eye: vec3<f32>, sun: vec3<f32>, normal: vec3<f32>) -> f32 {
    let cos_v = dot(eye, normal);
    let half_way = eye + sun;
    if cos_v <= 0.0 || dot(sun, normal) <= 0.0 || dot(half_way, half_way) <= 0.0 {
        return 0.0;
    }
    let h = normalize(half_way);
    let cos_beta = dot(h, normal);
    let c2 = max(cos_beta * cos_beta, 1e-12);
    let sigma2 = frame.sea.x;
    let density = exp(-((1.0 - c2) / c2) / sigma2) / (PI * sigma2);
    let masking = smith_masking(cos_v, sigma2) * smith_masking(dot(sun, normal), sigma2);
    return water_fresnel(dot(eye, h)) * density * masking / (4.0 * cos_v * c2 * c2);
}

// The mirror of unit `direction` in the surface with unit `normal` at `point`, laid on
// the local horizon where it would turn below (`mirror_direction`).
fn sea_mirror(point: vec3<f32>, direction: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let m = direction - 2.0 * dot(direction, normal) * normal;
    let up = normalize(point);
    return normalize(m - min(dot(m, up), 0.0) * up);
}

// The segment of the ray from the sea point `point` along unit `direction`, to the top
// or the ground (`ViewSegment::new` for a ray starting inside the atmosphere; a point a
// rounding below the ground starts on it).
fn mirror_segment(point: vec3<f32>, direction: vec3<f32>) -> Segment {
    let bottom = atmosphere.bottom_radius_m;
    let r = clamp(length(point), bottom, atmosphere.top_radius_m);
    var s: Segment;
    s.hit = true;
    s.cut = false;
    s.t_enter = 0.0;
    s.start = normalize(point) * r;
    s.q = (r - bottom) * (r + bottom);
    s.r_mu = dot(s.start, direction);
    s.start_dot_sun = dot(s.start, frame.sun_direction.xyz);
    return to_boundary(s);
}

// The normal of an element at `point` standing on the horizon across the sun
// (`transmitted_sun`): it sees half the sky and none of the sun.
fn across_normal(point: vec3<f32>) -> vec3<f32> {
    let up = normalize(point);
    let c = cross(up, frame.sun_direction.xyz);
    if dot(c, c) > 1e-12 {
        return normalize(c);
    }
    let other = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), abs(up.x) > 0.9);
    return normalize(cross(up, other));
}

// E_sun T_sun at `point` from the model's irradiance on the element facing the sun,
// `facing`, and on the element of `across_normal`, `across` (`transmitted_sun`).
fn sea_sun(point: vec3<f32>, facing: vec3<f32>, across: vec3<f32>) -> vec3<f32> {
    let mu_s = clamp(dot(normalize(point), frame.sun_direction.xyz), -1.0, 1.0);
    return max(facing - (1.0 + mu_s) * across, vec3<f32>(0.0));
}

// `r` (a ray along unit `direction` ending on the sea `surface` at `r.end`) with the
// water's light added (`radiance_with_sea`): the body lit by the model's `irradiance`,
// the model's `sky` radiance along the mirror direction, and the glint of the
// transmitted `sun`; the sea hides the sun disk.
fn add_sea(r: Radiance, surface: Surface, direction: vec3<f32>, irradiance: vec3<f32>,
    sky: vec3<f32>, sun: vec3<f32>) -> Radiance {
    var out = r;
    let eye = -direction;
    let f_view = water_fresnel(dot(eye, surface.normal));
    let glint = glint_factor(eye, frame.sun_direction.xyz, surface.normal);
    let water = (1.0 - f_view) * surface.albedo / PI * irradiance + f_view * sky + glint * sun;
    out.radiance += r.transmittance * water;
    out.reaches_space = false;
    return out;
}
