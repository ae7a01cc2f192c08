//! What each table was last built from, and which tables a new atmosphere makes stale.
//! Rebuilds follow the CPU's `Bruneton::update`: the columns and densities on
//! [`Inputs::COLUMNS`], the sun's transmittances and single scattering on
//! [`Inputs::EXTINCTION`], the orders also on the ground albedo and the Mie phase function
//! (unless Mie is pruned); the sun rebuilds nothing, except that the disk's angular
//! radius rebuilds single scattering and the orders of tables that hold the sun as a disk
//! (`sun_disk`).

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::table_inputs::Inputs;
use atmosphere_core::models::bruneton::sun_disk::disk_changed;

/// What each table was last built from.
#[derive(Debug, Default)]
pub struct Built {
    /// The columns table and the density table.
    pub columns: Option<Atmosphere>,
    /// The transmittance table.
    pub sun: Option<Atmosphere>,
    pub single: Option<Atmosphere>,
    /// With whether Mie was computed.
    pub orders: Option<(Atmosphere, bool)>,
}

/// The tables a frame must rebuild.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Stale {
    pub columns: bool,
    pub sun: bool,
    pub single: bool,
    /// The loop over orders, started again.
    pub orders: bool,
}

impl Built {
    /// The tables that `atmosphere` makes stale, for tables with the sun as a disk or not
    /// (`sun_disk`).
    pub fn stale(&self, atmosphere: &Atmosphere, sun_disk: bool) -> Stale {
        let single = Inputs::EXTINCTION.stale(self.single.as_ref(), atmosphere)
            || self
                .single
                .as_ref()
                .is_some_and(|old| disk_changed(sun_disk, old, atmosphere));
        let orders = self.orders.as_ref().is_none_or(|(old, mie)| {
            let inputs = if *mie {
                Inputs::GROUND_ALBEDO.union(Inputs::MIE_PHASE)
            } else {
                Inputs::GROUND_ALBEDO
            };
            inputs.stale(Some(old), atmosphere)
        });
        Stale {
            columns: Inputs::COLUMNS.stale(self.columns.as_ref(), atmosphere),
            sun: Inputs::EXTINCTION.stale(self.sun.as_ref(), atmosphere),
            single,
            orders: single || orders,
        }
    }

    /// Whether Mie was computed in the orders as built.
    pub fn mie(&self) -> bool {
        self.orders.as_ref().is_some_and(|(_, mie)| *mie)
    }
}
