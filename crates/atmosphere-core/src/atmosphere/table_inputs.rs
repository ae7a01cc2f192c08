//! Which parts of an atmosphere a table depends on, and which parts changed between two
//! atmospheres: a model rebuilds a table only when one of its inputs changed. The sun's direction is never an input of a
//! CPU table here: it is part of each view ray.

use std::ops::BitOr;

use crate::atmosphere::Atmosphere;

/// A set of atmosphere inputs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Inputs(u16);

impl Inputs {
    pub const NONE: Inputs = Inputs(0);
    /// Radii of the ground and the top of the atmosphere.
    pub const GEOMETRY: Inputs = Inputs(1);
    /// The Rayleigh density profile.
    pub const RAYLEIGH_PROFILE: Inputs = Inputs(1 << 1);
    /// The Rayleigh scattering coefficients.
    pub const RAYLEIGH_COEFFICIENTS: Inputs = Inputs(1 << 2);
    /// The aerosol density profile.
    pub const MIE_PROFILE: Inputs = Inputs(1 << 3);
    /// The aerosol scattering and extinction coefficients (the panel's aerosol density).
    pub const MIE_COEFFICIENTS: Inputs = Inputs(1 << 4);
    /// The aerosol phase function.
    pub const MIE_PHASE: Inputs = Inputs(1 << 5);
    /// The ozone density profile.
    pub const OZONE_PROFILE: Inputs = Inputs(1 << 6);
    /// The ozone absorption coefficients.
    pub const OZONE_COEFFICIENTS: Inputs = Inputs(1 << 7);
    /// The ground's albedo.
    pub const GROUND_ALBEDO: Inputs = Inputs(1 << 8);
    /// The solar spectrum and the sun's angular radius.
    pub const SUN: Inputs = Inputs(1 << 9);

    /// Everything that decides optical depth: a transmittance table's inputs.
    pub const EXTINCTION: Inputs = Inputs(
        Self::GEOMETRY.0
            | Self::RAYLEIGH_PROFILE.0
            | Self::RAYLEIGH_COEFFICIENTS.0
            | Self::MIE_PROFILE.0
            | Self::MIE_COEFFICIENTS.0
            | Self::OZONE_PROFILE.0
            | Self::OZONE_COEFFICIENTS.0,
    );
    /// Columns of matter per species (density integrals, no coefficients).
    pub const COLUMNS: Inputs = Inputs(
        Self::GEOMETRY.0 | Self::RAYLEIGH_PROFILE.0 | Self::MIE_PROFILE.0 | Self::OZONE_PROFILE.0,
    );
    /// Everything.
    pub const ALL: Inputs = Inputs((1 << 10) - 1);

    /// Both sets together (`|` in constants).
    pub const fn union(self, other: Inputs) -> Inputs {
        Inputs(self.0 | other.0)
    }

    /// True when the two sets share an input.
    pub fn intersects(self, other: Inputs) -> bool {
        self.0 & other.0 != 0
    }

    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// Whether a table that depends on these inputs must be rebuilt for `now`: it was
    /// never built (`built_from` is `None`) or one of its inputs changed since.
    pub fn stale(self, built_from: Option<&Atmosphere>, now: &Atmosphere) -> bool {
        built_from.is_none_or(|old| Inputs::changed(old, now).intersects(self))
    }

    /// The inputs that differ between `old` and `new`.
    pub fn changed(old: &Atmosphere, new: &Atmosphere) -> Inputs {
        let mut changed = Inputs::NONE;
        let mut mark = |differs: bool, input: Inputs| {
            if differs {
                changed = changed | input;
            }
        };
        mark(
            old.bottom_radius_m != new.bottom_radius_m || old.top_radius_m != new.top_radius_m,
            Inputs::GEOMETRY,
        );
        mark(
            old.rayleigh.density != new.rayleigh.density,
            Inputs::RAYLEIGH_PROFILE,
        );
        mark(
            old.rayleigh.scattering_per_m != new.rayleigh.scattering_per_m,
            Inputs::RAYLEIGH_COEFFICIENTS,
        );
        mark(old.mie.density != new.mie.density, Inputs::MIE_PROFILE);
        mark(
            old.mie.scattering_per_m != new.mie.scattering_per_m
                || old.mie.extinction_per_m != new.mie.extinction_per_m,
            Inputs::MIE_COEFFICIENTS,
        );
        mark(old.mie.phase != new.mie.phase, Inputs::MIE_PHASE);
        mark(
            old.ozone.density != new.ozone.density,
            Inputs::OZONE_PROFILE,
        );
        mark(
            old.ozone.absorption_per_m != new.ozone.absorption_per_m,
            Inputs::OZONE_COEFFICIENTS,
        );
        mark(
            old.ground_albedo != new.ground_albedo,
            Inputs::GROUND_ALBEDO,
        );
        mark(old.sun != new.sun, Inputs::SUN);
        changed
    }
}

impl BitOr for Inputs {
    type Output = Inputs;
    fn bitor(self, rhs: Inputs) -> Inputs {
        Inputs(self.0 | rhs.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::presets::earth;

    #[test]
    fn names_exactly_what_changed() {
        let a = earth();
        assert_eq!(Inputs::changed(&a, &a), Inputs::NONE);
        assert!(Inputs::COLUMNS.stale(None, &a));
        assert!(!Inputs::ALL.stale(Some(&a), &a));
        let mut b = a.clone();
        b.ground_albedo = 0.3;
        assert_eq!(Inputs::changed(&a, &b), Inputs::GROUND_ALBEDO);
        assert!(Inputs::GROUND_ALBEDO.stale(Some(&a), &b));
        assert!(!Inputs::COLUMNS.stale(Some(&a), &b));
        let mut c = a.clone();
        c.mie.scattering_per_m = a.mie.scattering_per_m.scaled(0.5);
        let changed = Inputs::changed(&a, &c);
        assert_eq!(changed, Inputs::MIE_COEFFICIENTS);
        assert!(changed.intersects(Inputs::EXTINCTION));
        assert!(!changed.intersects(Inputs::COLUMNS));
        assert!(Inputs::ALL.intersects(Inputs::SUN));
    }
}
