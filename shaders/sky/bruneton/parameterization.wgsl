// The mappings of Bruneton and Neyret 2008, section 4, between the parameters of the
// model's tables and their texels: the GPU twin of atmosphere-core's
// `bruneton/parameterization.rs` (u_r = rho / H; u_mu from the distance to the ray's end
// mapped over its range at r, one half of the mu axis per side of the horizon; u_mu_s =
// (1 - exp(-3 (mu_s - min_mu_s))) / (1 - exp(-3 (1 - min_mu_s))), or with `mu_s_knee`
// the paper's curve from -0.2 continued linearly below it; u_nu = (1 + nu) / 2 or,
// with `nu_by_angle`, 1 - acos(nu) / pi, and with `nu_edge` the nu weight taken between
// the texels' positions clamped to the ray's range of nu; E linear in r and mu_s).
//
// Radii enter as q = r^2 - bottom^2 (and r mu) rather than r alone: in f32 a radius near
// 6.4e6 m carries half a metre of rounding, and r - bottom is formed as q / (r + bottom)
// (docs/rendering.md, "Camera-relative rendering").

#import common/ground_ray.wgsl
#import sky/bruneton/bindings.wgsl
#import common/phase.wgsl

// A texel position along one axis: the lower texel and the weight of the next.
struct Axis {
    i: u32,
    w: f32,
}

// Where a point falls in S: one axis each for r, mu, mu_s, nu.
struct Position {
    r: Axis,
    mu: Axis,
    mu_s: Axis,
    nu: Axis,
}

// The physical parameters of a texel of S (`texel_parameters`).
struct Texel {
    q: f32,
    r: f32,
    mu: f32,
    mu_s: f32,
    nu: f32,
    ground: bool,
}

// H^2 = top^2 - bottom^2.
fn horizon_sq() -> f32 {
    let bottom = atmosphere.bottom_radius_m;
    let top = atmosphere.top_radius_m;
    return (top - bottom) * (top + bottom);
}

// The radius of q = r^2 - bottom^2.
fn radius_of_q(q: f32) -> f32 {
    let bottom = atmosphere.bottom_radius_m;
    return sqrt(bottom * bottom + q);
}

// Distance to the top boundary (`distance_to_exit`), with r^2 - top^2 = q - H^2.
fn top_distance(q: f32, r_mu: f32) -> f32 {
    let h2 = horizon_sq();
    let root = safe_sqrt(r_mu * r_mu - q + h2);
    if r_mu > 0.0 {
        let s = r_mu + root;
        return select(0.0, max((h2 - q) / s, 0.0), s > 0.0);
    }
    return max(-r_mu + root, 0.0);
}

// Length of the ray of a texel row: to the ground on the ground's half, else to the top.
fn ray_length(q: f32, r_mu: f32, ground: bool) -> f32 {
    return select(top_distance(q, r_mu), ground_distance(q, r_mu), ground);
}

// The cosine of the horizon seen from q (`horizon_mu`; 0 on the ground).
fn horizon_mu_of(q: f32, r: f32) -> f32 {
    return select(-sqrt(q) / r, 0.0, q <= 0.0);
}

// `Radii::distance_range`: the range (d_min, d_max) of the distance to the ray's end over
// the half of the mu axis chosen by `ground`: on the ground's half from straight down
// (q / (r + bottom)) to the horizon (rho); on the sky's half from straight up to the
// horizon, to the top boundary.
fn distance_range(q: f32, r: f32, ground: bool) -> vec2<f32> {
    let rho = safe_sqrt(q);
    if ground {
        return vec2<f32>(q / (r + atmosphere.bottom_radius_m), rho);
    }
    let h2 = horizon_sq();
    return vec2<f32>((h2 - q) / (atmosphere.top_radius_m + r), rho + sqrt(h2));
}

// `Radii::x_mu`, then on the sky's half `AngleMapping::sky_x_mu` (as `table_position`
// does): the unit coordinate within the half of the mu axis chosen by `ground`.
fn x_mu(q: f32, r: f32, r_mu: f32, ground: bool) -> f32 {
    let d = distance_range(q, r, ground);
    if ground {
        if d.y <= d.x {
            return 1.0;
        }
        let end = select(d.y, ground_distance(q, r_mu), hits_ground(q, r_mu));
        return clamp((d.y - end) / (d.y - d.x), 0.0, 1.0);
    }
    if d.y <= d.x {
        return 0.0;
    }
    return sky_x_mu(clamp((top_distance(q, r_mu) - d.x) / (d.y - d.x), 0.0, 1.0));
}

// `AngleMapping::sky_x_mu`: the sky half's unit coordinate from the paper's t, with
// `mu_zenith` (t + sqrt(t)) / 2.
fn sky_x_mu(t: f32) -> f32 {
    if bruneton.mu_zenith == 1u {
        return 0.5 * (t + sqrt(max(t, 0.0)));
    }
    return t;
}

// `AngleMapping::sky_t`: the inverse, t = s^2 with s = (sqrt(1 + 8 x) - 1) / 2.
fn sky_t(x: f32) -> f32 {
    if bruneton.mu_zenith == 1u {
        let s = 0.5 * (sqrt(1.0 + 8.0 * max(x, 0.0)) - 1.0);
        return s * s;
    }
    return x;
}

// `Radii::mu_from_x` of the sky half's t = `sky_t(x)` (as `texel_parameters` does).
fn mu_from_x(q: f32, r: f32, x: f32, ground: bool) -> f32 {
    let d = distance_range(q, r, ground);
    if ground {
        let end = d.y - x * (d.y - d.x);
        if end <= 0.0 {
            return -1.0;
        }
        return clamp(-(q + end * end) / (2.0 * r * end), -1.0, 1.0);
    }
    let end = d.x + sky_t(x) * (d.y - d.x);
    if end <= 0.0 {
        return 1.0;
    }
    return clamp((horizon_sq() - q - end * end) / (2.0 * r * end), -1.0, 1.0);
}

// u_mu_s (`AngleMapping::u_mu_s`): the paper's curve g = (1 - exp(-3 (mu_s - c))) /
// (1 - exp(-3 (1 - c))), c = min_mu_s (the paper's at -0.2); with `mu_s_knee` and
// min_mu_s below -0.2, c = -0.2 and below it g continues linearly with its slope there,
// u_mu_s = (g - g(min_mu_s)) / (1 - g(min_mu_s)).
fn mu_s_curve_start() -> f32 {
    if bruneton.mu_s_knee == 1u {
        return max(bruneton.min_mu_s, -0.2);
    }
    return bruneton.min_mu_s;
}

fn mu_s_norm() -> f32 {
    return 1.0 - exp(-3.0 * (1.0 - mu_s_curve_start()));
}

// The linear part's slope and its value at min_mu_s (0 when it is empty).
fn mu_s_linear_part() -> vec2<f32> {
    let slope = 3.0 / mu_s_norm();
    return vec2<f32>(slope, slope * (bruneton.min_mu_s - mu_s_curve_start()));
}

fn u_mu_s(mu_s: f32) -> f32 {
    let c = mu_s_curve_start();
    let linear = mu_s_linear_part();
    var g = linear.x * (mu_s - c);
    if mu_s >= c {
        g = (1.0 - exp(-3.0 * (mu_s - c))) / mu_s_norm();
    }
    return clamp((g - linear.y) / (1.0 - linear.y), 0.0, 1.0);
}

fn mu_s_from_u(u: f32) -> f32 {
    let c = mu_s_curve_start();
    let linear = mu_s_linear_part();
    let g = linear.y + u * (1.0 - linear.y);
    if g >= 0.0 {
        return -log(1.0 - g * mu_s_norm()) / 3.0 + c;
    }
    return c + g / linear.x;
}

// Whether S is read geometrically between mu_s texels i and i + 1
// (`AngleMapping::geometric_pair`): `geometric_mu_s` and both suns below the horizontal.
fn geometric_pair(i: u32) -> bool {
    return bruneton.geometric_mu_s == 1u && i + 1u < bruneton.mu_s_size
        && mu_s_from_u(texel_unit(i + 1u, bruneton.mu_s_size)) <= 0.0;
}

// The same for E's mu_s texels (`AngleMapping::irradiance_geometric_pair`).
fn irradiance_geometric_pair(i: u32) -> bool {
    let n = bruneton.irradiance_mu_s_size;
    let upper = bruneton.min_mu_s + texel_unit(i + 1u, n) * (1.0 - bruneton.min_mu_s);
    return bruneton.geometric_mu_s == 1u && i + 1u < n && upper <= 0.0;
}

// Between texels a and b along mu_s at weight w of b (`tables::along_mu_s`): linear, or
// with `geometric` a (b / a)^w per channel where both are positive.
fn along_mu_s(a: vec3<f32>, b: vec3<f32>, w: f32, geometric: bool) -> vec3<f32> {
    let linear = mix(a, b, w);
    if !geometric {
        return linear;
    }
    let positive = a > vec3<f32>(0.0) & b > vec3<f32>(0.0);
    let ratio = select(vec3<f32>(1.0), b / a, positive);
    return select(linear, a * exp2(w * log2(ratio)), positive);
}

// u_nu: (1 + nu) / 2 (the paper), or 1 - acos(nu) / pi with `nu_by_angle`
// (`AngleMapping::u_nu`). acos as atan2(sqrt((1 - nu)(1 + nu)), nu), accurate near
// nu = -/+1, where `nu_edge`'s weights divide differences of such angles.
fn u_nu(nu: f32) -> f32 {
    let c = clamp(nu, -1.0, 1.0);
    if bruneton.nu_by_angle == 1u {
        return clamp(1.0 - atan2(sqrt(max((1.0 - c) * (1.0 + c), 0.0)), c) / PI, 0.0, 1.0);
    }
    return 0.5 * (1.0 + c);
}

fn nu_from_u(u: f32) -> f32 {
    if bruneton.nu_by_angle == 1u {
        return -cos(PI * u);
    }
    return 2.0 * u - 1.0;
}

// E's unit coordinate along mu_s, linear over [min_mu_s, 1]
// (`AngleMapping::irradiance_x_mu_s`).
fn irradiance_x_mu_s(mu_s: f32) -> f32 {
    return clamp((mu_s - bruneton.min_mu_s) / (1.0 - bruneton.min_mu_s), 0.0, 1.0);
}

// The range of the view-sun cosine that view and sun zenith cosines allow (`nu_range`).
fn nu_range(mu: f32, mu_s: f32) -> vec2<f32> {
    let s = safe_sqrt((1.0 - mu * mu) * (1.0 - mu_s * mu_s));
    return vec2<f32>(mu * mu_s - s, mu * mu_s + s);
}

// The view-sun cosine clamped to what the view and sun zenith cosines allow.
fn clamp_nu(mu: f32, mu_s: f32, nu: f32) -> f32 {
    let range = nu_range(mu, mu_s);
    return clamp(nu, range.x, range.y);
}

// `NuAxis::weight`: the weight of the upper nu texel of `a` (placed at u = u_nu(nu)) for
// a ray of view and sun zenith cosines mu and mu_s. With `nu_edge`, between the two
// texels' positions clamped to the ray's range [u_nu(nu_min), u_nu(nu_max)]; the nominal
// weight otherwise, where neither texel is clamped, and where the clamped interval is
// under a thousandth of the texels' spacing.
fn nu_edge_weight(a: Axis, u: f32, mu: f32, mu_s: f32) -> f32 {
    if bruneton.nu_edge == 0u || a.w == 0.0 {
        return a.w;
    }
    let range = nu_range(mu, mu_s);
    let units = vec2<f32>(texel_unit(a.i, bruneton.nu_size), texel_unit(a.i + 1u, bruneton.nu_size));
    let cosines = vec2<f32>(nu_from_u(units.x), nu_from_u(units.y));
    if range.x <= cosines.x && range.y >= cosines.y {
        return a.w;
    }
    let lower = select(units.x, u_nu(range.x), range.x > cosines.x);
    let upper = select(units.y, u_nu(range.y), range.y < cosines.y);
    if upper - lower < 1e-3 * (units.y - units.x) {
        return a.w;
    }
    return clamp((u - lower) / (upper - lower), 0.0, 1.0);
}

// `azimuth_unit`: u = 1 - phi / pi of the azimuth phi between the view's and the sun's
// vertical planes, phi = atan2(sqrt(s^2 - c^2), c) with c = nu - mu mu_s and
// s^2 = (1 - mu^2)(1 - mu_s^2) (1 at the zenith, where every phi is one direction).
fn azimuth_unit(mu: f32, mu_s: f32, nu: f32) -> f32 {
    let c = nu - mu * mu_s;
    let s2 = max((1.0 - mu * mu) * (1.0 - mu_s * mu_s), 0.0);
    return clamp(1.0 - atan2(safe_sqrt(s2 - c * c), c) / PI, 0.0, 1.0);
}

// `nu_at_azimuth_unit`: the view-sun cosine at azimuth coordinate u.
fn nu_at_azimuth_unit(mu: f32, mu_s: f32, u: f32) -> f32 {
    let s = safe_sqrt((1.0 - mu * mu) * (1.0 - mu_s * mu_s));
    return clamp(mu * mu_s + s * cos(PI * (1.0 - u)), -1.0, 1.0);
}

// The nu axis of a look-up at (mu, mu_s, nu) (`NuAxis`): by azimuth with
// `nu_by_azimuth`, else by u_nu with `nu_edge`'s weight.
fn nu_axis(mu: f32, mu_s: f32, nu: f32) -> Axis {
    if bruneton.nu_by_azimuth == 1u {
        return axis(azimuth_unit(mu, mu_s, nu), bruneton.nu_size);
    }
    let u = u_nu(nu);
    let a = axis(u, bruneton.nu_size);
    return Axis(a.i, nu_edge_weight(a, u, mu, mu_s));
}

// `axis`: the lower texel (at most n - 2) and the weight of the next.
fn axis(x: f32, n: u32) -> Axis {
    let f = clamp(x, 0.0, 1.0) * f32(n - 1u);
    let i = min(u32(f), n - 2u);
    return Axis(i, clamp(f - f32(i), 0.0, 1.0));
}

// Unit coordinate of texel k of n.
fn texel_unit(k: u32, n: u32) -> f32 {
    return f32(k) / f32(n - 1u);
}

// `texel_parameters`: the parameters of texel (ir, imu, imus, inu) of S. A texel whose
// mu falls on the wrong side of the horizon by rounding is put on the horizon; its
// `ground` flag, not its mu, decides its half from then on.
fn texel(ir: u32, imu: u32, imus: u32, inu: u32) -> Texel {
    var t: Texel;
    let rho = sqrt(horizon_sq()) * texel_unit(ir, bruneton.r_size);
    t.q = rho * rho;
    t.r = radius_of_q(t.q);
    let half = bruneton.mu_size / 2u;
    t.ground = imu < half;
    let x = texel_unit(select(imu - half, imu, t.ground), half);
    t.mu = mu_from_x(t.q, t.r, x, t.ground);
    if t.ground != hits_ground(t.q, t.r * t.mu) {
        t.mu = horizon_mu_of(t.q, t.r);
    }
    t.mu_s = mu_s_from_u(texel_unit(imus, bruneton.mu_s_size));
    let u = texel_unit(inu, bruneton.nu_size);
    if bruneton.nu_by_azimuth == 1u {
        t.nu = nu_at_azimuth_unit(t.mu, t.mu_s, u);
    } else {
        t.nu = clamp_nu(t.mu, t.mu_s, nu_from_u(u));
    }
    return t;
}

// The coordinates of a texel of S: its texel along r, mu, mu_s and nu.
struct TexelCoords {
    r: u32,
    mu: u32,
    mu_s: u32,
    nu: u32,
}

// The texel of linear index `index` (`ScatteringSize::coords`): mu_s fastest, then r,
// mu, nu.
// Invocations along x of a flat dispatch over the texels of S (`FLAT_ROW_GROUPS` x `FLAT`
// of render-wgpu's `sky/bruneton/workgroups.rs`); further texels go along y.
const FLAT_ROW_INVOCATIONS: u32 = 65536u;

// The texel of a flat dispatch's invocation `id`.
fn flat_index(id: vec3<u32>) -> u32 {
    return id.x + id.y * FLAT_ROW_INVOCATIONS;
}

fn texel_coords(index: u32) -> TexelCoords {
    let rest = index / bruneton.mu_s_size;
    let rest2 = rest / bruneton.r_size;
    return TexelCoords(rest % bruneton.r_size, rest2 % bruneton.mu_size, index % bruneton.mu_s_size,
        rest2 / bruneton.mu_size);
}

// Where texel (ir, imu, imus, inu) of S lies in a 3D texture of S: (x = nu * mu_s_size +
// mu_s, y = mu, z = r).
fn texture_texel(ir: u32, imu: u32, imus: u32, inu: u32) -> vec3<u32> {
    return vec3<u32>(inu * bruneton.mu_s_size + imus, imu, ir);
}

// The parameters of the texel of linear index `index`.
fn texel_of_index(index: u32) -> Texel {
    let c = texel_coords(index);
    return texel(c.r, c.mu, c.mu_s, c.nu);
}

// `ScatteringSize::index`.
fn table_index(ir: u32, imu: u32, imus: u32, inu: u32) -> u32 {
    return ((inu * bruneton.mu_size + imu) * bruneton.r_size + ir) * bruneton.mu_s_size + imus;
}

// `table_position`: where (q, r mu, mu_s, nu) falls in S, on the half of the mu axis
// chosen by `ground`.
fn table_position(q: f32, r: f32, r_mu: f32, mu_s: f32, nu: f32, ground: bool) -> Position {
    let half = bruneton.mu_size / 2u;
    var mu = axis(x_mu(q, r, r_mu, ground), half);
    if !ground {
        mu.i += half;
    }
    return Position(
        axis(sqrt(max(q, 0.0) / horizon_sq()), bruneton.r_size),
        mu,
        axis(u_mu_s(mu_s), bruneton.mu_s_size),
        nu_axis(clamp(r_mu / r, -1.0, 1.0), mu_s, nu),
    );
}

// E's texel (ir, imus): (q, r, mu_s) (`IrradianceTable::texel_r_mu_s`).
fn irradiance_texel(index: u32) -> vec3<f32> {
    let altitude = texel_unit(index / bruneton.irradiance_mu_s_size, bruneton.irradiance_r_size) * (atmosphere.top_radius_m - atmosphere.bottom_radius_m);
    let q = altitude * (2.0 * atmosphere.bottom_radius_m + altitude);
    return vec3<f32>(q, atmosphere.bottom_radius_m + altitude, bruneton.min_mu_s + texel_unit(index % bruneton.irradiance_mu_s_size, bruneton.irradiance_mu_s_size) * (1.0 - bruneton.min_mu_s));
}
