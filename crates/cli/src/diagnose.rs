//! `propbet diagnose`: which physical effect is missing from the model; `propbet effects`:
//! the effects there are.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::Args;
use propbet_compare::{compare, Setup};
use propbet_diagnose::discover::{diagnose, Options};
use propbet_diagnose::report::{self, JsonOut};
use propbet_diagnose::{Data, Model};
use propbet_effects::Stack;

use crate::compare::MeasuredArgs;
use crate::output::{write_atomic, write_figure};
use crate::predict::ModelArgs;

/// Arguments of `propbet diagnose`.
#[derive(Debug, Args)]
pub struct DiagnoseArgs {
    /// The propeller model (effects given with --effect are part of the baseline).
    #[command(flatten)]
    pub model: ModelArgs,
    /// The measurements.
    #[command(flatten)]
    pub data: MeasuredArgs,
    /// Candidate effects: `all` (default) or a comma-separated list of ids (user effects too).
    #[arg(long, default_value = "all")]
    pub effects: String,
    /// Folds of the k-fold cross-validation.
    #[arg(long, default_value_t = 5)]
    pub folds: usize,
    /// Most effects the ladder adds.
    #[arg(long, default_value_t = 3)]
    pub max_steps: usize,
    /// Output directory (created if missing).
    #[arg(long, short)]
    pub out: PathBuf,
}

/// Runs `propbet diagnose`.
pub fn run(args: &DiagnoseArgs) -> Result<bool> {
    let model = args.model.build(false)?;
    if args.folds < 2 {
        bail!("--folds {}: at least 2", args.folds);
    }
    let list: Vec<String> = args
        .effects
        .split(',')
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .collect();
    let mut candidates = model.registry.select(&list)?;
    // Effects already in the baseline (--effect) are not candidates.
    candidates.retain(|c| !model.effects.active.iter().any(|a| a.effect.id() == c.id()));
    let (air, sets) = args.data.load()?;
    args.data.print_summary(&sets);
    let setup = Setup {
        rotor: &model.rotor,
        diameter: model.diameter,
        opts: model.opts,
        air,
        effects: Stack::baseline(),
    };
    let points = compare(&setup, &sets)?;
    let data = Data::from_points(&points)?;
    // The user's --effect stack stays in the model, under the candidates.
    let dmodel = Model {
        rotor: &model.rotor,
        opts: model.opts,
        diameter: model.diameter,
        fixed: model.effects.clone(),
    };
    let opts = Options {
        folds: args.folds,
        max_steps: args.max_steps,
        ..Options::default()
    };
    let d = diagnose(&dmodel, &data, &candidates, &opts)?;
    let prop = args.model.prop.display().to_string();
    let measured: Vec<String> = args.data.measured.iter().map(|p| p.display().to_string()).collect();
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let rep = report::build(&data, &d, &prop, &measured, &command)?;
    let mut inputs = args.model.inputs();
    inputs.extend(args.data.inputs());
    let plots = args.out.join("plots");
    std::fs::create_dir_all(&plots)
        .map_err(|e| anyhow::anyhow!("{}: cannot create the directory: {e}", plots.display()))?;
    for (name, fig) in &rep.figures {
        for ext in ["svg", "png"] {
            write_figure(&plots.join(format!("{name}.{ext}")), fig, &inputs)?;
        }
    }
    let json = JsonOut {
        prop: &prop,
        measured: &measured,
        command: &command,
        diagnosis: &d,
        final_params: d.ladder.last().map(|r| r.params.clone()).unwrap_or_default(),
        final_effects: d.final_stack.active.iter().map(|a| a.describe()).collect(),
    };
    let mut bytes = serde_json::to_vec_pretty(&json)?;
    bytes.push(b'\n');
    write_atomic(&args.out.join("diagnosis.json"), &[bytes], &inputs)?;
    write_atomic(&args.out.join("summary.md"), &[rep.markdown.as_bytes()], &inputs)?;
    write_atomic(&args.out.join("report.html"), &[rep.html.as_bytes()], &inputs)?;

    println!("{}", report::verdict(&d));
    println!("where the baseline fails:");
    for s in &d.before {
        println!("  {}", s.text);
    }
    println!("ranking (held-out RMS, p, significant):");
    for (i, s) in d.ranking.iter().enumerate() {
        match &s.note {
            Some(n) => println!("  {:>2}. {:<16} {n}", i + 1, s.id),
            None => println!(
                "  {:>2}. {:<16} {:>7.2} %  p {:<9.3e} {}",
                i + 1,
                s.id,
                100.0 * s.kfold_rms,
                s.p_value,
                if s.significant { "significant" } else { "-" }
            ),
        }
    }
    println!("ladder:");
    for r in &d.ladder {
        println!("  {:<60} held-out {:>6.2} %", r.stack, 100.0 * r.kfold_rms);
    }
    println!("report: {}", args.out.join("report.html").display());
    Ok(true)
}

/// Arguments of `propbet effects`.
#[derive(Debug, Args)]
pub struct EffectsArgs {
    /// Also list the effects of this user file.
    #[arg(long)]
    pub user_effects: Option<PathBuf>,
}

/// Lists the effects with their parameters, bounds and physics.
pub fn list(args: &EffectsArgs) -> Result<bool> {
    let registry = match &args.user_effects {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| anyhow::anyhow!("{}: cannot read: {e}", p.display()))?;
            propbet_effects::spec::Registry::with_user(propbet_effects::user::parse(&text, &p.display().to_string())?)?
        }
        None => propbet_effects::spec::Registry::default(),
    };
    use std::fmt::Write as _;
    let mut out = String::new();
    for e in &registry.effects {
        let hooks: Vec<String> = e.hooks().iter().map(|h| format!("{h:?}").to_lowercase()).collect();
        let _ = writeln!(out, "{} ({})", e.id(), hooks.join(", "));
        for p in e.params() {
            let neutral = p.neutral.map_or("none".to_string(), propbet_effects::fmt_value);
            let _ = writeln!(
                out,
                "    {} [{}]  neutral {neutral}, bounds [{}, {}]: {}",
                p.name,
                p.unit,
                propbet_effects::fmt_value(p.lower),
                propbet_effects::fmt_value(p.upper),
                p.doc
            );
        }
        let _ = writeln!(
            out,
            "    {}",
            e.explanation().split_whitespace().collect::<Vec<_>>().join(" ")
        );
    }
    // A closed pipe (`propbet effects | head`) is not an error.
    let _ = std::io::Write::write_all(&mut std::io::stdout().lock(), out.as_bytes());
    Ok(true)
}
