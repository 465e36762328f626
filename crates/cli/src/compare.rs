//! `propbet compare`: measured files against the model's prediction; writes the report
//! directory (report.html, metrics.json, summary.json, summary.md, points.csv, plots/*.svg and
//! *.png).

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, ValueEnum};
use propbet_api::spec::{CompareSpec, MeasuredSpec};

use crate::predict::ModelArgs;

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
    Ok(propbet_api::commands::compare::compare(&args.spec()?, &crate::output::Terminal::default())?.0)
}
