//! Heights that respect a finer land/sea mask: land above sea level where the mask says
//! land, sea floor below it where the mask says sea, continuous across the coastline.
//!
//! With `m` the mask's land fraction (bilinear between its cells' centres, so 1/2 on the
//! coastline) and `c = m - 1/2`, a height `h` becomes
//! `max(h, lift) min(1, 2c)` on the land side (`c > 0`) and
//! `min(h, -depth) min(1, -2c)` on the sea side (`c < 0`), 0 on the coastline: the data's
//! height where it already agrees with the mask and lies beyond the coastal band (within
//! one mask cell of the coast), otherwise raised to `lift` on land or lowered to `-depth`
//! in the sea, and brought to 0 across the band on both sides.

/// How far the coastline pushes heights that disagree with the mask.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoastSettings {
    /// The least height of land away from the coast, m.
    pub lift_m: f64,
    /// The least depth of the sea away from the coast, m.
    pub depth_m: f64,
}

/// The height `height_m` constrained by the land fraction `land_fraction` (in [0, 1]).
pub fn constrain_to_coast(height_m: f64, land_fraction: f64, settings: &CoastSettings) -> f64 {
    let c = land_fraction - 0.5;
    if c > 0.0 {
        height_m.max(settings.lift_m) * (2.0 * c).min(1.0)
    } else if c < 0.0 {
        height_m.min(-settings.depth_m) * (-2.0 * c).min(1.0)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SETTINGS: CoastSettings = CoastSettings {
        lift_m: 2.0,
        depth_m: 5.0,
    };

    #[test]
    fn land_is_above_the_sea_and_the_coast_is_continuous() {
        for h in [-4000.0, -3.0, 0.0, 1.0, 900.0] {
            for m in [0.0, 0.1, 0.49, 0.51, 0.8, 1.0] {
                let out = constrain_to_coast(h, m, &SETTINGS);
                assert_eq!(out > 0.0, m > 0.5, "{h} m at land fraction {m}: {out}");
                assert_eq!(out < 0.0, m < 0.5);
            }
            // Continuous: small steps of the fraction make small steps of the height.
            let mut previous = constrain_to_coast(h, 0.0, &SETTINGS);
            for k in 1..=1000 {
                let out = constrain_to_coast(h, k as f64 / 1000.0, &SETTINGS);
                assert!(
                    (out - previous).abs() <= 2e-3 * h.abs().max(5.0) + 1e-12,
                    "{h} {k}"
                );
                previous = out;
            }
        }
        // Heights that agree with the mask away from the coast are kept.
        assert_eq!(constrain_to_coast(900.0, 1.0, &SETTINGS), 900.0);
        assert_eq!(constrain_to_coast(-4000.0, 0.0, &SETTINGS), -4000.0);
        assert_eq!(constrain_to_coast(-4000.0, 1.0, &SETTINGS), 2.0);
        assert_eq!(constrain_to_coast(900.0, 0.0, &SETTINGS), -5.0);
    }
}
