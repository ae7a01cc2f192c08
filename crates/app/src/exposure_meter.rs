//! The exposure meter: the EV100 a frame's log-average luminance asks for.
//!
//! The renderer returns the frame's log-average (geometric mean) luminance `L` in cd/m^2
//! over the pixels that are not black (`Renderer::average_luminance`: space and the
//! night side do not count, and the sun's disk cannot swamp the mean as it would an
//! arithmetic one); a reflected-light meter then gives
//!
//! `EV100 = log2(L S / K)` with `S = 100` (ISO) and `K = 12.5` (the meter's calibration),
//!
//! as in Lagarde and de Rousiers 2014 ("Moving Frostbite to PBR", section 4.4), whose
//! saturation-based exposure the tone map applies: the average then maps to about 0.1
//! before the filmic curve, a mid grey. The viewer adapts to it over time; `atmos record`
//! meters each frame on its own, so that shards and resumed runs give the same frames.

/// The meter's ISO speed over its calibration constant, `S / K = 100 / 12.5`.
const ISO_OVER_K: f64 = 100.0 / 12.5;

/// The metered EV100's range: moonlit night to snow in full sun.
pub const AUTO_EV_RANGE: (f64, f64) = (-4.0, 20.0);

/// The metered EV100 of a log-average luminance, cd/m^2, within [`AUTO_EV_RANGE`].
pub fn metered_ev100(luminance_cd_m2: f64) -> f64 {
    (luminance_cd_m2.max(1e-9) * ISO_OVER_K)
        .log2()
        .clamp(AUTO_EV_RANGE.0, AUTO_EV_RANGE.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_meter_maps_luminance_to_ev100_within_its_range() {
        // 1 cd/m^2 is EV 3 (2^3 = 100 / 12.5); a clear sky of about 5,000 cd/m^2 15.3.
        assert!((metered_ev100(1.0) - 3.0).abs() < 1e-12);
        assert!((metered_ev100(5000.0) - 15.29).abs() < 0.01);
        assert_eq!(metered_ev100(0.0), AUTO_EV_RANGE.0);
        assert_eq!(metered_ev100(1e12), AUTO_EV_RANGE.1);
    }
}
