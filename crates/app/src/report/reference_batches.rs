//! A view's reference as the mean of independent batches: each batch is a whole run of
//! the reference with its own seed, so batches pooled with equal weights are one
//! estimate over all their paths, and taking a view's reference further by more
//! batches keeps the batches it has (`reference_cache.rs` records how many it pooled).

use atmosphere_core::models::sky_model::{ModelSettings, RayRadiance};
use atmosphere_core::numerics::sampling::mix_seed;

/// The settings of batch `batch` (from 0): the view's own for the first, so a view's
/// single run is its first batch, and for the others the same with a seed of their own.
pub fn batch_settings(settings: &ModelSettings, batch: usize) -> ModelSettings {
    let mut batch_settings = settings.clone();
    if batch > 0 {
        batch_settings.seed = mix_seed(&[settings.seed, batch as u64]);
    }
    batch_settings
}

/// Pools `pooled`, the mean of `pooled_batches` batches, with one more batch `next`,
/// ray by ray and wavelength by wavelength, every batch weighing the same: the mean of
/// the batches, and the standard error of a mean of independent estimates,
/// sqrt(sum of their variances) / their number. The transmittance is the first's (it
/// is computed, not drawn).
pub fn pool_batch(
    pooled: &[RayRadiance],
    pooled_batches: usize,
    next: &[RayRadiance],
) -> Vec<RayRadiance> {
    let k = pooled_batches as f64;
    let n = k + 1.0;
    pooled
        .iter()
        .zip(next)
        .map(|(a, b)| RayRadiance {
            radiance: a
                .radiance
                .iter()
                .zip(&b.radiance)
                .map(|(la, lb)| (k * la + lb) / n)
                .collect(),
            transmittance: a.transmittance.clone(),
            radiance_std_error: a
                .radiance_std_error
                .iter()
                .zip(&b.radiance_std_error)
                .map(|(sa, sb)| ((k * sa).powi(2) + sb.powi(2)).sqrt() / n)
                .collect(),
        })
        .collect()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A ray's answer at one wavelength, for the pooling tests here and in `mirror_rays.rs`.
    pub(crate) fn ray(radiance: f64, std_error: f64) -> RayRadiance {
        RayRadiance {
            radiance: vec![radiance],
            transmittance: vec![0.5],
            radiance_std_error: vec![std_error],
        }
    }

    #[test]
    fn batches_pooled_one_by_one_are_the_mean_of_all_and_its_standard_error() {
        let batches = [ray(1.0, 0.3), ray(2.0, 0.4), ray(6.0, 1.2)];
        let mut pooled = vec![batches[0].clone()];
        for (k, next) in batches.iter().enumerate().skip(1) {
            pooled = pool_batch(&pooled, k, std::slice::from_ref(next));
        }
        assert!((pooled[0].radiance[0] - 3.0).abs() < 1e-12);
        // sqrt(0.09 + 0.16 + 1.44) / 3
        let expected = 1.69_f64.sqrt() / 3.0;
        assert!((pooled[0].radiance_std_error[0] - expected).abs() < 1e-12);
        assert_eq!(pooled[0].transmittance, vec![0.5]);
        // Four batches of equal error halve it.
        let mut four = vec![ray(1.0, 0.2)];
        for k in 1..4 {
            four = pool_batch(&four, k, &[ray(1.0, 0.2)]);
        }
        assert!((four[0].radiance_std_error[0] - 0.1).abs() < 1e-12);
    }

    #[test]
    fn the_first_batch_is_the_view_s_own_run_and_the_others_draw_their_own_paths() {
        let settings = ModelSettings::default();
        assert_eq!(batch_settings(&settings, 0), settings);
        let seeds: Vec<u64> = (0..4).map(|b| batch_settings(&settings, b).seed).collect();
        let mut unique = seeds.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), seeds.len());
        let mut other = batch_settings(&settings, 1);
        other.seed = settings.seed;
        assert_eq!(other, settings);
    }
}
