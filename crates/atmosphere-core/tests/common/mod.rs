//! Helpers shared by the model tests.

use atmosphere_core::analysis::error_statistics::RelativeErrorStats;
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::sky_model::{SkyModel, ViewRay};

/// Luminance of `model` against `reference` on labelled rays, each printed: the signed
/// relative error per ray, in order, and their statistics.
pub fn luminance_errors<'a>(
    model: &dyn SkyModel,
    reference: &dyn SkyModel,
    rays: impl IntoIterator<Item = (String, &'a ViewRay)>,
) -> (Vec<f64>, RelativeErrorStats) {
    let color = SpectrumToColor::new(model.wavelengths_nm()).unwrap();
    let pairs: Vec<(f64, f64)> = rays
        .into_iter()
        .map(|(label, ray)| {
            let m = color.luminance_cd_m2(&model.radiance(ray).unwrap().radiance);
            let r = color.luminance_cd_m2(&reference.radiance(ray).unwrap().radiance);
            eprintln!(
                "{label}: model {m:.5} reference {r:.5} error {:+.4}",
                (m - r) / r
            );
            (m, r)
        })
        .collect();
    let signed = pairs.iter().map(|(m, r)| (m - r) / r).collect();
    (signed, RelativeErrorStats::new(pairs))
}
