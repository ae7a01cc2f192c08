//! Where the trapezoid nodes along a texel's ray lie, for single scattering and each
//! order's Delta S (Bruneton and Neyret 2008, section 4 and Algorithm 4.1, lines 3 and 8:
//! integrals along the ray of every texel of S). The paper's code spaces them evenly; by
//! default here they crowd quadratically towards the dense end of climbing and
//! descending rays (`crowded_distance`). With `density_nodes` they are placed by the
//! density's integral (`density_distances`), so that a thin, dense boundary layer (the
//! hazy preset's 1.2 km of aerosol) gets its share of nodes on every ray that crosses it.

/// Fine points per node of the march that places nodes by density.
pub const FINE_PER_NODE: usize = 4;

/// Distance of node i of n along a ray of length `length`: quadratic crowding towards the
/// start of climbing rays (`climbing`: mu >= 0), towards the end of rays that meet the
/// ground, evenly spaced on rays through a tangent point.
pub fn crowded_distance(length: f64, climbing: bool, ground: bool, i: usize, n: usize) -> f64 {
    let u = i as f64 / n as f64;
    if climbing {
        length * u * u
    } else if ground {
        length * (1.0 - (1.0 - u) * (1.0 - u))
    } else {
        length * u
    }
}

/// The distances of n + 1 nodes (n >= 1) at equal steps of
/// m(t) = t / d + a(tau(t)) / a(tau(d)), d the ray's length, tau the optical depth from
/// the ray's start and a(tau) = 1 - exp(-tau) the share of light that meets matter
/// before t (the integral of the integrand's density times transmittance): half the
/// nodes by distance, so that thin air keeps some, half by that share, so that a dense
/// layer gets nodes in proportion to the light it scatters and an opaque stretch beyond
/// it none. tau is the trapezoid of `extinction(t)` (per metre) over `FINE_PER_NODE` n
/// fine points at distances `fine(j)` (j = 0..=FINE_PER_NODE n, increasing from 0 to
/// d); m is inverted linearly between them. Without matter (tau(d) = 0) the nodes are
/// the fine points' by distance.
pub fn density_distances(
    n: usize,
    fine: impl Fn(usize) -> f64,
    extinction: impl Fn(f64) -> f64,
) -> Vec<f64> {
    let count = FINE_PER_NODE * n;
    let t: Vec<f64> = (0..=count).map(&fine).collect();
    let mut tau = vec![0.0; count + 1];
    let mut previous = extinction(t[0]);
    for j in 1..=count {
        let e = extinction(t[j]);
        tau[j] = tau[j - 1] + 0.5 * (t[j] - t[j - 1]) * (previous + e);
        previous = e;
    }
    let (length, depth) = (t[count], interacted(tau[count]));
    if length <= 0.0 {
        return vec![0.0; n + 1];
    }
    let measure = |j: usize| {
        let by_distance = t[j] / length;
        by_distance
            + if depth > 0.0 {
                interacted(tau[j]) / depth
            } else {
                by_distance
            }
    };
    let mut out = Vec::with_capacity(n + 1);
    out.push(0.0);
    let mut j = 0;
    for i in 1..n {
        let target = 2.0 * i as f64 / n as f64;
        while j + 1 < count && measure(j + 1) < target {
            j += 1;
        }
        let (m0, m1) = (measure(j), measure(j + 1));
        let w = if m1 > m0 {
            ((target - m0) / (m1 - m0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        out.push(t[j] + w * (t[j + 1] - t[j]));
    }
    out.push(length);
    out
}

/// 1 - exp(-tau), by its series below 1e-3 (as the GPU computes it in single
/// precision).
pub fn interacted(tau: f64) -> f64 {
    if tau < 1e-3 {
        tau * (1.0 - 0.5 * tau)
    } else {
        1.0 - (-tau).exp()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_the_nodes_fall_where_the_light_meets_a_dense_layer() {
        // A 100 km ray whose first 1 km holds 99 % of the matter (optical depth 0.99 of
        // 1): by distance alone 1 % of the nodes would fall there; with the light that
        // meets matter there (0.99 of all that does) about half of them.
        let n = 40;
        let fine = |j: usize| crowded_distance(100e3, false, false, j, FINE_PER_NODE * n);
        let extinction = |t: f64| if t < 1e3 { 0.99e-3 } else { 1e-7 };
        let d = density_distances(n, fine, extinction);
        assert_eq!(d.len(), n + 1);
        assert_eq!((d[0], d[n]), (0.0, 100e3));
        assert!(d.windows(2).all(|w| w[1] >= w[0]), "{d:?}");
        let inside = d.iter().filter(|&&t| t < 1e3).count();
        assert!(
            (18..=22).contains(&inside),
            "{inside} of {n} nodes in the layer"
        );
    }

    #[test]
    fn an_opaque_stretch_gets_only_the_nodes_by_distance() {
        // Optical depth 10 in the first 10 km of 100 km: the light meets matter in the
        // first 3 km (95 %), so half the nodes go there and the rest by distance.
        let n = 40;
        let fine = |j: usize| crowded_distance(100e3, false, false, j, FINE_PER_NODE * n);
        let d = density_distances(n, fine, |t| if t < 10e3 { 1e-3 } else { 0.0 });
        let first = d.iter().filter(|&&t| t < 3e3).count();
        let opaque = d.iter().filter(|&&t| (3e3..10e3).contains(&t)).count();
        assert!((20..=23).contains(&first), "{first} {d:?}");
        assert!(opaque <= 4, "{opaque} {d:?}");
    }

    #[test]
    fn without_matter_the_nodes_are_placed_by_distance() {
        let n = 8;
        let fine = |j: usize| crowded_distance(10.0, false, false, j, FINE_PER_NODE * n);
        let d = density_distances(n, fine, |_| 0.0);
        for (i, t) in d.iter().enumerate() {
            assert!((t - 10.0 * i as f64 / n as f64).abs() < 1e-9, "{d:?}");
        }
    }
}
