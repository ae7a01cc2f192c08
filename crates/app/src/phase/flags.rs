//! The flags of `atmos phase` that need more than a number: the particle, the size
//! distribution, a refractive index and the angle range, each read with its range.

use atmosphere_core::optics::mie::error::MieError;
use atmosphere_core::optics::mie::size_distribution::SizeDistribution;
use num_complex::Complex64;

/// The particles `atmos phase` knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Particle {
    /// Spheres of liquid water (cloud droplets, rain): Lorenz-Mie, refractive index from
    /// Hale and Querry 1973.
    Water,
    /// Rain: water drops of 0.1 to 3 mm radius in the Marshall-Palmer (1948)
    /// distribution of a rain rate, Lorenz-Mie.
    Rain,
    /// Hexagonal ice columns, ray traced with diffraction; Warren and Brandt 2008.
    IceColumn,
    /// Hexagonal ice plates, ray traced with diffraction; Warren and Brandt 2008.
    IcePlate,
}

impl Particle {
    pub fn name(self) -> &'static str {
        match self {
            Particle::Water => "water",
            Particle::Rain => "rain",
            Particle::IceColumn => "ice-column",
            Particle::IcePlate => "ice-plate",
        }
    }
}

/// The range of --radius-um: a 10 mm drop is past any raindrop that stays whole.
pub const RADIUS_RANGE_UM: [f64; 2] = [0.0, 10_000.0];

/// The most angles one run writes (a step of 1e-4 degree over the half circle).
pub const MAX_ANGLES: usize = 2_000_000;

/// The most wavelengths one run computes.
pub const MAX_WAVELENGTHS: usize = 64;

/// --radius-um: in (0, 10000].
pub fn parse_radius_um(text: &str) -> Result<f64, String> {
    let r: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("'{text}' is not a radius in um"))?;
    let [lo, hi] = RADIUS_RANGE_UM;
    if r.is_finite() && r > lo && r <= hi {
        Ok(r)
    } else {
        Err(format!("radius {text} um is outside (0, 10000] um"))
    }
}

/// How --distribution was given: its kind and parameters, turned into a
/// [`SizeDistribution`] once the radius is known.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DistributionFlag {
    Lognormal { sigma: f64 },
    ModifiedGamma { alpha: f64, gamma: f64 },
}

impl DistributionFlag {
    /// The distribution of this effective radius.
    pub fn with_effective_radius(&self, radius_m: f64) -> Result<SizeDistribution, MieError> {
        match *self {
            DistributionFlag::Lognormal { sigma } => SizeDistribution::lognormal(radius_m, sigma),
            DistributionFlag::ModifiedGamma { alpha, gamma } => {
                SizeDistribution::modified_gamma(radius_m, alpha, gamma)
            }
        }
    }

    /// The flag as the header repeats it.
    pub fn describe(&self) -> String {
        match self {
            DistributionFlag::Lognormal { sigma } => format!("lognormal:{sigma}"),
            DistributionFlag::ModifiedGamma { alpha, gamma } => {
                format!("modified-gamma:{alpha},{gamma}")
            }
        }
    }
}

/// --distribution: lognormal:SIGMA or modified-gamma:ALPHA,GAMMA, each parameter in its
/// range (checked here by building a distribution of radius 1 m).
pub fn parse_distribution(text: &str) -> Result<DistributionFlag, String> {
    let bad = || format!("'{text}' is not lognormal:SIGMA or modified-gamma:ALPHA,GAMMA");
    let (kind, params) = text.trim().split_once(':').ok_or_else(bad)?;
    let numbers: Vec<f64> = params
        .split(',')
        .map(|p| p.trim().parse::<f64>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    let flag = match (kind, numbers.as_slice()) {
        ("lognormal", &[sigma]) => DistributionFlag::Lognormal { sigma },
        ("modified-gamma", &[alpha, gamma]) => DistributionFlag::ModifiedGamma { alpha, gamma },
        _ => return Err(bad()),
    };
    flag.with_effective_radius(1.0).map_err(|e| e.to_string())?;
    Ok(flag)
}

/// --refractive-index: N, N+Ki or N-Ki with N in (0, 10] and K in [0, 10] (K > 0
/// absorbs; N-Ki is read as N+Ki, the sign conventions differ between authors).
pub fn parse_refractive_index(text: &str) -> Result<Complex64, String> {
    let bad = || format!("'{text}' is not a refractive index N or N+Ki (e.g. 1.33+1e-8i)");
    let t = text.trim();
    let (re, im) = match t.strip_suffix(['i', 'j']) {
        None => (t, "0"),
        Some(body) => {
            // The sign between the parts: the last + or - not part of an exponent.
            let bytes = body.as_bytes();
            let split = (1..bytes.len())
                .rev()
                .find(|&i| {
                    (bytes[i] == b'+' || bytes[i] == b'-') && !matches!(bytes[i - 1], b'e' | b'E')
                })
                .ok_or_else(bad)?;
            (&body[..split], &body[split + 1..])
        }
    };
    let re: f64 = re.trim().parse().map_err(|_| bad())?;
    let im: f64 = im.trim().parse().map_err(|_| bad())?;
    let m = Complex64::new(re, im.abs());
    atmosphere_core::optics::mie::coefficients::check_inputs(m, 1.0).map_err(|e| e.to_string())?;
    Ok(m)
}

/// --angles-deg START:END:STEP: the angles START, START + STEP, ... up to END, within
/// [0, 180] degrees, printed with as many decimals as the flag has.
#[derive(Clone, Debug, PartialEq)]
pub struct AngleRange {
    pub start: f64,
    pub step: f64,
    pub count: usize,
    pub decimals: usize,
}

impl AngleRange {
    pub fn angles_deg(&self) -> impl Iterator<Item = f64> + '_ {
        (0..self.count).map(|i| self.start + self.step * i as f64)
    }

    /// The cosines of the angles, in order: the scattering angles as Mie's functions
    /// take them.
    pub fn cosines(&self) -> Vec<f64> {
        self.angles_deg().map(|a| a.to_radians().cos()).collect()
    }
}

pub fn parse_angles(text: &str) -> Result<AngleRange, String> {
    let bad = || format!("'{text}' is not START:END:STEP in degrees, e.g. 0:180:0.1");
    let parts: Vec<&str> = text.trim().split(':').map(str::trim).collect();
    let [start_text, end_text, step_text] = parts.as_slice() else {
        return Err(bad());
    };
    let number = |s: &str| {
        s.parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(bad)
    };
    let (start, end, step) = (number(start_text)?, number(end_text)?, number(step_text)?);
    if !(0.0..=180.0).contains(&start) || !(0.0..=180.0).contains(&end) {
        return Err(format!("'{text}': angles must lie in [0, 180] degrees"));
    }
    if end < start {
        return Err(format!("'{text}': END is below START"));
    }
    if step <= 0.0 {
        return Err(format!("'{text}': STEP must be above 0"));
    }
    let steps = ((end - start) / step * (1.0 + 1e-12)).floor();
    if steps + 1.0 > MAX_ANGLES as f64 {
        return Err(format!(
            "'{text}' asks for {} angles; at most {MAX_ANGLES}",
            steps + 1.0
        ));
    }
    let decimals = [start_text, end_text, step_text]
        .iter()
        .map(|s| s.split_once('.').map_or(0, |(_, d)| d.len()))
        .max()
        .unwrap_or(0)
        .min(12);
    Ok(AngleRange {
        start,
        step,
        count: steps as usize + 1,
        decimals,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refractive_indices_in_every_spelling() {
        let m = |t| parse_refractive_index(t).unwrap();
        assert_eq!(m("1.33"), Complex64::new(1.33, 0.0));
        assert_eq!(m("1.33+1e-8i"), Complex64::new(1.33, 1e-8));
        assert_eq!(m("1.33-1E-8i"), Complex64::new(1.33, 1e-8));
        assert_eq!(m("1.5+1j"), Complex64::new(1.5, 1.0));
        assert_eq!(m(" 1.5e0 + 0.5i "), Complex64::new(1.5, 0.5));
        for bad in [
            "", "i", "1.33+", "abc", "1.33+xi", "1+1", "-1.33", "1", "11",
        ] {
            assert!(parse_refractive_index(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn angle_ranges_count_their_ends() {
        let a = parse_angles("0:180:0.1").unwrap();
        assert_eq!((a.count, a.decimals), (1801, 1));
        assert_eq!(a.angles_deg().last(), Some(a.start + a.step * 1800.0));
        assert_eq!(parse_angles("10:10:1").unwrap().count, 1);
        assert_eq!(parse_angles("0:1:0.3").unwrap().count, 4);
        for bad in [
            "0:180",
            "0:180:0",
            "0:180:-1",
            "-1:10:1",
            "0:181:1",
            "10:5:1",
            "0:180:1e-5",
            "a:b:c",
        ] {
            assert!(parse_angles(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn distributions_with_their_ranges() {
        assert_eq!(
            parse_distribution("lognormal:0.2"),
            Ok(DistributionFlag::Lognormal { sigma: 0.2 })
        );
        assert!(parse_distribution("modified-gamma:6,1").is_ok());
        for bad in [
            "lognormal",
            "lognormal:0",
            "lognormal:2",
            "gamma:1,1",
            "modified-gamma:6",
            "lognormal:x",
        ] {
            assert!(parse_distribution(bad).is_err(), "{bad}");
        }
    }
}
