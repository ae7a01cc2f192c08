//! The beams ground truth: each ray's single scattering by globally adaptive
//! Gauss-Legendre quadrature along it, with exact shadow rays against every occluder.
//!
//! The ray is cut at the analytic breakpoints (`breakpoints.rs`), each piece into a few
//! panels; a panel's error is the difference between the 8-point rule on it and on its
//! two halves. The panel with the largest error is halved until, at every wavelength,
//! the errors sum to at most `tolerance` times the radiance (or `max_panels` is
//! reached: `radiance_with_error` then says how far it got).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::beams::error::BeamError;
use crate::beams::in_scattering::InScattering;
use crate::beams::methods::breakpoints::breakpoints;
use crate::beams::methods::method::{BeamMethod, BeamSettings};
use crate::beams::ray::SceneRay;
use crate::beams::scene::BeamScene;
use crate::models::options::Setting;
use crate::numerics::quadrature::{GAUSS_LEGENDRE_8, mapped};

/// The relative error the quadrature stops at.
pub const TOLERANCE: Setting<f64> = Setting {
    model: "reference",
    key: "tolerance",
    range: 1e-9..=1e-2,
};
/// The most panels one ray may be cut into.
pub const MAX_PANELS: Setting<usize> = Setting {
    model: "reference",
    key: "max_panels",
    range: 16..=10_000_000,
};
/// Panels each piece between two breakpoints starts with.
const PANELS_PER_PIECE: usize = 4;

/// The reference method's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceSettings {
    pub tolerance: f64,
    pub max_panels: usize,
}

impl Default for ReferenceSettings {
    fn default() -> Self {
        ReferenceSettings {
            tolerance: 1e-5,
            max_panels: 400_000,
        }
    }
}

/// The reference, prepared for a scene.
#[derive(Debug)]
pub struct Reference {
    scattering: InScattering,
    settings: ReferenceSettings,
}

/// A ray's radiance with the quadrature's estimate of its relative error (the largest
/// over the wavelengths).
#[derive(Clone, Debug, PartialEq)]
pub struct RadianceWithError {
    pub radiance: Vec<f64>,
    pub relative_error: f64,
    pub panels: usize,
}

impl Reference {
    /// The reference for `scene`, its `tolerance` and `max_panels` read from the options.
    pub fn new(scene: &BeamScene, settings: &BeamSettings) -> Result<Reference, BeamError> {
        let defaults = ReferenceSettings::default();
        let own = settings.options.read_settings(
            "reference",
            |_: &ReferenceSettings| Ok(()),
            |r, _| {
                Ok(ReferenceSettings {
                    tolerance: r.number(&TOLERANCE, defaults.tolerance)?,
                    max_panels: r.count(&MAX_PANELS, defaults.max_panels)?,
                })
            },
        )?;
        Ok(Reference {
            scattering: InScattering::new(scene, &settings.wavelengths_nm),
            settings: own,
        })
    }

    /// The radiance of `ray` and how well it converged.
    pub fn radiance_with_error(&self, ray: &SceneRay) -> RadianceWithError {
        let n = self.scattering.wavelengths_nm.len();
        let t_end = self.scattering.ray_end_m(ray);
        let integrate = |a: f64, b: f64| -> Vec<f64> {
            let mut sum = vec![0.0; n];
            let mut term = vec![0.0; n];
            for (t, w) in mapped(&GAUSS_LEGENDRE_8, a, b) {
                term.iter_mut().for_each(|x| *x = 0.0);
                let mut visibility = |_, p, path: &_| self.scattering.shadow_ray(p, path);
                self.scattering.add_at(ray, t, &mut visibility, &mut term);
                sum.iter_mut().zip(&term).for_each(|(s, x)| *s += w * x);
            }
            sum
        };
        let panel = |a: f64, b: f64, whole: Vec<f64>| -> Panel {
            let mid = 0.5 * (a + b);
            let (left, right) = (integrate(a, mid), integrate(mid, b));
            let error = whole
                .iter()
                .zip(left.iter().zip(&right))
                .map(|(w, (l, r))| (l + r - w).abs())
                .collect();
            Panel {
                a,
                b,
                left,
                right,
                error,
                priority: 0.0,
            }
        };
        let edges = breakpoints(&self.scattering.scene, ray, t_end);
        let mut panels = Vec::new();
        for pair in edges.windows(2) {
            let h = (pair[1] - pair[0]) / PANELS_PER_PIECE as f64;
            for k in 0..PANELS_PER_PIECE {
                let (a, b) = (pair[0] + h * k as f64, pair[0] + h * (k + 1) as f64);
                if b > a {
                    panels.push(panel(a, b, integrate(a, b)));
                }
            }
        }
        let total = |panels: &[Panel]| -> Vec<f64> {
            let mut sum = vec![0.0; n];
            for p in panels {
                for k in 0..n {
                    sum[k] += p.left[k] + p.right[k];
                }
            }
            sum
        };
        // Errors are ranked relative to the first estimate of the radiance.
        let scale: Vec<f64> = total(&panels).iter().map(|x| x.abs().max(1e-300)).collect();
        let rank = |p: &mut Panel| {
            p.priority = p
                .error
                .iter()
                .zip(&scale)
                .map(|(e, s)| e / s)
                .fold(0.0, f64::max);
        };
        let mut error_sum = vec![0.0; n];
        let mut heap = BinaryHeap::new();
        for mut p in panels {
            rank(&mut p);
            error_sum
                .iter_mut()
                .zip(&p.error)
                .for_each(|(s, e)| *s += e);
            heap.push(p);
        }
        let mut radiance = vec![0.0; n];
        for p in heap.iter() {
            for k in 0..n {
                radiance[k] += p.left[k] + p.right[k];
            }
        }
        let converged = |error_sum: &[f64], radiance: &[f64]| {
            error_sum
                .iter()
                .zip(radiance)
                .all(|(e, r)| *e <= self.settings.tolerance * r.abs())
        };
        while heap.len() < self.settings.max_panels && !converged(&error_sum, &radiance) {
            let Some(worst) = heap.pop() else { break };
            let mid = 0.5 * (worst.a + worst.b);
            let (mut left, mut right) = (
                panel(worst.a, mid, worst.left.clone()),
                panel(mid, worst.b, worst.right.clone()),
            );
            for k in 0..n {
                error_sum[k] += left.error[k] + right.error[k] - worst.error[k];
                radiance[k] += left.left[k] + left.right[k] + right.left[k] + right.right[k]
                    - worst.left[k]
                    - worst.right[k];
            }
            rank(&mut left);
            rank(&mut right);
            heap.push(left);
            heap.push(right);
        }
        let relative_error = error_sum
            .iter()
            .zip(&radiance)
            .map(|(e, r)| if *e == 0.0 { 0.0 } else { e / r.abs() })
            .fold(0.0, f64::max);
        RadianceWithError {
            radiance,
            relative_error,
            panels: heap.len(),
        }
    }
}

impl BeamMethod for Reference {
    fn radiance(&self, ray: &SceneRay) -> Result<Vec<f64>, BeamError> {
        Ok(self.radiance_with_error(ray).radiance)
    }
}

/// A piece of the ray with the 8-point rule on each half and the error of the rule on
/// the whole against them.
#[derive(Debug)]
struct Panel {
    a: f64,
    b: f64,
    left: Vec<f64>,
    right: Vec<f64>,
    error: Vec<f64>,
    priority: f64,
}

impl PartialEq for Panel {
    fn eq(&self, other: &Self) -> bool {
        self.priority.total_cmp(&other.priority) == Ordering::Equal
    }
}

impl Eq for Panel {}

impl PartialOrd for Panel {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Panel {
    fn cmp(&self, other: &Self) -> Ordering {
        self.priority.total_cmp(&other.priority)
    }
}
