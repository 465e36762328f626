//! `propbet synth`: measurements made by the model with hidden effects and noise, with an
//! answer key, in the generic, UIUC or RCbenchmark format.

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, ValueEnum};
use propbet_api::commands::synth::SynthFormat as Format;

use crate::predict::ModelArgs;

/// Output format of `propbet synth`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SynthFormat {
    /// One CSV with self-describing columns (rpm, airspeed, thrust, torque, air).
    Generic,
    /// UIUC `J CT CP eta` files, one per RPM, in the --out directory.
    Uiuc,
    /// An RCbenchmark step log of the static points.
    Rcbenchmark,
}

/// Arguments of `propbet synth`.
#[derive(Debug, Args)]
pub struct SynthArgs {
    /// The propeller model; its `--effect`s are the hidden effects.
    #[command(flatten)]
    pub model: ModelArgs,
    /// Relative noise on thrust and torque (one standard deviation): 1% or 0.01.
    #[arg(long, default_value = "1%")]
    pub noise: String,
    /// Output format.
    #[arg(long, value_enum, default_value_t = SynthFormat::Generic)]
    pub format: SynthFormat,
    /// RPMs (list, start:stop:step or start:stop/N); default: four up to a 150 m/s tip speed.
    #[arg(long)]
    pub rpm: Option<String>,
    /// Advance ratios; default: nine from 0 to 80 % of the zero-thrust J (rcbenchmark: 0 only).
    #[arg(long)]
    pub j: Option<String>,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output file (generic, rcbenchmark) or directory (uiuc). The answer key is written next
    /// to it as `<out>.answer.json` (uiuc: `answer.json` in the directory).
    #[arg(long, short)]
    pub out: PathBuf,
}

/// Runs `propbet synth`.
pub fn run(args: &SynthArgs) -> Result<bool> {
    let command = propbet_api::commands::synth::SynthCommand {
        model: args.model.spec()?,
        noise: args.noise.clone(),
        format: match args.format {
            SynthFormat::Generic => Format::Generic,
            SynthFormat::Uiuc => Format::Uiuc,
            SynthFormat::Rcbenchmark => Format::Rcbenchmark,
        },
        rpm: args.rpm.clone(),
        j: args.j.clone(),
        seed: args.seed,
        out: args.out.clone(),
    };
    Ok(propbet_api::commands::synth::synth(
        &command,
        &crate::output::Terminal::default(),
    )?)
}
