//! The hillaire model's steps: a table build or the pass.

use crate::frame::plan::StepKind;
use crate::sky::hillaire::tables::Table;
use crate::sky::steps::PassStep;

/// One step of the model's plan.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HillaireStep {
    /// Builds a table.
    Table(Table),
    /// The per-pixel pass (`hillaire`), every frame.
    Pass,
}

impl PassStep for HillaireStep {
    fn name(self) -> &'static str {
        match self {
            HillaireStep::Table(table) => table.name(),
            HillaireStep::Pass => "hillaire",
        }
    }

    fn kind(self) -> StepKind {
        match self {
            HillaireStep::Table(_) => StepKind::TableBuild,
            HillaireStep::Pass => StepKind::Pass,
        }
    }
}
