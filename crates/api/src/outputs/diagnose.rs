//! `propbet diagnose`'s outputs: report.html, diagnosis.json, summary.json, summary.md and the
//! plots.

use crate::CommandResult as Result;
use propbet_pipeline::stages::Diagnosed;
use propbet_report::compare::FileEntry;
use propbet_report::diagnose::{self as report, JsonOut};
use propbet_settings::spec::DiagnoseSpec;

use crate::files::Outputs;

/// A diagnosis's outputs.
pub struct Diagnosis {
    /// Every file, in the order they are written.
    pub files: Outputs,
    /// The report's body (HTML, without the page around it): the run page holds it.
    pub body: String,
}

/// The outputs of a diagnosis; `command` is the one the report names, `use_it` the flags that
/// add its answer to a model (`--effect ...`).
pub fn outputs(spec: &DiagnoseSpec, d: &Diagnosed, command: &str, use_it: &str) -> Result<Diagnosis> {
    let prop = spec.model.prop.display().to_string();
    let measured: Vec<String> = d.names.clone();
    let dg = &d.diagnosis;
    let entries: Vec<FileEntry> = measured
        .iter()
        .zip(&d.sets)
        .map(|(path, set)| FileEntry {
            path: path.clone(),
            set,
        })
        .collect();
    let rep = report::build(&d.data, dg, &prop, &entries, &d.refused, command, use_it)?;
    let mut files = Outputs::default();
    for (name, fig) in &rep.figures {
        files.figure(&format!("plots/{name}"), fig)?;
    }
    let json = JsonOut {
        prop: &prop,
        measured: &measured,
        command,
        diagnosis: dg,
        final_params: dg.ladder.last().map(|r| r.params.clone()).unwrap_or_default(),
        final_effects: dg.final_effects(),
    };
    let mut bytes = serde_json::to_vec_pretty(&json)?;
    bytes.push(b'\n');
    files.add("diagnosis.json", bytes);
    let faults: usize = d.sets.iter().map(|s| s.faults()).sum();
    let warnings = propbet_pipeline::stages::batch_warnings(&d.names, &d.sets, &d.refused);
    let summary = serde_json::json!({
        "format": "propbet-diagnose-summary-1",
        "command": command,
        "clean": faults == 0 && warnings.is_empty(),
        "warnings": warnings,
        "problems": { "dropped_rows": faults },
        "diagnosis": report::diagnosis_json(dg),
    });
    let mut summary = serde_json::to_vec_pretty(&summary)?;
    summary.push(b'\n');
    files.add("summary.json", summary);
    files.add("summary.md", rep.markdown.as_bytes());
    files.add("report.html", rep.html.as_bytes());
    Ok(Diagnosis { files, body: rep.body })
}
