//! The fractions of a parallel beam a slab reflects, transmits and absorbs (fluxes
//! through its top and base over the incident flux, hemispherical), by Monte Carlo with
//! standard errors from the per-path variance.

use glam::DVec3;

use super::error::{CloudError, check_range};
use super::estimate::{Estimate, Tally};
use super::slab::Slab;
use super::tracking::{PathEnd, trace_path};
use crate::numerics::sampling::{Sampler, mix_seed};

/// The most paths one run traces.
pub const MAX_PATHS: u64 = 100_000_000;

/// A slab's response to a beam, each a fraction of the incident flux.
#[derive(Clone, Copy, Debug)]
pub struct SlabFractions {
    /// Out through the top, all orders of scattering.
    pub reflected: Estimate,
    /// Out through the base, direct beam included.
    pub transmitted: Estimate,
    /// Out through the base without a real collision: exp(-tau / mu0) in expectation.
    pub transmitted_direct: Estimate,
    pub absorbed: Estimate,
    /// Reflected + transmitted, with the standard error of the per-path sum.
    pub escaped: Estimate,
}

/// Traces `paths` paths entering the top of `slab` with cosine `mu0` in (0, 1] of the
/// beam's angle from the downward vertical, with seed `seed`.
pub fn slab_fractions(
    slab: &Slab,
    mu0: f64,
    paths: u64,
    seed: u64,
) -> Result<SlabFractions, CloudError> {
    check_range("incident cosine mu0", mu0, 0.0, 1.0)?;
    if mu0 == 0.0 {
        return Err(CloudError(
            "incident cosine mu0 = 0 is a grazing beam that never enters the slab".into(),
        ));
    }
    if !(2..=MAX_PATHS).contains(&paths) {
        return Err(CloudError(format!(
            "paths = {paths} must lie in [2, {MAX_PATHS}]"
        )));
    }
    let entry = DVec3::new(0.0, 0.0, slab.thickness_m());
    let direction = DVec3::new((1.0 - mu0 * mu0).sqrt(), 0.0, -mu0);
    let mut sampler = Sampler::new(mix_seed(&[seed]));
    let [
        mut reflected,
        mut transmitted,
        mut direct,
        mut absorbed,
        mut escaped,
    ] = [Tally::default(); 5];
    for _ in 0..paths {
        let (r, t, d, a) = match trace_path(slab, entry, direction, &mut sampler) {
            PathEnd::Escaped {
                direction,
                scatterings,
                weight,
                ..
            } => {
                if direction.z > 0.0 {
                    (weight, 0.0, 0.0, 0.0)
                } else {
                    let direct = if scatterings == 0 { weight } else { 0.0 };
                    (0.0, weight, direct, 0.0)
                }
            }
            PathEnd::Absorbed { weight } => (0.0, 0.0, 0.0, weight),
        };
        reflected.add(r);
        transmitted.add(t);
        direct.add(d);
        absorbed.add(a);
        escaped.add(r + t);
    }
    Ok(SlabFractions {
        reflected: reflected.estimate(),
        transmitted: transmitted.estimate(),
        transmitted_direct: direct.estimate(),
        absorbed: absorbed.estimate(),
        escaped: escaped.estimate(),
    })
}
