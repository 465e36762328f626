//! `propbet compare`'s outputs: report.html, metrics.json, summary.json, summary.md,
//! points.csv, electric.csv (with a motor) and the plots.

use crate::CommandResult as Result;
use propbet_model::Model;
use propbet_pipeline::stages::{Compared, Reference};
use propbet_report::answer::ReferenceScore;
use propbet_report::compare::{self as report, FileEntry, ReferenceInput, ReportInput};
use propbet_report::table::csv_rows;
use propbet_settings::spec::CompareSpec;

use crate::files::Outputs;

/// A comparison's outputs.
pub struct Comparison {
    /// Every file, in the order they are written.
    pub files: Outputs,
    /// The report's body (HTML, without the page around it): the run page holds it.
    pub body: String,
    /// The score of the reference (APC's or QPROP's table), if one was given.
    pub reference: Option<ReferenceScore>,
    /// The figure the run page leads with.
    pub lead: Option<propbet_plot::Figure>,
}

/// The outputs of comparing `model` with the measurements (`c`), with the reference `other`
/// and the electrical comparison if given; `command` is the one the report names.
pub fn outputs(
    spec: &CompareSpec,
    model: &Model,
    c: &Compared,
    other: Option<&Reference>,
    electric: Option<&crate::compare::electric::Electric>,
    command: &str,
) -> Result<Comparison> {
    let (curves, band) = c.curves(model, 1)?;
    let mut prop_notes = model.loaded.warnings.clone();
    if spec.model.qprop_compat {
        prop_notes.push(format!(
            "read as QPROP 1.22 does (--qprop-compat): tip-loss radius {} m",
            model.rotor.tip_radius
        ));
    }
    if !model.effects.is_empty() {
        prop_notes.push(format!("model with effects: {}", model.effects.describe()));
    }
    let other_at = |rpm: f64, j: f64| other.and_then(|r| r.at(rpm, j));
    let rep = report::build(&ReportInput {
        reference: other.map(|r| ReferenceInput {
            name: r.name.clone(),
            at: &other_at,
        }),
        prop: spec.model.prop.display().to_string(),
        prop_notes,
        files: c
            .names
            .iter()
            .zip(&c.sets)
            .map(|(p, set)| FileEntry { path: p.clone(), set })
            .collect(),
        refused: &c.refused,
        warnings: c.warnings(),
        points: &c.points,
        band: Some(&band),
        band_sources: propbet_model::band::BandSpec::sources_text(&model.loaded.file),
        metrics: &c.metrics,
        diameter: model.diameter,
        curves: &curves,
        command: command.to_string(),
        electric,
    })?;
    let mut files = Outputs::default();
    for (name, fig) in &rep.figures {
        files.figure(&format!("plots/{name}"), fig)?;
    }
    let mut json = serde_json::to_vec_pretty(&rep.json)?;
    json.push(b'\n');
    files.add("metrics.json", json);
    let summary = report::summary_json(
        command,
        &c.metrics,
        &c.points,
        c.problems(),
        &c.warnings(),
        rep.reference.as_ref(),
        electric,
    );
    if let Some(e) = electric {
        files.add("electric.csv", csv_rows(&e.points, true)?);
    }
    let mut summary = serde_json::to_vec_pretty(&summary)?;
    summary.push(b'\n');
    files.add("summary.json", summary);
    files.add("summary.md", rep.markdown.as_bytes());
    files.add("points.csv", propbet_report::table::points::csv(&c.names, &c.points)?);
    files.add("report.html", rep.html.as_bytes());
    let lead = report::lead_figure(&rep.figures);
    Ok(Comparison {
        files,
        body: rep.body,
        reference: rep.reference,
        lead,
    })
}
