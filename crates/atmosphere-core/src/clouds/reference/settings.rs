//! How many paths the cloud path tracer follows for a view ray: until the standard
//! error of the ray's radiance falls below a fraction of it at every wavelength, at
//! least `min_paths` and at most `max_paths`.

use crate::clouds::error::{CloudError, check_range};

/// Paths are followed in batches of this many between checks of the error.
pub const BATCH_PATHS: u64 = 256;

/// The stopping rule and the seed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathSettings {
    /// Stop once the radiance's standard error is below this fraction of it, in
    /// [1e-4, 0.5].
    pub target_relative_error: f64,
    /// Paths followed before the error is trusted, in [16, 1e8].
    pub min_paths: u64,
    /// Paths at most, in [min_paths, 1e8]: a ray that has not converged by then is
    /// answered with its larger error.
    pub max_paths: u64,
    /// The random sequence's seed (each ray mixes its own geometry into it).
    pub seed: u64,
}

impl Default for PathSettings {
    fn default() -> PathSettings {
        PathSettings {
            target_relative_error: 0.01,
            min_paths: 1024,
            max_paths: 200_000,
            seed: 1,
        }
    }
}

impl PathSettings {
    /// Refuses a setting out of its range, by name.
    pub fn check(&self) -> Result<(), CloudError> {
        check_range(
            "cloud path tracer target_relative_error",
            self.target_relative_error,
            1e-4,
            0.5,
        )?;
        check_range(
            "cloud path tracer min_paths",
            self.min_paths as f64,
            16.0,
            1e8,
        )?;
        check_range(
            "cloud path tracer max_paths",
            self.max_paths as f64,
            self.min_paths as f64,
            1e8,
        )
    }
}
