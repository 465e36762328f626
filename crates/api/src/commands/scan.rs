//! `propbet scan`: a mesh or a cloud → sections and their fits, the scan's files written and
//! its summary told.

use std::path::Path;

use propbet_pipeline::stages::{self, Scanned};
use propbet_settings::spec::{ScanSpec, StageSpec};

use crate::console::Console;
use crate::CommandResult as Result;

/// Runs a scan stage: its files written, its summary told; false when a station could not be
/// measured or fitted (said).
pub fn run(spec: &ScanSpec, console: &dyn Console) -> Result<bool> {
    crate::files::refuse_inputs_inside(&spec.out, &inputs(spec))?;
    let s = stages::scan(spec)?;
    write(spec, &s, console)?;
    print_summary(&s, console);
    console.out(&format!("wrote {}", spec.out.display()));
    Ok(s.clean())
}

/// The files a scan reads (none may be overwritten).
fn inputs(spec: &ScanSpec) -> Vec<&Path> {
    std::iter::once(spec.input.as_path())
        .chain(spec.reference.as_deref())
        .collect()
}

/// Writes the scan stage's outputs into `spec.out` ([`crate::outputs::scan`]).
pub fn write(spec: &ScanSpec, sc: &Scanned, console: &dyn Console) -> Result<()> {
    let command = console.command(&StageSpec::Scan(spec.clone()));
    crate::outputs::scan::outputs(spec, sc)?.write(&spec.out, &command, &inputs(spec))
}

/// The scan's summary.
pub fn print_summary(sc: &Scanned, console: &dyn Console) {
    let (g, reference) = (&sc.geometry, sc.reference.as_deref());
    console.out(&propbet_report::scan::summary(g));
    console.out(&format!("  {}", propbet_report::scan::accuracy(g)));
    for n in &g.notes {
        console.out(&format!("  {n}"));
    }
    for f in &g.failed {
        console.out(&format!("  r/R {:.3}: {}", f.r_r, f.reason));
    }
    if let Some(line) = reference.and_then(|t| propbet_report::scan::reference_check(g, t)) {
        console.out(&line);
    }
}
