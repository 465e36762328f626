//! `propbet synth`: measurements made by the model with hidden effects and noise, with an
//! answer key, in the generic, UIUC or RCbenchmark format.

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, ValueEnum};
use propbet_pipeline::stages::{self, SynthSpec};

use propbet_api::files::write_atomic;
use propbet_api::settings::values::parse_list;

use crate::predict::{load_model, ModelArgs};

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
    let mspec = args.model.spec()?;
    let mut answer_path = args.out.as_os_str().to_owned();
    answer_path.push(".answer.json");
    let answer_path = PathBuf::from(answer_path);
    match args.format {
        SynthFormat::Uiuc => propbet_api::files::refuse_inputs_inside(&args.out, &mspec.inputs())?,
        _ => propbet_api::files::refuse_outputs_over_inputs(&[&args.out, &answer_path], &mspec.inputs())?,
    }
    let m = load_model(&mspec, false)?;
    let spec = SynthSpec {
        noise: stages::parse_noise(&args.noise)?,
        format: match args.format {
            SynthFormat::Generic => stages::SynthFormat::Generic,
            SynthFormat::Uiuc => stages::SynthFormat::Uiuc,
            SynthFormat::Rcbenchmark => stages::SynthFormat::Rcbenchmark,
        },
        rpms: args.rpm.as_deref().map(|r| parse_list("--rpm", r)).transpose()?,
        js: args.j.as_deref().map(|j| parse_list("--j", j)).transpose()?,
        seed: args.seed,
        prop: args.model.prop.display().to_string(),
        stem: args
            .model
            .prop
            .file_stem()
            .map_or("synth".into(), |s| s.to_string_lossy().replace('_', "-")),
    };
    let made = stages::synth(&spec, &m)?;
    let inputs = mspec.inputs();
    let mut answer_bytes = serde_json::to_vec_pretty(&made.answer)?;
    answer_bytes.push(b'\n');
    match &made.files {
        stages::SynthFiles::Named(files) => {
            std::fs::create_dir_all(&args.out)
                .map_err(|e| anyhow::anyhow!("{}: cannot create the directory: {e}", args.out.display()))?;
            for (name, text) in files {
                write_atomic(&args.out.join(name), &[text.as_bytes()], &inputs)?;
            }
            write_atomic(&args.out.join("answer.json"), &[&answer_bytes], &inputs)?;
        }
        stages::SynthFiles::One(text) => {
            write_atomic(&args.out, &[text.as_bytes()], &inputs)?;
            write_atomic(&answer_path, &[&answer_bytes], &inputs)?;
        }
    }
    eprintln!(
        "propbet: {} points ({} RPMs x {} J) with {} and {:.2} % noise -> {}",
        made.points,
        made.plan.rpms.len(),
        made.plan.js.len(),
        made.effects,
        100.0 * spec.noise,
        args.out.display()
    );
    Ok(true)
}
