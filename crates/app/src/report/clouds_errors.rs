//! A clouds row's luminance error against the path-traced reference per view: relative
//! RMS, maximum and signed mean of (L - L_ref) / L_ref over the view's rays, beside the
//! reference's own relative standard error of luminance (the wavelengths' paths are
//! independent, so the luminance's variance is the sum of its weights squared times
//! theirs).

use atmosphere_core::color::SpectrumToColor;

use crate::cloud_rays::CloudAnswer;
use crate::report::clouds_reference::CloudReference;
use crate::report::clouds_rows::{CloudRow, RowAnswers};
use crate::report::clouds_scene::ViewScene;

/// A row's error on one view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewError {
    /// Relative RMS of the luminance error.
    pub rms: f64,
    /// Largest relative luminance error.
    pub max: f64,
    /// Signed mean of the relative luminance error.
    pub bias: f64,
    /// The CPU time of a 1280 x 720 frame, s.
    pub frame_s: f64,
}

/// A row's results: per view, `None` where the row is not measured there.
#[derive(Clone, Debug, PartialEq)]
pub struct RowResult {
    pub row: CloudRow,
    pub per_view: Vec<Option<ViewError>>,
    /// Every relative error of the measured views' rays, in order.
    pub ray_errors: Vec<f64>,
}

impl RowResult {
    /// RMS over every ray of the measured views.
    pub fn rms(&self) -> f64 {
        rms(&self.ray_errors)
    }

    pub fn max(&self) -> f64 {
        self.ray_errors.iter().fold(0.0, |m, e| m.max(e.abs()))
    }

    /// Mean CPU frame time over the measured views, s.
    pub fn frame_s(&self) -> f64 {
        let times: Vec<f64> = self.per_view.iter().flatten().map(|v| v.frame_s).collect();
        times.iter().sum::<f64>() / times.len().max(1) as f64
    }
}

fn rms(errors: &[f64]) -> f64 {
    (errors.iter().map(|e| e * e).sum::<f64>() / errors.len().max(1) as f64).sqrt()
}

/// The relative luminance error of each of `answers` against `reference`.
pub fn relative_errors(
    answers: &[CloudAnswer],
    reference: &[CloudAnswer],
    color: &SpectrumToColor,
) -> Vec<f64> {
    answers
        .iter()
        .zip(reference)
        .map(|(a, r)| {
            let truth = color.luminance_cd_m2(&r.radiance.radiance);
            color.luminance_cd_m2(&a.radiance.radiance) / truth - 1.0
        })
        .collect()
}

/// The reference's relative standard error of luminance on each ray.
pub fn reference_errors(reference: &[CloudAnswer], color: &SpectrumToColor) -> Vec<f64> {
    let waves = color.wavelengths_nm().len();
    let weights: Vec<f64> = (0..waves)
        .map(|w| {
            let mut unit = vec![0.0; waves];
            unit[w] = 1.0;
            color.luminance_cd_m2(&unit)
        })
        .collect();
    reference
        .iter()
        .map(|r| {
            let variance: f64 = r
                .radiance
                .radiance_std_error
                .iter()
                .zip(&weights)
                .map(|(s, c)| (s * c).powi(2))
                .sum();
            variance.sqrt() / color.luminance_cd_m2(&r.radiance.radiance)
        })
        .collect()
}

/// The row's results from its answers on each view (`None` where not measured).
pub fn row_result(
    row: CloudRow,
    answers: &[Option<RowAnswers>],
    reference: &CloudReference,
    color: &SpectrumToColor,
) -> RowResult {
    let mut ray_errors = Vec::new();
    let per_view = answers
        .iter()
        .zip(reference)
        .map(|(a, r)| {
            a.as_ref().map(|a| {
                let errors = relative_errors(&a.answers, r, color);
                ray_errors.extend(&errors);
                ViewError {
                    rms: rms(&errors),
                    max: errors.iter().fold(0.0, |m, e| m.max(e.abs())),
                    bias: errors.iter().sum::<f64>() / errors.len().max(1) as f64,
                    frame_s: a.frame_s(),
                }
            })
        })
        .collect();
    RowResult {
        row,
        per_view,
        ray_errors,
    }
}

/// `clouds_errors.csv`: a row per setting and view, relative errors in per cent.
pub fn errors_csv(results: &[RowResult], scenes: &[ViewScene]) -> String {
    let mut text = "setting,view,rms_percent,max_percent,bias_percent,cpu_frame_s\n".to_string();
    for r in results {
        for (v, scene) in r.per_view.iter().zip(scenes) {
            if let Some(v) = v {
                text.push_str(&format!(
                    "{},{},{:.3},{:.3},{:+.3},{:.4e}\n",
                    r.row,
                    scene.view.id(),
                    100.0 * v.rms,
                    100.0 * v.max,
                    100.0 * v.bias,
                    v.frame_s
                ));
            }
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use atmosphere_core::models::sky_model::RayRadiance;

    fn answer(l: f64, s: f64) -> CloudAnswer {
        CloudAnswer {
            radiance: RayRadiance {
                radiance: vec![l; 3],
                transmittance: vec![1.0; 3],
                radiance_std_error: vec![s; 3],
            },
            cloud_transmittance: 1.0,
            paths: None,
        }
    }

    #[test]
    fn errors_are_relative_to_the_reference_luminance() {
        let color = SpectrumToColor::new(&[680.0, 550.0, 440.0]).unwrap();
        let reference = [answer(2.0, 0.1), answer(4.0, 0.0)];
        let errors = relative_errors(&[answer(3.0, 0.0), answer(3.0, 0.0)], &reference, &color);
        assert!((errors[0] - 0.5).abs() < 1e-12 && (errors[1] + 0.25).abs() < 1e-12);
        // Equal relative errors at three wavelengths: the luminance's is smaller by
        // the root of the sum of squared weights over their sum.
        let own = reference_errors(&reference, &color);
        assert!(own[0] > 0.05 / 3f64.sqrt() - 1e-12 && own[0] <= 0.05 + 1e-12);
        assert_eq!(own[1], 0.0);
    }
}
