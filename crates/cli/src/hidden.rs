//! `propbet hidden`: known effects added to real measurements (validate's props and files), and
//! how often the diagnosis finds them with their size.

use anyhow::Result;
use clap::Args;
use propbet_api::diagnose::inject::{Finding, Injection};
use propbet_validate::{hidden_prop, sections_for, PropSections};

use crate::polar::Bar;
use crate::validate::ValidateArgs;
use propbet_api::files::write_atomic;

/// Arguments of `propbet hidden`.
#[derive(Debug, Args)]
pub struct HiddenArgs {
    /// The props, their files and the model, as `propbet validate` takes them.
    #[command(flatten)]
    pub validate: ValidateArgs,
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
    let (spec, props, generic) = crate::validate::spec(&a.validate)?;
    let lock = propbet_api::files::claim_folder(&spec.out, "propbet hidden")?;
    let (quiet, engine) = (a.validate.xfoil.quiet, spec.xfoil.process.engine);
    let mut rows: Vec<(String, Finding)> = Vec::new();
    let mut skipped = Vec::new();
    for (k, prop) in props.iter().enumerate() {
        let sections = match sections_for(&spec, prop, generic.as_ref()) {
            PropSections::Use(s) => s,
            PropSections::NotValidated(why) => {
                skipped.push((prop.clone(), why));
                continue;
            }
        };
        eprintln!("propbet hidden [{}/{}] {prop}", k + 1, props.len());
        let bar = Bar::new(quiet, engine);
        match hidden_prop(&spec, prop, &sections, &injections, &move |d, t| bar.tick(d, t)) {
            Ok(found) => rows.extend(found.into_iter().map(|f| (prop.clone(), f))),
            Err(e) => skipped.push((prop.clone(), format!("{e:#}"))),
        }
    }
    if rows.is_empty() {
        anyhow::bail!("no prop could be diagnosed: {skipped:?}");
    }
    let md = propbet_report::hidden::markdown(&rows, &skipped);
    write_atomic(
        &spec.out.join("hidden.csv"),
        &[propbet_report::hidden::csv(&rows)?],
        &[],
    )?;
    write_atomic(&spec.out.join("hidden.md"), &[md.as_bytes()], &[])?;
    lock.finish()?;
    crate::output::print_page(&md);
    Ok(skipped.is_empty())
}
