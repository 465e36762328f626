//! `propbet polar` (polars of one section) and `propbet polars` (polars of every station of a
//! blade at its operating Reynolds and Mach numbers, reduced to a QPROP prop file).

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use propbet_api::SectionRequest;

/// The section to analyse.
#[derive(Debug, Args)]
pub struct AirfoilArgs {
    /// Coordinate file (Selig or Lednicer), or a NACA 4-digit name such as `naca4412`.
    #[arg(long)]
    pub airfoil: String,
    /// Scale the section to this thickness ratio t/c (0.06 or 6%), keeping its camber line.
    #[arg(long)]
    pub thickness: Option<String>,
}

/// Arguments of `propbet polar`.
#[derive(Debug, Args)]
pub struct PolarArgs {
    /// The section.
    #[command(flatten)]
    pub section: AirfoilArgs,
    /// Reynolds numbers: a list (5e4,1e5) or a range.
    #[arg(long)]
    pub re: String,
    /// Mach number.
    #[arg(long, default_value_t = 0.0)]
    pub mach: f64,
    /// XFOIL settings.
    #[command(flatten)]
    pub xfoil: SectionRequest,
    /// Polar table (CSV; default: standard output).
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Figure of the polars and the QPROP fit (.svg or .png).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// The QPROP fit at each Re, with residuals, as JSON.
    #[arg(long)]
    pub fit_out: Option<PathBuf>,
}

/// Runs `propbet polar`; false when some polar failed (the others are written).
pub fn run_polar(a: &PolarArgs) -> Result<bool> {
    let command = propbet_api::commands::polar::PolarCommand {
        airfoil: a.section.airfoil.clone(),
        thickness: a.section.thickness.clone(),
        re: a.re.clone(),
        mach: a.mach,
        xfoil: a.xfoil.clone(),
        out: a.out.clone(),
        plot: a.plot.clone(),
        fit_out: a.fit_out.clone(),
    };
    Ok(propbet_api::commands::polar::polar(
        &command,
        &crate::output::Terminal::default(),
    )?)
}

/// Runs `propbet polars`; false when a station has no fit (its coefficients are kept from the
/// geometry file, and it is reported).
pub fn run_polars(args: &propbet_api::PolarsRequest) -> Result<bool> {
    Ok(propbet_api::commands::polar::polars(
        &args.spec()?,
        &crate::output::Terminal::default(),
    )?)
}
