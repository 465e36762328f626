//! `propbet compare`: measured files against the model's prediction; writes the report
//! directory (report.html, metrics.json, summary.json, summary.md, points.csv, plots/*.svg and
//! *.png).

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, ValueEnum};
use propbet_api::compare::ComparedPoint;
use propbet_api::measure::{MeasuredSet, Refused};
use propbet_pipeline::model::Model;
use propbet_pipeline::spec::{CompareSpec, MeasuredSpec};
use propbet_pipeline::stages::{self, Compared, Reference};
use propbet_report::answer::ReferenceScore;
use propbet_report::compare as report;

use crate::predict::{load_model_at, ModelArgs};

/// Which RPM column of a thrust-stand log to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum RpmSourceArg {
    /// The optical (once-per-revolution) sensor.
    Optical,
    /// The ESC's electrical speed.
    Electrical,
}

impl RpmSourceArg {
    /// The name the request takes.
    pub fn name(self) -> &'static str {
        match self {
            RpmSourceArg::Optical => "optical",
            RpmSourceArg::Electrical => "electrical",
        }
    }
}

/// Arguments of `propbet compare`.
#[derive(Debug, Args)]
pub struct CompareArgs {
    /// The propeller model.
    #[command(flatten)]
    pub model: ModelArgs,
    /// The measurements.
    #[command(flatten)]
    pub data: MeasuredArgs,
    /// APC's predictions for this prop (a PER3 file, `PER3_10x47SF.dat`): drawn beside propbet's
    /// prediction and scored on the same points.
    #[arg(long, value_name = "FILE")]
    pub per3: Option<PathBuf>,
    /// A QPROP output for this prop (QPROP's printed sweep, one or several speeds): drawn
    /// beside propbet's prediction and scored on the same points (its T and Q, with the model's
    /// diameter and the output's density).
    #[arg(long, value_name = "FILE", conflicts_with = "per3")]
    pub qprop_output: Option<PathBuf>,
    /// A QPROP motor file (`propbet motor fit` writes one): the log's supply current and
    /// electrical power scored against what this motor draws for the predicted torque.
    #[arg(long, value_name = "FILE")]
    pub motor: Option<PathBuf>,
    /// Output directory (created if missing).
    #[arg(long, short)]
    pub out: PathBuf,
}

/// Measured files and how to read them (shared by `compare` and `diagnose`).
#[derive(Debug, Args)]
pub struct MeasuredArgs {
    /// Measured files: RCbenchmark/Tyto CSV, UIUC .txt, or generic CSV.
    #[arg(long, required = true, num_args = 1..)]
    pub measured: Vec<PathBuf>,
    #[arg(long = propbet_api::settings::POLES.flag, help = propbet_api::settings::POLES.help)]
    pub poles: Option<u32>,
    #[arg(long = propbet_api::settings::RPM_SOURCE.flag, help = propbet_api::settings::RPM_SOURCE.help, value_enum)]
    pub rpm_source: Option<RpmSourceArg>,
    #[arg(long = propbet_api::settings::AIR.flag, help = propbet_api::settings::AIR.help)]
    pub atmosphere: Option<String>,
    #[arg(long = propbet_api::settings::RHO.flag, help = propbet_api::settings::RHO.help, allow_negative_numbers = true)]
    pub rho: Option<f64>,
    /// Column map (TOML) for generic CSV files.
    #[arg(long)]
    pub columns: Option<PathBuf>,
}

impl MeasuredArgs {
    /// The measurements' spec (flags in SI).
    pub fn spec(&self) -> Result<MeasuredSpec> {
        Ok(self.request().spec()?)
    }

    /// What the flags ask for.
    pub fn request(&self) -> propbet_api::MeasuredRequest {
        propbet_api::MeasuredRequest {
            files: self.measured.clone(),
            poles: self.poles,
            rpm_source: self.rpm_source.map(|s| s.name().to_string()),
            atmosphere: self.atmosphere.clone(),
            rho: self.rho,
            columns: self.columns.clone(),
        }
    }
}

/// One line per file read (rows, points, what was dropped) and per file refused (why).
pub fn print_measured(names: &[String], sets: &[MeasuredSet], refused: &[Refused]) {
    for (n, s) in names.iter().zip(sets) {
        eprintln!(
            "propbet: {n}: {} rows -> {} points; {}",
            s.rows,
            s.points.len(),
            propbet_api::measure::summarise_dropped(&s.dropped)
        );
    }
    for r in refused {
        eprintln!("propbet: warning: {}: not read: {}", r.file, r.reason);
    }
}

/// Says on the terminal how many measured rows were dropped as faulty (the report lists them)
/// and each set's plausibility warning; returns the count of both (`compare` and `diagnose` exit
/// 1 when it is not zero).
pub fn warn_faulty_rows(names: &[String], sets: &[MeasuredSet]) -> usize {
    let faults: usize = sets.iter().map(MeasuredSet::faults).sum();
    if faults > 0 {
        eprintln!("propbet: {faults} rows were dropped as faulty; they are listed in the report");
    }
    let mut warned = 0;
    for (n, s) in names.iter().zip(sets) {
        for w in &s.warnings {
            eprintln!("propbet: warning: {n}: {w}");
            warned += 1;
        }
    }
    faults + warned
}

impl CompareArgs {
    /// The stage's spec (flags in SI).
    pub fn spec(&self) -> Result<CompareSpec> {
        Ok(CompareSpec {
            model: self.model.spec()?,
            measured: self.data.spec()?,
            per3: self.per3.clone(),
            qprop_output: self.qprop_output.clone(),
            motor: self.motor.clone(),
            out: self.out.clone(),
        })
    }
}

/// Runs `propbet compare`; returns false when rows were dropped as faulty, the solver did not
/// converge somewhere or the measurements cannot be of this propeller (all reported).
pub fn run(args: &CompareArgs) -> Result<bool> {
    Ok(run_spec(&args.spec()?)?.0)
}

/// Runs a compare stage of `spec`: its files written, its answer printed; whether it ran
/// clean, and what it wrote.
pub fn run_spec(spec: &CompareSpec) -> Result<(bool, Written)> {
    propbet_api::files::refuse_inputs_inside(&spec.out, &inputs(spec))?;
    let model = load_model_at(&spec.model, || propbet_api::model::cover(&spec.measured), false)?;
    // A reference that cannot be read stops the command before anything is computed.
    let other = reference(spec, model.diameter)?;
    let c = stages::compare(&model, &spec.measured)?;
    let electric = match &spec.motor {
        Some(m) => {
            let e = stages::electric(&c, &model, m)?;
            if e.is_none() {
                eprintln!(
                    "propbet: warning: --motor: no compared point logged the supply's voltage and current; nothing electrical to score"
                );
            }
            e
        }
        None => None,
    };
    let written = write(spec, &model, &c, other.as_ref(), electric.as_ref())?;
    print(spec, &c, written.reference.as_ref());
    if let Some(e) = &electric {
        println!("{}", crate::output::wrapped(&report::electric_sentence(e), "", "  "));
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

/// Writes the comparison's outputs into `spec.out` (`propbet_api::outputs::compare`).
pub fn write(
    spec: &CompareSpec,
    model: &Model,
    c: &Compared,
    other: Option<&Reference>,
    electric: Option<&propbet_api::compare::electric::Electric>,
) -> Result<Written> {
    let command = crate::argv::command(&propbet_pipeline::spec::StageSpec::Compare(spec.clone()));
    let mut made = propbet_api::outputs::compare::outputs(spec, model, c, other, electric, &command)?;
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
fn inputs(spec: &CompareSpec) -> Vec<&std::path::Path> {
    let mut inputs = spec.model.inputs();
    inputs.extend(spec.measured.inputs());
    inputs.extend(spec.per3.as_deref());
    inputs.extend(spec.qprop_output.as_deref());
    inputs.extend(spec.motor.as_deref());
    inputs
}

/// The reference `spec` names ([`Reference::load`]), its reading's warning on the terminal.
pub fn reference(spec: &CompareSpec, diameter: f64) -> Result<Option<Reference>> {
    let r = Reference::load(spec, diameter)?;
    if let Some(w) = r.as_ref().and_then(|r| r.warning.as_ref()) {
        eprintln!("propbet: warning: {w}");
    }
    Ok(r)
}

/// A short summary on the terminal; `reference`: another code's name and headline (from
/// [`write`]), printed under propbet's.
pub fn print(spec: &CompareSpec, c: &Compared, reference: Option<&ReferenceScore>) {
    print_measured(&c.names, &c.sets, &c.refused);
    let m = &c.metrics;
    // The headline: the scored window, static and forward flight apart (as the report).
    for g in &m.headline {
        println!("{}:", g.name);
        for q in ["thrust", "torque"] {
            if let Some(x) = g.metrics.get(q).filter(|x| x.mean_rel.is_nan()) {
                println!(
                    "{q:>7}: n {:>3}  no relative error: every measured value is below 5 % of the largest",
                    x.n
                );
            } else if let Some(x) = g.metrics.get(q) {
                println!(
                    "{q:>7}: n {:>3}  mean error {:+6.1} %  mean |error| {:5.1} %  worst {:+6.1} % ({})",
                    x.n,
                    100.0 * x.mean_rel,
                    100.0 * x.mean_abs_rel,
                    100.0 * x.max_rel,
                    x.max_rel_at
                );
            }
        }
        let theirs = reference.and_then(|r| {
            let e = |q: &str| r.mean_error(&g.name, q);
            Some((r.name.clone(), e("thrust")?, e("torque")))
        });
        if let Some((name, t, q)) = theirs {
            let torque = q.map_or(String::new(), |q| format!(", torque {:+.1} %", 100.0 * q));
            println!("  {name}: thrust mean error {:+.1} %{torque}", 100.0 * t);
        }
    }
    if m.outside_window > 0 {
        println!(
            "({} point(s) at or beyond 85 % of their sweep's zero-thrust J: in the report, not in these numbers)",
            m.outside_window
        );
    }
    if m.overall.points == 0 {
        let mut reasons: Vec<&str> = c
            .points
            .iter()
            .flat_map(|p| p.flags.iter().map(String::as_str))
            .collect();
        reasons.sort_unstable();
        reasons.dedup();
        println!(
            "no point could be scored: all {} points are flagged ({})",
            c.points.len(),
            reasons.join("; ")
        );
    }
    println!("report: {}", spec.out.join("report.html").display());
    if let Some(m) = c.mismatch() {
        eprintln!("propbet: warning: {}", m.message());
    }
    let (_, unconverged) = c.problems();
    warn_faulty_rows(&c.names, &c.sets);
    if unconverged > 0 {
        eprintln!("propbet: {unconverged} station solutions did not converge");
    }
    let flagged: Vec<&ComparedPoint> = c.points.iter().filter(|p| !p.model_flags.is_empty()).collect();
    if let Some(first) = flagged.first() {
        eprintln!(
            "propbet: warning: the prediction is physically implausible at {} of {} points (column model_flags of points.csv), for example at {:.0} rpm, J {:.3}: {}",
            flagged.len(),
            c.points.len(),
            first.rpm,
            first.j,
            first.model_flags.join("; ")
        );
    }
}
