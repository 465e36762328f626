//! `propbet hidden`: known effects added to real measurements (validate's props and files), and
//! how often the diagnosis finds them with their size.

use anyhow::Result;
use clap::Args;
use propbet_api::diagnose::inject::Injection;

use propbet_api::commands::validate::ValidateRequest;

/// Arguments of `propbet hidden`.
#[derive(Debug, Args)]
pub struct HiddenArgs {
    /// The props, their files and the model, as `propbet validate` takes them.
    #[command(flatten)]
    pub validate: ValidateRequest,
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

/// Runs `propbet hidden`.
pub fn run(a: &HiddenArgs) -> Result<bool> {
    let mut injections = Vec::new();
    for e in &a.inject {
        for &s in &a.sizes {
            injections.push(Injection::new(e.trim(), s).map_err(|why| anyhow::anyhow!("--inject/--sizes: {why}"))?);
        }
    }
    let (spec, props, generic) = a.validate.spec()?;
    let term = crate::output::Terminal::default();
    Ok(propbet_api::commands::validate::hidden(
        &spec,
        &props,
        generic.as_ref(),
        &injections,
        &term,
    )?)
}
