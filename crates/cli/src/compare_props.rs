//! `propbet compare-props`: propellers side by side on one motor and battery, ranked by
//! grams per watt at hover; the page, a CSV and the ranked table on the terminal.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use propbet_api::settings::values::parse_list;
use propbet_pipeline::spec::{ModelSpec, SweepAxis};
use propbet_pipeline::stages::SideProp;

use crate::predict::{BladeArgs, FluidArgs};

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
    pub air: FluidArgs,
    /// Output directory (report.html, props.csv, plots/).
    #[arg(long, short)]
    pub out: PathBuf,
}

/// The default model of a propeller file.
fn model_spec(prop: &std::path::Path, blade: &BladeArgs) -> Result<ModelSpec> {
    Ok(blade.request(prop).spec()?)
}

/// The full-throttle curves' airspeeds without `--v` [m/s]: 0 to 20 in 2.
pub fn default_speeds() -> Vec<f64> {
    (0..=10).map(|k| 2.0 * k as f64).collect()
}

/// The hover thrust [N] checked.
fn check_hover(hover: f64) -> Result<()> {
    if !(hover > 0.0 && hover.is_finite()) {
        anyhow::bail!("--hover {hover}: the thrust of one propeller at hover, in newtons, above 0");
    }
    Ok(())
}

/// Propellers side by side, each (its name, its model) on the motor through the supply:
/// ranked by g/W at `hover` thrust [N], with full throttle over the airspeeds [m/s].
pub fn side(
    models: &[(String, ModelSpec)],
    motor: &propbet_api::motor::Motor,
    supply: &propbet_api::motor::Supply,
    hover: f64,
    speeds: &[f64],
    air: &propbet_pipeline::spec::AirSpec,
) -> Result<Vec<SideProp>> {
    check_hover(hover)?;
    let omegas = propbet_pipeline::stages::polar_omegas(motor, &[], Some(supply.source(1.0).0));
    let mut loaded = Vec::new();
    for (name, spec) in models {
        let model = crate::predict::load_model_at(spec, || Ok((omegas.clone(), SweepAxis::V(speeds.to_vec()))), false)?;
        loaded.push((name.clone(), model));
    }
    let (fluid, _) = air.fluid()?;
    Ok(propbet_pipeline::stages::side_by_side(
        &loaded, &fluid, motor, supply, hover, speeds,
    )?)
}

/// The ranked table's columns (props.csv's).
pub fn table(props: &[SideProp], hover: f64) -> Result<propbet_report::table::columns::Table> {
    Ok(propbet_report::table::props::columns(props, hover)?)
}

/// The answer's sentences.
pub fn answer(props: &[SideProp], motor: &str, battery: &str, hover: f64) -> Vec<String> {
    let setup = propbet_report::props::Setup {
        motor,
        battery,
        hover_thrust: hover,
        command: "",
    };
    propbet_report::props::answer(props, &setup)
}

/// Runs `propbet compare-props`.
pub fn run(args: &ComparePropsArgs) -> Result<bool> {
    check_hover(args.hover)?;
    let supply = propbet_api::supply(&args.battery, args.esc_ohms)?;
    let file = propbet_pipeline::stages::read_motor(&args.motor)?;
    let speeds = match &args.v {
        Some(v) => parse_list("--v", v)?,
        None => default_speeds(),
    };
    let mut models = Vec::new();
    let mut inputs: Vec<PathBuf> = vec![args.motor.clone()];
    for prop in &args.props {
        let name = prop
            .file_name()
            .map_or_else(|| prop.display().to_string(), |n| n.to_string_lossy().into());
        inputs.push(prop.clone());
        models.push((name, model_spec(prop, &args.blade)?));
    }
    let props = side(&models, &file.motor, &supply, args.hover, &speeds, &args.air.spec()?)?;
    let command = std::iter::once("propbet".to_string())
        .chain(std::env::args().skip(1))
        .collect::<Vec<_>>()
        .join(" ");
    let setup = propbet_report::props::Setup {
        motor: &file.name,
        battery: &args.battery,
        hover_thrust: args.hover,
        command: &command,
    };
    let inputs: Vec<&std::path::Path> = inputs.iter().map(PathBuf::as_path).collect();
    propbet_api::files::refuse_inputs_inside(&args.out, &inputs)?;
    propbet_api::outputs::props::outputs(&props, &setup)?.write(&args.out, &command, &inputs)?;
    for a in propbet_report::props::answer(&props, &setup) {
        println!("{}", crate::output::wrapped(&a, "", "  "));
    }
    println!(
        "{:>4}  {:<28} {:>9} {:>9} {:>10} {:>8}",
        "rank", "propeller", "hover g/W", "hover A", "full T [N]", "full A"
    );
    for (k, p) in props.iter().enumerate() {
        let h = p.hover.as_ref().ok();
        let f = p.full.first().and_then(|(_, r)| r.as_ref().ok());
        let cell = |x: Option<f64>, d: usize| x.map_or("–".to_string(), |x| format!("{x:.d$}"));
        println!(
            "{:>4}  {:<28} {:>9} {:>9} {:>10} {:>8}",
            k + 1,
            p.name,
            cell(p.hover_g_per_w(), 2),
            cell(h.map(|x| x.2.battery_amps), 1),
            cell(f.map(|x| x.0.loads.thrust), 2),
            cell(f.map(|x| x.2.battery_amps), 1)
        );
    }
    println!("report: {}", args.out.join("report.html").display());
    Ok(props.iter().all(|p| p.hover.is_ok()))
}
