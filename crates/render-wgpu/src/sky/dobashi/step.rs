//! The dobashi model's steps: its table builds and the pass.

use crate::frame::plan::StepKind;
use crate::sky::steps::PassStep;

/// One step of the model's plan.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DobashiStep {
    /// The columns table g_l.
    GL,
    /// The segment tables of the sampling planes.
    PlaneTables,
    /// The segment tables of the sample spheres.
    SphereTables,
    /// The ambient term's table.
    Ambient,
    /// The per-pixel pass.
    Pass,
}

impl PassStep for DobashiStep {
    fn name(self) -> &'static str {
        match self {
            DobashiStep::GL => "g_l",
            DobashiStep::PlaneTables => "plane_tables",
            DobashiStep::SphereTables => "sphere_tables",
            DobashiStep::Ambient => "ambient",
            DobashiStep::Pass => "dobashi",
        }
    }

    fn kind(self) -> StepKind {
        match self {
            DobashiStep::Pass => StepKind::Pass,
            _ => StepKind::TableBuild,
        }
    }
}
