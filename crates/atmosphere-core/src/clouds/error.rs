//! Why a cloud medium or a transport run was refused.

use std::fmt;

/// A cloud parameter out of its range, named with the value given.
#[derive(Clone, Debug, PartialEq)]
pub struct CloudError(pub String);

impl fmt::Display for CloudError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for CloudError {}

/// `Ok` when `value` is finite and within `[lo, hi]`, else an error naming `what`.
pub fn check_range(what: &str, value: f64, lo: f64, hi: f64) -> Result<(), CloudError> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(())
    } else {
        Err(CloudError(format!(
            "{what} = {value} must lie in [{lo}, {hi}]"
        )))
    }
}
