//! The frame planner's record: which table builds and passes a frame runs, in order, and
//! which it skips and why, by name. Each model decides its own steps (typed, in
//! `crate::sky::steps`, which records them here); the renderer adds the terrain and the
//! tone map. Each step comes back with the frame, with its GPU time when the adapter can
//! measure it.

/// Why a table build is skipped when nothing it depends on changed.
pub const INPUTS_UNCHANGED: &str = "inputs unchanged";

/// Whether a step builds a table or renders.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepKind {
    TableBuild,
    Pass,
}

/// One step of a frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanStep {
    /// The table or pass, named like its shader or CPU twin (`g_l`, `nishita`, `tone_map`).
    pub name: &'static str,
    pub kind: StepKind,
    /// GPU time, ms; `None` where the adapter has no timestamp queries.
    pub gpu_ms: Option<f64>,
}

/// The steps a frame runs, in order, and those it skips with the reason.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct FramePlan {
    pub steps: Vec<PlanStep>,
    pub skipped: Vec<(&'static str, &'static str)>,
    /// Whether the frame's rays may end on a surface (`surface_buffer.rs`), set by the
    /// renderer before the model plans: a surface may lie at any distance in any
    /// direction, so passes that serve nearby ground serve it too.
    pub surface: bool,
    /// Whether the frame's sun map shades the air below the cloud layer's base, set by
    /// the renderer before the model plans (hillaire then runs its cloud shafts;
    /// `clouds/frame_cloud_shafts.rs`).
    pub cloud_shafts: bool,
    /// What a progressive table build ([`crate::Renderer::set_progressive`]) is doing
    /// this frame when more of it follows in later frames (`bruneton: order 3 of at most
    /// 32, Delta S slice 2 of 16`): the image is not final yet. `None` when the tables
    /// are complete.
    pub building: Option<String>,
}

impl FramePlan {
    /// Adds a step that runs.
    pub fn run(&mut self, name: &'static str, kind: StepKind) {
        self.steps.push(PlanStep {
            name,
            kind,
            gpu_ms: None,
        });
    }

    /// Records a step left out and why.
    pub fn skip(&mut self, name: &'static str, why: &'static str) {
        self.skipped.push((name, why));
    }

    /// Whether the step `name` runs.
    pub fn runs(&self, name: &str) -> bool {
        self.steps.iter().any(|s| s.name == name)
    }

    /// Sum of the steps' GPU times, ms, when every step was timed.
    pub fn total_gpu_ms(&self) -> Option<f64> {
        self.steps.iter().map(|s| s.gpu_ms).sum()
    }
}

impl std::fmt::Display for FramePlan {
    /// One line: `g_l 1.20 ms, nishita 3.40 ms, tone_map 0.10 ms; skipped: ...;
    /// building: ...`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (i, step) in self.steps.iter().enumerate() {
            let sep = if i == 0 { "" } else { ", " };
            match step.gpu_ms {
                Some(ms) => write!(f, "{sep}{} {ms:.2} ms", step.name)?,
                None => write!(f, "{sep}{}", step.name)?,
            }
        }
        for (i, (name, why)) in self.skipped.iter().enumerate() {
            let sep = if i == 0 { "; skipped: " } else { ", " };
            write!(f, "{sep}{name} ({why})")?;
        }
        if let Some(building) = &self.building {
            write!(f, "; building: {building}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stale_tables_run_and_fresh_ones_are_skipped_with_why() {
        let mut plan = FramePlan::default();
        plan.skip("g_l", INPUTS_UNCHANGED);
        plan.run("nishita", StepKind::Pass);
        plan.run("tone_map", StepKind::Pass);
        assert!(!plan.runs("g_l") && plan.runs("nishita"));
        assert_eq!(
            plan.to_string(),
            "nishita, tone_map; skipped: g_l (inputs unchanged)"
        );
        assert_eq!(plan.total_gpu_ms(), None);
        plan.steps.iter_mut().for_each(|s| s.gpu_ms = Some(1.5));
        assert_eq!(plan.total_gpu_ms(), Some(3.0));
        plan.building = Some("bruneton: single scattering".into());
        assert!(
            plan.to_string()
                .ends_with("(inputs unchanged); building: bruneton: single scattering"),
            "{plan}"
        );
    }
}
