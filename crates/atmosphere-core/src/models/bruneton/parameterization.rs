//! The mappings of Bruneton and Neyret 2008, section 4, between the physical parameters
//! of the tables and unit coordinates:
//!
//! - scattering S(r, mu, mu_s, nu): u_r = rho / H; u_mu = 1/2 + (r mu + sqrt(Delta)) /
//!   (2 rho) for rays that meet the ground (r mu < 0, Delta > 0), else
//!   1/2 - (r mu - sqrt(Delta + H^2)) / (2 rho + 2 H); u_mu_s = (1 - exp(-3 mu_s - 0.6)) /
//!   (1 - exp(-3.6)); u_nu = (1 + nu) / 2, with H = sqrt(Rt^2 - Rg^2),
//!   rho = sqrt(r^2 - Rg^2) and Delta = r^2 mu^2 - rho^2. u_mu is refined as in
//!   Bruneton 2017: the distance d to the ray's end is mapped from its range at r
//!   ([r - Rg, rho] to the ground, [Rt - r, rho + H] to the top) rather than from
//!   [0, rho] and [0, rho + H] ([`Radii::x_mu`]); u_mu_s may start at another lowest
//!   sun cosine (the curve shifted, or continued linearly below -0.2) and u_nu run
//!   linearly in the scattering angle ([`AngleMapping`]); a look-up may weigh its two nu
//!   texels between their positions clamped to the ray's range of nu ([`NuAxis`]);
//! - irradiance E(r, mu_s): linear in r over [Rg, Rt] and in mu_s over [-0.2, 1] (the
//!   paper's implementation; [min_mu_s, 1] in general).
//!
//! u_mu is discontinuous at the horizon: ground rays take [0, 1/2), the others (1/2, 1].
//! As in the paper's implementation, each half is its own set of texels (the first and
//! the second half of the mu axis), so that interpolation never mixes the two sides of
//! the horizon. Texel k of an axis of n texels lies at unit coordinate k / (n - 1): the
//! first and last texels sit on the ends of the range.

use crate::optics::geometry::{distance_to_entry, distance_to_exit, ray_hits_ground, safe_sqrt};

/// The lowest sun cosine of the paper's tables: u_mu_s = 0 at mu_s = -0.2.
pub const PAPER_MIN_MU_S: f64 = -0.2;

/// Planet radii of the mappings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Radii {
    pub bottom_m: f64,
    pub top_m: f64,
}

impl Radii {
    /// H = sqrt(Rt^2 - Rg^2): the distance to the top boundary of a horizontal ray from
    /// the ground.
    pub fn horizon_length(&self) -> f64 {
        safe_sqrt((self.top_m - self.bottom_m) * (self.top_m + self.bottom_m))
    }

    /// rho = sqrt(r^2 - Rg^2): the distance to the horizon from radius r.
    pub fn rho(&self, r: f64) -> f64 {
        safe_sqrt((r - self.bottom_m) * (r + self.bottom_m))
    }

    /// u_r = rho / H.
    pub fn u_r(&self, r: f64) -> f64 {
        (self.rho(r) / self.horizon_length()).clamp(0.0, 1.0)
    }

    /// Inverse of [`Radii::u_r`].
    pub fn r_from_u(&self, u_r: f64) -> f64 {
        let rho = self.horizon_length() * u_r;
        (rho * rho + self.bottom_m * self.bottom_m).sqrt()
    }

    /// The range [d_min, d_max] of the distance to the ray's end (the ground, or the top
    /// boundary) from radius r over one half of the mu axis: [r - Rg, rho] for rays that
    /// meet the ground, [Rt - r, rho + H] for the others.
    fn distance_range(&self, r: f64, ground: bool) -> (f64, f64) {
        let rho = self.rho(r);
        if ground {
            (r - self.bottom_m, rho)
        } else {
            (self.top_m - r, rho + self.horizon_length())
        }
    }

    /// The unit coordinate within the half of the mu axis chosen by `ground`: the
    /// distance d to the ray's end mapped linearly from its range at r (Bruneton 2017's
    /// refinement of the paper's d / rho and d / (rho + H), which spend a few texels on
    /// distances no ray from r has: at the ground mu in [0.86, 1] fell within one
    /// texel). x = 0 at the horizon and 1 straight down on the ground's side, 0 at the
    /// zenith and 1 at the horizon on the sky's. A ray whose geometry disagrees with
    /// `ground` by rounding falls on the horizon's texel.
    pub fn x_mu(&self, r: f64, mu: f64, ground: bool) -> f64 {
        let (d_min, d_max) = self.distance_range(r, ground);
        if d_max <= d_min {
            return if ground { 1.0 } else { 0.0 };
        }
        if ground {
            let d = if ray_hits_ground(r, mu, self.bottom_m) {
                distance_to_entry(r, mu, self.bottom_m).unwrap_or(0.0)
            } else {
                d_max
            };
            ((d_max - d) / (d_max - d_min)).clamp(0.0, 1.0)
        } else {
            let d = distance_to_exit(r, mu, self.top_m);
            ((d - d_min) / (d_max - d_min)).clamp(0.0, 1.0)
        }
    }

    /// Inverse of [`Radii::x_mu`]: mu at unit coordinate x within the half of the mu
    /// axis chosen by `ground`, clamped to [-1, 1] where x lies outside the range the
    /// radius can reach (x = 1 on the ground's side is straight down).
    pub fn mu_from_x(&self, r: f64, x: f64, ground: bool) -> f64 {
        let rho = self.rho(r);
        let h = self.horizon_length();
        let (d_min, d_max) = self.distance_range(r, ground);
        if ground {
            let d = d_max - x * (d_max - d_min);
            if d <= 0.0 {
                return -1.0;
            }
            // Rg^2 = r^2 + d^2 + 2 r mu d.
            (-(rho * rho + d * d) / (2.0 * r * d)).clamp(-1.0, 1.0)
        } else {
            let d = d_min + x * (d_max - d_min);
            if d <= 0.0 {
                return 1.0;
            }
            // Rt^2 = r^2 + d^2 + 2 r mu d.
            ((h * h - rho * rho - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0)
        }
    }
}

/// How the sun's zenith cosine and the view-sun cosine map to unit coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AngleMapping {
    /// The lowest sun cosine of S and E (u_mu_s = 0 there); lower suns are clamped to
    /// it. The paper's -0.2 (101.5 deg) stops short of nautical twilight's -0.208.
    pub min_mu_s: f64,
    /// u_nu linear in the scattering angle, 1 - acos(nu) / pi, rather than in its cosine
    /// (the paper's (1 + nu) / 2): the paper's first texel spans the 44 degrees of the
    /// forward lobe, where multiple scattering in haze and twilight varies most.
    pub nu_by_angle: bool,
    /// Below the paper's -0.2 (the knee), u_mu_s continues the paper's curve linearly
    /// with its slope there, down to `min_mu_s`, instead of shifting the whole curve to
    /// start at `min_mu_s` ([`AngleMapping::u_mu_s`]). No effect when `min_mu_s` is not
    /// below -0.2.
    pub mu_s_knee: bool,
    /// S and E read geometrically along mu_s between two texels whose suns are both
    /// below the horizontal (`tables::along_mu_s`), while building and rendering; linearly
    /// (the paper) everywhere otherwise.
    pub geometric_mu_s: bool,
    /// Look-ups weigh their two nu texels between the texels' positions clamped to the
    /// range of nu the ray's (mu, mu_s) allow ([`NuAxis::weight`]) rather than by their
    /// nominal u_nu (the paper).
    pub nu_edge: bool,
    /// The fourth coordinate is the azimuth phi between the view's and the sun's
    /// vertical planes, u = 1 - phi / pi ([`azimuth_unit`]), instead of a function of nu
    /// alone: every texel then holds a direction its (mu, mu_s) allows, so no texel is
    /// clamped to the edge of its range of nu and a look-up is continuous across texels
    /// (with nu, a ray in the sun's vertical plane reads texels clamped at other mu, and
    /// its radiance jumps where its nu crosses a texel). Excludes `nu_by_angle` and
    /// `nu_edge`.
    pub nu_by_azimuth: bool,
    /// The sky half of the mu axis spreads its texels towards the zenith: its unit
    /// coordinate is (t + sqrt(t)) / 2 of the paper's t, the distance to the top mapped
    /// from its range ([`AngleMapping::sky_x_mu`]). Near the zenith d - d_min grows as
    /// the square of the zenith angle, so at the paper's t the whole sky above 55 deg
    /// falls within one texel from the ground at 64 texels; sqrt(t) is linear in the
    /// angle there. At the horizon the texels are 3/4 of the paper's density.
    pub mu_zenith: bool,
}

impl AngleMapping {
    /// The paper's mappings (section 4).
    pub const PAPER: AngleMapping = AngleMapping {
        min_mu_s: PAPER_MIN_MU_S,
        nu_by_angle: false,
        mu_s_knee: false,
        geometric_mu_s: false,
        nu_edge: false,
        nu_by_azimuth: false,
        mu_zenith: false,
    };

    /// The lowest sun cosine of the paper's curve: `min_mu_s`, or the knee (-0.2) when
    /// the mapping is linear below it.
    fn curve_start(&self) -> f64 {
        if self.mu_s_knee {
            self.min_mu_s.max(PAPER_MIN_MU_S)
        } else {
            self.min_mu_s
        }
    }

    /// 1 - exp(-3 (1 - c)), c the curve's start: the normalisation of the curve.
    fn mu_s_norm(&self) -> f64 {
        1.0 - (-3.0 * (1.0 - self.curve_start())).exp()
    }

    /// The curve's slope at its start, 3 / (1 - exp(-3 (1 - c))), and the value of the
    /// linear part at `min_mu_s` (negative; 0 when the linear part is empty).
    fn linear_part(&self) -> (f64, f64) {
        let slope = 3.0 / self.mu_s_norm();
        (slope, slope * (self.min_mu_s - self.curve_start()))
    }

    /// u_mu_s. The paper's curve g(mu_s) = (1 - exp(-3 (mu_s - c))) / (1 - exp(-3 (1 - c))),
    /// c = -0.2, is the paper's (1 - exp(-3 mu_s - 0.6)) / (1 - exp(-3.6)); without the
    /// knee c = min_mu_s (the curve shifted) and u_mu_s = g. With it, below c,
    /// g continues as g'(c) (mu_s - c), and u_mu_s = (g - g(min_mu_s)) / (1 - g(min_mu_s)):
    /// twilight's sky dims by about e per 0.02 of mu_s below the horizon at a rate that
    /// hardly changes, so texels evenly spaced there (at the paper's densest spacing)
    /// serve it, while above -0.2 the paper's curve keeps its shape. Clamped to [0, 1].
    pub fn u_mu_s(&self, mu_s: f64) -> f64 {
        let c = self.curve_start();
        let (slope, lowest) = self.linear_part();
        let g = if mu_s >= c {
            (1.0 - (-3.0 * (mu_s - c)).exp()) / self.mu_s_norm()
        } else {
            slope * (mu_s - c)
        };
        ((g - lowest) / (1.0 - lowest)).clamp(0.0, 1.0)
    }

    /// Inverse of [`AngleMapping::u_mu_s`].
    pub fn mu_s_from_u(&self, u: f64) -> f64 {
        let c = self.curve_start();
        let (slope, lowest) = self.linear_part();
        let g = lowest + u * (1.0 - lowest);
        if g >= 0.0 {
            -(1.0 - g * self.mu_s_norm()).ln() / 3.0 + c
        } else {
            c + g / slope
        }
    }

    /// Whether S is read geometrically between mu_s texels `i` and `i + 1` of `n`.
    pub fn geometric_pair(&self, i: usize, n: usize) -> bool {
        self.geometric_mu_s && i + 1 < n && self.mu_s_from_u(texel_unit(i + 1, n)) <= 0.0
    }

    /// Whether E is read geometrically between its mu_s texels `i` and `i + 1` of `n`.
    pub fn irradiance_geometric_pair(&self, i: usize, n: usize) -> bool {
        self.geometric_mu_s && i + 1 < n && self.irradiance_mu_s(texel_unit(i + 1, n)) <= 0.0
    }

    /// The unit coordinate within the sky half of the mu axis from the paper's t in
    /// [0, 1] (0 at the zenith): t itself, or with `mu_zenith` (t + sqrt(t)) / 2.
    pub fn sky_x_mu(&self, t: f64) -> f64 {
        if self.mu_zenith {
            0.5 * (t + t.max(0.0).sqrt())
        } else {
            t
        }
    }

    /// Inverse of [`AngleMapping::sky_x_mu`]: with `mu_zenith` t = s^2 for the root
    /// s = (sqrt(1 + 8 x) - 1) / 2 of s^2 + s = 2 x.
    pub fn sky_t(&self, x: f64) -> f64 {
        if self.mu_zenith {
            let s = 0.5 * ((1.0 + 8.0 * x.max(0.0)).sqrt() - 1.0);
            s * s
        } else {
            x
        }
    }

    /// u_nu: (1 + nu) / 2 (the paper), or 1 - acos(nu) / pi.
    pub fn u_nu(&self, nu: f64) -> f64 {
        let nu = nu.clamp(-1.0, 1.0);
        if self.nu_by_angle {
            1.0 - nu.acos() / std::f64::consts::PI
        } else {
            0.5 * (1.0 + nu)
        }
    }

    /// Inverse of [`AngleMapping::u_nu`].
    pub fn nu_from_u(&self, u: f64) -> f64 {
        if self.nu_by_angle {
            -(std::f64::consts::PI * u).cos()
        } else {
            2.0 * u - 1.0
        }
    }

    /// E's unit coordinate along mu_s: linear over [min_mu_s, 1] (the paper's
    /// implementation).
    pub fn irradiance_x_mu_s(&self, mu_s: f64) -> f64 {
        ((mu_s - self.min_mu_s) / (1.0 - self.min_mu_s)).clamp(0.0, 1.0)
    }

    /// Inverse of [`AngleMapping::irradiance_x_mu_s`].
    pub fn irradiance_mu_s(&self, x: f64) -> f64 {
        self.min_mu_s + x * (1.0 - self.min_mu_s)
    }
}

/// The range of the view-sun cosine that view and sun zenith cosines mu and mu_s allow:
/// mu mu_s -/+ sqrt((1 - mu^2)(1 - mu_s^2)) (the sun in the view's vertical plane, on
/// its side or the other).
pub fn nu_range(mu: f64, mu_s: f64) -> (f64, f64) {
    let s = safe_sqrt((1.0 - mu * mu) * (1.0 - mu_s * mu_s));
    (mu * mu_s - s, mu * mu_s + s)
}

/// The cosine of the view-sun angle clamped to what view and sun zenith cosines allow.
pub fn clamp_nu(mu: f64, mu_s: f64, nu: f64) -> f64 {
    let (low, high) = nu_range(mu, mu_s);
    nu.clamp(low, high)
}

/// The unit coordinate of the azimuth phi between the view's and the sun's vertical
/// planes, u = 1 - phi / pi (1 towards the sun), from nu = mu mu_s + s cos(phi) with
/// s = sqrt((1 - mu^2)(1 - mu_s^2)): phi = atan2(sqrt(s^2 - c^2), c), c = nu - mu mu_s,
/// with no division, so that a view or sun at the zenith (s = 0, where every phi is the
/// same direction) gives u = 1 and a nu just outside its range by rounding the edge.
pub fn azimuth_unit(mu: f64, mu_s: f64, nu: f64) -> f64 {
    let c = nu - mu * mu_s;
    let s2 = ((1.0 - mu * mu) * (1.0 - mu_s * mu_s)).max(0.0);
    1.0 - safe_sqrt(s2 - c * c).atan2(c) / std::f64::consts::PI
}

/// Inverse of [`azimuth_unit`]: the view-sun cosine at unit azimuth coordinate u for view
/// and sun zenith cosines mu and mu_s.
pub fn nu_at_azimuth_unit(mu: f64, mu_s: f64, u: f64) -> f64 {
    let s = safe_sqrt((1.0 - mu * mu) * (1.0 - mu_s * mu_s));
    (mu * mu_s + s * (std::f64::consts::PI * (1.0 - u)).cos()).clamp(-1.0, 1.0)
}

/// A view-sun cosine's place along the nu axis: its lower texel, the nominal weight of
/// the next, and what [`NuAxis::weight`] needs to move that weight for a ray's (mu, mu_s).
#[derive(Clone, Copy, Debug)]
pub struct NuAxis {
    pub lower: usize,
    pub nominal_weight: f64,
    angles: AngleMapping,
    /// u_nu of the look-up, and of the two texels with their nominal cosines.
    u: f64,
    units: [f64; 2],
    cosines: [f64; 2],
}

impl NuAxis {
    /// Where nu falls on an axis of `n` texels of `angles` for a ray of view and sun
    /// zenith cosines mu and mu_s (which only `nu_by_azimuth` reads here).
    pub fn new(angles: &AngleMapping, n: usize, mu: f64, mu_s: f64, nu: f64) -> NuAxis {
        let u = if angles.nu_by_azimuth {
            azimuth_unit(mu, mu_s, nu)
        } else {
            angles.u_nu(nu)
        };
        let (lower, nominal_weight) = axis(u, n);
        let units = [texel_unit(lower, n), texel_unit((lower + 1).min(n - 1), n)];
        NuAxis {
            lower,
            nominal_weight,
            angles: *angles,
            u,
            units,
            cosines: units.map(|x| angles.nu_from_u(x)),
        }
    }

    /// The weight of the upper texel for a ray of view and sun zenith cosines mu and
    /// mu_s. Each texel holds its nu clamped to the range its own (mu, mu_s) allow
    /// ([`clamp_nu`]), so near the edge of that range a texel holds the edge's value, not
    /// its nominal one. With `nu_edge` the weight is taken between the two texels'
    /// positions clamped to the ray's range [u_nu(nu_min), u_nu(nu_max)] ([`nu_range`]),
    /// w = (u - max(u_i, u_nu(nu_min))) / (min(u_i+1, u_nu(nu_max)) - max(u_i, u_nu(nu_min))),
    /// so that a ray next to the edge reads mostly the texel holding the edge's value.
    /// The nominal weight without `nu_edge`, where neither texel is clamped, and where
    /// the clamped interval is under a thousandth of the texels' spacing (mu or mu_s near
    /// +-1, where they fix nu).
    pub fn weight(&self, mu: f64, mu_s: f64) -> f64 {
        if !self.angles.nu_edge || self.nominal_weight == 0.0 {
            return self.nominal_weight;
        }
        let (low, high) = nu_range(mu, mu_s);
        let [c0, c1] = self.cosines;
        if low <= c0 && high >= c1 {
            return self.nominal_weight;
        }
        let a = if low > c0 {
            self.angles.u_nu(low)
        } else {
            self.units[0]
        };
        let b = if high < c1 {
            self.angles.u_nu(high)
        } else {
            self.units[1]
        };
        if b - a < 1e-3 * (self.units[1] - self.units[0]) {
            return self.nominal_weight;
        }
        ((self.u - a) / (b - a)).clamp(0.0, 1.0)
    }
}

/// Texel position along an axis of `n` texels for a unit coordinate: the lower texel
/// index (at most n - 2) and the interpolation weight of the next one.
pub fn axis(x: f64, n: usize) -> (usize, f64) {
    if n < 2 {
        return (0, 0.0);
    }
    let f = (x.clamp(0.0, 1.0) * (n - 1) as f64).max(0.0);
    let i = (f as usize).min(n - 2);
    let w = (f - i as f64).clamp(0.0, 1.0);
    // Texel centres hit by rounding count as exact (one texel, weight 0).
    if w < 1e-9 {
        (i, 0.0)
    } else if w > 1.0 - 1e-9 && i + 2 < n {
        (i + 1, 0.0)
    } else if w > 1.0 - 1e-9 {
        (i, 1.0)
    } else {
        (i, w)
    }
}

/// Unit coordinate of texel `k` of `n`.
pub fn texel_unit(k: usize, n: usize) -> f64 {
    if n < 2 {
        0.0
    } else {
        k as f64 / (n - 1) as f64
    }
}

/// Sizes of the 4D scattering table: (r, mu, mu_s, nu), and how its angles map to its
/// axes. The mu axis has an even size: its first half is for rays that meet the ground.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScatteringSize {
    pub r: usize,
    pub mu: usize,
    pub mu_s: usize,
    pub nu: usize,
    pub angles: AngleMapping,
}

impl ScatteringSize {
    pub fn texels(&self) -> usize {
        self.r * self.mu * self.mu_s * self.nu
    }

    /// Linear index of texel (r, mu, mu_s, nu): mu_s fastest, then r, mu, nu. Along one
    /// view ray nu is fixed and the texels of equal (r, mu) and neighbouring mu_s are
    /// built one after the other, so they read neighbouring memory.
    pub fn index(&self, ir: usize, imu: usize, imus: usize, inu: usize) -> usize {
        ((inu * self.mu + imu) * self.r + ir) * self.mu_s + imus
    }

    /// (ir, imu, imus, inu) of a linear index.
    pub fn coords(&self, index: usize) -> (usize, usize, usize, usize) {
        let imus = index % self.mu_s;
        let rest = index / self.mu_s;
        let ir = rest % self.r;
        let rest = rest / self.r;
        (ir, rest % self.mu, imus, rest / self.mu)
    }

    /// Texels in one half of the mu axis.
    pub fn half_mu(&self) -> usize {
        self.mu / 2
    }
}

/// The physical parameters at a texel of the scattering table: (r, mu, mu_s, nu) and
/// whether its ray meets the ground.
pub fn texel_parameters(
    radii: &Radii,
    size: &ScatteringSize,
    ir: usize,
    imu: usize,
    imus: usize,
    inu: usize,
) -> (f64, f64, f64, f64, bool) {
    let r = radii.r_from_u(texel_unit(ir, size.r));
    let half = size.half_mu();
    let ground = imu < half;
    let x = texel_unit(if ground { imu } else { imu - half }, half);
    let x = if ground { x } else { size.angles.sky_t(x) };
    let mut mu = radii.mu_from_x(r, x, ground);
    // Keep the texel on its side of the horizon (rounding at the horizon itself).
    let hits = ray_hits_ground(r, mu, radii.bottom_m);
    if ground && !hits {
        mu = crate::optics::geometry::horizon_mu(r, radii.bottom_m) - 1e-12;
    } else if !ground && hits {
        mu = crate::optics::geometry::horizon_mu(r, radii.bottom_m) + 1e-12;
    }
    let mu_s = size.angles.mu_s_from_u(texel_unit(imus, size.mu_s));
    let u = texel_unit(inu, size.nu);
    let nu = if size.angles.nu_by_azimuth {
        nu_at_azimuth_unit(mu, mu_s, u)
    } else {
        clamp_nu(mu, mu_s, size.angles.nu_from_u(u))
    };
    (r, mu, mu_s, nu, ground)
}

/// Where (r, mu, mu_s, nu) falls in the table: for each axis the lower texel and the
/// weight of the next. `ground` chooses the half of the mu axis (it must be the same for
/// every point of one view ray).
pub fn table_position(
    radii: &Radii,
    size: &ScatteringSize,
    r: f64,
    mu: f64,
    mu_s: f64,
    nu: f64,
    ground: bool,
) -> [(usize, f64); 4] {
    let half = size.half_mu();
    let x_mu = radii.x_mu(r, mu, ground);
    let x_mu = if ground {
        x_mu
    } else {
        size.angles.sky_x_mu(x_mu)
    };
    let (imu, wmu) = axis(x_mu, half);
    [
        axis(radii.u_r(r), size.r),
        (if ground { imu } else { imu + half }, wmu),
        axis(size.angles.u_mu_s(mu_s), size.mu_s),
        {
            let nu_axis = NuAxis::new(&size.angles, size.nu, mu, mu_s, nu);
            (nu_axis.lower, nu_axis.weight(mu, mu_s))
        },
    ]
}

/// Sizes and mapping of the irradiance table E(r, mu_s): (mu_s, r).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IrradianceMapping {
    pub radii: Radii,
    pub angles: AngleMapping,
    pub mu_s_size: usize,
    pub r_size: usize,
}

impl IrradianceMapping {
    pub fn unit_from_r_mu_s(&self, r: f64, mu_s: f64) -> (f64, f64) {
        (
            ((r - self.radii.bottom_m) / (self.radii.top_m - self.radii.bottom_m)).clamp(0.0, 1.0),
            self.angles.irradiance_x_mu_s(mu_s),
        )
    }

    pub fn r_mu_s_from_unit(&self, x_r: f64, x_mu_s: f64) -> (f64, f64) {
        (
            self.radii.bottom_m + x_r * (self.radii.top_m - self.radii.bottom_m),
            self.angles.irradiance_mu_s(x_mu_s),
        )
    }

    /// Linear index of texel (r, mu_s).
    pub fn index(&self, ir: usize, imus: usize) -> usize {
        ir * self.mu_s_size + imus
    }

    pub fn texels(&self) -> usize {
        self.mu_s_size * self.r_size
    }
}
