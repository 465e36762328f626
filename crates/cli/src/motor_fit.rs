//! `propbet motor fit`: a QPROP motor file (type 1: R, Io, Kv; with `--kq` type 2: R, Io, Kv,
//! Kq) fitted to thrust-stand logs that carry speed, torque, voltage and current, with the
//! fit's numbers in its comments.

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, Subcommand};
use propbet_api::motor::FitKind;

/// `propbet motor`'s subcommands.
#[derive(Debug, Subcommand)]
pub enum MotorCommand {
    /// Fit R, Io and Kv to stand logs' speed, torque, voltage and current; write a QPROP motor
    /// file.
    Fit(FitArgs),
}

/// Arguments of `propbet motor fit`.
#[derive(Debug, Args)]
pub struct FitArgs {
    /// The logs.
    #[command(flatten)]
    pub measured: propbet_api::MeasuredRequest,
    /// The maker's Kv [rpm/V]: R and Io are fitted for it (without it Kv is found from the
    /// ESC command's duty).
    #[arg(long)]
    pub kv: Option<f64>,
    /// Fit the torque constant Kq on its own (a QPROP type 2 motor: R, Io, Kv, Kq): Kq and Io
    /// from the motor's current at the ESC's duty, R and Kv from the supply power. Needs the
    /// ESC command.
    #[arg(long)]
    pub kq: bool,
    /// The motor's name in the file (default: the first log's name).
    #[arg(long)]
    pub name: Option<String>,
    /// The motor file to write (default: standard output).
    #[arg(long, short)]
    pub out: Option<PathBuf>,
}

/// Runs `propbet motor ...`.
pub fn run(command: &MotorCommand) -> Result<bool> {
    match command {
        MotorCommand::Fit(a) => fit(a),
    }
}

fn fit(args: &FitArgs) -> Result<bool> {
    let kind = if args.kq { FitKind::Type2 } else { FitKind::Type1 };
    let term = crate::output::Terminal::default();
    Ok(propbet_api::commands::motor::fit(
        &args.measured.spec()?,
        args.kv,
        kind,
        args.name.clone(),
        args.out.as_deref(),
        &term,
    )?)
}
