//! `propbet compare`: measured files against the model's prediction; writes the report
//! directory (report.html, metrics.json, summary.json, summary.md, points.csv, plots/*.svg and
//! *.png).

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use propbet_api::spec::CompareSpec;

use crate::predict::ModelArgs;

/// Arguments of `propbet compare`.
#[derive(Debug, Args)]
pub struct CompareArgs {
    /// The propeller model.
    #[command(flatten)]
    pub model: ModelArgs,
    /// The measurements.
    #[command(flatten)]
    pub data: propbet_api::MeasuredRequest,
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
