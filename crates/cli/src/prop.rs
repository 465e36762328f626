//! `propbet prop`: inspect a QPROP prop file and optionally write it back normalised.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use propbet_api::spec::ModelSpec;

/// Arguments of `propbet prop`.
#[derive(Debug, Args)]
pub struct PropArgs {
    /// The blade file: a QPROP prop file, APC's design file (PE0), a UIUC geometry table or a
    /// blade table (CSV).
    pub file: PathBuf,
    #[arg(long = propbet_api::settings::UNITS.flag, help = propbet_api::settings::UNITS.help)]
    pub units: Option<String>,
    /// Read as QPROP 1.22 does (R on line 2 unscaled, REref of the first station).
    #[arg(long)]
    pub qprop_compat: bool,
    /// Write the prop file back to this path as QPROP 1.22 reads what propbet reads: metres and
    /// degrees, R on line 2, every row's drag law on one REref.
    #[arg(long)]
    pub write: Option<PathBuf>,
}

impl PropArgs {
    /// The file as a model's spec reads it (its units, QPROP's reading).
    pub fn model_spec(&self) -> Result<ModelSpec> {
        Ok(ModelSpec {
            units: self
                .units
                .as_deref()
                .map(propbet_api::settings::values::parse_length_unit)
                .transpose()?,
            qprop_compat: self.qprop_compat,
            ..ModelSpec::prop(self.file.clone())
        })
    }
}

/// Runs `propbet prop`.
pub fn run(args: &PropArgs) -> Result<bool> {
    let term = crate::output::Terminal::default();
    Ok(propbet_api::commands::prop::prop(
        &args.model_spec()?,
        args.write.as_deref(),
        &term,
    )?)
}
