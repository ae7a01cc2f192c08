//! The integrals along every texel's view ray (Bruneton and Neyret 2008, Algorithm 4.1):
//! single scattering (Eq. 5 with a point sun) and Delta S of each order, T times Delta J
//! integrated by the trapezoid rule on nodes shared by a texel row.

use rayon::prelude::*;

use crate::models::bruneton::builder::{Builder, to_f32};
use crate::models::bruneton::node_placement::{FINE_PER_NODE, crowded_distance, density_distances};
use crate::models::bruneton::parameterization::{
    AngleMapping, NuAxis, axis, azimuth_unit, table_position, texel_parameters,
};
use crate::models::bruneton::tables::{Table4, along_mu_s};
use crate::optics::column::optical_depth;
use crate::optics::geometry::radius_at;

/// One trapezoid node of a texel row's ray (see `Builder::ray_nodes`).
#[derive(Clone, Copy, Debug)]
struct RayNode {
    r: f64,
    /// The view's zenith cosine at the node (for `nu_edge`'s weights and
    /// `nu_by_azimuth`'s texels).
    mu: f64,
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

/// [`axis`] of [`AngleMapping::u_mu_s`] tabulated over mu_s in [-1, 1] (4097 points,
/// linearly interpolated: within 1e-5 of a texel of the exact position in the table's
/// range at the paper's sizes), to spare an exponential per node and texel of Delta S.
struct MuSAxis {
    size: usize,
    positions: Vec<f64>,
}

impl MuSAxis {
    const POINTS: usize = 4097;

    fn new(size: usize, angles: &AngleMapping) -> MuSAxis {
        let step = 2.0 / (Self::POINTS - 1) as f64;
        MuSAxis {
            size,
            positions: (0..Self::POINTS)
                .map(|i| angles.u_mu_s(-1.0 + step * i as f64) * (size - 1) as f64)
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

impl Builder<'_> {
    /// The trapezoid nodes along the ray of texel row (r, mu), placed by
    /// `node_placement.rs` (crowded, or by density with `density_nodes`): distance, radius, mu there,
    /// densities, the trapezoid weight times the transmittance from the ray's start (from
    /// a running trapezoid of the densities), and the r and mu axes of the table there.
    /// Every texel with this (r, mu) shares them; only mu_s and nu differ.
    fn ray_nodes(&self, r: f64, mu: f64, ground: bool) -> Vec<RayNode> {
        let d = self.ray_length(r, mu, ground);
        let n = self.settings.view_samples.max(1);
        let size = self.settings.scattering_size;
        let crowded = |i: usize, count: usize| crowded_distance(d, mu >= 0.0, ground, i, count);
        let distances: Vec<f64> = if self.settings.density_nodes {
            let extinction = |t: f64| {
                let r_t = radius_at(r, mu, t).clamp(self.radii.bottom_m, self.radii.top_m);
                let rho = self.densities.at(r_t - self.radii.bottom_m);
                optical_depth(rho, self.channels.extinction[1])
            };
            density_distances(n, |j| crowded(j, FINE_PER_NODE * n), extinction)
        } else {
            (0..=n).map(|i| crowded(i, n)).collect()
        };
        let position = |i: usize| distances[i];
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
                mu: mu_t,
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

    /// Delta S of an order: T times Delta J integrated along every texel's ray. Along a
    /// row's ray r and mu are fixed at each node, so Delta J there is first interpolated
    /// in (r, mu) for every (mu_s, nu) texel once per row, then in mu_s and nu for each
    /// texel of the row. Single precision: the sums have at most a few hundred terms.
    pub(crate) fn scattering_of(&self, density: &Table4) -> Table4 {
        let size = self.settings.scattering_size;
        let per_node = size.nu * size.mu_s;
        let mu_s_axis = MuSAxis::new(size.mu_s, &size.angles);
        // Which pairs of neighbouring mu_s texels Delta J is read between geometrically
        // (`geometric_mu_s`: both suns below the horizontal; `along_mu_s`).
        let geometric: Vec<bool> = (0..size.mu_s)
            .map(|i| size.angles.geometric_pair(i, size.mu_s))
            .collect();
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
            let by_azimuth = size.angles.nu_by_azimuth;
            for &(mu_s, nu) in texels {
                let nu_axis = NuAxis::new(&size.angles, size.nu, nodes[0].mu, mu_s, nu);
                // The nu weight moves along the ray with `nu_edge` (the node's mu and
                // mu_s bound its nu), and the texels too with `nu_by_azimuth` (the node's
                // mu and mu_s turn the ray's nu into another azimuth); else both are the
                // texel's own.
                let fixed = (!size.angles.nu_edge).then_some(nu_axis.nominal_weight as f32);
                let mut sum = [0.0f32; 3];
                for ((node, plane), t) in nodes
                    .iter()
                    .zip(planes.chunks_exact(per_node))
                    .zip(&weights)
                {
                    let mu_s_t = node.sun_cosine(mu_s, nu);
                    let (inu, wnu) = if by_azimuth {
                        let (i, w) = axis(azimuth_unit(node.mu, mu_s_t, nu), size.nu);
                        (i, w as f32)
                    } else {
                        let w = fixed.unwrap_or_else(|| nu_axis.weight(node.mu, mu_s_t) as f32);
                        (nu_axis.lower, w)
                    };
                    let (imus, wmus) = mu_s_axis.at(mu_s_t);
                    let lo = &plane[inu * size.mu_s + imus..];
                    let hi = &plane[(inu + 1) * size.mu_s + imus..];
                    for k in 0..3 {
                        let (a, b) = if geometric[imus] {
                            let g = |x: f32, y: f32| {
                                along_mu_s(f64::from(x), f64::from(y), f64::from(wmus), true) as f32
                            };
                            (g(lo[0][k], lo[1][k]), g(hi[0][k], hi[1][k]))
                        } else {
                            (
                                lo[0][k] + wmus * (lo[1][k] - lo[0][k]),
                                hi[0][k] + wmus * (hi[1][k] - hi[0][k]),
                            )
                        };
                        sum[k] += t[k] * (a + wnu * (b - a));
                    }
                }
                out.push([sum.map(f64::from), [0.0; 3]]);
            }
        })
        .0
    }
}
