//! The guide's mixture with the phase function, checked through the path tracer.

use glam::DVec3;

use crate::numerics::sampling::Sampler;
use crate::reference::Reference;
use crate::reference::guide::DirectionGuide;
use crate::reference::path_tracer::PathTracer;
use crate::reference::scatterer::Scatterer;
use crate::reference::twilight_fixture::nautical_twilight_at_440;

/// Directions drawn from the mixture of guide and phase function (or cosine) carry
/// weights whose mean is the integral of the phase function (or of cosine / pi over
/// the hemisphere): 1. A guide whose density disagreed with its draws would miss it.
#[test]
fn mixture_weights_integrate_the_phase_function_and_the_cosine() {
    let (earth, settings, sun) = nautical_twilight_at_440();
    let reference = Reference::prepare(&earth, &settings).unwrap();
    let unguided = reference.tracer(0, sun);
    let ground = DVec3::new(0.0, 0.0, earth.bottom_radius_m);
    let air = DVec3::new(0.0, 0.0, earth.bottom_radius_m + 12_000.0);
    for (anchor, scatterer) in [
        (
            air,
            Scatterer::Air {
                rayleigh: 2e-6,
                mie: 1e-6,
            },
        ),
        (ground, Scatterer::Ground(DVec3::Z)),
    ] {
        assert!(unguided.in_umbra(anchor));
        let guide = DirectionGuide::new(anchor, sun, |d| unguided.rough_incoming(anchor, d))
            .expect("lit air in view");
        let tracer = PathTracer {
            guide: Some(&guide),
            ..unguided
        };
        let outgoing = DVec3::new(0.3, 0.2, 0.9).normalize();
        let mut sampler = Sampler::new(3);
        let n = 200_000;
        let (mut sum, mut sum_sq, mut towards_sun) = (0.0, 0.0, 0usize);
        for _ in 0..n {
            let (direction, weight) = tracer.scatter(anchor, outgoing, scatterer, &mut sampler);
            sum += weight;
            sum_sq += weight * weight;
            towards_sun += usize::from(direction.dot(sun) > 0.9);
        }
        let mean = sum / n as f64;
        let std_error = ((sum_sq / n as f64 - mean * mean) / n as f64).sqrt();
        assert!(
            (mean - 1.0).abs() < 4.0 * std_error,
            "{scatterer:?}: mean weight {mean} +- {std_error}"
        );
        // The guide does send directions towards the sun, where the lit air is.
        assert!(towards_sun > n / 4, "{scatterer:?}: {towards_sun} of {n}");
    }
}
