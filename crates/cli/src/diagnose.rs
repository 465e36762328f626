//! `propbet diagnose`: which physical effect is missing from the model; `propbet effects`:
//! the effects there are.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use propbet_pipeline::spec::{DiagnoseSpec, StageSpec};
use propbet_pipeline::stages::{self, Diagnosed};
use propbet_report::diagnose as report;

use crate::compare::{print_measured, warn_faulty_rows, MeasuredArgs};
use crate::predict::{load_model_at, ModelArgs};

/// Arguments of `propbet diagnose`.
#[derive(Debug, Args)]
pub struct DiagnoseArgs {
    /// The propeller model (effects given with --effect are part of the baseline).
    #[command(flatten)]
    pub model: ModelArgs,
    /// The measurements.
    #[command(flatten)]
    pub data: MeasuredArgs,
    /// Candidate effects: `all` (default) or a comma-separated list of ids (user effects too).
    #[arg(long, default_value = "all")]
    pub effects: String,
    #[arg(long = propbet_api::settings::FOLDS.flag, help = propbet_api::settings::FOLDS.help, default_value_t = propbet_api::settings::FOLDS.default)]
    pub folds: usize,
    #[arg(long = propbet_api::settings::MAX_STEPS.flag, help = propbet_api::settings::MAX_STEPS.help, default_value_t = propbet_api::settings::MAX_STEPS.default)]
    pub max_steps: usize,
    #[arg(long = propbet_api::settings::WINDOW.flag, help = propbet_api::settings::WINDOW.help, default_value_t = propbet_api::settings::WINDOW.default)]
    pub window: f64,
    /// Output directory (created if missing).
    #[arg(long, short)]
    pub out: PathBuf,
}

impl DiagnoseArgs {
    /// The stage's spec (flags in SI).
    pub fn spec(&self) -> Result<DiagnoseSpec> {
        let request = propbet_api::DiagnoseRequest {
            effects: Some(self.effects.split(',').map(str::to_string).collect()),
            folds: Some(self.folds),
            max_steps: Some(self.max_steps),
            window: Some(self.window),
        };
        Ok(request.spec(self.model.spec()?, self.data.spec()?, self.out.clone())?)
    }
}

/// Runs `propbet diagnose`; returns false (exit 1, as `compare`) when measured rows were
/// dropped as faulty: the diagnosis ran on the rest, the report lists them.
pub fn run(args: &DiagnoseArgs) -> Result<bool> {
    Ok(run_spec(&args.spec()?)?.0)
}

/// Runs a diagnose stage of `spec`: its files written, its answer printed; whether it ran
/// clean, and what it wrote.
pub fn run_spec(spec: &DiagnoseSpec) -> Result<(bool, Written)> {
    let mut inputs = spec.model.inputs();
    inputs.extend(spec.measured.inputs());
    propbet_api::files::refuse_inputs_inside(&spec.out, &inputs)?;
    let model = load_model_at(&spec.model, || propbet_api::model::cover(&spec.measured), false)?;
    let d = stages::diagnose(&model, spec)?;
    let written = write(spec, &d)?;
    print(spec, &d);
    let warned = warn_faulty_rows(&d.names, &d.sets);
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

/// Writes the diagnosis's outputs into `spec.out` (`propbet_api::outputs::diagnose`).
pub fn write(spec: &DiagnoseSpec, d: &Diagnosed) -> Result<Written> {
    let command = crate::argv::command(&StageSpec::Diagnose(spec.clone()));
    let use_it = crate::argv::effect_args(&d.diagnosis).join(" ");
    let mut made = propbet_api::outputs::diagnose::outputs(spec, d, &command, &use_it)?;
    let mut inputs = spec.model.inputs();
    inputs.extend(spec.measured.inputs());
    made.files.write(&spec.out, &command, &inputs)?;
    Ok(Written {
        body: made.body,
        diagnosis: made.files.take("diagnosis.json"),
        summary: made.files.take("summary.json"),
    })
}

/// The diagnosis on the terminal.
pub fn print(spec: &DiagnoseSpec, d: &Diagnosed) {
    print_measured(&d.names, &d.sets, &d.refused);
    print_result(&d.diagnosis);
    println!("report: {}", spec.out.join("report.html").display());
}

/// The diagnosis on the terminal: verdict, where the baseline fails, ranking, ladder.
pub fn print_result(d: &propbet_api::diagnose::Diagnosis) {
    println!("{}", crate::output::wrapped(&report::verdict(d), "", ""));
    println!("where the baseline fails:");
    for s in &d.before {
        println!("{}", crate::output::wrapped(&report::signature_text(s), "  ", "    "));
    }
    println!("ranking (held-out RMS, p, significant):");
    for (i, s) in d.ranking.iter().enumerate() {
        let remark = report::ladder_remark(d, s);
        match &s.note {
            Some(n) => println!("  {:>2}. {:<16} {n}", i + 1, s.id),
            None => println!(
                "  {:>2}. {:<16} {:>7.2} %  p {:<9.3e} {}",
                i + 1,
                s.id,
                100.0 * s.kfold_rms,
                s.p_value,
                if s.significant { "significant" } else { "-" }
            ),
        }
        if let Some(r) = remark {
            println!("{}", crate::output::wrapped(&format!("({r})"), "      ", "       "));
        }
    }
    println!("ladder (held-out error; the thrust error's trend with J at fixed RPM and with RPM at fixed J):");
    let trend = |t: Option<f64>| t.map_or("–".to_string(), |t| format!("{:+.1} %", 100.0 * t));
    for r in &d.ladder {
        println!(
            "  {:<60} held-out {:>6.2} %  J trend {:>7}  RPM trend {:>7}",
            r.stack,
            100.0 * r.kfold_rms,
            trend(r.thrust_j_trend),
            trend(r.thrust_rpm_trend)
        );
    }
}

/// Arguments of `propbet effects`.
#[derive(Debug, Args)]
pub struct EffectsArgs {
    /// Also list the effects of this user file.
    #[arg(long)]
    pub user_effects: Option<PathBuf>,
}

/// Lists the effects with their parameters, bounds and physics.
pub fn list(args: &EffectsArgs) -> Result<bool> {
    let registry = propbet_pipeline::model::effect_registry(args.user_effects.as_deref())?;
    use std::fmt::Write as _;
    let mut out = String::new();
    for e in &registry.effects {
        let hooks: Vec<String> = e.hooks().iter().map(|h| format!("{h:?}").to_lowercase()).collect();
        let _ = writeln!(out, "{} ({})", e.id(), hooks.join(", "));
        for p in e.params() {
            let neutral = p.neutral.map_or("none".to_string(), propbet_api::effects::fmt_value);
            let (lo, hi) = p.expected_range();
            let _ = writeln!(
                out,
                "    {} [{}]  neutral {neutral}, bounds [{}, {}], physically expected [{}, {}]: {}",
                p.name,
                p.unit,
                propbet_api::effects::fmt_value(p.lower),
                propbet_api::effects::fmt_value(p.upper),
                propbet_api::effects::fmt_value(lo),
                propbet_api::effects::fmt_value(hi),
                p.doc
            );
        }
        let _ = writeln!(
            out,
            "    {}",
            e.explanation().split_whitespace().collect::<Vec<_>>().join(" ")
        );
    }
    let _ = writeln!(
        out,
        "transition (section)\n    ncrit [-]  neutral: the polars' own Ncrit, bounds: the lowest and highest Ncrit \
         computed. Known where the polars (--polars FILE, a case's tables) were also computed at other Ncrit values \
         (propbet polars --ncrit-effect 3,9; [polars] ncrit_effect in a case): each station's lift and drag move by \
         the difference between its tables at the fitted Ncrit and at the model's own."
    );
    // A closed pipe (`propbet effects | head`) is not an error.
    let _ = std::io::Write::write_all(
        &mut std::io::stdout().lock(),
        crate::output::for_terminal(&out).as_bytes(),
    );
    Ok(true)
}
