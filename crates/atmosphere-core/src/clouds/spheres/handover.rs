//! Which form of the one cloud field a frame shows: the volume layer near and inside it
//! (`layer/`), Dobashi, Yamamoto and Nishita 2002 section 5.4's cloud spheres from far
//! away, or both blended across a band of camera altitudes so that a continuous ascent
//! shows no pop. The band starts at the altitude where the two were measured to agree
//! (`tests/cloud_spheres_handover.rs`: the mean radiance of a view from 50 km within a
//! few per cent) and ends where the spheres alone take over.

use std::fmt;
use std::str::FromStr;

use crate::clouds::error::CloudError;

/// The camera altitude above which the spheres start to take over from the layer, m.
pub const HANDOVER_START_M: f64 = 50_000.0;
/// The camera altitude above which the spheres alone show the cloud, m.
pub const HANDOVER_END_M: f64 = 100_000.0;

/// The form of the cloud field a frame shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CloudForm {
    /// Chosen by the camera's altitude ([`sphere_weight`]).
    #[default]
    Auto,
    /// The volume layer's march at every altitude.
    Layer,
    /// The cloud spheres at every altitude.
    Spheres,
}

impl fmt::Display for CloudForm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            CloudForm::Auto => "auto",
            CloudForm::Layer => "layer",
            CloudForm::Spheres => "spheres",
        })
    }
}

impl FromStr for CloudForm {
    type Err = CloudError;

    fn from_str(s: &str) -> Result<Self, CloudError> {
        match s {
            "auto" => Ok(CloudForm::Auto),
            "layer" => Ok(CloudForm::Layer),
            "spheres" => Ok(CloudForm::Spheres),
            other => Err(CloudError(format!(
                "cloud form {other:?} is not one of auto, layer, spheres"
            ))),
        }
    }
}

/// The spheres' share of the cloud a frame shows with the camera `altitude_m` above the
/// ground: 0 for the layer alone, 1 for the spheres alone. `Auto` gives 0 up to
/// [`HANDOVER_START_M`], 1 from [`HANDOVER_END_M`], and between them the smoothstep
/// x^2 (3 - 2 x) of the altitude's place x in the band, whose slope is 0 at both ends
/// so that an ascent at constant speed eases into and out of the blend.
pub fn sphere_weight(form: CloudForm, altitude_m: f64) -> f64 {
    match form {
        CloudForm::Layer => 0.0,
        CloudForm::Spheres => 1.0,
        CloudForm::Auto => {
            let x = ((altitude_m - HANDOVER_START_M) / (HANDOVER_END_M - HANDOVER_START_M))
                .clamp(0.0, 1.0);
            x * x * (3.0 - 2.0 * x)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_weight_rises_smoothly_through_the_band() {
        assert_eq!(sphere_weight(CloudForm::Auto, 1_000.0), 0.0);
        assert_eq!(sphere_weight(CloudForm::Auto, HANDOVER_START_M), 0.0);
        assert_eq!(sphere_weight(CloudForm::Auto, 75_000.0), 0.5);
        assert_eq!(sphere_weight(CloudForm::Auto, HANDOVER_END_M), 1.0);
        assert_eq!(sphere_weight(CloudForm::Auto, 1e6), 1.0);
        assert_eq!(sphere_weight(CloudForm::Layer, 1e6), 0.0);
        assert_eq!(sphere_weight(CloudForm::Spheres, 1.0), 1.0);
        // Monotone, and no step larger than 1.5 times the band's mean slope.
        let steps = 200;
        let band = HANDOVER_END_M - HANDOVER_START_M;
        let mut last = 0.0;
        for i in 1..=steps {
            let h = HANDOVER_START_M + band * f64::from(i) / f64::from(steps);
            let w = sphere_weight(CloudForm::Auto, h);
            assert!(w >= last && w - last <= 1.5 / f64::from(steps), "{h}: {w}");
            last = w;
        }
    }

    #[test]
    fn forms_read_and_write_by_name() {
        for form in [CloudForm::Auto, CloudForm::Layer, CloudForm::Spheres] {
            assert_eq!(form.to_string().parse::<CloudForm>(), Ok(form));
        }
        let e = "volume".parse::<CloudForm>().unwrap_err();
        assert!(
            e.0.contains("\"volume\" is not one of auto, layer, spheres"),
            "{e}"
        );
    }
}
