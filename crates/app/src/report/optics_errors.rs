//! An optics row's error against the path-traced reference per view: relative RMS,
//! maximum and signed mean of (L - L_ref) / L_ref of luminance over the view's rays
//! (`clouds_errors.rs`'s), and the colour's CIEDE2000 difference (Sharma, Wu and Dalal
//! 2005) with the white at the reference's luminance on each ray, so that both
//! lightness and the bows' and halos' hues count.

use atmosphere_core::analysis::color_difference::{D65_WHITE, ciede2000, xyz_to_lab};
use atmosphere_core::color::SpectrumToColor;

use crate::cloud_rays::CloudAnswer;
use crate::report::clouds_errors::relative_errors;
use crate::report::optics_reference::{OpticsReference, as_answer};
use crate::report::optics_rows::{OpticsRow, RowAnswers};
use crate::report::optics_scene::OpticsScene;

/// A row's error on one view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewError {
    /// Relative RMS of the luminance error.
    pub rms: f64,
    /// Largest relative luminance error.
    pub max: f64,
    /// Signed mean of the relative luminance error.
    pub bias: f64,
    /// Mean CIEDE2000 difference.
    pub delta_e: f64,
    /// The CPU time of a 1280 x 720 frame, s.
    pub frame_s: f64,
}

/// A row's results on every view.
#[derive(Clone, Debug, PartialEq)]
pub struct RowResult {
    pub row: OpticsRow,
    pub per_view: Vec<ViewError>,
    /// Every relative luminance error of the views' rays, in order.
    pub ray_errors: Vec<f64>,
    /// Every CIEDE2000 difference, in order.
    pub delta_e: Vec<f64>,
}

fn rms(errors: &[f64]) -> f64 {
    (errors.iter().map(|e| e * e).sum::<f64>() / errors.len().max(1) as f64).sqrt()
}

fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len().max(1) as f64
}

impl RowResult {
    /// RMS over every ray of every view.
    pub fn rms(&self) -> f64 {
        rms(&self.ray_errors)
    }

    pub fn max(&self) -> f64 {
        self.ray_errors.iter().fold(0.0, |m, e| m.max(e.abs()))
    }

    pub fn bias(&self) -> f64 {
        mean(&self.ray_errors)
    }

    pub fn delta_e(&self) -> f64 {
        mean(&self.delta_e)
    }

    /// Mean CPU frame time over the views, s.
    pub fn frame_s(&self) -> f64 {
        mean(&self.per_view.iter().map(|v| v.frame_s).collect::<Vec<_>>())
    }
}

/// The CIEDE2000 difference of each of `answers` from `reference`, the white at the
/// reference's luminance.
pub fn colour_differences(
    answers: &[CloudAnswer],
    reference: &[CloudAnswer],
    color: &SpectrumToColor,
) -> Vec<f64> {
    answers
        .iter()
        .zip(reference)
        .map(|(a, r)| {
            let truth = color.xyz_cd_m2(&r.radiance.radiance);
            let white = D65_WHITE.map(|w| w * truth[1]);
            let lab = |xyz| xyz_to_lab(xyz, white);
            ciede2000(lab(color.xyz_cd_m2(&a.radiance.radiance)), lab(truth))
        })
        .collect()
}

/// The row's results from its answers on each view.
pub fn row_result(
    row: OpticsRow,
    answers: &[RowAnswers],
    reference: &OpticsReference,
    color: &SpectrumToColor,
) -> RowResult {
    let mut ray_errors = Vec::new();
    let mut delta_e = Vec::new();
    let per_view = answers
        .iter()
        .zip(reference)
        .map(|(a, r)| {
            let truth: Vec<CloudAnswer> = r.iter().map(as_answer).collect();
            let errors = relative_errors(&a.answers, &truth, color);
            let colours = colour_differences(&a.answers, &truth, color);
            ray_errors.extend(&errors);
            delta_e.extend(&colours);
            ViewError {
                rms: rms(&errors),
                max: errors.iter().fold(0.0, |m, e| m.max(e.abs())),
                bias: mean(&errors),
                delta_e: mean(&colours),
                frame_s: a.frame_s(),
            }
        })
        .collect();
    RowResult {
        row,
        per_view,
        ray_errors,
        delta_e,
    }
}

/// `optics_errors.csv`: a row per setting and view, relative errors in per cent.
pub fn errors_csv(results: &[RowResult], scenes: &[OpticsScene]) -> String {
    let mut text =
        "setting,view,rms_percent,max_percent,bias_percent,delta_e2000,cpu_frame_s\n".to_string();
    for r in results {
        for (v, scene) in r.per_view.iter().zip(scenes) {
            text.push_str(&format!(
                "{},{},{:.3},{:.3},{:+.3},{:.3},{:.4e}\n",
                r.row,
                scene.view.id,
                100.0 * v.rms,
                100.0 * v.max,
                100.0 * v.bias,
                v.delta_e,
                v.frame_s
            ));
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use atmosphere_core::models::sky_model::RayRadiance;

    fn answer(radiance: [f64; 3]) -> CloudAnswer {
        CloudAnswer {
            radiance: RayRadiance {
                radiance: radiance.to_vec(),
                transmittance: vec![1.0; 3],
                radiance_std_error: vec![0.0; 3],
            },
            cloud_transmittance: 1.0,
            paths: None,
        }
    }

    #[test]
    fn the_colour_difference_sees_hue_where_luminance_does_not() {
        let color = SpectrumToColor::new(&[680.0, 550.0, 440.0]).unwrap();
        let grey = answer([1.0, 1.0, 1.0]);
        let one = std::slice::from_ref(&grey);
        assert!(colour_differences(one, one, &color)[0] < 1e-9);
        // More red and less blue at the same luminance: no luminance error, a colour one.
        let weights: Vec<f64> = (0..3)
            .map(|c| {
                let mut unit = [0.0; 3];
                unit[c] = 1.0;
                color.luminance_cd_m2(&unit)
            })
            .collect();
        let shift = 0.2;
        let redder = answer([1.0 + shift, 1.0, 1.0 - shift * weights[0] / weights[2]]);
        let luminance = relative_errors(std::slice::from_ref(&redder), one, &color)[0];
        assert!(luminance.abs() < 1e-12, "{luminance}");
        assert!(colour_differences(&[redder], &[grey], &color)[0] > 2.0);
    }
}
