//! `propbet run CASE_DIR`: the main job. A case directory's `case.toml` names a scan (or a
//! prop file), the sections, the operating points, the measurements and the air; the run
//! chains scan → XFOIL or NeuralFoil polars at each station's Reynolds number → BEMT sweeps → comparison →
//! diagnosis in memory (`propbet_pipeline::run::run_case`), each stage the documented command
//! it is equivalent to, then writes every stage's outputs and one HTML report that holds them.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Result;
use clap::Args;
use propbet_pipeline::case::RunPlan;
use propbet_pipeline::run::{run_case, Event, Finished, RunOutcome, StageRecord};
use propbet_pipeline::spec::StageSpec;
use propbet_pipeline::spec::XfoilProcessSpec;

use crate::output::emit;
use crate::polar::{Bar, XfoilProcess};
use propbet_api::files::write_atomic;

/// Arguments of `propbet run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// Case directory holding `case.toml` (default: the shipped `props/apcsp_10x7`, APC's 10x7 Sport
    /// from its design file against UIUC's measurements).
    pub case: Option<PathBuf>,
    /// Output directory (default: `run_<case directory name>` in the current directory).
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// XFOIL executable, polar cache, progress bars (passed on to the polars stage).
    #[command(flatten)]
    pub xfoil: XfoilProcess,
    /// Print every stage's full terminal output (each station's polar fit, the measured files
    /// again for the diagnosis), as the stages' own commands do; by default a summary per stage.
    #[arg(long)]
    pub verbose: bool,
    /// Read files the case names outside its folder (by default every file a case names lies
    /// in it, links followed).
    #[arg(long)]
    pub inputs_anywhere: bool,
}

/// What `propbet run` is asked: its flags, typed.
pub struct RunRequest {
    /// Case directory (None: the shipped default case).
    pub case: Option<PathBuf>,
    /// Output directory (None: `run_<case directory name>`).
    pub out: Option<PathBuf>,
    /// XFOIL, the polar cache, the progress bars.
    pub xfoil: XfoilProcessSpec,
    /// Every stage's full terminal output.
    pub verbose: bool,
    /// Files the case names may lie outside its folder.
    pub inputs_anywhere: bool,
}

/// A finished stage on the terminal: its time (`--verbose`), or its short status lines.
fn print_done(n: usize, total: usize, record: &StageRecord, lines: &[String], verbose: bool) {
    if verbose {
        eprintln!(
            "propbet [{n}/{total}] {}: {:.1} s{}",
            record.spec.name(),
            record.seconds,
            if record.clean { "" } else { " (with reported problems)" }
        );
    } else {
        let (first, rest) = lines.split_first().map_or(("", &[][..]), |(f, r)| (f.as_str(), r));
        eprintln!(
            "propbet [{n}/{total}] {}: {first} ({:.1} s)",
            record.spec.name(),
            record.seconds
        );
        for l in rest {
            eprintln!("  {l}");
        }
    }
}

/// Runs `propbet run`.
pub fn run(a: &RunArgs) -> Result<bool> {
    Ok(run_request(&RunRequest {
        case: a.case.clone(),
        out: a.out.clone(),
        xfoil: a.xfoil.spec()?,
        verbose: a.verbose,
        inputs_anywhere: a.inputs_anywhere,
    })?
    .0)
}

/// What a run wrote that a caller reads as data, as it wrote it (None: the case has no such
/// stage).
#[derive(Debug, Default)]
pub struct RunFiles {
    /// summary.json.
    pub summary: Vec<u8>,
    /// predict/sweep.csv.
    pub sweep: Option<Vec<u8>>,
    /// compare/points.csv.
    pub points: Option<Vec<u8>>,
    /// diagnose/diagnosis.json.
    pub diagnosis: Option<Vec<u8>>,
}

/// Runs a case as `propbet run` does; false when a stage reported problems; and what it wrote
/// ([`RunFiles`]).
pub fn run_request(a: &RunRequest) -> Result<(bool, RunFiles)> {
    let t_all = Instant::now();
    let (dir, out) = propbet_api::case::case_and_out(a.case.as_deref(), a.out.as_deref())?;
    let plan = propbet_api::case::plan(&dir, &out, &a.xfoil)?;
    propbet_api::case::check_paths(&plan, &dir, &out, a.inputs_anywhere)?;
    // Until the report is written the folder says it is incomplete: a run that fails or is
    // interrupted leaves INCOMPLETE.txt, naming the case; a finished run removes it.
    let lock = propbet_api::files::claim_folder(&out, &format!("propbet run {}", dir.display()))?;
    let bar = Bar::new(a.xfoil.quiet, a.xfoil.engine);
    let mut pages: Vec<(&'static str, String)> = Vec::new();
    let mut reference: Option<propbet_report::answer::ReferenceScore> = None;
    let mut lead: Option<propbet_plot::Figure> = None;
    let mut write_err: Option<anyhow::Error> = None;
    let mut files = RunFiles::default();
    let verbose = a.verbose;
    let outcome = run_case(&plan, &|d, t| bar.tick(d, t), &mut |e| match e {
        Event::Start { n, total, spec } => {
            if verbose {
                eprintln!("propbet [{n}/{total}] {}: {}", spec.name(), crate::argv::command(spec));
            }
        }
        Event::Done { n, total, record, made } => {
            let mut lines = Vec::new();
            if write_err.is_none() {
                match write_stage(record, &made, verbose) {
                    Ok(w) => {
                        if let Some(page) = w.page {
                            pages.push((record.spec.name(), page));
                        }
                        if w.reference.is_some() {
                            reference = w.reference;
                        }
                        if w.lead.is_some() {
                            lead = w.lead;
                        }
                        lines = w.brief;
                        files.sweep = w.sweep.or(files.sweep.take());
                        files.points = w.points.or(files.points.take());
                        files.diagnosis = w.diagnosis.or(files.diagnosis.take());
                    }
                    Err(e) => write_err = Some(e),
                }
            }
            print_done(n, total, record, &lines, verbose);
        }
    })?;
    if let Some(e) = write_err {
        return Err(e);
    }

    // The report.
    let t0 = Instant::now();
    let total = outcome.stages.len() + 1;
    let commands = run_commands(&plan, &outcome);
    let html = propbet_report::run::page(&plan, &outcome, &pages, reference.as_ref(), lead.as_ref(), &commands)?;
    let report_path = out.join("report.html");
    write_atomic(&report_path, &[html.as_bytes()], &[dir.join("case.toml").as_path()])?;
    let mut summary = serde_json::to_vec_pretty(&propbet_report::run::summary_json(&plan, &outcome, &commands))?;
    summary.push(b'\n');
    write_atomic(
        &out.join("summary.json"),
        &[&summary],
        &[dir.join("case.toml").as_path()],
    )?;
    files.summary = summary;
    if a.verbose {
        eprintln!("propbet [{total}/{total}] report: {:.1} s", t0.elapsed().as_secs_f64());
    }
    lock.finish()?;
    println!(
        "{}: {} stages in {:.1} s; report: {}",
        plan.name,
        total,
        t_all.elapsed().as_secs_f64(),
        report_path.display()
    );
    let problems: Vec<&str> = outcome
        .stages
        .iter()
        .filter(|s| !s.clean)
        .map(|s| s.spec.name())
        .collect();
    if !problems.is_empty() {
        eprintln!(
            "propbet: exit 1: done, with problems the report lists under 'Every note of the stages' (stages: {})",
            problems.join(", ")
        );
    }
    Ok((outcome.clean(), files))
}

pub(crate) fn create_parent(path: &Path) -> Result<()> {
    if let Some(d) = path.parent() {
        std::fs::create_dir_all(d).map_err(|e| anyhow::anyhow!("{}: cannot create: {e}", d.display()))?;
    }
    Ok(())
}

/// What a stage left for the terminal and the report.
#[derive(Default)]
struct Written {
    /// The compare or diagnose page's body, for the run's report.
    page: Option<String>,
    /// Another code's prediction scored beside propbet's (compare's reference headline).
    reference: Option<propbet_report::answer::ReferenceScore>,
    /// The figure the run's report leads with (compare's).
    lead: Option<propbet_plot::Figure>,
    /// The stage's short status: its first line, then a few details (empty with `--verbose`,
    /// which prints the stage's own full output instead).
    brief: Vec<String>,
    /// The sweep's table as written (predict).
    sweep: Option<Vec<u8>>,
    /// points.csv as written (compare).
    points: Option<Vec<u8>>,
    /// diagnosis.json as written (diagnose).
    diagnosis: Option<Vec<u8>>,
}

/// Writes a finished stage's outputs and prints its summary: with `verbose` the stage's own
/// full output, as its command prints it; otherwise a few short lines (`Written::brief`).
fn write_stage(record: &StageRecord, made: &Finished, verbose: bool) -> Result<Written> {
    let mut w = Written::default();
    match (&record.spec, made) {
        (StageSpec::Scan(spec), Finished::Scan(s)) => {
            crate::scan::write(spec, s)?;
            if verbose {
                crate::scan::print_summary(s);
            }
            w.brief.push(propbet_report::scan::summary(&s.geometry));
        }
        (StageSpec::Polars(spec), Finished::Polars(p, input)) => {
            if verbose {
                crate::polar::print_polars(spec, input, p);
            }
            create_parent(&spec.out_prop)?;
            crate::polar::write_polars(spec, p)?;
            w.brief = propbet_report::polar::brief(p);
        }
        (StageSpec::Predict(spec), Finished::Predict(points, model, export)) => {
            if verbose {
                for warning in &model.loaded.warnings {
                    eprintln!("propbet: warning: {warning}");
                }
            }
            if let Some(o) = &spec.out {
                create_parent(o)?;
            }
            let sweep = propbet_api::outputs::predict::sweep_table(spec, model, points)?;
            emit(spec.out.as_deref(), &[&sweep], &spec.model.inputs())?;
            w.sweep = Some(sweep);
            if let (Ok(x), Some(dir)) = (export, spec.out.as_ref().and_then(|o| o.parent())) {
                write_atomic(
                    &dir.join(propbet_api::qprop::export::FILE_NAME),
                    &[propbet_api::qprop::write_prop(&x.file)],
                    &spec.model.inputs(),
                )?;
            }
            w.brief = propbet_report::run::brief::predict(points, spec, export);
        }
        (StageSpec::Powered(spec), Finished::Powered(table, model, fluid)) => {
            let run =
                propbet_report::table::powered::PoweredRun::new((*table).clone(), model, fluid, spec.supply.is_some());
            if let Some(o) = &spec.out {
                create_parent(o)?;
            }
            let mut inputs = spec.model.inputs();
            inputs.push(spec.motor.as_path());
            emit(spec.out.as_deref(), &[run.body(spec.format)?], &inputs)?;
            if verbose {
                for line in run.warnings() {
                    eprintln!("propbet: {line}");
                }
            }
            w.brief = propbet_report::powered::brief(table, spec);
            w.page = Some(propbet_report::powered::section(table, spec));
        }
        (StageSpec::Compare(spec), Finished::Compare(c, model)) => {
            let other = crate::compare::reference(spec, model.diameter)?;
            let electric = match &spec.motor {
                Some(m) => propbet_pipeline::stages::electric(c, model, m)?,
                None => None,
            };
            let crate::compare::Written {
                body: page,
                reference,
                lead,
                points,
                ..
            } = crate::compare::write(spec, model, c, other.as_ref(), electric.as_ref())?;
            w.points = Some(points);
            w.lead = lead;
            if verbose {
                crate::compare::print(spec, c, reference.as_ref());
            }
            w.brief = propbet_report::run::brief::compare(c, reference.as_ref(), electric.as_ref());
            w.page = Some(page);
            w.reference = reference;
        }
        (StageSpec::Diagnose(spec), Finished::Diagnose(d)) => {
            let written = crate::diagnose::write(spec, d)?;
            w.page = Some(written.body);
            w.diagnosis = Some(written.diagnosis);
            if verbose {
                crate::diagnose::print(spec, d);
            }
            w.brief = propbet_report::diagnose::brief(&d.diagnosis);
        }
        _ => unreachable!("a stage's record and artifact match"),
    }
    Ok(w)
}

/// The equivalent commands the run's page and summary show: each stage's, the export of its
/// prediction, and the calibrated model's where the diagnosis found something (written beside
/// the sweep, never over it).
fn run_commands(plan: &RunPlan, outcome: &RunOutcome) -> propbet_report::run::Commands {
    let out = &plan.out;
    let calibrated = outcome.diagnosed.as_ref().filter(|d| d.diagnosis.found).map(|d| {
        let mut spec = plan.predict.clone();
        spec.out = Some(out.join("predict").join("calibrated_sweep.csv"));
        let mut cmd = crate::argv::command(&StageSpec::Predict(spec));
        for e in crate::argv::effect_args(&d.diagnosis) {
            cmd.push(' ');
            cmd.push_str(&e);
        }
        cmd
    });
    propbet_report::run::Commands {
        stages: outcome.stages.iter().map(|s| crate::argv::command(&s.spec)).collect(),
        export: crate::argv::export_command(&plan.predict, &out.join("export")),
        calibrated,
    }
}
