//! `propbet validate`: every UIUC propeller that has a geometry file and a matching APC PE0
//! file is predicted (UIUC's r/R, c/R, β, or with `--geometry pe0` APC's design c and β at
//! UIUC's r/R; APC's airfoils scaled to the PE0 thickness ratio at
//! each station; XFOIL polars at each station's Re) and compared with every static and J-sweep
//! file, before and after the diagnosis' ladder. Each prop is run as the documented commands
//! (`polars`, `compare`, `diagnose`, `compare --effect ...`) in its own directory; the table of
//! relative CT and CP errors is written as Markdown and CSV.

use anyhow::Result;
use propbet_api::commands::validate::ValidateRequest;

/// Runs `propbet validate`: false when a prop reported problems; and what it wrote.
pub fn run(a: &ValidateRequest) -> Result<(bool, propbet_api::commands::validate::Written)> {
    let (spec, props, generic) = a.spec()?;
    let term = crate::output::Terminal::default();
    Ok(propbet_api::commands::validate::validate(
        &spec,
        &props,
        generic.as_ref(),
        &term,
    )?)
}
