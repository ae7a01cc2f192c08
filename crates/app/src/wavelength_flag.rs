//! A wavelength flag's value (`--wavelengths 680,550,440`): the number in nm and the
//! text the user wrote, which names the output columns.

use std::str::FromStr;

/// A wavelength as the user wrote it: the text names the output columns.
#[derive(Clone, Debug, PartialEq)]
pub struct Wavelength {
    pub nm: f64,
    pub label: String,
}

impl FromStr for Wavelength {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let label = s.trim();
        match label.parse::<f64>() {
            Ok(nm) if nm.is_finite() => Ok(Wavelength {
                nm,
                label: label.to_string(),
            }),
            _ => Err(format!("'{label}' is not a wavelength in nm")),
        }
    }
}
