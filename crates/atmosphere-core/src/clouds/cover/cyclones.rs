//! Extratropical cyclones: the comma-shaped cloud of a mid-latitude low, a spiral band
//! wound around a dense core whose tail trails towards the equator as the cold front.
//!
//! Each cyclone is a logarithmic spiral in the tangent plane at its centre,
//! `r = r_core exp(b theta)`, turning anticlockwise seen from above in the north and
//! clockwise in the south (the Coriolis sense of a low), under an envelope that fades it
//! out within `reach` of the centre. Centres are drawn from the seed along the storm
//! tracks (40 to 65 degrees of latitude in each hemisphere).

use std::f64::consts::TAU;

use glam::DVec3;

use crate::geo::equirectangular::direction;
use crate::numerics::gradient_noise::{derived_seed, gradient_noise};

/// Cyclones per hemisphere (a typical count of active lows on a weather map).
const PER_HEMISPHERE: u32 = 6;
/// Radius of the dense core, radians of arc (about 250 km on the Earth).
const CORE_RAD: f64 = 0.04;
/// Angular distance at which a cyclone's cloud has faded (about 2,200 km).
const REACH_RAD: f64 = 0.35;
/// Growth of the spiral per radian of turn: a pitch angle near 20 degrees.
const SPIRAL_GROWTH: f64 = 0.36;
/// How much clearer than their surroundings the gaps between a cyclone's bands are.
const DRY_SLOT: f64 = 0.25;
/// Half-width of the spiral band as a fraction of one turn.
const BAND_HALF_WIDTH: f64 = 0.16;

/// One cyclone: its centre and tangent frame.
#[derive(Clone, Debug)]
struct Cyclone {
    centre: DVec3,
    east: DVec3,
    north: DVec3,
    /// +1 in the north, -1 in the south: the sense of the spiral.
    sense: f64,
    /// Rotation of the spiral about its centre, radians.
    phase: f64,
}

/// The cyclones of one cover, drawn from its seed.
#[derive(Clone, Debug)]
pub struct Cyclones {
    cyclones: Vec<Cyclone>,
    seed: u32,
}

fn unit(hash: u32) -> f64 {
    f64::from(hash >> 8) / f64::from(1u32 << 24)
}

impl Cyclones {
    pub fn new(seed: u32) -> Self {
        let mut cyclones = Vec::new();
        for k in 0..2 * PER_HEMISPHERE {
            let h = derived_seed(seed, 1000 + k);
            let sense = if k < PER_HEMISPHERE { 1.0 } else { -1.0 };
            let lat = sense * (40.0 + 25.0 * unit(h)).to_radians();
            let lon = (unit(derived_seed(h, 1)) * 360.0 - 180.0).to_radians();
            let centre = direction(lat, lon);
            let east = DVec3::Z.cross(centre).normalize();
            let north = centre.cross(east);
            let phase = unit(derived_seed(h, 2)) * TAU;
            cyclones.push(Cyclone {
                centre,
                east,
                north,
                sense,
                phase,
            });
        }
        Cyclones { cyclones, seed }
    }

    /// Cloudiness of the cyclones at `point` (unit): 0 far from every low, up to 1 in a
    /// core or on a band, down to -`DRY_SLOT` between the bands, where the air sinks;
    /// where two lows overlap their fields add.
    pub fn cloudiness(&self, point: DVec3) -> f64 {
        let mut value = 0.0;
        for c in &self.cyclones {
            let distance = c.centre.dot(point).clamp(-1.0, 1.0).acos();
            if distance >= REACH_RAD {
                continue;
            }
            let theta = c.sense * point.dot(c.north).atan2(point.dot(c.east));
            // Which turn of the spiral the point lies nearest, as a phase in turns; a
            // little noise keeps the bands from looking drawn with a ruler.
            let wobble = 0.15 * gradient_noise(derived_seed(self.seed, 7), point * 20.0);
            let turns = ((distance.max(1e-9) / CORE_RAD).ln() / SPIRAL_GROWTH - theta - c.phase)
                / TAU
                + wobble;
            let off_band = (turns - turns.round()).abs() / BAND_HALF_WIDTH;
            let on_band = (-off_band * off_band).exp();
            let core = (-(distance / CORE_RAD).powi(2)).exp();
            let envelope = 1.0 - (distance / REACH_RAD).powi(2);
            value += envelope * ((1.0 + DRY_SLOT) * on_band.max(core) - DRY_SLOT);
        }
        value
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geo::equirectangular::lat_lon;

    #[test]
    fn centres_lie_on_the_storm_tracks_and_cores_are_cloudier_than_around_them() {
        let cyclones = Cyclones::new(42);
        for c in &cyclones.cyclones {
            let lat = lat_lon(c.centre).0.to_degrees();
            assert!((40.0..=65.0).contains(&lat.abs()), "{lat}");
            assert!(lat.signum() == c.sense);
            let around: f64 = (0..16)
                .map(|k| {
                    let a = k as f64 * TAU / 16.0;
                    let p = c.centre + 0.2 * (a.cos() * c.east + a.sin() * c.north);
                    cyclones.cloudiness(p.normalize())
                })
                .sum::<f64>()
                / 16.0;
            assert!(cyclones.cloudiness(c.centre) > around + 0.3);
        }
        // The tropics see none.
        assert_eq!(cyclones.cloudiness(direction(0.1, 1.0)), 0.0);
    }
}
