//! `atmos stability`: the stiff and extreme cases of `atmosphere_core::analysis::stability`
//! through every model (or the chosen ones), as a table of pass or fail and the worst
//! value seen.

use std::io::Write;

use anyhow::{Context, bail};
use atmosphere_core::analysis::stability;
use atmosphere_core::models::id::ModelId;

use crate::cli::StabilityArgs;

/// Runs the sweep and prints a Markdown table; fails if any case fails.
pub fn run(args: &StabilityArgs) -> anyhow::Result<()> {
    let models: Vec<ModelId> = if args.model.is_empty() {
        ModelId::ALL.to_vec()
    } else {
        args.model.clone()
    };
    let mut out = std::io::stdout().lock();
    writeln!(out, "| model | case | result | worst | failure |")?;
    writeln!(out, "|---|---|---|---|---|")?;
    let (mut cases, mut failures) = (0, 0);
    for id in models {
        eprintln!("stability: running {id}...");
        let results = stability::run(id).with_context(|| format!("model {id}"))?;
        for r in results {
            cases += 1;
            if !r.passed {
                failures += 1;
            }
            writeln!(
                out,
                "| {id} | {} | {} | {:.3e} | {} |",
                r.case,
                if r.passed { "pass" } else { "FAIL" },
                r.worst,
                r.failure.as_deref().unwrap_or("")
            )?;
        }
    }
    writeln!(
        out,
        "\n{cases} cases: {} passed, {failures} failed",
        cases - failures
    )?;
    if failures > 0 {
        bail!("{failures} stability case(s) failed");
    }
    Ok(())
}
