//! The bookkeeping every model's `SkyModel::update` shares: which inputs changed between
//! the atmosphere its tables were built from and the new one, and the names of the tables
//! rebuilt.

use crate::atmosphere::Atmosphere;
use crate::atmosphere::table_inputs::Inputs;
use crate::models::error::ModelError;
use crate::optics::transmittance_table::TransmittanceTable;

/// One update of a model's tables from `old` to `new`.
#[derive(Debug)]
pub struct TableUpdate {
    /// The inputs that differ between the two atmospheres.
    pub changed: Inputs,
    rebuilt: Vec<&'static str>,
}

impl TableUpdate {
    /// Checks `new` and finds what changed since `old`.
    pub fn new(old: &Atmosphere, new: &Atmosphere) -> Result<TableUpdate, ModelError> {
        new.validate()?;
        Ok(TableUpdate {
            changed: Inputs::changed(old, new),
            rebuilt: Vec::new(),
        })
    }

    /// Replaces `table` by `build()` when one of `inputs` changed, naming it `name`.
    pub fn rebuild<T>(
        &mut self,
        inputs: Inputs,
        name: &'static str,
        table: &mut T,
        build: impl FnOnce() -> T,
    ) {
        if self.changed.intersects(inputs) {
            *table = build();
            self.rebuilt.push(name);
        }
    }

    /// Replaces a table of columns of matter (`size` as in [`TransmittanceTable::build`])
    /// by one built from `atmosphere` when the columns changed ([`Inputs::COLUMNS`]).
    pub fn rebuild_columns(
        &mut self,
        name: &'static str,
        table: &mut TransmittanceTable,
        atmosphere: &Atmosphere,
        (width, height): (usize, usize),
    ) {
        self.rebuild(Inputs::COLUMNS, name, table, || {
            TransmittanceTable::build(atmosphere, width, height)
        });
    }

    /// Names tables rebuilt by the model itself.
    pub fn mark(&mut self, names: &[&'static str]) {
        self.rebuilt.extend_from_slice(names);
    }

    /// The names of the tables rebuilt, in order.
    pub fn rebuilt(self) -> Vec<&'static str> {
        self.rebuilt
    }
}
