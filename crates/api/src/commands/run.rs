//! `propbet run CASE_DIR`: the main job. A case directory's `case.toml` names a scan (or a
//! prop file), the sections, the operating points, the measurements and the air; the run
//! chains scan → polars → sweeps → comparison → diagnosis in memory
//! (`propbet_pipeline::run::run_case`), each stage the documented command it is equivalent
//! to, writes every stage's outputs as it finishes and one HTML report that holds them.

use std::path::{Path, PathBuf};
use std::time::Instant;

use propbet_pipeline::case::RunPlan;
use propbet_pipeline::run::{run_case, Event, Finished, RunOutcome, StageRecord};
use propbet_settings::spec::{PredictSpec, StageSpec, XfoilProcessSpec};

use crate::console::{emit, Console};
use crate::files::write_atomic;
use crate::{CommandError, CommandResult as Result};

/// What `propbet run` is asked.
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

/// A finished stage told: its time (`verbose`), or its short status lines.
fn print_done(n: usize, total: usize, record: &StageRecord, lines: &[String], verbose: bool, console: &dyn Console) {
    if verbose {
        console.err(&format!(
            "propbet [{n}/{total}] {}: {:.1} s{}",
            record.spec.name(),
            record.seconds,
            if record.clean { "" } else { " (with reported problems)" }
        ));
    } else {
        let (first, rest) = lines.split_first().map_or(("", &[][..]), |(f, r)| (f.as_str(), r));
        console.err(&format!(
            "propbet [{n}/{total}] {}: {first} ({:.1} s)",
            record.spec.name(),
            record.seconds
        ));
        for l in rest {
            console.err(&format!("  {l}"));
        }
    }
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
pub fn run(a: &RunRequest, console: &dyn Console) -> Result<(bool, RunFiles)> {
    let t_all = Instant::now();
    let (dir, out) = crate::case::case_and_out(a.case.as_deref(), a.out.as_deref())?;
    let plan = crate::case::plan(&dir, &out, &a.xfoil)?;
    crate::case::check_paths(&plan, &dir, &out, a.inputs_anywhere)?;
    // Until the report is written the folder says it is incomplete: a run that fails or is
    // interrupted leaves INCOMPLETE.txt, naming the case; a finished run removes it.
    let lock = crate::files::claim_folder(&out, &format!("propbet run {}", dir.display()))?;
    let mut pages: Vec<(&'static str, String)> = Vec::new();
    let mut reference: Option<propbet_report::answer::ReferenceScore> = None;
    let mut lead: Option<propbet_plot::Figure> = None;
    let mut write_err: Option<CommandError> = None;
    let mut files = RunFiles::default();
    let verbose = a.verbose;
    let outcome = run_case(&plan, &|d, t| console.progress(&a.xfoil, d, t), &mut |e| match e {
        Event::Start { n, total, spec } => {
            if verbose {
                console.err(&format!(
                    "propbet [{n}/{total}] {}: {}",
                    spec.name(),
                    console.command(spec)
                ));
            }
        }
        Event::Done { n, total, record, made } => {
            console.progress_done();
            let mut lines = Vec::new();
            if write_err.is_none() {
                match write_stage(record, &made, verbose, console) {
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
            print_done(n, total, record, &lines, verbose, console);
        }
    });
    console.progress_done();
    let outcome = outcome?;
    if let Some(e) = write_err {
        return Err(e);
    }

    // The report.
    let t0 = Instant::now();
    let total = outcome.stages.len() + 1;
    let commands = run_commands(&plan, &outcome, console);
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
        console.err(&format!(
            "propbet [{total}/{total}] report: {:.1} s",
            t0.elapsed().as_secs_f64()
        ));
    }
    lock.finish()?;
    console.out(&format!(
        "{}: {} stages in {:.1} s; report: {}",
        plan.name,
        total,
        t_all.elapsed().as_secs_f64(),
        report_path.display()
    ));
    let problems: Vec<&str> = outcome
        .stages
        .iter()
        .filter(|s| !s.clean)
        .map(|s| s.spec.name())
        .collect();
    if !problems.is_empty() {
        console.err(&format!(
            "propbet: exit 1: done, with problems the report lists under 'Every note of the stages' (stages: {})",
            problems.join(", ")
        ));
    }
    Ok((outcome.clean(), files))
}

/// Creates the folder `path` goes in.
pub(crate) fn create_parent(path: &Path) -> Result<()> {
    if let Some(d) = path.parent() {
        std::fs::create_dir_all(d)
            .map_err(|e| CommandError::Message(format!("{}: cannot create: {e}", d.display())))?;
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
    /// which tells the stage's own full output instead).
    brief: Vec<String>,
    /// The sweep's table as written (predict).
    sweep: Option<Vec<u8>>,
    /// points.csv as written (compare).
    points: Option<Vec<u8>>,
    /// diagnosis.json as written (diagnose).
    diagnosis: Option<Vec<u8>>,
}

/// Writes a finished stage's outputs and tells its summary: with `verbose` the stage's own
/// full output, as its command tells it; otherwise a few short lines (`Written::brief`).
fn write_stage(record: &StageRecord, made: &Finished, verbose: bool, console: &dyn Console) -> Result<Written> {
    let mut w = Written::default();
    match (&record.spec, made) {
        (StageSpec::Scan(spec), Finished::Scan(s)) => {
            super::scan::write(spec, s, console)?;
            if verbose {
                super::scan::print_summary(s, console);
            }
            w.brief.push(propbet_report::scan::summary(&s.geometry));
        }
        (StageSpec::Polars(spec), Finished::Polars(p, input)) => {
            if verbose {
                super::polar::print_polars(spec, input, p, console);
            }
            create_parent(&spec.out_prop)?;
            super::polar::write_polars(spec, p)?;
            w.brief = propbet_report::polar::brief(p);
        }
        (StageSpec::Predict(spec), Finished::Predict(points, model, export)) => {
            if verbose {
                for warning in &model.loaded.warnings {
                    console.err(&format!("propbet: warning: {warning}"));
                }
            }
            if let Some(o) = &spec.out {
                create_parent(o)?;
            }
            let sweep = crate::outputs::predict::sweep_table(spec, model, points)?;
            emit(console, spec.out.as_deref(), &[&sweep], &spec.model.inputs())?;
            w.sweep = Some(sweep);
            if let (Ok(x), Some(dir)) = (export, spec.out.as_ref().and_then(|o| o.parent())) {
                write_atomic(
                    &dir.join(crate::qprop::export::FILE_NAME),
                    &[crate::qprop::write_prop(&x.file)],
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
            emit(console, spec.out.as_deref(), &[run.body(spec.format)?], &inputs)?;
            if verbose {
                for line in run.warnings() {
                    console.err(&format!("propbet: {line}"));
                }
            }
            w.brief = propbet_report::powered::brief(table, spec);
            w.page = Some(propbet_report::powered::section(table, spec));
        }
        (StageSpec::Compare(spec), Finished::Compare(c, model)) => {
            let other = super::compare::reference(spec, model.diameter, console)?;
            let electric = match &spec.motor {
                Some(m) => propbet_pipeline::stages::electric(c, model, m)?,
                None => None,
            };
            let super::compare::Written {
                body: page,
                reference,
                lead,
                points,
                ..
            } = super::compare::write(spec, model, c, other.as_ref(), electric.as_ref(), console)?;
            w.points = Some(points);
            w.lead = lead;
            if verbose {
                super::compare::print(spec, c, reference.as_ref(), console);
            }
            w.brief = propbet_report::run::brief::compare(c, reference.as_ref(), electric.as_ref());
            w.page = Some(page);
            w.reference = reference;
        }
        (StageSpec::Diagnose(spec), Finished::Diagnose(d)) => {
            let written = super::diagnose::write(spec, d, console)?;
            w.page = Some(written.body);
            w.diagnosis = Some(written.diagnosis);
            if verbose {
                super::diagnose::print(spec, d, console);
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
fn run_commands(plan: &RunPlan, outcome: &RunOutcome, console: &dyn Console) -> propbet_report::run::Commands {
    let out = &plan.out;
    let calibrated = outcome.diagnosed.as_ref().filter(|d| d.diagnosis.found).map(|d| {
        let mut spec = plan.predict.clone();
        spec.out = Some(out.join("predict").join("calibrated_sweep.csv"));
        let mut cmd = console.command(&StageSpec::Predict(spec));
        for e in console.effect_args(&d.diagnosis) {
            cmd.push(' ');
            cmd.push_str(&e);
        }
        cmd
    });
    propbet_report::run::Commands {
        stages: outcome.stages.iter().map(|s| console.command(&s.spec)).collect(),
        export: console.export_command(&plan.predict, &out.join("export")),
        calibrated,
    }
}

/// The prediction of a case directory, as `propbet run` makes it into `out`: its scan and
/// polars stages run (their files written under `out`, as the run writes them), and its
/// prediction's spec returned (the model those stages made, the case's sweep and air), with the
/// polars stage's blade and sections (geometry, airfoil, station airfoils) where it has one.
#[allow(clippy::type_complexity)]
pub fn case_prediction(
    dir: &Path,
    out: &Path,
    xfoil: &crate::ProcessRequest,
    console: &dyn Console,
) -> Result<(PredictSpec, Option<(PathBuf, Option<String>, Option<PathBuf>)>)> {
    let case = propbet_pipeline::case::read_case(dir)?;
    let plan = case.plan(dir, out, &xfoil.spec()?)?;
    let mut sections = None;
    for stage in plan.stages() {
        match &stage {
            // Their problems are told, as each command tells them.
            StageSpec::Scan(spec) => {
                super::scan::run(spec, console)?;
            }
            StageSpec::Polars(spec) => {
                for p in std::iter::once(spec.out_prop.as_path()).chain(spec.out_polars.as_deref()) {
                    create_parent(p)?;
                }
                sections = Some((
                    spec.geometry.clone(),
                    spec.airfoil.clone(),
                    spec.station_airfoils.clone(),
                ));
                super::polar::polars(spec, console)?;
            }
            StageSpec::Predict(spec) => return Ok((spec.clone(), sections)),
            _ => {}
        }
    }
    Err(CommandError::Message(format!(
        "{}: the case has no prediction stage",
        dir.display()
    )))
}
