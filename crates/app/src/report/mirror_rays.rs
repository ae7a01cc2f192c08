//! A view whose optical axis lies in the sun's vertical plane is symmetric about that
//! plane: its ray in column `c` of a row and its ray in column `columns - 1 - c` are
//! mirror images, and in the report's atmospheres (spherical shells over a uniform
//! ground, the sun far away) both carry the same radiance. The reference draws the two
//! with seeds of their own, so they are independent estimates of one value; pooled, each
//! pair is one estimate over twice the paths, at no cost (the standard error of the mean
//! of two, `reference_batches::pool_batch`). The cache keeps each ray's own estimate.

use atmosphere_core::models::sky_model::RayRadiance;

use crate::report::reference_batches::pool_batch;
use crate::report::reference_cache::ReferenceRadiance;
use crate::report::views::ReportView;

/// `reference` with every view's mirror rays pooled; other views as they are.
pub fn pool_mirror_rays(views: &[ReportView], reference: ReferenceRadiance) -> ReferenceRadiance {
    views
        .iter()
        .zip(reference)
        .map(|(view, answers)| pool_view(view, &answers))
        .collect()
}

/// One view's answers, each ray pooled with its mirror where it has one.
fn pool_view(view: &ReportView, answers: &[RayRadiance]) -> Vec<RayRadiance> {
    (0..answers.len())
        .map(|i| match view.mirror_ray(i) {
            Some(m) => pool_batch(
                std::slice::from_ref(&answers[i]),
                1,
                std::slice::from_ref(&answers[m]),
            )
            .remove(0),
            None => answers[i].clone(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::reference_batches::tests::ray;
    use crate::report::views::report_views;
    use atmosphere_core::atmosphere::Atmosphere;
    use atmosphere_core::models::id::ModelId;
    use atmosphere_core::models::registry::prepare;
    use atmosphere_core::models::sky_model::ModelSettings;

    fn view(id: &str) -> ReportView {
        report_views(16, 9)
            .into_iter()
            .find(|v| v.id == id)
            .unwrap()
    }

    #[test]
    fn mirror_rays_are_pooled_into_the_mean_of_two_and_its_standard_error() {
        let nautical = view("nautical");
        let mut answers: Vec<RayRadiance> = (0..144).map(|i| ray(i as f64, 0.1)).collect();
        answers[2] = ray(1.0, 0.3);
        answers[13] = ray(3.0, 0.4);
        let pooled = pool_view(&nautical, &answers);
        for i in [2, 13] {
            assert!((pooled[i].radiance[0] - 2.0).abs() < 1e-12);
            assert!((pooled[i].radiance_std_error[0] - 0.25).abs() < 1e-12);
        }
        // Row 3, columns 0 and 15: rays 48 and 63.
        assert!((pooled[48].radiance[0] - 55.5).abs() < 1e-12);
        assert_eq!(pooled[63].radiance, pooled[48].radiance);
        // A view looking across the sun's plane keeps every ray as it is.
        let noon = view("noon");
        assert_eq!(pool_view(&noon, &answers), answers);
    }

    #[test]
    fn a_model_gives_mirror_rays_the_same_radiance() {
        // The premise of the pooling: on a view along the sun's azimuth, mirror rays see
        // the same sky, to rounding.
        let earth = Atmosphere::preset("earth").unwrap();
        let model = prepare(ModelId::Hillaire, &earth, &ModelSettings::default()).unwrap();
        for id in ["sunset", "twilight", "nautical", "orbit-twilight"] {
            let view = view(id);
            let rays = view.rays(&earth);
            let (mut pairs, mut total) = (0, 0.0);
            for (i, ray) in rays.iter().enumerate() {
                let Some(m) = view.mirror_ray(i) else {
                    continue;
                };
                let (a, b) = (ray.direction, rays[m].direction);
                assert!(
                    (a.x - b.x).abs() < 1e-12 && (a.y + b.y).abs() < 1e-12,
                    "{id} {i}"
                );
                let (la, lb) = (
                    model.radiance(ray).unwrap().radiance,
                    model.radiance(&rays[m]).unwrap().radiance,
                );
                total += la.iter().sum::<f64>();
                for (x, y) in la.iter().zip(&lb) {
                    assert!(
                        (x - y).abs() <= 1e-9 * x.abs().max(1e-30),
                        "{id} {i}: {x} {y}"
                    );
                }
                pairs += 1;
            }
            assert_eq!(pairs, 144, "{id}");
            assert!(total > 0.0, "{id}: a dark view shows nothing");
        }
    }
}
