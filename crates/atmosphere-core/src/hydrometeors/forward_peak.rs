//! The forward peak of a volume's phase table, taken as no scattering: delta-M's
//! truncation (Wiscombe 1977). Within [`FORWARD_PEAK_DEG`] of the forward direction the
//! channel table P_c is replaced by its value there; the fraction f_c of the scattering
//! it loses is taken off the extinction, beta_c' = beta (1 - f_c), and the rest is
//! P_c' = P_c,t / (1 - f_c), so that beta_c' P_c' = beta P_c at every angle past the
//! peak. Light diffracted (or sent through a crystal's parallel faces) by less than that
//! angle arrives as if unscattered, as it does in the path tracer (`reference/`), where
//! the sun's and the view's light are attenuated by beta_c' alone. Computed once per
//! table, where a table is reduced to the frame's channels (`scene.rs`).

use serde::{Deserialize, Serialize};

use super::channel_phase::ChannelPhase;

/// The forward peak's half-width taken as no scattering, degrees.
pub const FORWARD_PEAK_DEG: f64 = 1.0;
/// The largest share of a channel's scattering the peak may take.
const MAX_PEAK_FRACTION: f64 = 0.99;

/// How the volumes' march counts the light in the forward peak.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum ForwardPeak {
    /// As no scattering (delta-M): the extinction beta (1 - f_c), the truncated table.
    #[default]
    Unscattered,
    /// As extinction: the whole beta and the whole table (the light in the peak lost).
    Extinction,
}

impl ForwardPeak {
    /// The setting's name on command lines and in scene files.
    pub fn name(self) -> &'static str {
        match self {
            ForwardPeak::Unscattered => "unscattered",
            ForwardPeak::Extinction => "extinction",
        }
    }
}

/// A channel table's forward peak: f_c and the table's value at the peak's edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeakTruncation {
    /// f_c: each channel's share of the scattering within [`FORWARD_PEAK_DEG`], above
    /// the value at the edge (at most 0.99).
    pub peak_fraction: [f64; 3],
    /// P_c at [`FORWARD_PEAK_DEG`], sr^-1.
    pub edge: [f64; 3],
}

impl PeakTruncation {
    /// The peak of `phase`, a table by angle: over the bins whose centre lies within
    /// [`FORWARD_PEAK_DEG`], each bin's value above the edge's times its ring's solid
    /// angle (the rule the table's unit integral holds by), so that the truncated table
    /// integrates to one as the whole table does.
    pub fn of(phase: &ChannelPhase) -> PeakTruncation {
        let edge = phase.value_at(FORWARD_PEAK_DEG);
        let mut excess = [0.0; 3];
        let rule = phase.cosine_rule();
        for (b, (v, (_, width))) in phase.values.iter().zip(rule).enumerate() {
            if (b as f64 + 0.5) * phase.bin_deg >= FORWARD_PEAK_DEG {
                break;
            }
            let ring = 2.0 * std::f64::consts::PI * width;
            for c in 0..3 {
                excess[c] += (v[c] - edge[c]) * ring;
            }
        }
        PeakTruncation {
            peak_fraction: excess.map(|f| f.clamp(0.0, MAX_PEAK_FRACTION)),
            edge,
        }
    }

    /// The truncated table P_c' at the bins of `phase` (a table by angle): flat at the
    /// edge's value over the bins whose centre lies within the peak.
    pub fn table(&self, phase: &ChannelPhase) -> ChannelPhase {
        let values = phase
            .values
            .iter()
            .enumerate()
            .map(|(b, v)| {
                let in_peak = (b as f64 + 0.5) * phase.bin_deg < FORWARD_PEAK_DEG;
                std::array::from_fn(|c| {
                    let flat = if in_peak { self.edge[c] } else { v[c] };
                    flat / (1.0 - self.peak_fraction[c])
                })
            })
            .collect();
        ChannelPhase {
            values,
            ..phase.clone()
        }
    }
}

/// `phase` and the share of each channel's scattering the march takes out of the
/// extinction, for `setting`: the truncated table and f_c for a table by angle and
/// [`ForwardPeak::Unscattered`]; otherwise `phase` itself and no share. A table over the
/// sky (falling plates) keeps its peak: it is read by the direction seen, not by the
/// scattering angle, so the peak has no fixed place in it.
pub fn truncated(phase: ChannelPhase, setting: ForwardPeak) -> (ChannelPhase, [f64; 3]) {
    if setting == ForwardPeak::Extinction || phase.sky.is_some() {
        return (phase, [0.0; 3]);
    }
    let peak = PeakTruncation::of(&phase);
    (peak.table(&phase), peak.peak_fraction)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The integral of channel 0 of `t` over the sphere, bin by bin.
    fn integral(t: &ChannelPhase) -> f64 {
        t.values
            .iter()
            .enumerate()
            .map(|(b, v)| {
                let [from, to] = [b, b + 1].map(|k| (k as f64 * t.bin_deg).to_radians());
                v[0] * 2.0 * std::f64::consts::PI * (from.cos() - to.cos())
            })
            .sum()
    }

    /// A table of unit integral: a peak `peak` times the rest's value in its first bin.
    fn peaked(peak: f64) -> ChannelPhase {
        let bin_deg = 0.5;
        let bins = (180.0 / bin_deg) as usize;
        let values = (0..bins)
            .map(|b| if b == 0 { [peak; 3] } else { [1.0; 3] })
            .collect();
        let mut table = ChannelPhase {
            bin_deg,
            sky: None,
            values,
        };
        let whole = integral(&table);
        table
            .values
            .iter_mut()
            .for_each(|v| *v = v.map(|x| x / whole));
        table
    }

    #[test]
    fn the_truncated_table_times_its_extinction_keeps_the_light_past_the_peak() {
        let phase = peaked(5_000.0);
        let (table, f) = truncated(phase.clone(), ForwardPeak::Unscattered);
        assert!(f[0] > 0.05 && f[0] < 0.99, "{f:?}");
        for angle in [1.5, 10.0, 90.0, 179.0] {
            let before = phase.value_at(angle)[1];
            let after = table.value_at(angle)[1] * (1.0 - f[1]);
            assert!((before - after).abs() <= 1e-12 * before, "{angle}");
        }
        // Within the peak the table is flat at its edge's value.
        let edge = phase.value_at(FORWARD_PEAK_DEG)[2] / (1.0 - f[2]);
        assert!((table.values[0][2] - edge).abs() <= 1e-12 * edge);
        // It integrates to one as the whole table does.
        assert!((integral(&phase) - 1.0).abs() < 1e-12);
        assert!(
            (integral(&table) - 1.0).abs() < 1e-12,
            "{}",
            integral(&table)
        );
        let (same, none) = truncated(phase.clone(), ForwardPeak::Extinction);
        assert_eq!((same, none), (phase.clone(), [0.0; 3]));
        let mut plates = phase;
        plates.sky = Some(crate::hydrometeors::spectral_phase::SKY_GRID);
        assert_eq!(
            truncated(plates.clone(), ForwardPeak::Unscattered).1,
            [0.0; 3]
        );
    }

    #[test]
    fn the_setting_reads_back_by_name() {
        for setting in [ForwardPeak::Unscattered, ForwardPeak::Extinction] {
            let text = format!("v = \"{}\"", setting.name());
            let read: std::collections::BTreeMap<String, ForwardPeak> =
                toml::from_str(&text).unwrap();
            assert_eq!(read["v"], setting);
        }
        assert_eq!(ForwardPeak::default(), ForwardPeak::Unscattered);
    }
}
