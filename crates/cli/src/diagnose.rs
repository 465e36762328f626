//! `propbet diagnose`: which physical effect is missing from the model; `propbet effects`:
//! the effects there are.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use propbet_api::spec::DiagnoseSpec;

use crate::predict::ModelArgs;

/// Arguments of `propbet diagnose`.
#[derive(Debug, Args)]
pub struct DiagnoseArgs {
    /// The propeller model (effects given with --effect are part of the baseline).
    #[command(flatten)]
    pub model: ModelArgs,
    /// The measurements.
    #[command(flatten)]
    pub data: propbet_api::MeasuredRequest,
    /// Candidate effects: `all` (default) or a comma-separated list of ids (user effects too).
    #[arg(long, default_value = "all")]
    pub effects: String,
    #[arg(long = propbet_api::settings::FOLDS.flag, help = propbet_api::settings::FOLDS.help, default_value_t = propbet_api::settings::FOLDS.default)]
    pub folds: usize,
    #[arg(long = propbet_api::settings::MAX_STEPS.flag, help = propbet_api::settings::MAX_STEPS.help, default_value_t = propbet_api::settings::MAX_STEPS.default)]
    pub max_steps: usize,
    #[arg(long = propbet_api::settings::WINDOW.flag, help = propbet_api::settings::WINDOW.help, default_value_t = propbet_api::settings::WINDOW.default)]
    pub window: f64,
    /// Output directory (created if missing).
    #[arg(long, short)]
    pub out: PathBuf,
}

impl DiagnoseArgs {
    /// The stage's spec (flags in SI).
    pub fn spec(&self) -> Result<DiagnoseSpec> {
        let request = propbet_api::DiagnoseRequest {
            effects: Some(self.effects.split(',').map(str::to_string).collect()),
            folds: Some(self.folds),
            max_steps: Some(self.max_steps),
            window: Some(self.window),
        };
        Ok(request.spec(self.model.spec()?, self.data.spec()?, self.out.clone())?)
    }
}

/// Runs `propbet diagnose`; returns false (exit 1, as `compare`) when measured rows were
/// dropped as faulty: the diagnosis ran on the rest, the report lists them.
pub fn run(args: &DiagnoseArgs) -> Result<bool> {
    Ok(propbet_api::commands::diagnose::diagnose(&args.spec()?, &crate::output::Terminal::default())?.0)
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
    let term = crate::output::Terminal::default();
    Ok(propbet_api::commands::diagnose::effects(
        args.user_effects.as_deref(),
        &term,
    )?)
}
