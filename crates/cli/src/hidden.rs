//! `propbet hidden`: known effects added to real measurements (validate's props and files, or
//! one stand log with its propeller's file: `propbet hidden log`), and how the diagnosis
//! answers them.

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, Subcommand};
use propbet_api::diagnose::inject::Injection;

use propbet_api::commands::validate::ValidateRequest;

use crate::predict::ModelArgs;

/// Arguments of `propbet hidden`.
#[derive(Debug, Args)]
pub struct HiddenArgs {
    /// One stand log instead of validate's props.
    #[command(subcommand)]
    pub log: Option<HiddenCommand>,
    /// The props, their files and the model, as `propbet validate` takes them.
    #[command(flatten)]
    pub validate: Option<ValidateRequest>,
    /// What is added.
    #[command(flatten)]
    pub inject: InjectArgs,
}

/// `propbet hidden`'s subcommands.
#[derive(Debug, Subcommand)]
pub enum HiddenCommand {
    /// The same on one set of measured files (a thrust-stand step test) with its propeller's
    /// file, as `compare` takes them: `propbet hidden log --prop P --measured LOG -o OUT`
    Log(Box<HiddenLogArgs>),
}

/// Arguments of `propbet hidden log`.
#[derive(Debug, Args)]
pub struct HiddenLogArgs {
    /// The propeller model.
    #[command(flatten)]
    pub model: ModelArgs,
    /// The measurements.
    #[command(flatten)]
    pub data: propbet_api::MeasuredRequest,
    /// What is added.
    #[command(flatten)]
    pub inject: InjectArgs,
    /// Output directory (created if missing).
    #[arg(long, short)]
    pub out: PathBuf,
}

/// The effects added and their sizes.
#[derive(Debug, Args)]
pub struct InjectArgs {
    /// The effects added to the measurements, each at every size.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "thrust-tare,torque-tare,rpm-scale,density"
    )]
    pub inject: Vec<String>,
    /// Sizes: each effect's relative change of the static loads (0.05: 5 %).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "0.03,0.05,0.1",
        allow_negative_numbers = true
    )]
    pub sizes: Vec<f64>,
}

impl InjectArgs {
    fn injections(&self) -> Result<Vec<Injection>> {
        let mut injections = Vec::new();
        for e in &self.inject {
            for &s in &self.sizes {
                injections.push(Injection::new(e.trim(), s).map_err(|why| anyhow::anyhow!("--inject/--sizes: {why}"))?);
            }
        }
        Ok(injections)
    }
}

/// Runs `propbet hidden`.
pub fn run(a: &HiddenArgs) -> Result<bool> {
    let term = crate::output::Terminal::default();
    if let Some(HiddenCommand::Log(l)) = &a.log {
        propbet_api::commands::validate::hidden_log(
            &l.model.spec()?,
            &l.data.spec()?,
            &l.inject.injections()?,
            &l.out,
            &term,
        )?;
        return Ok(true);
    }
    let injections = a.inject.injections()?;
    let Some(validate) = &a.validate else {
        anyhow::bail!("propbet hidden needs --uiuc, --pe0, --airfoils and --out (or `propbet hidden log`)");
    };
    let (spec, props, generic) = validate.spec()?;
    Ok(propbet_api::commands::validate::hidden(
        &spec,
        &props,
        generic.as_ref(),
        &injections,
        &term,
    )?)
}
