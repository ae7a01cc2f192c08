//! Bruneton and Neyret 2008, Algorithm 4.1: single scattering into S, then each order in
//! turn: Delta J from the previous order's radiance (scattered light plus light reflected
//! by the ground), Delta S by integrating T Delta J along every texel's ray, Delta E from
//! the previous order's sky radiance; added to S and E, until an order adds less than a
//! threshold.
//!
//! Delta J is computed from angular moments of the incoming radiance at each (r, mu_s)
//! rather than by a separate sphere quadrature at each of the 4D table's texels: the
//! Rayleigh phase function is a quadratic form in the direction, so its integral is exact
//! from the moments of order 0 and 2; the Mie phase function uses the delta-M
//! approximation with three Legendre terms (a forward peak times the radiance along the
//! view plus a smooth remainder). The sphere quadrature per (r, mu_s) is the paper's
//! implementation's 16 x 32 directions, split at the horizon. This keeps the build within
//! seconds on two cores; see docs/models/bruneton.md.

use std::f64::consts::PI;
use std::time::Instant;

use rayon::prelude::*;

use crate::atmosphere::Atmosphere;
use crate::models::bruneton::BrunetonSettings;
use crate::models::bruneton::parameterization::{
    IrradianceMapping, Radii, axis, table_position, texel_parameters, u_mu_s, u_nu,
};
use crate::models::bruneton::tables::{DensityTable, IrradianceTable, Table4};
use crate::numerics::quadrature::{GAUSS_LEGENDRE_8, mapped};
use crate::optics::column::optical_depth;
use crate::optics::geometry::{
    distance_to_entry, distance_to_exit, horizon_mu, radius_at, ray_hits_ground,
};
use crate::optics::phase::{PhaseFunction, rayleigh};
use crate::optics::transmittance_table::TransmittanceTable;

/// The coefficients of three wavelengths (one table channel each). The tables hold
/// radiance and irradiance per unit solar irradiance (W m^-2 nm^-1 at the top of the
/// atmosphere), so the solar spectrum is not among them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Channels {
    /// Extinction per species (Rayleigh, Mie, ozone) at density 1, m^-1.
    pub extinction: [[f64; 3]; 3],
    pub rayleigh_scattering: [f64; 3],
    pub mie_scattering: [f64; 3],
}

impl Channels {
    pub fn new(atmosphere: &Atmosphere, wavelengths_nm: [f64; 3]) -> Channels {
        let c = wavelengths_nm.map(|l| atmosphere.coefficients(l));
        Channels {
            extinction: c.map(|c| c.extinction_per_species()),
            rayleigh_scattering: c.map(|c| c.rayleigh_scattering_per_m),
            mie_scattering: c.map(|c| c.mie_scattering_per_m),
        }
    }

    /// [`Channels::transmittance`] of every texel of a column table.
    pub fn transmittances(&self, table: &TransmittanceTable) -> Vec<[f64; 3]> {
        table
            .columns
            .iter()
            .map(|c| self.transmittance(*c))
            .collect()
    }

    /// exp(-optical depth) of a column at each channel.
    pub fn transmittance(&self, column: [f64; 3]) -> [f64; 3] {
        self.extinction.map(|e| (-optical_depth(column, e)).exp())
    }
}

/// The delta-M form of the Mie phase function with three Legendre terms (Wiscombe 1977):
/// p(nu) ~ f delta(1 - nu) / (2 pi) + (1 - f) / (4 pi) (1 + 3 chi1 P1(nu) + 5 chi2 P2(nu)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeltaM {
    pub forward_fraction: f64,
    pub chi1: f64,
    pub chi2: f64,
}

impl DeltaM {
    /// Legendre moments of `phase` by quadrature in the scattering angle (fine near the
    /// forward peak), then truncation.
    pub fn new(phase: &PhaseFunction) -> DeltaM {
        let n = 20_000;
        let h = PI / n as f64;
        let mut chi = [0.0; 4];
        for k in 0..n {
            for (t, w) in mapped(&GAUSS_LEGENDRE_8, h * k as f64, h * (k + 1) as f64) {
                let x = t.cos();
                let p = phase.eval(x) * 2.0 * PI * t.sin() * w;
                let p2 = 0.5 * (3.0 * x * x - 1.0);
                let p3 = 0.5 * (5.0 * x * x * x - 3.0 * x);
                chi[0] += p;
                chi[1] += p * x;
                chi[2] += p * p2;
                chi[3] += p * p3;
            }
        }
        let f = (chi[3] / chi[0]).clamp(0.0, 0.999);
        DeltaM {
            forward_fraction: f,
            chi1: (chi[1] / chi[0] - f) / (1.0 - f),
            chi2: (chi[2] / chi[0] - f) / (1.0 - f),
        }
    }
}

/// The radiance field of the previous order, as the tables hold it.
#[derive(Clone, Copy)]
enum Previous<'a> {
    /// Single scattering: Rayleigh and Mie without phase functions (no Mie table when
    /// pruned).
    Single {
        rayleigh: &'a Table4,
        mie: Option<&'a Table4>,
    },
    /// An order of two or more: full radiance.
    Multiple(&'a Table4),
}

/// The ground irradiance of the order before the previous one.
#[derive(Clone, Copy)]
enum PreviousIrradiance<'a> {
    /// Direct sunlight (order 0).
    Direct,
    Table(&'a IrradianceTable),
}

/// One trapezoid node of a texel row's ray (see `Builder::ray_nodes`).
#[derive(Clone, Copy, Debug)]
struct RayNode {
    r: f64,
    /// r / r_t and t / r_t, with r the ray's start and t the node's distance: the sun
    /// cosine there is mu_s r / r_t + nu t / r_t.
    start_ratio: f64,
    distance_ratio: f64,
    densities: [f64; 3],
    weighted_transmittance: [f64; 3],
    r_axis: (usize, f64),
    mu_axis: (usize, f64),
}

impl RayNode {
    /// The sun's zenith cosine at the node for a sun at mu_s seen at nu from the start.
    fn sun_cosine(&self, mu_s: f64, nu: f64) -> f64 {
        (mu_s * self.start_ratio + nu * self.distance_ratio).clamp(-1.0, 1.0)
    }
}

/// [`axis`] of [`u_mu_s`] tabulated over mu_s in [-1, 1] (4097 points, linearly
/// interpolated: within 1e-5 of a texel of the exact position where mu_s >= -0.2, the
/// table's range), to spare an exponential per node and texel of Delta S.
struct MuSAxis {
    size: usize,
    positions: Vec<f64>,
}

impl MuSAxis {
    const POINTS: usize = 4097;

    fn new(size: usize) -> MuSAxis {
        let step = 2.0 / (Self::POINTS - 1) as f64;
        MuSAxis {
            size,
            positions: (0..Self::POINTS)
                .map(|i| u_mu_s(-1.0 + step * i as f64) * (size - 1) as f64)
                .collect(),
        }
    }

    /// The lower texel (at most size - 2) and the weight of the next at mu_s.
    fn at(&self, mu_s: f64) -> (usize, f32) {
        let f = (mu_s + 1.0) * 0.5 * (Self::POINTS - 1) as f64;
        let i = (f as usize).min(Self::POINTS - 2);
        let w = f - i as f64;
        let x = (self.positions[i] + w * (self.positions[i + 1] - self.positions[i]))
            .clamp(0.0, (self.size - 1) as f64);
        let lower = (x as usize).min(self.size - 2);
        (lower, (x - lower as f64) as f32)
    }
}

/// The values of one texel row (ir, imu): two tables, over (nu, mu_s).
type RowValues = (usize, usize, Vec<[[f32; 3]; 2]>);

/// How long an order took and how much it added.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrderStats {
    /// 1 = single scattering.
    pub order: u32,
    /// max over channels of (sum over texels of the order's radiance) / (sum of all
    /// orders so far, this one included); NaN for an order left out because it held more
    /// light than the one before (the iteration would diverge).
    pub share: f64,
    pub seconds: f64,
}

/// The tables of three wavelengths.
#[derive(Clone, Debug)]
pub struct Tables {
    pub channels: Channels,
    /// Single Rayleigh scattering without its phase function (C* of the paper minus the
    /// multiple part).
    pub single_rayleigh: Table4,
    /// Single Mie scattering without its phase function (C_M of the paper); `None` when
    /// pruned (no aerosol).
    pub single_mie: Option<Table4>,
    /// All orders from two up, full radiance.
    pub multiple: Table4,
    /// Ground irradiance from the sky, orders one up to the last but one (direct
    /// sunlight is added when rendering).
    pub irradiance: IrradianceTable,
    pub orders: Vec<OrderStats>,
}

/// Everything the build needs.
#[derive(Debug)]
pub struct Builder<'a> {
    pub atmosphere: &'a Atmosphere,
    pub settings: &'a BrunetonSettings,
    pub radii: Radii,
    pub transmittance: &'a TransmittanceTable,
    pub densities: &'a DensityTable,
    pub channels: Channels,
    /// The channels' transmittance at each texel of `transmittance`: interpolated
    /// directly, it spares three exponentials per look-up.
    pub sun_transmittances: Vec<[f64; 3]>,
    /// The Mie phase function's delta-M form; `None` prunes all Mie work (no aerosol).
    pub delta_m: Option<DeltaM>,
    pub max_orders: u32,
}

fn to_f32(a: [f64; 3]) -> [f32; 3] {
    [a[0] as f32, a[1] as f32, a[2] as f32]
}

impl Builder<'_> {
    /// Transmittance to the sun (a point) from (r, mu_s); zero behind the planet.
    pub fn sun_transmittance(&self, r: f64, mu_s: f64) -> [f64; 3] {
        if ray_hits_ground(r, mu_s, self.radii.bottom_m) {
            return [0.0; 3];
        }
        self.transmittance
            .interpolate(&self.sun_transmittances, r, mu_s)
    }

    /// Direct sunlight on a horizontal surface at (r, mu_s), per unit solar irradiance.
    fn direct_irradiance(&self, r: f64, mu_s: f64) -> [f64; 3] {
        let t = self.sun_transmittance(r, mu_s);
        let c = mu_s.max(0.0);
        t.map(|t| t * c)
    }

    /// Transmittance of the segment of length d from (r, mu), from the column table.
    pub fn segment_transmittance(&self, r: f64, mu: f64, d: f64, ground: bool) -> [f64; 3] {
        let r_d = radius_at(r, mu, d).clamp(self.radii.bottom_m, self.radii.top_m);
        let mu_d = ((r * mu + d) / r_d).clamp(-1.0, 1.0);
        let (a, b) = if ground {
            (
                self.transmittance.column(r_d, -mu_d),
                self.transmittance.column(r, -mu),
            )
        } else {
            (
                self.transmittance.column(r, mu),
                self.transmittance.column(r_d, mu_d),
            )
        };
        self.channels
            .transmittance([0, 1, 2].map(|k| (a[k] - b[k]).max(0.0)))
    }

    fn ray_length(&self, r: f64, mu: f64, ground: bool) -> f64 {
        if ground {
            distance_to_entry(r, mu, self.radii.bottom_m).unwrap_or(0.0)
        } else {
            distance_to_exit(r, mu, self.radii.top_m)
        }
    }

    /// The trapezoid nodes along the ray of texel row (r, mu): distance, radius, mu there,
    /// densities, the trapezoid weight times the transmittance from the ray's start (from
    /// a running trapezoid of the densities), and the r and mu axes of the table there.
    /// Every texel with this (r, mu) shares them; only mu_s and nu differ.
    fn ray_nodes(&self, r: f64, mu: f64, ground: bool) -> Vec<RayNode> {
        let d = self.ray_length(r, mu, ground);
        let n = self.settings.view_samples.max(1);
        let size = self.settings.scattering_size;
        // Nodes crowd where the air is densest: at the start of rays that climb, at the
        // end of rays that meet the ground; evenly spaced on rays through a tangent point.
        let position = |i: usize| {
            let u = i as f64 / n as f64;
            if mu >= 0.0 {
                d * u * u
            } else if ground {
                d * (1.0 - (1.0 - u) * (1.0 - u))
            } else {
                d * u
            }
        };
        let mut column = [0.0; 3];
        let mut previous = [0.0; 3];
        let mut nodes = Vec::with_capacity(n + 1);
        for i in 0..=n {
            let t = position(i);
            let r_t = radius_at(r, mu, t).clamp(self.radii.bottom_m, self.radii.top_m);
            let rho = self.densities.at(r_t - self.radii.bottom_m);
            if i > 0 {
                let dx = t - position(i - 1);
                for k in 0..3 {
                    column[k] += 0.5 * dx * (previous[k] + rho[k]);
                }
            }
            previous = rho;
            let w = 0.5 * (position((i + 1).min(n)) - position(i.saturating_sub(1)));
            let transmittance = self.channels.transmittance(column);
            let mu_t = ((r * mu + t) / r_t).clamp(-1.0, 1.0);
            let p = table_position(&self.radii, &size, r_t, mu_t, 0.0, 0.0, ground);
            nodes.push(RayNode {
                r: r_t,
                start_ratio: r / r_t,
                distance_ratio: t / r_t,
                densities: rho,
                weighted_transmittance: [0, 1, 2].map(|k| w * transmittance[k]),
                r_axis: p[0],
                mu_axis: p[1],
            });
        }
        nodes
    }

    /// Applies `f(nodes, texels, out)` to every row of the scattering table, the
    /// texels of equal (r, mu), in parallel: `texels` holds the (mu_s, nu) of the row's
    /// texels (nu slice by nu slice, mu_s fastest), and `f` pushes one pair of values per
    /// texel to `out`. Returns the first values' table, and the second's if `second`.
    fn map_rays<F>(&self, second: bool, f: F) -> (Table4, Option<Table4>)
    where
        F: Fn(&[RayNode], &[(f64, f64)], &mut Vec<[[f64; 3]; 2]>) + Sync,
    {
        let size = self.settings.scattering_size;
        let rows: Vec<RowValues> = (0..size.r * size.mu)
            .into_par_iter()
            .map(|row| {
                let (ir, imu) = (row % size.r, row / size.r);
                let (r, mu, _, _, ground) = texel_parameters(&self.radii, &size, ir, imu, 0, 0);
                let nodes = self.ray_nodes(r, mu, ground);
                let texels: Vec<(f64, f64)> = (0..size.nu * size.mu_s)
                    .map(|i| {
                        let (inu, imus) = (i / size.mu_s, i % size.mu_s);
                        let (_, _, mu_s, nu, _) =
                            texel_parameters(&self.radii, &size, ir, imu, imus, inu);
                        (mu_s, nu)
                    })
                    .collect();
                let mut values = Vec::with_capacity(texels.len());
                f(&nodes, &texels, &mut values);
                let out = values
                    .iter()
                    .map(|v| [to_f32(v[0]), to_f32(v[1])])
                    .collect();
                (ir, imu, out)
            })
            .collect();
        let mut a = Table4::zeros(size);
        let mut b = second.then(|| Table4::zeros(size));
        for (ir, imu, values) in rows {
            let mut it = values.into_iter();
            for inu in 0..size.nu {
                for imus in 0..size.mu_s {
                    let v = it.next().unwrap_or([[0.0; 3]; 2]);
                    let index = size.index(ir, imu, imus, inu);
                    a.data[index] = v[0];
                    if let Some(b) = &mut b {
                        b.data[index] = v[1];
                    }
                }
            }
        }
        (a, b)
    }

    /// The single-scattering tables (Rayleigh, Mie unless pruned), without phase
    /// functions, per unit solar irradiance (paper Eq. 5 with a point sun).
    pub fn single_scattering(&self) -> (Table4, Option<Table4>) {
        let ch = self.channels;
        self.map_rays(self.delta_m.is_some(), |nodes, texels, out| {
            for &(mu_s, nu) in texels {
                let mut sums = [[0.0; 3]; 2];
                for node in nodes {
                    let rho = node.densities;
                    if rho[0] == 0.0 && rho[1] == 0.0 {
                        continue;
                    }
                    let mu_s_t = node.sun_cosine(mu_s, nu);
                    let sun = self.sun_transmittance(node.r, mu_s_t);
                    for k in 0..3 {
                        let c = node.weighted_transmittance[k] * sun[k];
                        sums[0][k] += c * rho[0];
                        sums[1][k] += c * rho[1];
                    }
                }
                out.push([
                    [0, 1, 2].map(|k| sums[0][k] * ch.rayleigh_scattering[k]),
                    [0, 1, 2].map(|k| sums[1][k] * ch.mie_scattering[k]),
                ]);
            }
        })
    }

    /// Radiance of the previous order seen from (r, mu) towards nu, sky part only.
    fn previous_radiance(
        &self,
        previous: Previous,
        r: f64,
        mu: f64,
        mu_s: f64,
        nu: f64,
        ground: bool,
    ) -> [f64; 3] {
        match previous {
            Previous::Single { rayleigh: ray, mie } => {
                let pr = rayleigh(nu);
                let mut l = ray
                    .lookup(&self.radii, r, mu, mu_s, nu, ground)
                    .map(|a| pr * a);
                if let Some(mie) = mie {
                    let b = mie.lookup(&self.radii, r, mu, mu_s, nu, ground);
                    let pm = self.atmosphere.mie.phase.eval(nu);
                    for k in 0..3 {
                        l[k] += pm * b[k];
                    }
                }
                l
            }
            Previous::Multiple(table) => table.lookup(&self.radii, r, mu, mu_s, nu, ground),
        }
    }

    /// Radiance of order k arriving at (r) from direction (mu, nu): the scattered light of
    /// order k plus, for directions towards the ground, the ground's reflection of the
    /// irradiance of order k - 1, attenuated.
    fn incoming(
        &self,
        previous: Previous,
        previous_irradiance: PreviousIrradiance,
        r: f64,
        mu: f64,
        mu_s: f64,
        nu: f64,
    ) -> [f64; 3] {
        let ground = ray_hits_ground(r, mu, self.radii.bottom_m);
        let mut l = self.previous_radiance(previous, r, mu, mu_s, nu, ground);
        if ground {
            let d = self.ray_length(r, mu, true);
            let mu_s_g = ((r * mu_s + d * nu) / self.radii.bottom_m).clamp(-1.0, 1.0);
            let e = match previous_irradiance {
                PreviousIrradiance::Direct => self.direct_irradiance(self.radii.bottom_m, mu_s_g),
                PreviousIrradiance::Table(table) => table.lookup(self.radii.bottom_m, mu_s_g),
            };
            let t = self.segment_transmittance(r, mu, d, true);
            let albedo = self.atmosphere.ground_albedo / PI;
            for k in 0..3 {
                l[k] += t[k] * albedo * e[k];
            }
        }
        l
    }

    /// Directions (zenith angle nodes with weights) over [a, b] by composite
    /// Gauss-Legendre, 8 nodes per panel.
    fn theta_nodes(&self, a: f64, b: f64, panels: usize) -> Vec<(f64, f64)> {
        let step = (b - a) / panels as f64;
        (0..panels)
            .flat_map(|p| {
                let lo = a + step * p as f64;
                mapped(&GAUSS_LEGENDRE_8, lo, lo + step).collect::<Vec<_>>()
            })
            .collect()
    }

    fn theta_panels(&self) -> usize {
        self.settings.sphere_samples.0.div_ceil(16).max(1)
    }

    /// Azimuths over [0, pi] (the field is symmetric about the sun's vertical plane) with
    /// weights that count both sides.
    fn phi_nodes(&self) -> Vec<(f64, f64)> {
        let n = (self.settings.sphere_samples.1 / 2).max(1);
        let step = PI / n as f64;
        (0..n)
            .map(|i| (step * (i as f64 + 0.5), 2.0 * step))
            .collect()
    }

    /// Ground irradiance (upper hemisphere) of an order's sky radiance.
    fn irradiance_of(&self, previous: Previous) -> IrradianceTable {
        let mapping = IrradianceMapping {
            radii: self.radii,
            mu_s_size: self.settings.irradiance_size.0,
            r_size: self.settings.irradiance_size.1,
        };
        let mut table = IrradianceTable::zeros(mapping);
        let thetas = self.theta_nodes(0.0, 0.5 * PI, self.theta_panels());
        let phis = self.phi_nodes();
        let values: Vec<[f32; 3]> = (0..mapping.texels())
            .into_par_iter()
            .map(|index| {
                let (ir, imus) = (index / mapping.mu_s_size, index % mapping.mu_s_size);
                let (r, mu_s) = table.texel_r_mu_s(ir, imus);
                let sin_s = (1.0 - mu_s * mu_s).max(0.0).sqrt();
                let mut e = [0.0; 3];
                for &(theta, wt) in &thetas {
                    let (st, ct) = theta.sin_cos();
                    for &(phi, wp) in &phis {
                        let nu = st * phi.cos() * sin_s + ct * mu_s;
                        let l = self.previous_radiance(previous, r, ct, mu_s, nu, false);
                        let w = wt * wp * st * ct;
                        for k in 0..3 {
                            e[k] += w * l[k];
                        }
                    }
                }
                to_f32(e)
            })
            .collect();
        table.data = values;
        table
    }

    /// Delta J of the next order from the incoming radiance of the previous one.
    fn scattering_density(
        &self,
        previous: Previous,
        previous_irradiance: PreviousIrradiance,
    ) -> Table4 {
        let size = self.settings.scattering_size;
        let ch = &self.channels;
        let dm = self.delta_m;
        let phis = self.phi_nodes();
        let panels = self.theta_panels();
        let blocks: Vec<(usize, usize, Vec<[f32; 3]>)> = (0..size.r * size.mu_s)
            .into_par_iter()
            .map(|pair| {
                let (ir, imus) = (pair % size.r, pair / size.r);
                let (r, _, mu_s, _, _) = texel_parameters(&self.radii, &size, ir, 0, imus, 0);
                let sin_s = (1.0 - mu_s * mu_s).max(0.0).sqrt();
                let theta_h = horizon_mu(r, self.radii.bottom_m).acos();
                let mut thetas = self.theta_nodes(0.0, theta_h, panels);
                thetas.extend(self.theta_nodes(theta_h, PI, panels));
                // Moments per channel: L0, Fx, Fz, Mxx, Myy, Mzz, Mxz.
                let mut m = [[0.0f64; 7]; 3];
                for &(theta, wt) in &thetas {
                    let (st, ct) = theta.sin_cos();
                    for &(phi, wp) in &phis {
                        let (sp, cp) = phi.sin_cos();
                        let (wx, wy, wz) = (st * cp, st * sp, ct);
                        let nu = wx * sin_s + wz * mu_s;
                        let l = self.incoming(previous, previous_irradiance, r, ct, mu_s, nu);
                        let w = wt * wp * st;
                        let basis = [1.0, wx, wz, wx * wx, wy * wy, wz * wz, wx * wz];
                        for k in 0..3 {
                            let wl = w * l[k];
                            for (mk, b) in m[k].iter_mut().zip(basis) {
                                *mk += wl * b;
                            }
                        }
                    }
                }
                let rho = self.densities.at(r - self.radii.bottom_m);
                let mut out = Vec::with_capacity(size.mu * size.nu);
                for inu in 0..size.nu {
                    for imu in 0..size.mu {
                        let (_, mu, _, nu, _) =
                            texel_parameters(&self.radii, &size, ir, imu, imus, inu);
                        let vx = if sin_s > 1e-9 {
                            (nu - mu * mu_s) / sin_s
                        } else {
                            0.0
                        };
                        let vy = (1.0 - mu * mu - vx * vx).max(0.0).sqrt();
                        let vz = mu;
                        let l_v = dm
                            .map(|_| self.incoming(previous, previous_irradiance, r, mu, mu_s, nu));
                        let mut j = [0.0; 3];
                        for k in 0..3 {
                            let [l0, fx, fz, mxx, myy, mzz, mxz] = m[k];
                            let q =
                                mxx * vx * vx + myy * vy * vy + mzz * vz * vz + 2.0 * mxz * vx * vz;
                            j[k] =
                                ch.rayleigh_scattering[k] * rho[0] * 3.0 / (16.0 * PI) * (l0 + q);
                            if let (Some(dm), Some(l_v)) = (dm, l_v) {
                                let p1 = vx * fx + vz * fz;
                                let p2 = 0.5 * (3.0 * q - l0);
                                let j_m = dm.forward_fraction * l_v[k]
                                    + (1.0 - dm.forward_fraction) / (4.0 * PI)
                                        * (l0 + 3.0 * dm.chi1 * p1 + 5.0 * dm.chi2 * p2);
                                j[k] += ch.mie_scattering[k] * rho[1] * j_m.max(0.0);
                            }
                            j[k] = j[k].max(0.0);
                        }
                        out.push(to_f32(j));
                    }
                }
                (ir, imus, out)
            })
            .collect();
        let mut table = Table4::zeros(size);
        for (ir, imus, values) in blocks {
            let mut it = values.into_iter();
            for inu in 0..size.nu {
                for imu in 0..size.mu {
                    table.data[size.index(ir, imu, imus, inu)] = it.next().unwrap_or([0.0; 3]);
                }
            }
        }
        table
    }

    /// Delta S of an order: T times Delta J integrated along every texel's ray. Along a
    /// row's ray r and mu are fixed at each node, so Delta J there is first interpolated
    /// in (r, mu) for every (mu_s, nu) texel once per row, then in mu_s and nu for each
    /// texel of the row. Single precision: the sums have at most a few hundred terms.
    fn scattering_of(&self, density: &Table4) -> Table4 {
        let size = self.settings.scattering_size;
        let per_node = size.nu * size.mu_s;
        let mu_s_axis = MuSAxis::new(size.mu_s);
        self.map_rays(false, |nodes, texels, out| {
            // Delta J at each node over (nu, mu_s). The table holds mu_s fastest, then r,
            // so the two r corners of a nu slice are neighbouring runs of mu_s texels.
            let mut planes = vec![[0.0f32; 3]; nodes.len() * per_node];
            for (node, plane) in nodes.iter().zip(planes.chunks_exact_mut(per_node)) {
                let ((ir, wr), (imu, wmu)) = (node.r_axis, node.mu_axis);
                let (wr, wmu) = (wr as f32, wmu as f32);
                let w = [
                    (1.0 - wr) * (1.0 - wmu),
                    wr * (1.0 - wmu),
                    (1.0 - wr) * wmu,
                    wr * wmu,
                ];
                for (inu, slice) in plane.chunks_exact_mut(size.mu_s).enumerate() {
                    let lower = size.index(ir, imu, 0, inu);
                    let upper = size.index(ir, imu + 1, 0, inu);
                    let run = |start: usize| &density.data[start..start + 2 * size.mu_s];
                    let (a, b) = (run(lower), run(upper));
                    for (j, v) in slice.iter_mut().enumerate() {
                        let (a0, a1) = (a[j], a[j + size.mu_s]);
                        let (b0, b1) = (b[j], b[j + size.mu_s]);
                        for k in 0..3 {
                            v[k] = w[0] * a0[k] + w[1] * a1[k] + w[2] * b0[k] + w[3] * b1[k];
                        }
                    }
                }
            }
            let weights: Vec<[f32; 3]> = nodes
                .iter()
                .map(|n| n.weighted_transmittance.map(|t| t as f32))
                .collect();
            for &(mu_s, nu) in texels {
                let (inu, wnu) = axis(u_nu(nu), size.nu);
                let wnu = wnu as f32;
                let mut sum = [0.0f32; 3];
                for ((node, plane), t) in nodes
                    .iter()
                    .zip(planes.chunks_exact(per_node))
                    .zip(&weights)
                {
                    let (imus, wmus) = mu_s_axis.at(node.sun_cosine(mu_s, nu));
                    let lo = &plane[inu * size.mu_s + imus..];
                    let hi = &plane[(inu + 1) * size.mu_s + imus..];
                    for k in 0..3 {
                        let a = lo[0][k] + wmus * (lo[1][k] - lo[0][k]);
                        let b = hi[0][k] + wmus * (hi[1][k] - hi[0][k]);
                        sum[k] += t[k] * (a + wnu * (b - a));
                    }
                }
                out.push([sum.map(f64::from), [0.0; 3]]);
            }
        })
        .0
    }

    /// Per-channel sums of a table's radiance over the texels (phase functions applied
    /// for single scattering).
    fn sums(&self, previous: Previous) -> [f64; 3] {
        let size = self.settings.scattering_size;
        let mut out = [0.0; 3];
        for index in 0..size.texels() {
            let v = match previous {
                Previous::Single { rayleigh: ray, mie } => {
                    let (ir, imu, imus, inu) = size.coords(index);
                    let (_, _, _, nu, _) = texel_parameters(&self.radii, &size, ir, imu, imus, inu);
                    let pr = rayleigh(nu);
                    let mut v = ray.data[index].map(|a| pr * a as f64);
                    if let Some(mie) = mie {
                        let pm = self.atmosphere.mie.phase.eval(nu);
                        for k in 0..3 {
                            v[k] += pm * mie.data[index][k] as f64;
                        }
                    }
                    v
                }
                Previous::Multiple(t) => t.data[index].map(f64::from),
            };
            for k in 0..3 {
                out[k] += v[k];
            }
        }
        out
    }

    /// Algorithm 4.1.
    pub fn build(&self) -> Tables {
        let start = Instant::now();
        let (single_rayleigh, single_mie) = self.single_scattering();
        let first = OrderStats {
            order: 1,
            share: 1.0,
            seconds: start.elapsed().as_secs_f64(),
        };
        self.multiple_orders(single_rayleigh, single_mie, first)
    }

    /// Algorithm 4.1 from its loop on, given the single-scattering tables (built by
    /// [`Builder::single_scattering`] and timed in `first`): orders two and up and the
    /// irradiance table.
    pub fn multiple_orders(
        &self,
        single_rayleigh: Table4,
        single_mie: Option<Table4>,
        first: OrderStats,
    ) -> Tables {
        let size = self.settings.scattering_size;
        let mut orders = vec![first];
        let mut totals = self.sums(Previous::Single {
            rayleigh: &single_rayleigh,
            mie: single_mie.as_ref(),
        });
        let mapping = IrradianceMapping {
            radii: self.radii,
            mu_s_size: self.settings.irradiance_size.0,
            r_size: self.settings.irradiance_size.1,
        };
        let mut multiple = Table4::zeros(size);
        let mut irradiance = IrradianceTable::zeros(mapping);
        let mut previous_table: Option<Table4> = None;
        let mut previous_e: Option<IrradianceTable> = None;
        let mut previous_added: Option<[f64; 3]> = None;
        for order in 2..=self.max_orders {
            let start = Instant::now();
            let previous = match &previous_table {
                None => Previous::Single {
                    rayleigh: &single_rayleigh,
                    mie: single_mie.as_ref(),
                },
                Some(t) => Previous::Multiple(t),
            };
            let previous_irradiance = match &previous_e {
                None => PreviousIrradiance::Direct,
                Some(e) => PreviousIrradiance::Table(e),
            };
            // Delta E of order - 1 lights the ground for this order's reflection.
            let delta_e = self.irradiance_of(previous);
            let density = self.scattering_density(previous, previous_irradiance);
            let delta_s = self.scattering_of(&density);
            let added = self.sums(Previous::Multiple(&delta_s));
            // No order can hold more light than the one before it: growth means the
            // approximations of the order step amplify (optically thick atmospheres), so
            // stop without it rather than diverge.
            if let Some(before) = previous_added
                && (0..3).any(|k| added[k] > before[k])
            {
                orders.push(OrderStats {
                    order,
                    share: f64::NAN,
                    seconds: start.elapsed().as_secs_f64(),
                });
                break;
            }
            previous_added = Some(added);
            irradiance.add(&delta_e);
            multiple.add(&delta_s);
            let mut share: f64 = 0.0;
            for k in 0..3 {
                totals[k] += added[k];
                if totals[k] > 0.0 {
                    share = share.max(added[k] / totals[k]);
                }
            }
            orders.push(OrderStats {
                order,
                share,
                seconds: start.elapsed().as_secs_f64(),
            });
            previous_table = Some(delta_s);
            previous_e = Some(delta_e);
            if share < self.settings.order_threshold {
                break;
            }
        }
        Tables {
            channels: self.channels,
            single_rayleigh,
            single_mie,
            multiple,
            irradiance,
            orders,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delta_m_of_henyey_greenstein_has_its_known_moments() {
        let g: f64 = 0.8;
        let dm = DeltaM::new(&PhaseFunction::HenyeyGreenstein { g });
        let f = g.powi(3);
        assert!((dm.forward_fraction - f).abs() < 1e-4, "{dm:?}");
        assert!((dm.chi1 - (g - f) / (1.0 - f)).abs() < 1e-4, "{dm:?}");
        assert!((dm.chi2 - (g * g - f) / (1.0 - f)).abs() < 1e-4, "{dm:?}");
    }
}
