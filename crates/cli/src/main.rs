//! The `propbet` command: thin glue over the library crates. Parses flags, converts them once
//! to SI, runs, and maps the outcome to an exit code: 0 ok, 1 ran with failures (reported),
//! 2 error.

use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod compare;
mod diagnose;
mod output;
mod polar;
mod predict;
mod prop;
mod run;
mod scan;
mod synth;
mod validate;
mod values;

/// Propeller performance from geometry, and why it disagrees with the thrust stand.
#[derive(Debug, Parser)]
#[command(name = "propbet", version, about)]
pub(crate) struct Cli {
    /// Worker threads for sweeps (default: all cores).
    #[arg(long, global = true)]
    threads: Option<usize>,
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Debug, Subcommand)]
pub(crate) enum Command {
    /// Predict thrust, torque, power and coefficients of a QPROP prop file over RPM x J (or V).
    Predict(Box<predict::PredictArgs>),
    /// Inspect a QPROP prop file: stations, warnings; optionally write it back normalised.
    Prop(prop::PropArgs),
    /// Polars of one section from XFOIL at given Reynolds numbers, with their QPROP fit.
    Polar(Box<polar::PolarArgs>),
    /// Polars of every station of a blade at its operating Re and Mach, reduced to a QPROP file.
    Polars(Box<polar::PolarsArgs>),
    /// Compare measured data (thrust stand, wind tunnel, CSV) with the prediction: metrics,
    /// plots and an HTML report.
    Compare(Box<compare::CompareArgs>),
    /// Which physical effect is missing: candidate effects fitted to the measurements, ranked
    /// by held-out error, and the ladder of effects that help.
    Diagnose(Box<diagnose::DiagnoseArgs>),
    /// List the effects (built-in and user-defined) with their parameters and physics.
    Effects(diagnose::EffectsArgs),
    /// Write synthetic measurements made by the model with hidden effects and noise.
    Synth(Box<synth::SynthArgs>),
    /// The main job: a case directory (case.toml) from scan to report — scan, XFOIL polars,
    /// sweeps, comparison with the measurements, diagnosis, one HTML report.
    Run(Box<run::RunArgs>),
    /// Validation on real data: every UIUC propeller with a geometry file and an APC PE0 file,
    /// predicted and compared with its static and J-sweep files, before and after calibration.
    Validate(Box<validate::ValidateArgs>),
    /// Blade geometry from a scan (STL mesh or PLY / COLMAP / XYZ cloud): sections, airfoil
    /// fits, geometry CSV, geom.txt, QPROP prop file, airfoil files and plots.
    Scan(Box<scan::ScanArgs>),
}

fn run(cli: Cli) -> anyhow::Result<bool> {
    if let Some(n) = cli.threads {
        if n == 0 {
            anyhow::bail!("--threads must be at least 1");
        }
        rayon::ThreadPoolBuilder::new().num_threads(n).build_global()?;
    }
    dispatch(cli.command)
}

/// Runs one command (also the stages of `propbet run`).
pub(crate) fn dispatch(command: Command) -> anyhow::Result<bool> {
    match command {
        Command::Run(a) => run::run(&a),
        Command::Validate(a) => validate::run(&a),
        Command::Predict(a) => predict::run(&a),
        Command::Prop(a) => prop::run(&a),
        Command::Polar(a) => polar::run_polar(&a),
        Command::Polars(a) => polar::run_polars(&a),
        Command::Compare(a) => compare::run(&a),
        Command::Diagnose(a) => diagnose::run(&a),
        Command::Effects(a) => diagnose::list(&a),
        Command::Synth(a) => synth::run(&a),
        Command::Scan(a) => scan::run(&a),
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    match run(cli) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("propbet: error: {e:#}");
            ExitCode::from(2)
        }
    }
}
