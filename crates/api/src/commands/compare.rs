//! `propbet compare`: measured files against the model's prediction; its report folder
//! written (report.html, metrics.json, summary.json, summary.md, points.csv, plots) and its
//! headline told.

use std::path::Path;

use propbet_model::Model;
use propbet_pipeline::stages::{self, Compared, Reference};
use propbet_report::answer::ReferenceScore;
use propbet_settings::spec::{CompareSpec, StageSpec};

use super::predict::load_model_at;
use crate::compare::ComparedPoint;
use crate::console::Console;
use crate::measure::{MeasuredSet, Refused};
use crate::CommandResult as Result;

/// One line per file read (rows, points, what was dropped) and per file refused (why).
pub fn print_measured(names: &[String], sets: &[MeasuredSet], refused: &[Refused], console: &dyn Console) {
    for (n, s) in names.iter().zip(sets) {
        console.err(&format!(
            "propbet: {n}: {} rows -> {} points; {}",
            s.rows,
            s.points.len(),
            crate::measure::summarise_dropped(&s.dropped)
        ));
    }
    for r in refused {
        console.err(&format!("propbet: warning: {}: not read: {}", r.file, r.reason));
    }
}

/// Tells how many measured rows were dropped as faulty (the report lists them) and each
/// set's plausibility warning; returns the count of both (`compare` and `diagnose` exit 1
/// when it is not zero).
pub fn warn_faulty_rows(names: &[String], sets: &[MeasuredSet], console: &dyn Console) -> usize {
    let faults: usize = sets.iter().map(MeasuredSet::faults).sum();
    if faults > 0 {
        console.err(&format!(
            "propbet: {faults} rows were dropped as faulty; they are listed in the report"
        ));
    }
    let mut warned = 0;
    for (n, s) in names.iter().zip(sets) {
        for w in &s.warnings {
            console.err(&format!("propbet: warning: {n}: {w}"));
            warned += 1;
        }
    }
    faults + warned
}

/// Runs a compare stage of `spec`: its files written, its answer told; whether it ran clean
/// (false when rows were dropped as faulty, the solver did not converge somewhere or the
/// measurements cannot be of this propeller, all told), and what it wrote.
pub fn compare(spec: &CompareSpec, console: &dyn Console) -> Result<(bool, Written)> {
    crate::files::refuse_inputs_inside(&spec.out, &inputs(spec))?;
    let model = load_model_at(&spec.model, || crate::model::cover(&spec.measured), false, console)?;
    // A reference that cannot be read stops the command before anything is computed.
    let other = reference(spec, model.diameter, console)?;
    let c = stages::compare(&model, stages::load_batch(&spec.measured)?)?;
    let electric = match &spec.motor {
        Some(m) => {
            let e = stages::electric(&c, &model, m)?;
            if e.is_none() {
                console.err(
                    "propbet: warning: --motor: no compared point logged the supply's voltage and current; nothing electrical to score",
                );
            }
            e
        }
        None => None,
    };
    let written = write(spec, &model, &c, other.as_ref(), electric.as_ref(), console)?;
    print(spec, &c, written.reference.as_ref(), console);
    if let Some(e) = &electric {
        console.out_sentence(&propbet_report::compare::electric_sentence(e), "", "  ");
    }
    Ok((c.clean(), written))
}

/// What `compare` wrote that a caller reads: the report's body, the reference's score, the
/// lead figure, and the bytes of metrics.json, summary.json and points.csv.
pub struct Written {
    /// The report's body (the run page holds it).
    pub body: String,
    /// The reference's score, if one was given.
    pub reference: Option<ReferenceScore>,
    /// The figure the run page leads with.
    pub lead: Option<propbet_plot::Figure>,
    /// metrics.json.
    pub metrics: Vec<u8>,
    /// summary.json.
    pub summary: Vec<u8>,
    /// points.csv.
    pub points: Vec<u8>,
}

/// Writes the comparison's outputs into `spec.out` ([`crate::outputs::compare`]).
pub fn write(
    spec: &CompareSpec,
    model: &Model,
    c: &Compared,
    other: Option<&Reference>,
    electric: Option<&crate::compare::electric::Electric>,
    console: &dyn Console,
) -> Result<Written> {
    let command = console.command(&StageSpec::Compare(spec.clone()));
    let mut made = crate::outputs::compare::outputs(spec, model, c, other, electric, &command)?;
    made.files.write(&spec.out, &command, &inputs(spec))?;
    Ok(Written {
        body: made.body,
        reference: made.reference,
        lead: made.lead,
        metrics: made.files.take("metrics.json"),
        summary: made.files.take("summary.json"),
        points: made.files.take("points.csv"),
    })
}

/// The files a comparison reads (none may be overwritten).
fn inputs(spec: &CompareSpec) -> Vec<&Path> {
    let mut inputs = spec.model.inputs();
    inputs.extend(spec.measured.inputs());
    inputs.extend(spec.per3.as_deref());
    inputs.extend(spec.qprop_output.as_deref());
    inputs.extend(spec.motor.as_deref());
    inputs
}

/// The reference `spec` names ([`Reference::load`]), its reading's warning told.
pub fn reference(spec: &CompareSpec, diameter: f64, console: &dyn Console) -> Result<Option<Reference>> {
    let r = Reference::load(spec, diameter)?;
    if let Some(w) = r.as_ref().and_then(|r| r.warning.as_ref()) {
        console.err(&format!("propbet: warning: {w}"));
    }
    Ok(r)
}

/// The comparison's short summary; `reference`: another code's name and headline (from
/// [`write`]), under propbet's.
pub fn print(spec: &CompareSpec, c: &Compared, reference: Option<&ReferenceScore>, console: &dyn Console) {
    print_measured(&c.names, &c.sets, &c.refused, console);
    let m = &c.metrics;
    // The headline: the scored window, static and forward flight apart (as the report).
    for g in &m.headline {
        console.out(&format!("{}:", g.name));
        for q in ["thrust", "torque"] {
            if let Some(x) = g.metrics.get(q).filter(|x| x.mean_rel.is_nan()) {
                console.out(&format!(
                    "{q:>7}: n {:>3}  no relative error: every measured value is below 5 % of the largest",
                    x.n
                ));
            } else if let Some(x) = g.metrics.get(q) {
                console.out(&format!(
                    "{q:>7}: n {:>3}  mean error {:+6.1} %  mean |error| {:5.1} %  worst {:+6.1} % ({})",
                    x.n,
                    100.0 * x.mean_rel,
                    100.0 * x.mean_abs_rel,
                    100.0 * x.max_rel,
                    x.max_rel_at
                ));
            }
        }
        let theirs = reference.and_then(|r| {
            let e = |q: &str| r.mean_error(&g.name, q);
            Some((r.name.clone(), e("thrust")?, e("torque")))
        });
        if let Some((name, t, q)) = theirs {
            let torque = q.map_or(String::new(), |q| format!(", torque {:+.1} %", 100.0 * q));
            console.out(&format!("  {name}: thrust mean error {:+.1} %{torque}", 100.0 * t));
        }
    }
    if m.outside_window > 0 {
        console.out(&format!(
            "({} point(s) at or beyond 85 % of their sweep's zero-thrust J: in the report, not in these numbers)",
            m.outside_window
        ));
    }
    if m.overall.points == 0 {
        let mut reasons: Vec<&str> = c
            .points
            .iter()
            .flat_map(|p| p.flags.iter().map(String::as_str))
            .collect();
        reasons.sort_unstable();
        reasons.dedup();
        console.out(&format!(
            "no point could be scored: all {} points are flagged ({})",
            c.points.len(),
            reasons.join("; ")
        ));
    }
    console.out(&format!("report: {}", spec.out.join("report.html").display()));
    if let Some(m) = c.mismatch() {
        console.err(&format!("propbet: warning: {}", m.message()));
    }
    let (_, unconverged) = c.problems();
    warn_faulty_rows(&c.names, &c.sets, console);
    if unconverged > 0 {
        console.err(&format!("propbet: {unconverged} station solutions did not converge"));
    }
    let flagged: Vec<&ComparedPoint> = c.points.iter().filter(|p| !p.model_flags.is_empty()).collect();
    if let Some(first) = flagged.first() {
        console.err(&format!(
            "propbet: warning: the prediction is physically implausible at {} of {} points (column model_flags of points.csv), for example at {:.0} rpm, J {:.3}: {}",
            flagged.len(),
            c.points.len(),
            first.rpm,
            first.j,
            first.model_flags.join("; ")
        ));
    }
}
