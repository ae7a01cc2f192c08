//! The fixed views of the report's optics section: the three shipped scenes of rain and
//! ice optics (`assets/scenes/optics/`: the rain shaft with its bows, the cirrus with
//! its halos, the droplet deck with its glory and cloudbow), each answered on a line
//! of rays across its phenomenon, at fine angular steps where the bows, halos and rings
//! lie (their positions matter), from the antisolar point or the sun
//! (docs/optics-rendering.md, "The optics in the report").

use atmosphere_core::clouds::reference::settings::PathSettings;
use atmosphere_core::hydrometeors::reference::ray::turned;
use glam::DVec3;

/// The size of the views' GPU frames (the scenes' own camera and field of view), a
/// quarter of 1280 x 720 in each direction: a software adapter's frames are slow.
pub const FRAME_SIZE: (u32, u32) = (320, 180);

/// What a view's angles are measured from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Centre {
    Sun,
    Antisolar,
}

/// Which way the line of rays leaves the centre.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sweep {
    /// Upwards in the vertical plane through the centre.
    Up,
    /// Sideways, along the horizontal at right angles to the centre.
    Across,
}

/// One view of the section.
#[derive(Clone, Debug, PartialEq)]
pub struct OpticsView {
    pub id: &'static str,
    pub title: &'static str,
    /// The shipped scene's file in `assets/scenes/optics/`: its camera, sun, sky model
    /// and volume.
    pub scene: &'static str,
    pub centre: Centre,
    pub sweep: Sweep,
    /// The rays' angles from the centre, degrees.
    pub angles_deg: Vec<f64>,
    /// The path tracer's stopping rule on this view.
    pub paths: PathSettings,
}

/// From `lo` to `hi` in steps of `step`, both ends included.
pub fn steps(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let n = ((hi - lo) / step).round() as usize;
    (0..=n).map(|k| lo + step * k as f64).collect()
}

impl OpticsView {
    /// The rays' unit directions from a camera at `camera_m` with the sun towards the
    /// unit `sun`.
    pub fn directions(&self, camera_m: DVec3, sun: DVec3) -> Vec<DVec3> {
        let up = camera_m.normalize();
        let centre = match self.centre {
            Centre::Sun => sun,
            Centre::Antisolar => -sun,
        };
        let towards = match self.sweep {
            Sweep::Up => (up - centre * up.dot(centre)).normalize(),
            Sweep::Across => up.cross(centre).normalize(),
        };
        self.angles_deg
            .iter()
            .map(|a| turned(centre, towards, *a))
            .collect()
    }
}

/// The report's three views.
pub fn optics_views() -> Vec<OpticsView> {
    let paths = |target_relative_error, max_paths| PathSettings {
        target_relative_error,
        min_paths: 2_048,
        max_paths,
        ..PathSettings::default()
    };
    vec![
        // Up from the antisolar point (30 degrees below the horizon) through the bright
        // sky inside the primary, the primary (42 degrees), Alexander's dark band and
        // the secondary (51 degrees).
        OpticsView {
            id: "rainbow",
            title: "rain shaft: the bows",
            scene: "rainbow.toml",
            centre: Centre::Antisolar,
            sweep: Sweep::Up,
            angles_deg: steps(38.0, 54.0, 0.5),
            paths: paths(0.005, 400_000),
        },
        // Up from the sun (20 degrees up) across the 22 and 46 degree halos.
        OpticsView {
            id: "halo",
            title: "cirrus: the halos",
            scene: "halo.toml",
            centre: Centre::Sun,
            sweep: Sweep::Up,
            angles_deg: [
                steps(18.0, 26.0, 0.5),
                steps(30.0, 38.0, 4.0),
                steps(42.0, 50.0, 0.5),
            ]
            .concat(),
            paths: paths(0.005, 400_000),
        },
        // Sideways from the antisolar point (45 degrees below the horizon) across the
        // glory's rings and the cloudbow (38 degrees).
        OpticsView {
            id: "glory",
            title: "droplet deck: glory and cloudbow",
            scene: "glory.toml",
            centre: Centre::Antisolar,
            sweep: Sweep::Across,
            angles_deg: [steps(0.0, 3.0, 0.25), steps(34.0, 42.0, 0.5)].concat(),
            paths: paths(0.005, 400_000),
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rays_lie_at_their_angles_from_the_centre() {
        let camera = DVec3::Z * 6_360_002.0;
        let sun = DVec3::new(0.0, -30f64.to_radians().cos(), 30f64.to_radians().sin());
        for view in optics_views() {
            assert!(view.paths.check().is_ok(), "{}", view.id);
            let directions = view.directions(camera, sun);
            let centre = if view.centre == Centre::Sun {
                sun
            } else {
                -sun
            };
            for (d, a) in directions.iter().zip(&view.angles_deg) {
                let angle = d.dot(centre).clamp(-1.0, 1.0).acos().to_degrees();
                assert!((angle - a).abs() < 1e-9, "{} {angle} {a}", view.id);
            }
        }
        // Up from the antisolar point 30 degrees below the horizon: 42 degrees out is
        // 12 degrees above it.
        let view = &optics_views()[0];
        let d = turned(-sun, DVec3::new(0.0, 0.5, 3f64.sqrt() / 2.0), 42.0);
        assert!((d.z.asin().to_degrees() - 12.0).abs() < 1e-9);
        assert_eq!(view.centre, Centre::Antisolar);
    }
}
