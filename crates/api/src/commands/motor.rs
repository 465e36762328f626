//! `propbet motor fit` (a motor's R, Io and Kv fitted to a stand log's electrical columns)
//! and `propbet compare-props` (propellers side by side on one motor and battery).

use std::path::{Path, PathBuf};

use propbet_pipeline::stages::SideProp;
use propbet_report::table::columns::Table;
use propbet_settings::spec::{AirSpec, MeasuredSpec, ModelSpec, SweepAxis};

use crate::console::{emit, Console};
use crate::motor::{FitKind, Motor, MotorFile, Supply};
use crate::CommandResult as Result;

/// Runs `propbet motor fit`: the motor file written to `out` (None: standard output), the
/// fit's steps, notes and misses told.
pub fn fit(
    spec: &MeasuredSpec,
    kv: Option<f64>,
    kind: FitKind,
    name: Option<String>,
    out: Option<&Path>,
    console: &dyn Console,
) -> Result<bool> {
    let crate::outputs::motor::Fitted {
        fit: f, text, lines, ..
    } = crate::outputs::motor::fitted(spec, kv, kind, name)?;
    let inputs: Vec<&Path> = spec.files.iter().map(PathBuf::as_path).collect();
    emit(console, out, &[text.as_bytes()], &inputs)?;
    for l in &lines {
        console.err(&format!("propbet motor fit: {l}"));
    }
    for n in &f.notes {
        console.err_sentence(&format!("propbet: note: {n}"), "", "  ");
    }
    if let Some(w) = &f.misses {
        console.err_sentence(&format!("propbet: where the motor model misses: {w}"), "", "  ");
    }
    if let Some(out) = out {
        console.err(&format!("propbet motor fit: -> {}", out.display()));
    }
    Ok(true)
}

/// The full-throttle curves' airspeeds without `--v` [m/s]: 0 to 20 in 2.
pub fn default_speeds() -> Vec<f64> {
    (0..=10).map(|k| 2.0 * k as f64).collect()
}

/// The hover thrust [N] checked.
fn check_hover(hover: f64) -> Result<()> {
    if !(hover > 0.0 && hover.is_finite()) {
        crate::command_error::refuse!("--hover {hover}: the thrust of one propeller at hover, in newtons, above 0");
    }
    Ok(())
}

/// Propellers side by side, each (its name, its model) on the motor through the supply:
/// ranked by g/W at `hover` thrust [N], with full throttle over the airspeeds [m/s].
pub fn side(
    models: &[(String, ModelSpec)],
    motor: &Motor,
    supply: &Supply,
    hover: f64,
    speeds: &[f64],
    air: &AirSpec,
    console: &dyn Console,
) -> Result<Vec<SideProp>> {
    check_hover(hover)?;
    let omegas = propbet_pipeline::stages::polar_omegas(motor, &[], Some(supply.source(1.0).0));
    let mut loaded = Vec::new();
    for (name, spec) in models {
        let model = super::predict::load_model_at(
            spec,
            || Ok((omegas.clone(), SweepAxis::V(speeds.to_vec()))),
            false,
            console,
        )?;
        loaded.push((name.clone(), model));
    }
    let (fluid, _) = air.fluid()?;
    Ok(propbet_pipeline::stages::side_by_side(
        &loaded, &fluid, motor, supply, hover, speeds,
    )?)
}

/// What `propbet compare-props` is asked.
pub struct PropsCommand {
    /// Each propeller: its name and its model.
    pub models: Vec<(String, ModelSpec)>,
    /// The motor file.
    pub motor: PathBuf,
    /// The battery, as its text says it (`3S,2200mAh`).
    pub battery: String,
    /// The ESC's resistance [ohm].
    pub esc_ohms: f64,
    /// The thrust of one propeller at hover [N].
    pub hover: f64,
    /// The full-throttle curves' airspeeds [m/s] (None: [`default_speeds`]).
    pub speeds: Option<Vec<f64>>,
    /// The air.
    pub air: AirSpec,
    /// The output folder.
    pub out: PathBuf,
    /// The command line, as the report shows it.
    pub command: String,
}

/// Runs `propbet compare-props`: its report written, the ranking told; false when some
/// propeller cannot hover at that thrust.
pub fn compare_props(c: &PropsCommand, console: &dyn Console) -> Result<bool> {
    check_hover(c.hover)?;
    let supply = crate::supply(&c.battery, c.esc_ohms)?;
    let file = propbet_pipeline::stages::read_motor(&c.motor)?;
    let speeds = c.speeds.clone().unwrap_or_else(default_speeds);
    let props = side(&c.models, &file.motor, &supply, c.hover, &speeds, &c.air, console)?;
    let setup = propbet_report::props::Setup {
        motor: &file.name,
        battery: &c.battery,
        hover_thrust: c.hover,
        command: &c.command,
    };
    let inputs: Vec<&Path> = std::iter::once(c.motor.as_path())
        .chain(c.models.iter().map(|(_, m)| m.prop.as_path()))
        .collect();
    crate::files::refuse_inputs_inside(&c.out, &inputs)?;
    crate::outputs::props::outputs(&props, &setup)?.write(&c.out, &c.command, &inputs)?;
    for a in propbet_report::props::answer(&props, &setup) {
        console.out_sentence(&a, "", "  ");
    }
    console.out(&format!(
        "{:>4}  {:<28} {:>9} {:>9} {:>10} {:>8}",
        "rank", "propeller", "hover g/W", "hover A", "full T [N]", "full A"
    ));
    for (k, p) in props.iter().enumerate() {
        let h = p.hover.as_ref().ok();
        let f = p.full.first().and_then(|(_, r)| r.as_ref().ok());
        let cell = |x: Option<f64>, d: usize| x.map_or("–".to_string(), |x| format!("{x:.d$}"));
        console.out(&format!(
            "{:>4}  {:<28} {:>9} {:>9} {:>10} {:>8}",
            k + 1,
            p.name,
            cell(p.hover_g_per_w(), 2),
            cell(h.map(|x| x.2.battery_amps), 1),
            cell(f.map(|x| x.0.loads.thrust), 2),
            cell(f.map(|x| x.2.battery_amps), 1)
        ));
    }
    console.out(&format!("report: {}", c.out.join("report.html").display()));
    Ok(props.iter().all(|p| p.hover.is_ok()))
}

/// `propbet compare-props` in memory (the battery and ESC as `battery`'s text says them;
/// airspeeds [m/s] of the full-throttle curves, None: the command's): props.csv's columns and
/// the answer's sentences.
#[allow(clippy::too_many_arguments)]
pub fn compare_props_columns(
    models: &[(String, ModelSpec)],
    motor: &MotorFile,
    supply: &Supply,
    battery: &str,
    hover: f64,
    speeds: Option<Vec<f64>>,
    air: &AirSpec,
    console: &dyn Console,
) -> Result<(Table, Vec<String>)> {
    let speeds = speeds.unwrap_or_else(default_speeds);
    let props = side(models, &motor.motor, supply, hover, &speeds, air, console)?;
    let setup = propbet_report::props::Setup {
        motor: &motor.name,
        battery,
        hover_thrust: hover,
        command: "",
    };
    Ok((
        propbet_report::table::props::columns(&props, hover)?,
        propbet_report::props::answer(&props, &setup),
    ))
}
