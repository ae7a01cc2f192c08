//! The frame planner: the one place that decides which table builds and passes a frame
//! runs, and which it skips. Each step comes back with the frame, with its GPU time when
//! the adapter can measure it.

/// Whether a step builds a table or renders.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepKind {
    TableBuild,
    Pass,
}

/// One step of a frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanStep {
    /// The table or pass, named like its shader (`g_l`, `nishita`, `tone_map`).
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
}

impl FramePlan {
    /// The plan of a nishita frame: the g_l table only when its inputs (atmosphere
    /// columns, table size) changed since it was last built, then the per-pixel pass and
    /// the tone map.
    pub fn nishita(table_stale: bool) -> FramePlan {
        let step = |name, kind| PlanStep {
            name,
            kind,
            gpu_ms: None,
        };
        let mut plan = FramePlan::default();
        if table_stale {
            plan.steps.push(step("g_l", StepKind::TableBuild));
        } else {
            plan.skipped.push(("g_l", "inputs unchanged"));
        }
        plan.steps.push(step("nishita", StepKind::Pass));
        plan.steps.push(step("tone_map", StepKind::Pass));
        plan
    }

    /// Whether the step `name` runs.
    pub fn runs(&self, name: &str) -> bool {
        self.steps.iter().any(|s| s.name == name)
    }
}

impl std::fmt::Display for FramePlan {
    /// One line: `g_l 1.20 ms, nishita 3.40 ms, tone_map 0.10 ms; skipped: ...`.
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
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unchanged_tables_are_skipped() {
        let first = FramePlan::nishita(true);
        assert!(first.runs("g_l") && first.runs("nishita") && first.runs("tone_map"));
        let next = FramePlan::nishita(false);
        assert!(!next.runs("g_l"));
        assert_eq!(
            next.to_string(),
            "nishita, tone_map; skipped: g_l (inputs unchanged)"
        );
    }
}
