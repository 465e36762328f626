//! `propbet compare-props`: propellers side by side on one motor and battery, ranked by
//! grams per watt at hover; the page, a CSV and the ranked table on the terminal.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use propbet_api::settings::values::parse_list;

use crate::predict::BladeArgs;

/// Arguments of `propbet compare-props`.
#[derive(Debug, Args)]
pub struct ComparePropsArgs {
    /// The propellers (QPROP prop files, APC's PE0 files, UIUC tables, blade tables), each
    /// read with propbet's default model.
    #[arg(required = true, num_args = 1..)]
    pub props: Vec<PathBuf>,
    /// The sections of blade files without coefficients.
    #[command(flatten)]
    pub blade: BladeArgs,
    /// The QPROP motor file.
    #[arg(long, value_name = "FILE")]
    pub motor: PathBuf,
    /// The battery (as `predict --battery`: `3S,2200mAh,R=5mOhm`).
    #[arg(long, value_name = "SPEC")]
    pub battery: String,
    /// The ESC's resistance [ohm].
    #[arg(long, default_value_t = propbet_api::motor::ESC_OHMS, value_name = "OHMS")]
    pub esc_ohms: f64,
    /// The thrust of one propeller at hover [N] (the craft's weight over its propellers).
    #[arg(long, value_name = "N")]
    pub hover: f64,
    /// Airspeeds of the full-throttle curves [m/s] (list or range syntax; default 0:20/11).
    #[arg(long, allow_hyphen_values = true)]
    pub v: Option<String>,
    /// Air properties.
    #[command(flatten)]
    pub air: propbet_api::AirRequest,
    /// Output directory (report.html, props.csv, plots/).
    #[arg(long, short)]
    pub out: PathBuf,
}

/// Runs `propbet compare-props`.
pub fn run(args: &ComparePropsArgs) -> Result<bool> {
    let mut models = Vec::new();
    for prop in &args.props {
        let name = prop
            .file_name()
            .map_or_else(|| prop.display().to_string(), |n| n.to_string_lossy().into());
        models.push((name, args.blade.request(prop).spec()?));
    }
    let command = propbet_api::commands::motor::PropsCommand {
        models,
        motor: args.motor.clone(),
        battery: args.battery.clone(),
        esc_ohms: args.esc_ohms,
        hover: args.hover,
        speeds: args.v.as_deref().map(|v| parse_list("--v", v)).transpose()?,
        air: args.air.spec()?,
        out: args.out.clone(),
        command: std::iter::once("propbet".to_string())
            .chain(std::env::args().skip(1))
            .collect::<Vec<_>>()
            .join(" "),
    };
    let term = crate::output::Terminal::default();
    Ok(propbet_api::commands::motor::compare_props(&command, &term)?)
}
