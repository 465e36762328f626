//! `propbet serve`'s flags: the workbench of a case folder, or of `compare`'s flags.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;

use crate::predict::ModelFlags;

/// Arguments of `propbet serve` (`--measured`, required by `compare`, only with `--prop`
/// here).
#[derive(Debug, Args)]
#[command(mut_arg("measured", |a| a.required(false).requires("prop")))]
pub struct ServeArgs {
    /// Case directory holding `case.toml` with `[measured]` files (default: the shipped
    /// `props/apcsp_10x7`); none where `--prop` and `--measured` are given.
    #[arg(conflicts_with = "prop")]
    pub case: Option<PathBuf>,
    /// The blade against the measurements, as `compare --prop` takes it (instead of a case;
    /// with `--measured`).
    #[arg(long, requires = "measured")]
    pub prop: Option<PathBuf>,
    /// How the blade is read and what is changed in it, as `compare` takes them (XFOIL and
    /// the polar cache for a case too).
    #[command(flatten)]
    pub model: ModelFlags,
    /// The measurements, as `compare` takes them (with `--prop`).
    #[command(flatten)]
    pub data: Option<propbet_api::MeasuredRequest>,
    /// The server's own flags.
    #[command(flatten)]
    pub serve: propbet_serve::ServeOptions,
}

/// Runs `propbet serve`.
pub fn run(a: &ServeArgs) -> Result<bool> {
    let xfoil = a.model.blade.process.spec()?;
    let source = match (&a.prop, &a.data) {
        (Some(prop), Some(data)) => {
            propbet_serve::Source::Flags(Box::new((a.model.request(prop).spec()?, data.spec()?)))
        }
        (None, None) => {
            if a.model.blade.airfoil.is_some() {
                anyhow::bail!("--airfoil needs --prop: a case's model is its own");
            }
            propbet_serve::Source::Case(a.case.clone())
        }
        (None, Some(_)) => anyhow::bail!("--measured needs --prop (or a case folder without either)"),
        (Some(_), None) => anyhow::bail!("--prop needs --measured: the workbench compares a model with measurements"),
    };
    propbet_serve::run(&source, &xfoil, &a.serve, &crate::output::Terminal::default())?;
    Ok(true)
}
