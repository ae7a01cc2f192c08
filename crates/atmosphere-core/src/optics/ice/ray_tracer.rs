//! One ray through a crystal by geometric optics: at the entry face the reflected part
//! leaves and the rest is refracted in; inside, the ray is attenuated by
//! exp(-4 pi k s / lambda) over a path s (Bohren and Huffman 1983, Eq. 2.52), and at each
//! face the transmitted part leaves (Fresnel, unpolarised) and the reflected part goes
//! on, until its weight is below [`WEIGHT_THRESHOLD`]. Every part that leaves is handed
//! to a callback with its direction and weight; the weights that leave, the absorbed
//! and the dropped remainder sum to the incident 1.

use glam::DVec3;

use super::crystal::HexagonalPrism;
use super::fresnel::{reflect, refract, unpolarised_reflectance};

/// The weight below which a ray inside is dropped (counted in [`RayOutcome::dropped`]).
pub const WEIGHT_THRESHOLD: f64 = 1e-7;

/// The most faces a ray meets inside before it is dropped: rays that came in must get
/// out (optics is reversible), so this only bounds the rare long paths.
pub const MAX_INTERACTIONS: usize = 10_000;

/// The medium's real index and the absorption coefficient 4 pi k / lambda.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IceOptics {
    pub index: f64,
    pub absorption_per_m: f64,
}

/// What became of one ray's unit weight besides what left the crystal.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RayOutcome {
    pub absorbed: f64,
    /// What was left inside below the threshold or past the interaction limit.
    pub dropped: f64,
}

/// Traces a ray that starts outside at `origin` travelling along unit `direction`;
/// None when it misses the crystal. `leave(direction, weight)` receives what leaves.
pub fn trace(
    crystal: &HexagonalPrism,
    optics: IceOptics,
    origin: DVec3,
    direction: DVec3,
    mut leave: impl FnMut(DVec3, f64),
) -> Option<RayOutcome> {
    let (t, normal) = crystal.entry(origin, direction)?;
    let n = optics.index;
    let mut point = origin + t * direction;
    let reflected = unpolarised_reflectance(1.0, n, -direction.dot(normal));
    leave(reflect(direction, normal), reflected);
    let mut weight = 1.0 - reflected;
    // Refraction into the denser medium always exists.
    let mut d = refract(direction, normal, 1.0 / n).unwrap_or(direction);
    let mut outcome = RayOutcome::default();
    for _ in 0..MAX_INTERACTIONS {
        let (s, face) = crystal.exit(point, d);
        point += s * d;
        let kept = weight * (-optics.absorption_per_m * s).exp();
        outcome.absorbed += weight - kept;
        weight = kept;
        let r = unpolarised_reflectance(n, 1.0, d.dot(face));
        if r < 1.0
            && let Some(out) = refract(d, -face, n)
        {
            leave(out, weight * (1.0 - r));
        }
        weight *= r;
        d = reflect(d, face);
        if weight < WEIGHT_THRESHOLD {
            break;
        }
    }
    outcome.dropped = weight;
    Some(outcome)
}
