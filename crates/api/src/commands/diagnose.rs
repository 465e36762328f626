//! `propbet diagnose`: which physical effect is missing from the model, its report written
//! and its ranking told; `propbet effects`: the effects there are.

use propbet_pipeline::stages::{self, Diagnosed};
use propbet_report::diagnose as report;
use propbet_settings::spec::{DiagnoseSpec, StageSpec};

use super::compare::{print_measured, warn_faulty_rows};
use super::predict::load_model_at;
use crate::console::Console;
use crate::CommandResult as Result;

/// Runs a diagnose stage of `spec`: its files written, its answer told; whether it ran clean
/// (false, as `compare`, when measured rows were dropped as faulty: the diagnosis ran on the
/// rest, the report lists them), and what it wrote.
pub fn diagnose(spec: &DiagnoseSpec, console: &dyn Console) -> Result<(bool, Written)> {
    let mut inputs = spec.model.inputs();
    inputs.extend(spec.measured.inputs());
    crate::files::refuse_inputs_inside(&spec.out, &inputs)?;
    let model = load_model_at(&spec.model, || crate::model::cover(&spec.measured), false, console)?;
    let d = stages::diagnose(&model, spec)?;
    let written = write(spec, &d, console)?;
    print(spec, &d, console);
    let warned = warn_faulty_rows(&d.names, &d.sets, console);
    Ok((warned == 0 && d.refused.is_empty(), written))
}

/// What the diagnose stage wrote, as it wrote it.
pub struct Written {
    /// The report page's body (the run's page nests it).
    pub body: String,
    /// diagnosis.json.
    pub diagnosis: Vec<u8>,
    /// summary.json.
    pub summary: Vec<u8>,
}

/// Writes the diagnosis's outputs into `spec.out` ([`crate::outputs::diagnose`]).
pub fn write(spec: &DiagnoseSpec, d: &Diagnosed, console: &dyn Console) -> Result<Written> {
    let command = console.command(&StageSpec::Diagnose(spec.clone()));
    let use_it = console.effect_args(&d.diagnosis).join(" ");
    let mut made = crate::outputs::diagnose::outputs(spec, d, &command, &use_it)?;
    let mut inputs = spec.model.inputs();
    inputs.extend(spec.measured.inputs());
    made.files.write(&spec.out, &command, &inputs)?;
    Ok(Written {
        body: made.body,
        diagnosis: made.files.take("diagnosis.json"),
        summary: made.files.take("summary.json"),
    })
}

/// The diagnosis told: the files read, the answer, where the report is.
pub fn print(spec: &DiagnoseSpec, d: &Diagnosed, console: &dyn Console) {
    print_measured(&d.names, &d.sets, &d.refused, console);
    print_result(&d.diagnosis, console);
    console.out(&format!("report: {}", spec.out.join("report.html").display()));
}

/// The diagnosis told: verdict, where the baseline fails, ranking, ladder.
pub fn print_result(d: &crate::diagnose::Diagnosis, console: &dyn Console) {
    console.out_sentence(&report::verdict(d), "", "");
    console.out("where the baseline fails:");
    for s in &d.before {
        console.out_sentence(&report::signature_text(s), "  ", "    ");
    }
    console.out("ranking (held-out RMS, p, significant):");
    for (i, s) in d.ranking.iter().enumerate() {
        let remark = report::ladder_remark(d, s);
        match &s.note {
            Some(n) => console.out(&format!("  {:>2}. {:<16} {n}", i + 1, s.id)),
            None => console.out(&format!(
                "  {:>2}. {:<16} {:>7.2} %  p {:<9.3e} {}",
                i + 1,
                s.id,
                100.0 * s.kfold_rms,
                s.p_value,
                if s.significant { "significant" } else { "-" }
            )),
        }
        if let Some(r) = remark {
            console.out_sentence(&format!("({r})"), "      ", "       ");
        }
    }
    console.out("ladder (held-out error; the thrust error's trend with J at fixed RPM and with RPM at fixed J):");
    let trend = |t: Option<f64>| t.map_or("–".to_string(), |t| format!("{:+.1} %", 100.0 * t));
    for r in &d.ladder {
        console.out(&format!(
            "  {:<60} held-out {:>6.2} %  J trend {:>7}  RPM trend {:>7}",
            r.stack,
            100.0 * r.kfold_rms,
            trend(r.thrust_j_trend),
            trend(r.thrust_rpm_trend)
        ));
    }
}

/// `propbet effects`: the effects (built-in, and those of a user file) with their
/// parameters, bounds and physics, line by line.
pub fn effects(user_effects: Option<&std::path::Path>, console: &dyn Console) -> Result<bool> {
    let registry = propbet_model::effect_registry(user_effects)?;
    let value = crate::effects::fmt_value;
    for e in &registry.effects {
        let hooks: Vec<String> = e.hooks().iter().map(|h| format!("{h:?}").to_lowercase()).collect();
        console.out(&format!("{} ({})", e.id(), hooks.join(", ")));
        for p in e.params() {
            let neutral = p.neutral.map_or("none".to_string(), value);
            let (lo, hi) = p.expected_range();
            console.out(&format!(
                "    {} [{}]  neutral {neutral}, bounds [{}, {}], physically expected [{}, {}]: {}",
                p.name,
                p.unit,
                value(p.lower),
                value(p.upper),
                value(lo),
                value(hi),
                p.doc
            ));
        }
        console.out(&format!(
            "    {}",
            e.explanation().split_whitespace().collect::<Vec<_>>().join(" ")
        ));
    }
    console.out("transition (section)");
    console.out(
        "    ncrit [-]  neutral: the polars' own Ncrit, bounds: the lowest and highest Ncrit \
         computed. Known where the polars (--polars FILE, a case's tables) were also computed at other Ncrit values \
         (propbet polars --ncrit-effect 3,9; [polars] ncrit_effect in a case): each station's lift and drag move by \
         the difference between its tables at the fitted Ncrit and at the model's own.",
    );
    Ok(true)
}
