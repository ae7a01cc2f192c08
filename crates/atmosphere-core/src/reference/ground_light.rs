//! The light of order two and up that the ground reflects, estimated once and shared by
//! every view ray that ends on the ground in the umbra (`shared_ground=true`).
//!
//! Over spherical shells, a uniform Lambertian ground and a far sun, the light scattered
//! at least once that reaches a ground point depends on one number alone: mu_s, the
//! cosine of the sun's zenith angle there (the parameterization of Bruneton and Neyret
//! 2008, section 4, at the ground's radius, the view's angles integrated over the
//! hemisphere). The ground sends a view ray its albedo times G(mu_s) = E(mu_s) / pi,
//! E the irradiance of that light, times the ray's transmittance.
//!
//! Drawn per ray (`last_event.rs`), each path from the ground picks one direction of the
//! sky and follows one path along it, so a ray carries the whole noise of the twilight
//! sky. Here G is the mean of the sky's radiance over the cosine-weighted hemisphere,
//! estimated on nodes of mu_s: the hemisphere is cut into strata (in elevation, narrow
//! near the horizon, by azimuth over half a turn, the sky being symmetric about the
//! sun's vertical plane), two directions are drawn in each from the cosine-weighted
//! density within it, and the sky's radiance
//! along each is the reference's own: single scattering by quadrature and the higher
//! orders by the guided estimator of the sky's rays. With two directions per stratum the
//! spread within each stratum gives the standard error, directions and paths together.
//! A ray takes the linear interpolation between the two nodes about its ground point's
//! mu_s; every ground ray near a camera falls between the same two.
//!
//! A node is computed in a frame of its own (the sun along +z, the point in the x-z
//! plane) from a seed of the reference's seed, the node and the side, so it is the same
//! whichever ray asks first. Rays travelling to either side of the sun's vertical plane
//! at their ground point take nodes of their own: a ray and its mirror image about that
//! plane carry the same radiance, and their estimates stay independent, so their mean
//! has half the variance of one (the report pools them).

use std::collections::HashMap;
use std::f64::consts::PI;
use std::sync::{Arc, Mutex, OnceLock};

use glam::DVec3;

use crate::models::error::ModelError;
use crate::models::sky_model::ViewRay;
use crate::numerics::sampling::{Sampler, mix_seed, orthonormal_basis};

/// Spacing of the nodes in mu_s: the interpolation's error, an eighth of the second
/// difference of neighbouring nodes, lies far below their Monte Carlo error
/// (docs/models/reference.md, "The ground's light, shared").
pub(crate) const MU_S_STEP: f64 = 1e-3;

/// Edges of the strata in elevation, degrees: narrow near the horizon, where twilight's
/// bright band changes fastest with elevation.
const ELEVATION_EDGES_DEG: [f64; 14] = [
    0.0, 1.0, 2.0, 3.5, 5.5, 8.0, 11.0, 15.0, 20.0, 27.0, 36.0, 48.0, 64.0, 90.0,
];
/// Strata in azimuth over half a turn from the sun's.
const AZIMUTH_STRATA: usize = 8;
/// Directions drawn in each stratum: two, so that their spread gives its variance.
const PER_STRATUM: usize = 2;
/// Rays of the sky a node follows.
pub(crate) const NODE_RAYS: usize = (ELEVATION_EDGES_DEG.len() - 1) * AZIMUTH_STRATA * PER_STRATUM;

/// G at one node and wavelength (units of the spectral radiance), with its standard
/// error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroundEstimate {
    pub mean: f64,
    pub std_error: f64,
}

/// The sky's radiance along a ray from the ground, per wavelength (an unbiased
/// estimate); the second argument is the ray's seed.
pub(crate) type SkyRadiance<'a> =
    &'a (dyn Fn(&ViewRay, u64) -> Result<Vec<f64>, ModelError> + Sync);

/// Which node: the node of mu_s, the side of the sun's plane, the guiding (as a number).
type NodeKey = (i64, bool, u8);

/// A node's estimate per wavelength, or why its rays failed; computed once.
type Node = Arc<OnceLock<Result<Vec<GroundEstimate>, String>>>;

/// One stratum's weighted mean and its variance per wavelength, or why a ray failed.
type Stratum = Result<Vec<(f64, f64)>, ModelError>;

/// The nodes estimated so far, each computed once, on first use, for every wavelength.
#[derive(Debug, Default)]
pub(crate) struct GroundLight {
    nodes: Mutex<HashMap<NodeKey, Node>>,
}

impl GroundLight {
    /// G at wavelength index `w` for a ray travelling along `direction` to the ground
    /// point `point` (planet-centred), the sun towards `sun`: the two nodes about its mu_s
    /// interpolated linearly, with the standard error of that interpolation of
    /// independent nodes. `guiding` (a number for the key) and `seed` set the nodes;
    /// `sky` follows the rays of a node.
    pub(crate) fn reflected(
        &self,
        w: usize,
        (point, direction, sun): (DVec3, DVec3, DVec3),
        (guiding, seed): (u8, u64),
        bottom_radius_m: f64,
        sky: SkyRadiance<'_>,
    ) -> Result<GroundEstimate, ModelError> {
        let up = point.normalize();
        let mu_s = up.dot(sun).clamp(-1.0, 1.0);
        let side = direction.dot(up.cross(sun)) < 0.0;
        let x = mu_s / MU_S_STEP;
        let below = x.floor();
        let t = x - below;
        let node = |k: i64| -> Result<GroundEstimate, ModelError> {
            let cell = {
                let mut nodes = self.nodes.lock().unwrap_or_else(|e| e.into_inner());
                nodes.entry((k, side, guiding)).or_default().clone()
            };
            let node = cell.get_or_init(|| {
                let seed = mix_seed(&[seed, k as u64, side as u64, guiding as u64]);
                estimate_node(k as f64 * MU_S_STEP, bottom_radius_m, seed, sky)
                    .map_err(|e| e.to_string())
            });
            match node {
                Ok(values) => Ok(values[w]),
                Err(why) => Err(ModelError::Ray(format!("the ground's shared light: {why}"))),
            }
        };
        let (a, b) = (node(below as i64)?, node(below as i64 + 1)?);
        Ok(GroundEstimate {
            mean: (1.0 - t) * a.mean + t * b.mean,
            std_error: ((1.0 - t) * a.std_error).hypot(t * b.std_error),
        })
    }
}

/// G at `mu_s` for every wavelength, in the node's own frame: the sum over the strata of
/// their cosine weight times the mean of the sky's radiance on their two directions, its
/// variance the sum of weight^2 (difference of the two)^2 / 4. The strata run on
/// threads of their own (not the caller's pool: a node is computed inside its lock,
/// where a pool could hand the thread another ray waiting on that lock), each from its
/// own seed, so the node is the same whatever the number of threads.
fn estimate_node(
    mu_s: f64,
    bottom_radius_m: f64,
    seed: u64,
    sky: SkyRadiance<'_>,
) -> Result<Vec<GroundEstimate>, ModelError> {
    let mu_s = mu_s.clamp(-1.0, 1.0);
    let sun = DVec3::Z;
    let point = bottom_radius_m * DVec3::new((1.0 - mu_s * mu_s).sqrt(), 0.0, mu_s);
    let up = point.normalize();
    let towards_sun = (sun - up * sun.dot(up))
        .try_normalize()
        .unwrap_or_else(|| orthonormal_basis(up).0);
    let side = up.cross(towards_sun);
    let strata = (ELEVATION_EDGES_DEG.len() - 1) * AZIMUTH_STRATA;
    // The weighted mean of one stratum's two directions, and its variance, per wavelength.
    let stratum = |s: usize| -> Stratum {
        let (i, j) = (s / AZIMUTH_STRATA, s % AZIMUTH_STRATA);
        // The cosine-weighted measure is uniform in sin^2 of the zenith angle, the cos^2
        // of the elevation.
        let [low, high] = [i, i + 1].map(|e| ELEVATION_EDGES_DEG[e].to_radians().cos().powi(2));
        let weight = (low - high) / AZIMUTH_STRATA as f64;
        let mut sampler = Sampler::new(mix_seed(&[seed, i as u64, j as u64]));
        let mut pair = Vec::with_capacity(PER_STRATUM);
        for k in 0..PER_STRATUM {
            let sin2 = high + (low - high) * sampler.uniform();
            let phi = PI * (j as f64 + sampler.uniform()) / AZIMUTH_STRATA as f64;
            let (sin, cos) = (sin2.sqrt(), (1.0 - sin2).max(0.0).sqrt());
            let direction = sin * phi.cos() * towards_sun + sin * phi.sin() * side + cos * up;
            let ray = ViewRay {
                origin_m: point,
                direction,
                sun_direction: sun,
                max_distance_m: None,
            };
            pair.push(sky(&ray, mix_seed(&[seed, i as u64, j as u64, k as u64]))?);
        }
        Ok(pair[0]
            .iter()
            .zip(&pair[1])
            .map(|(a, b)| {
                (
                    weight * 0.5 * (a + b),
                    weight * weight * 0.25 * (a - b).powi(2),
                )
            })
            .collect())
    };
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(strata);
    let mut results: Vec<Option<Stratum>> = (0..strata).map(|_| None).collect();
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                let stratum = &stratum;
                scope.spawn(move || {
                    (t..strata)
                        .step_by(threads)
                        .map(|s| (s, stratum(s)))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        for handle in handles {
            let done = handle
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            for (s, result) in done {
                results[s] = Some(result);
            }
        }
    });
    let mut sum: Vec<(f64, f64)> = Vec::new();
    for result in results.into_iter().flatten() {
        let values = result?;
        if sum.is_empty() {
            sum = vec![(0.0, 0.0); values.len()];
        }
        for (total, (mean, variance)) in sum.iter_mut().zip(values) {
            total.0 += mean;
            total.1 += variance;
        }
    }
    Ok(sum
        .iter()
        .map(|(mean, variance)| GroundEstimate {
            mean: *mean,
            std_error: variance.sqrt(),
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    const EARTH_RADIUS_M: f64 = 6_360_000.0;

    /// A node of a sky whose radiance is `f(direction, up)` on every wavelength (two).
    fn node_of(
        f: impl Fn(DVec3, DVec3) -> f64 + Sync,
        mu_s: f64,
        seed: u64,
    ) -> Vec<GroundEstimate> {
        let sky = |ray: &ViewRay, _seed: u64| {
            let value = f(ray.direction, ray.origin_m.normalize());
            Ok(vec![value, 2.0 * value])
        };
        estimate_node(mu_s, EARTH_RADIUS_M, seed, &sky).unwrap()
    }

    #[test]
    fn the_strata_weigh_the_hemisphere_by_the_cosine() {
        // A uniform sky of radiance L gives G = E / pi = L, exactly and without error.
        for g in node_of(|_, _| 1.0, -0.2, 1).iter().zip([1.0, 2.0]) {
            assert!(
                (g.0.mean - g.1).abs() < 1e-12 && g.0.std_error == 0.0,
                "{g:?}"
            );
        }
        // L = cos(zenith): G = (1/pi) * integral of cos^2 over the hemisphere = 2/3, within
        // the reported error (from the two directions of each stratum).
        let g = node_of(|d, up| d.dot(up), 0.3, 2)[0];
        assert!(g.std_error > 0.0 && g.std_error < 0.01, "{g:?}");
        assert!((g.mean - 2.0 / 3.0).abs() < 4.0 * g.std_error, "{g:?}");
        // Every direction is above the ground.
        let g = node_of(|d, up| f64::from(d.dot(up) < 0.0), -0.1, 3)[0];
        assert_eq!(g.mean, 0.0);
    }

    #[test]
    fn the_errors_describe_the_scatter_between_seeds() {
        // A sky bright in a band near the horizon towards the sun, like twilight's: the
        // nodes' spread over seeds matches their reported standard error.
        let band = |d: DVec3, up: DVec3| {
            let elevation = d.dot(up).asin().to_degrees();
            let towards_sun = (DVec3::Z - up * up.z).normalize().dot(d).max(0.0);
            1.0 + 20.0 * (-elevation / 4.0).exp() * towards_sun
        };
        let runs: Vec<GroundEstimate> = (0..24).map(|s| node_of(band, -0.2, s)[0]).collect();
        let mean = runs.iter().map(|g| g.mean).sum::<f64>() / runs.len() as f64;
        let spread = (runs.iter().map(|g| (g.mean - mean).powi(2)).sum::<f64>()
            / (runs.len() - 1) as f64)
            .sqrt();
        let reported = runs.iter().map(|g| g.std_error).sum::<f64>() / runs.len() as f64;
        assert!(
            spread > 0.6 * reported && spread < 1.6 * reported,
            "spread {spread:e} reported {reported:e}"
        );
        assert!(reported < 0.02 * mean, "{reported:e} of {mean:e}");
    }

    #[test]
    fn a_ray_takes_its_nodes_by_side_and_interpolates_between_them() {
        // A sky whose radiance is the node's mu_s plus a draw of its seed: the nodes tell
        // which seed and frame they were computed with.
        let sky = |ray: &ViewRay, seed: u64| {
            let mu_s = ray.origin_m.normalize().z;
            Ok(vec![mu_s + (seed % 1000) as f64 * 1e-9])
        };
        let light = GroundLight::default();
        let sun = DVec3::Z;
        let at = |mu_s: f64, along: DVec3| {
            let point = EARTH_RADIUS_M * DVec3::new((1.0 - mu_s * mu_s).sqrt(), 0.0, mu_s);
            light
                .reflected(0, (point, along, sun), (2, 7), EARTH_RADIUS_M, &sky)
                .unwrap()
                .mean
        };
        let (left, right) = (DVec3::Y, -DVec3::Y);
        // Linear in mu_s between the nodes, up to the seeds' draws.
        let mid = -0.2005;
        assert!((at(mid, left) - mid).abs() < 2e-6, "{}", at(mid, left));
        // The same ground point and side: the same nodes, the same value; the other side:
        // nodes of their own.
        assert_eq!(at(mid, left), at(mid, left + 0.1 * DVec3::Z));
        assert_ne!(at(mid, left), at(mid, right));
    }
}
