//! The parameters of a planet's atmosphere, its presets, TOML files and validation.

pub mod density;
pub mod limits;
pub mod ozone;
pub mod presets;
pub mod solar;
pub mod spectra;
pub mod spectral;
pub mod table_inputs;
pub(crate) mod tabulated;
pub mod text_file;

use std::path::Path;

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::atmosphere::density::DensityProfile;
use crate::atmosphere::limits::{
    MAX_BOTTOM_RADIUS_M, MAX_COEFFICIENT_PER_M, MAX_IRRADIANCE_W_M2_NM, MAX_THICKNESS_RATIO,
    MIN_SUN_ANGULAR_RADIUS_RAD, profile_past_f32, real_time_problem, spectrum_above,
};
use crate::atmosphere::spectral::Spectral;
use crate::atmosphere::text_file::{TOML_LIMITS, TextFileError, read_text};
use crate::optics::phase::PhaseFunction;

/// What goes wrong when an atmosphere is read or checked. Each message names the field.
#[derive(Debug, Error)]
pub enum AtmosphereError {
    #[error("cannot read atmosphere file {path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error(transparent)]
    File(#[from] TextFileError),
    #[error("atmosphere file {path} is not valid TOML for an atmosphere: {message}")]
    Parse { path: String, message: String },
    #[error("invalid atmosphere: {field}: {message}")]
    Invalid { field: String, message: String },
    #[error("unknown atmosphere preset '{0}' (known: earth, clear, hazy, mars)")]
    UnknownPreset(String),
}

/// Molecular (Rayleigh) scattering: no absorption.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rayleigh {
    /// Scattering coefficient at density 1, m^-1.
    pub scattering_per_m: Spectral,
    pub density: DensityProfile,
}

/// Aerosols (Mie): scattering, extinction (scattering plus absorption) and a phase function.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mie {
    /// Scattering coefficient at density 1, m^-1.
    pub scattering_per_m: Spectral,
    /// Extinction coefficient at density 1, m^-1; at least the scattering coefficient.
    pub extinction_per_m: Spectral,
    pub density: DensityProfile,
    pub phase: PhaseFunction,
}

/// An absorbing gas such as ozone: absorption only.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Absorber {
    /// Absorption coefficient at density 1, m^-1.
    pub absorption_per_m: Spectral,
    pub density: DensityProfile,
}

/// The sun as seen from the planet.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sun {
    /// Spectral irradiance at the top of the atmosphere, W m^-2 nm^-1.
    pub irradiance_w_m2_nm: Spectral,
    /// Angular radius of the disk, radians.
    pub angular_radius_rad: f64,
}

/// A planet and its atmosphere. Lengths in metres, coefficients in m^-1.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Atmosphere {
    pub name: String,
    /// Radius of the ground, m.
    pub bottom_radius_m: f64,
    /// Radius of the top of the atmosphere, m: above it the medium is empty.
    pub top_radius_m: f64,
    pub rayleigh: Rayleigh,
    pub mie: Mie,
    pub ozone: Absorber,
    /// Lambertian reflectance of the ground.
    pub ground_albedo: f64,
    pub sun: Sun,
}

/// The coefficients of an atmosphere at one wavelength, at density 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coefficients {
    pub lambda_nm: f64,
    pub rayleigh_scattering_per_m: f64,
    pub mie_scattering_per_m: f64,
    pub mie_extinction_per_m: f64,
    pub ozone_absorption_per_m: f64,
    pub solar_irradiance_w_m2_nm: f64,
}

impl Coefficients {
    /// Extinction per unit column of each species, in the order of
    /// [`crate::medium::Species`]: Rayleigh, Mie, ozone.
    pub fn extinction_per_species(&self) -> [f64; 3] {
        [
            self.rayleigh_scattering_per_m,
            self.mie_extinction_per_m,
            self.ozone_absorption_per_m,
        ]
    }
}

/// Wavelengths checked when validating spectral recipes (the visible range).
const VALIDATION_WAVELENGTHS_NM: [f64; 6] = [360.0, 440.0, 550.0, 680.0, 780.0, 830.0];

impl Atmosphere {
    /// Reads and validates a TOML file.
    pub fn load(path: &Path) -> Result<Atmosphere, AtmosphereError> {
        let text = read_text(path, TOML_LIMITS)?;
        Atmosphere::from_toml(&text).map_err(|e| match e {
            AtmosphereError::Parse { message, .. } => AtmosphereError::Parse {
                path: path.display().to_string(),
                message,
            },
            other => other,
        })
    }

    /// Parses and validates TOML text.
    pub fn from_toml(text: &str) -> Result<Atmosphere, AtmosphereError> {
        let atmosphere: Atmosphere = toml::from_str(text).map_err(|e| AtmosphereError::Parse {
            path: "<text>".into(),
            message: e.to_string(),
        })?;
        atmosphere.validate()?;
        Ok(atmosphere)
    }

    /// The TOML text of this atmosphere, which [`Atmosphere::from_toml`] reads back.
    pub fn to_toml(&self) -> String {
        toml::to_string_pretty(self).expect("an atmosphere always serialises")
    }

    /// Writes the TOML file atomically (a temporary file renamed into place).
    pub fn save(&self, path: &Path) -> Result<(), AtmosphereError> {
        let io = |source| AtmosphereError::Io {
            path: path.display().to_string(),
            source,
        };
        let tmp = path.with_extension("toml.partial");
        std::fs::write(&tmp, self.to_toml()).map_err(io)?;
        std::fs::rename(&tmp, path).map_err(io)
    }

    /// Checks that every value is physically possible; the error names the first field
    /// that is not.
    pub fn validate(&self) -> Result<(), AtmosphereError> {
        let invalid = |field: &str, message: String| {
            Err(AtmosphereError::Invalid {
                field: field.to_string(),
                message,
            })
        };
        if !(self.bottom_radius_m.is_finite() && self.bottom_radius_m > 0.0) {
            return invalid(
                "bottom_radius_m",
                format!("{} must be finite and > 0", self.bottom_radius_m),
            );
        }
        if self.bottom_radius_m > MAX_BOTTOM_RADIUS_M {
            return invalid(
                "bottom_radius_m",
                format!(
                    "{:e} m must be at most {MAX_BOTTOM_RADIUS_M:e} m, the largest planet the models are tested on",
                    self.bottom_radius_m
                ),
            );
        }
        if !(self.top_radius_m.is_finite() && self.top_radius_m > self.bottom_radius_m) {
            return invalid(
                "top_radius_m",
                format!(
                    "{} must be finite and above bottom_radius_m ({})",
                    self.top_radius_m, self.bottom_radius_m
                ),
            );
        }
        if self.thickness_m() > MAX_THICKNESS_RATIO * self.bottom_radius_m {
            return invalid(
                "top_radius_m",
                format!(
                    "{:e} m makes the atmosphere {:e} m thick, more than {MAX_THICKNESS_RATIO} x bottom_radius_m ({:e} m)",
                    self.top_radius_m,
                    self.thickness_m(),
                    self.bottom_radius_m
                ),
            );
        }
        let spectra = [
            ("rayleigh.scattering_per_m", &self.rayleigh.scattering_per_m),
            ("mie.scattering_per_m", &self.mie.scattering_per_m),
            ("mie.extinction_per_m", &self.mie.extinction_per_m),
            ("ozone.absorption_per_m", &self.ozone.absorption_per_m),
            ("sun.irradiance_w_m2_nm", &self.sun.irradiance_w_m2_nm),
        ];
        for (field, spectrum) in spectra {
            let max = match field {
                "sun.irradiance_w_m2_nm" => (MAX_IRRADIANCE_W_M2_NM, "W m^-2 nm^-1"),
                _ => (MAX_COEFFICIENT_PER_M, "m^-1"),
            };
            let problem = spectrum.problem();
            if let Some(message) = problem.or_else(|| spectrum_above(spectrum, max.0, max.1)) {
                return invalid(field, message);
            }
        }
        let profiles = [
            ("rayleigh.density", &self.rayleigh.density),
            ("mie.density", &self.mie.density),
            ("ozone.density", &self.ozone.density),
        ];
        for (field, profile) in profiles {
            let problem = profile.problem();
            if let Some(message) = problem.or_else(|| profile_past_f32(profile, self.thickness_m()))
            {
                return invalid(field, message);
            }
        }
        if let Some(message) = self.mie.phase.problem() {
            return invalid("mie.phase", message);
        }
        for lambda in VALIDATION_WAVELENGTHS_NM {
            let scattering = self.mie.scattering_per_m.at(lambda);
            let extinction = self.mie.extinction_per_m.at(lambda);
            if extinction < scattering * (1.0 - 1e-12) {
                return invalid(
                    "mie.extinction_per_m",
                    format!(
                        "extinction {extinction:e} is below scattering {scattering:e} at {lambda} nm"
                    ),
                );
            }
        }
        if !(self.ground_albedo.is_finite() && (0.0..=1.0).contains(&self.ground_albedo)) {
            return invalid(
                "ground_albedo",
                format!("{} must lie in [0, 1]", self.ground_albedo),
            );
        }
        let radius = self.sun.angular_radius_rad;
        if !(radius.is_finite() && (MIN_SUN_ANGULAR_RADIUS_RAD..0.5).contains(&radius)) {
            return invalid(
                "sun.angular_radius_rad",
                format!("{radius} must lie in [{MIN_SUN_ANGULAR_RADIUS_RAD:e}, 0.5) radians"),
            );
        }
        Ok(())
    }

    /// Checks that this (valid) atmosphere lies in the range of the real-time models and
    /// the GPU ([`limits::REAL_TIME_BOTTOM_RADIUS_M`],
    /// [`limits::REAL_TIME_MIN_THICKNESS_RATIO`]); the reference alone computes beyond it.
    pub fn check_real_time_range(&self) -> Result<(), AtmosphereError> {
        match real_time_problem(self.bottom_radius_m, self.thickness_m()) {
            Some((field, message)) => Err(AtmosphereError::Invalid {
                field: field.to_string(),
                message,
            }),
            None => Ok(()),
        }
    }

    /// Thickness of the atmosphere, m.
    pub fn thickness_m(&self) -> f64 {
        self.top_radius_m - self.bottom_radius_m
    }

    /// The coefficients at one wavelength.
    pub fn coefficients(&self, lambda_nm: f64) -> Coefficients {
        Coefficients {
            lambda_nm,
            rayleigh_scattering_per_m: self.rayleigh.scattering_per_m.at(lambda_nm),
            mie_scattering_per_m: self.mie.scattering_per_m.at(lambda_nm),
            mie_extinction_per_m: self.mie.extinction_per_m.at(lambda_nm),
            ozone_absorption_per_m: self.ozone.absorption_per_m.at(lambda_nm),
            solar_irradiance_w_m2_nm: self.sun.irradiance_w_m2_nm.at(lambda_nm),
        }
    }

    /// This atmosphere with its aerosol (Mie) coefficients multiplied by `factor`: the
    /// panel's aerosol density.
    pub fn with_aerosol_scale(&self, factor: f64) -> Atmosphere {
        let mut out = self.clone();
        out.mie.scattering_per_m = self.mie.scattering_per_m.scaled(factor);
        out.mie.extinction_per_m = self.mie.extinction_per_m.scaled(factor);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_is_valid_and_round_trips_through_toml() {
        for name in ["earth", "clear", "hazy", "mars"] {
            let atmosphere = Atmosphere::preset(name).unwrap();
            atmosphere.validate().unwrap();
            let back = Atmosphere::from_toml(&atmosphere.to_toml()).unwrap();
            assert_eq!(back, atmosphere, "{name}");
        }
    }

    #[test]
    fn impossible_values_are_rejected_naming_the_field() {
        let earth = Atmosphere::preset("earth").unwrap();
        let field_of = |a: Atmosphere| match a.validate() {
            Err(AtmosphereError::Invalid { field, .. }) => field,
            other => panic!("expected an invalid field, got {other:?}"),
        };
        let mut a = earth.clone();
        a.top_radius_m = a.bottom_radius_m;
        assert_eq!(field_of(a), "top_radius_m");
        let mut a = earth.clone();
        a.top_radius_m = f64::MAX;
        assert_eq!(field_of(a), "top_radius_m");
        let mut a = earth.clone();
        a.bottom_radius_m = f64::NAN;
        assert_eq!(field_of(a), "bottom_radius_m");
        let mut a = earth.clone();
        a.rayleigh.scattering_per_m = Spectral::Constant { value: -1e-6 };
        assert_eq!(field_of(a), "rayleigh.scattering_per_m");
        let mut a = earth.clone();
        a.mie.extinction_per_m = Spectral::Constant { value: 1e-6 };
        assert_eq!(field_of(a), "mie.extinction_per_m");
        let mut a = earth.clone();
        a.ground_albedo = 1.5;
        assert_eq!(field_of(a), "ground_albedo");
        let mut a = earth.clone();
        a.mie.phase = PhaseFunction::CornetteShanks { g: 1.2 };
        assert_eq!(field_of(a), "mie.phase");
        let mut a = earth;
        a.sun.angular_radius_rad = 0.0;
        assert_eq!(field_of(a), "sun.angular_radius_rad");
    }

    #[test]
    fn values_past_the_models_or_f32_are_rejected_naming_the_field() {
        let earth = Atmosphere::preset("earth").unwrap();
        let field_of = |a: Atmosphere| match a.validate() {
            Err(AtmosphereError::Invalid { field, .. }) => field,
            other => panic!("expected an invalid field, got {other:?}"),
        };
        let mut a = earth.clone();
        a.sun.irradiance_w_m2_nm = Spectral::SolarAstmG173 { scale: 1e300 };
        assert_eq!(field_of(a), "sun.irradiance_w_m2_nm");
        let mut a = earth.clone();
        a.mie.scattering_per_m = Spectral::Constant { value: 2.0 };
        a.mie.extinction_per_m = Spectral::Constant { value: 2.0 };
        assert_eq!(field_of(a), "mie.scattering_per_m");
        let mut a = earth.clone();
        a.rayleigh.density.layers[0].exp_scale_per_m = 0.01;
        assert_eq!(field_of(a), "rayleigh.density");
        let mut a = earth.clone();
        a.sun.angular_radius_rad = 1e-6;
        assert_eq!(field_of(a), "sun.angular_radius_rad");
        let mut a = earth.clone();
        a.bottom_radius_m = 1e12;
        a.top_radius_m = 1e12 + 60e3;
        assert_eq!(field_of(a), "bottom_radius_m");
        // The reference computes up to 1e10 m, the real-time models to 1e8 m.
        let mut a = earth;
        a.bottom_radius_m = 1e9;
        a.top_radius_m = 1e9 + 60e3;
        a.validate().unwrap();
        let message = a.check_real_time_range().unwrap_err().to_string();
        assert!(
            message.contains("bottom_radius_m: 1e9 m is outside"),
            "{message}"
        );
        for name in ["earth", "clear", "hazy", "mars"] {
            Atmosphere::preset(name)
                .unwrap()
                .check_real_time_range()
                .unwrap();
        }
    }

    #[test]
    fn toml_errors_are_reported() {
        let earth = Atmosphere::preset("earth").unwrap().to_toml();
        let broken = earth.replace("ground_albedo = 0.1", "ground_albedo = \"grey\"");
        let err = Atmosphere::from_toml(&broken).unwrap_err().to_string();
        assert!(err.contains("ground_albedo"), "{err}");
        let impossible = earth.replace("ground_albedo = 0.1", "ground_albedo = -0.1");
        let err = Atmosphere::from_toml(&impossible).unwrap_err().to_string();
        assert!(err.contains("ground_albedo"), "{err}");
        assert!(matches!(
            Atmosphere::preset("venus"),
            Err(AtmosphereError::UnknownPreset(_))
        ));
    }
}
