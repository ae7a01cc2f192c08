//! The ground truth of the rain shaft, cirrus layer and droplet deck in planet frames: a
//! Monte Carlo path tracer through a homogeneous volume (all orders of scattering, the
//! volume's own phase table at the frame's three wavelengths, next-event estimation of
//! the sun through the atmosphere at every collision, the sky model's light where a
//! path leaves), composited with the sky model's air in front of and behind the volume,
//! with a standard error per ray. The pieces are the cloud path tracer's
//! (`clouds/reference/`: the phase sampler, the sun through the atmosphere, the light
//! around the volume, the tally and the stopping rule); [`phase`] draws directions
//! from a channel table, [`path`] follows one path, [`ray`] answers a view ray.

pub mod path;
pub mod phase;
pub mod ray;
