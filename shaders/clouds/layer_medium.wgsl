// Library: the cloud layer's shell and density, twin of atmosphere-core's
// `clouds/layer/shell.rs`, `profile.rs` and `field.rs`: cover (bilinear on the grid) x
// vertical profile x detail erosion, in the shell between the base and top radii.

#import clouds/layer_params.wgsl
#import clouds/gradient_noise.wgsl

const DETAIL_SEED: u32 = 0x5eedc10du;

// Bilinear cover at a planet-fixed point (geo's `bilinear_taps`: wraps in longitude,
// clamps at the poles' rows).
fn cover_at(p: vec3<f32>) -> f32 {
    let w = layer.sizes.x;
    let h = layer.sizes.y;
    let lat = atan2(p.z, length(p.xy));
    let lon = atan2(p.y, p.x);
    let x = (lon + PI) / (2.0 * PI) * f32(w) - 0.5;
    let y = (0.5 * PI - lat) / PI * f32(h) - 0.5;
    let x0 = floor(x);
    let fx = x - x0;
    let i0 = u32((i32(x0) % i32(w) + i32(w)) % i32(w));
    let i1 = (i0 + 1u) % w;
    var j0 = 0u;
    var j1 = 0u;
    var fy = 0.0;
    if y >= f32(h) - 1.0 {
        j0 = h - 1u;
        j1 = h - 1u;
    } else if y > 0.0 {
        j0 = u32(floor(y));
        j1 = j0 + 1u;
        fy = y - floor(y);
    }
    let c00 = textureLoad(cover, vec2<u32>(i0, j0), 0).x;
    let c10 = textureLoad(cover, vec2<u32>(i1, j0), 0).x;
    let c01 = textureLoad(cover, vec2<u32>(i0, j1), 0).x;
    let c11 = textureLoad(cover, vec2<u32>(i1, j1), 0).x;
    return mix(mix(c00, c10, fx), mix(c01, c11, fx), fy);
}

fn smoothstep_01(edge0: f32, edge1: f32, x: f32) -> f32 {
    let t = clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// `profile.rs`'s vertical_profile: rise over the lowest tenth, fall over the upper two
// fifths of the cloud, whose top lies at 0.35 + 0.65 cover.
fn vertical_profile(x: f32, c: f32) -> f32 {
    if x < 0.0 || x > 1.0 {
        return 0.0;
    }
    let top = 0.35 + 0.65 * c;
    return smoothstep_01(0.0, 0.1, x) * (1.0 - smoothstep_01(0.6 * top, top, x));
}

// Extinction at `p`, m^-1, with `octaves` octaves of detail noise (`field.rs`'s
// density_with_octaves; 0 octaves: the noise's mean).
fn layer_extinction(p: vec3<f32>, octaves: u32) -> f32 {
    let x = (length(p) - layer.radii_m.y) / layer.radii_m.w;
    if x < 0.0 || x > 1.0 {
        return 0.0;
    }
    let c = min(cover_at(p) * layer.medium.z, 1.0);
    if c <= 0.0 {
        return 0.0;
    }
    // Above the cloud's top (or at its base) no noise can give it density.
    let profile = vertical_profile(x, c);
    if profile <= 0.0 {
        return 0.0;
    }
    var erosion = 1.0;
    if layer.detail.y > 0.0 {
        let n = fractal_noise(DETAIL_SEED, p / layer.detail.x, octaves, 0.5);
        erosion = 1.0 - layer.detail.y * (0.5 - 0.5 * clamp(n, -1.0, 1.0));
    }
    return layer.medium.x * clamp(c * profile * erosion, 0.0, 1.0);
}

// (r mu)^2 - (r - radius)(r + radius), without the cancellation of the naive form.
fn shell_discriminant(r: f32, mu: f32, radius: f32) -> f32 {
    return (r * mu) * (r * mu) - (r - radius) * (r + radius);
}

// Distance to the near crossing of the sphere `radius` from outside it, or -1.
fn shell_entry(r: f32, mu: f32, radius: f32) -> f32 {
    let d = shell_discriminant(r, mu, radius);
    if d < 0.0 || (mu >= 0.0 && r >= radius) {
        return -1.0;
    }
    let q = -r * mu + sqrt(d);
    if q <= 0.0 {
        return 0.0;
    }
    return max((r - radius) * (r + radius) / q, 0.0);
}

// Distance from inside the sphere `radius` to where the ray leaves it.
fn shell_exit(r: f32, mu: f32, radius: f32) -> f32 {
    let root = sqrt(max(shell_discriminant(r, mu, radius), 0.0));
    if mu > 0.0 {
        let q = r * mu + root;
        return select(0.0, max(-((r - radius) * (r + radius)) / q, 0.0), q > 0.0);
    }
    return max(-r * mu + root, 0.0);
}

// From `p` inside the shell along unit `d`: the distance to its boundary.
fn layer_boundary(p: vec3<f32>, d: vec3<f32>) -> f32 {
    let r = clamp(length(p), layer.radii_m.y, layer.radii_m.z);
    let mu = clamp(dot(p, d) / length(p), -1.0, 1.0);
    let base = shell_entry(r, mu, layer.radii_m.y);
    return select(shell_exit(r, mu, layer.radii_m.z), base, base >= 0.0);
}

// The first interval (t0, t1) of the ray inside the shell, ended on the ground;
// t0 >= t1 when there is none.
fn layer_segment(o: vec3<f32>, d: vec3<f32>) -> vec2<f32> {
    let r = length(o);
    let mu = clamp(dot(o, d) / r, -1.0, 1.0);
    var t = vec2<f32>(1.0, 0.0);
    if r > layer.radii_m.z {
        let t0 = shell_entry(r, mu, layer.radii_m.z);
        if t0 < 0.0 {
            return vec2<f32>(1.0, 0.0);
        }
        var t1 = shell_entry(r, mu, layer.radii_m.y);
        if t1 < 0.0 {
            t1 = -r * mu + sqrt(max(shell_discriminant(r, mu, layer.radii_m.z), 0.0));
        }
        t = vec2<f32>(t0, t1);
    } else if r >= layer.radii_m.y {
        t = vec2<f32>(0.0, layer_boundary(o, d));
    } else {
        t = vec2<f32>(shell_exit(r, mu, layer.radii_m.y), shell_exit(r, mu, layer.radii_m.z));
    }
    let rg = max(r, layer.radii_m.x);
    if mu < 0.0 && shell_discriminant(rg, mu, layer.radii_m.x) >= 0.0 {
        let ground = shell_entry(rg, mu, layer.radii_m.x);
        if ground >= 0.0 {
            t.y = min(t.y, ground);
        }
    }
    return t;
}
