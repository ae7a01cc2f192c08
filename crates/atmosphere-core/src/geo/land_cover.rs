//! The land's colour below the colour map's resolution: rock where the ground is steep,
//! snow above a snow line that depends on latitude and season, never at the sea.
//!
//! A point of land at latitude `phi`, height `h` above sea level, with the cosine
//! `c = n . up` of its slope, in a season given by the sun's declination `delta` (the
//! planet-fixed sun direction's angle above the equator, so that a sun placed by date or
//! by angles implies one), has the albedo
//!     a = mix(mix(a_map, a_rock, r), a_snow, s (1 - r)),
//! with `a_map` the colour map's (the Blue Marble's) albedo and
//! - the rock share `r = smoothstep(cos 30 deg, cos 40 deg, c)` reversed: none below a
//!   30 degree slope, all above 40 degrees, near the angle of repose of loose rock
//!   (about 35 degrees), past which ground sheds its soil and its snow;
//! - the snow share `s = smoothstep(-B/2, B/2, h - H(phi, delta))` above the snow line
//!   `H`, over a band `B` of 300 m, 0 at or below sea level;
//! - the snow line where a zonal sea-level temperature, cooled with height at the
//!   standard atmosphere's 6.5 K/km (U.S. Standard Atmosphere 1976, its first layer),
//!   reaches -5 deg C, `H = (T_0(phi_t) + 5 K) / (6.5 K/km)` with
//!   `T_0 = 27 deg C - 35 K sin^2(phi_t)`, at the thermal latitude `phi_t = phi - 0.4 delta` (summer warms a hemisphere as if it
//!   lay nearer the equator). This is this project's rule, not a paper's: its three
//!   constants put the line at about 5 km in the tropics (the glaciers of the Andes and
//!   East Africa), 1.4 km in the Alps in January and 3.0 km in July (the Alps' summer
//!   snow line), and at sea level poleward of about 64 degrees at the winter solstice.
//!
//! CPU twin of `land_albedo` in `shaders/terrain/terrain.wgsl`.

/// Linear albedo of bare rock at 680, 550 and 440 nm: a grey granite or limestone.
pub const ROCK_ALBEDO: [f64; 3] = [0.22, 0.20, 0.18];

/// Linear albedo of old snow in the visible (Warren 1982, Optical properties of snow:
/// 0.8 to 0.9 for snow some days old; fresh snow reaches 0.95).
pub const SNOW_ALBEDO: [f64; 3] = [0.82, 0.84, 0.86];

/// The rock share's slope band: none where `n . up` is above the first cosine, all
/// below the second.
pub const ROCK_SLOPE_COS: [f64; 2] = [0.866_025_403_784_438_6, 0.766_044_443_118_978];

/// The snow line's band, m: the snow share rises from 0 to 1 across it.
pub const SNOW_BAND_M: f64 = 300.0;

/// The sea-level temperature at the thermal equator, deg C.
const EQUATOR_TEMPERATURE_C: f64 = 27.0;
/// Its fall from the thermal equator to the thermal pole, K.
const POLE_DROP_K: f64 = 35.0;
/// The temperature at the snow line, deg C.
const SNOW_TEMPERATURE_C: f64 = -5.0;
/// The standard atmosphere's lapse rate below 11 km, K/m.
const LAPSE_RATE_K_M: f64 = 6.5e-3;
/// The thermal latitude's shift per radian of the sun's declination.
const SEASON_SHIFT: f64 = 0.4;

/// The snow line of one season: `H(phi) = at_equator_m - drop_to_pole_m sin^2(phi - shift_rad)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SnowLine {
    /// The line's height at the thermal equator, m.
    pub at_equator_m: f64,
    /// How far it falls from there to the thermal pole, m.
    pub drop_to_pole_m: f64,
    /// The thermal equator's latitude, rad.
    pub shift_rad: f64,
}

impl SnowLine {
    /// The snow line when the sun stands at declination `declination_rad` (from a sun
    /// direction `s` in planet-fixed axes with z the north pole: `asin(s.z)`).
    pub fn for_declination(declination_rad: f64) -> SnowLine {
        SnowLine {
            at_equator_m: (EQUATOR_TEMPERATURE_C - SNOW_TEMPERATURE_C) / LAPSE_RATE_K_M,
            drop_to_pole_m: POLE_DROP_K / LAPSE_RATE_K_M,
            shift_rad: SEASON_SHIFT * declination_rad,
        }
    }

    /// The line's height at latitude `latitude_rad`, m (below 0: snow down to the sea).
    pub fn height_m(&self, latitude_rad: f64) -> f64 {
        let s = (latitude_rad - self.shift_rad).sin();
        self.at_equator_m - self.drop_to_pole_m * s * s
    }
}

/// Hermite smoothstep of `x` from `e0` to `e1` (WGSL's `smoothstep`).
fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The rock share of ground whose normal makes cosine `cos_slope` with the vertical.
pub fn rock_share(cos_slope: f64) -> f64 {
    smoothstep(ROCK_SLOPE_COS[0], ROCK_SLOPE_COS[1], cos_slope)
}

/// The snow share at `height_m` above sea level below a snow line at `line_m`: none at
/// or below sea level.
pub fn snow_share(height_m: f64, line_m: f64) -> f64 {
    if height_m <= 0.0 {
        return 0.0;
    }
    smoothstep(-0.5 * SNOW_BAND_M, 0.5 * SNOW_BAND_M, height_m - line_m)
}

/// The land's albedo at latitude `latitude_rad` and `height_m`, with slope cosine
/// `cos_slope`, under `snow_line`, from the colour map's `map` albedo.
pub fn land_albedo(
    map: [f64; 3],
    latitude_rad: f64,
    height_m: f64,
    cos_slope: f64,
    snow_line: &SnowLine,
) -> [f64; 3] {
    let r = rock_share(cos_slope);
    let s = snow_share(height_m, snow_line.height_m(latitude_rad)) * (1.0 - r);
    std::array::from_fn(|c| {
        let ground = map[c] + (ROCK_ALBEDO[c] - map[c]) * r;
        ground + (SNOW_ALBEDO[c] - ground) * s
    })
}
