//! `propbet synth`: measurements made by the model with hidden effects and noise, with an
//! answer key, in the generic, UIUC or RCbenchmark format.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::{Args, ValueEnum};
use propbet_atmosphere::AirState;
use propbet_diagnose::synth::{self, Plan};
use propbet_diagnose::Model;
use propbet_effects::Stack;
use serde_json::json;

use crate::output::write_atomic;
use propbet_pipeline::values::parse_list;

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

fn parse_noise(s: &str) -> Result<f64> {
    let t = s.trim();
    let v = match t.strip_suffix('%') {
        Some(p) => p.trim().parse::<f64>().map(|x| x / 100.0),
        None => t.parse::<f64>(),
    }
    .map_err(|_| anyhow::anyhow!("--noise '{s}': not a number (write 1% or 0.01)"))?;
    if !(0.0..0.5).contains(&v) {
        bail!("--noise '{s}': must be between 0 and 50 %");
    }
    Ok(v)
}

/// Runs `propbet synth`.
pub fn run(args: &SynthArgs) -> Result<bool> {
    let mspec = args.model.spec()?;
    let mut answer_path = args.out.as_os_str().to_owned();
    answer_path.push(".answer.json");
    let answer_path = PathBuf::from(answer_path);
    match args.format {
        SynthFormat::Uiuc => crate::output::refuse_inputs_inside(&args.out, &mspec.inputs())?,
        _ => crate::output::refuse_outputs_over_inputs(&[&args.out, &answer_path], &mspec.inputs())?,
    }
    let m = load_model(&mspec, false)?;
    let noise = parse_noise(&args.noise)?;
    let state = AirState::ISA;
    let fluid = state.fluid();
    // The model without the hidden effects decides the default plan.
    let base = Model {
        rotor: &m.rotor,
        opts: m.opts,
        diameter: m.diameter,
        fixed: Stack::baseline(),
    };
    let rpms = match &args.rpm {
        Some(r) => parse_list("--rpm", r)?,
        None => synth::default_rpms(m.diameter),
    };
    if let Some(bad) = rpms.iter().find(|&&r| r.is_nan() || r <= 0.0) {
        bail!("--rpm: rotation speeds must be positive, found {bad}");
    }
    let js = match (&args.j, args.format) {
        (Some(j), _) => parse_list("--j", j)?,
        (None, SynthFormat::Rcbenchmark) => vec![0.0],
        (None, _) => synth::default_js(&base, &fluid, rpms[rpms.len() / 2]),
    };
    if let Some(bad) = js.iter().find(|&&j| j < 0.0) {
        bail!("--j: advance ratios must not be negative, found {bad}");
    }
    let plan = Plan {
        rpms,
        js,
        noise,
        seed: args.seed,
        fluid,
        logged: (state.temperature - 273.15, state.pressure),
    };
    let points = synth::generate(&base, &m.effects, &plan)?;
    let inputs = mspec.inputs();
    let mut key = serde_json::Map::new();
    for a in &m.effects.active {
        let params: serde_json::Map<String, serde_json::Value> = a
            .effect
            .params()
            .iter()
            .zip(&a.values)
            .map(|(p, v)| (p.name.clone(), json!(v)))
            .collect();
        key.insert(a.effect.id().to_string(), serde_json::Value::Object(params));
    }
    if key.is_empty() {
        key.insert("none".into(), json!({}));
    }
    let answer = json!({
        "prop": args.model.prop.display().to_string(),
        "effects": key,
        "noise": noise,
        "format": format!("{:?}", args.format).to_lowercase(),
        "rho_true": fluid.rho,
        "seed": args.seed,
        "made_by": "propbet synth",
    });
    let mut answer_bytes = serde_json::to_vec_pretty(&answer)?;
    answer_bytes.push(b'\n');
    match args.format {
        SynthFormat::Generic | SynthFormat::Rcbenchmark => {
            let text = if args.format == SynthFormat::Generic {
                synth::write_generic(&points, &plan)
            } else {
                synth::write_rcbenchmark(&points, &plan)
            };
            write_atomic(&args.out, &[text.as_bytes()], &inputs)?;
            write_atomic(&answer_path, &[&answer_bytes], &inputs)?;
        }
        SynthFormat::Uiuc => {
            std::fs::create_dir_all(&args.out)
                .map_err(|e| anyhow::anyhow!("{}: cannot create the directory: {e}", args.out.display()))?;
            let stem = args
                .model
                .prop
                .file_stem()
                .map_or("synth".into(), |s| s.to_string_lossy().replace('_', "-"));
            for (name, text) in synth::write_uiuc(&points, &plan, m.diameter, &stem) {
                write_atomic(&args.out.join(name), &[text.as_bytes()], &inputs)?;
            }
            write_atomic(&args.out.join("answer.json"), &[&answer_bytes], &inputs)?;
        }
    }
    eprintln!(
        "propbet: {} points ({} RPMs x {} J) with {} and {:.2} % noise -> {}",
        points.len(),
        plan.rpms.len(),
        plan.js.len(),
        m.effects.describe(),
        100.0 * noise,
        args.out.display()
    );
    Ok(true)
}
