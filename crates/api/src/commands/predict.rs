//! `propbet predict`: a propeller over RPM x (J or V), or on a motor (`--motor`) at voltages,
//! currents, thrusts or throttles; its tables written (or on standard output) and what a
//! person is told of them.

use propbet_model::Model;
use propbet_pipeline::stages::polar_omegas;
use propbet_report::table::columns::Table;
use propbet_report::table::powered::PoweredRun;
use propbet_settings::spec::{ModelSpec, PoweredSpec, PredictSpec, SweepAxis};

use crate::console::{emit, Console};
use crate::motor::MotorFile;
use crate::CommandResult as Result;

/// Reads the model a spec names, telling what a person is told of it (the prop file's
/// warnings; a blade file's polars, computed over `points`, with their progress).
pub fn load_model_at(
    spec: &ModelSpec,
    points: impl FnOnce() -> Result<(Vec<f64>, SweepAxis)>,
    keep_stations: bool,
    console: &dyn Console,
) -> Result<Model> {
    let tick = |d, t| {
        if let Some(design) = &spec.design {
            console.progress(&design.process, d, t);
        }
    };
    let loaded = crate::model::load(spec, points, keep_stations, &tick);
    if spec.design.is_some() {
        console.progress_done();
    }
    let loaded = loaded?;
    if let Some(p) = &loaded.polars {
        console.err_sentence(&format!("propbet: {p}"), "", "  ");
    }
    for w in &loaded.warnings {
        console.err(&format!("propbet: warning: {w}"));
    }
    Ok(loaded.model)
}

/// Reads a QPROP prop file's model, telling its warnings.
pub fn load_model(spec: &ModelSpec, keep_stations: bool, console: &dyn Console) -> Result<Model> {
    let m = crate::model::prop_file(spec, keep_stations)?;
    for w in &m.loaded.warnings {
        console.err(&format!("propbet: warning: {w}"));
    }
    Ok(m)
}

/// Runs `propbet predict`; whether every station of every point converged.
pub fn predict(spec: &PredictSpec, console: &dyn Console) -> Result<bool> {
    let keep = spec.stations.is_some();
    let model = load_model_at(
        &spec.model,
        || Ok((spec.omegas.clone(), spec.axis.clone())),
        keep,
        console,
    )?;
    let t = crate::outputs::predict::tables(spec, &model, keep)?;
    let inputs = spec.model.inputs();
    emit(console, spec.out.as_deref(), &t.body, &inputs)?;
    if let (Some(path), Some(table)) = (&spec.stations, &t.stations) {
        emit(console, Some(path), std::slice::from_ref(table), &inputs)?;
    }
    let (failed, failed_points) = t.failed;
    if failed > 0 {
        console.err(&format!(
            "propbet: {failed} station solutions at {failed_points} operating points did not converge; \
             they are flagged in the per-station table"
        ));
    }
    // What it wrote, in one line (a table on standard output speaks for itself).
    if let Some(out) = &spec.out {
        let speeds = spec.omegas.len();
        let points = speeds
            * match &spec.axis {
                SweepAxis::J(v) | SweepAxis::V(v) => v.len().max(1),
            };
        console.err(&format!(
            "propbet predict: {points} operating points at {speeds} speed{} -> {}{}{}",
            if speeds == 1 { "" } else { "s" },
            out.display(),
            spec.stations
                .as_ref()
                .map_or(String::new(), |s| format!(", stations -> {}", s.display())),
            if spec.band { " (with the uncertainty band)" } else { "" }
        ));
    }
    // How close a prediction of a prop of this family or maker line came on propbet's
    // validation; a kind it holds none of is told so.
    let file = spec.model.prop.file_name().and_then(|n| n.to_str());
    let table = crate::compare::expected::shipped();
    if let Some(e) = crate::compare::expected::sentence(file, &table) {
        console.err_sentence(&format!("propbet: {e}"), "", "  ");
    }
    Ok(failed == 0)
}

/// `propbet predict`'s tables as columns ([`crate::outputs::predict::columns`]): the sweep's,
/// the per-station table's when `stations`, and the count of station solutions that did not
/// converge and of the points they are at.
pub fn columns(
    spec: &PredictSpec,
    stations: bool,
    console: &dyn Console,
) -> Result<(Table, Option<Table>, (usize, usize))> {
    let model = load_model_at(
        &spec.model,
        || Ok((spec.omegas.clone(), spec.axis.clone())),
        stations,
        console,
    )?;
    crate::outputs::predict::columns(spec, &model, stations)
}

/// `spec`'s model on `motor` (the file `spec.motor` names, read, or a motor made in memory)
/// at each driver value and airspeed, each point's stations kept when `keep_stations`; a blade
/// file's polars computed over the speeds the motor can reach.
pub fn solve_powered(
    spec: &PoweredSpec,
    motor: &MotorFile,
    keep_stations: bool,
    console: &dyn Console,
) -> Result<PoweredRun> {
    let supply = spec.supply.as_ref();
    let model = load_model_at(
        &spec.model,
        || {
            let battery = supply.map(|s| s.source(1.0).0);
            Ok((
                polar_omegas(&motor.motor, &spec.drives, battery),
                SweepAxis::V(spec.speeds.clone()),
            ))
        },
        keep_stations,
        console,
    )?;
    let fluid = spec.air.fluid()?;
    let table = propbet_pipeline::stages::powered_table(
        &model,
        &fluid.0,
        motor.clone(),
        supply,
        &spec.drives,
        &spec.speeds,
        spec.band,
    )?;
    Ok(PoweredRun::new(table, &model, &fluid, supply.is_some()))
}

/// Runs `propbet predict --motor`; whether every point has its operating point and every
/// station converged.
pub fn powered(spec: &PoweredSpec, console: &dyn Console) -> Result<bool> {
    let file = propbet_pipeline::stages::read_motor(&spec.motor)?;
    let run = solve_powered(spec, &file, spec.stations.is_some(), console)?;
    let mut inputs = spec.model.inputs();
    inputs.push(spec.motor.as_path());
    emit(console, spec.out.as_deref(), &[run.body(spec.format)?], &inputs)?;
    if let Some(path) = &spec.stations {
        crate::files::write_atomic(
            path,
            &[propbet_report::table::sweep::stations_csv(&run.solved())?],
            &inputs,
        )?;
    }
    for line in run.warnings() {
        console.err(&format!("propbet: {line}"));
    }
    if let Some(out) = &spec.out {
        console.err(&format!(
            "propbet predict: {} operating points on {} ({}) -> {}{}",
            run.table.points.len(),
            file.name,
            spec.motor.display(),
            out.display(),
            spec.stations
                .as_ref()
                .map_or(String::new(), |s| format!(", stations -> {}", s.display()))
        ));
    }
    Ok(run.table.clean())
}

/// `propbet predict --motor` in memory (its format and output files aside): the powered
/// table's columns, each point without an operating point with the reason, and with
/// `stations` the per-station table of every operating point found. `motor` is the motor
/// itself (`spec.motor`, its file, is not read).
pub fn powered_columns(
    spec: &PoweredSpec,
    motor: &MotorFile,
    stations: bool,
    console: &dyn Console,
) -> Result<(Table, Vec<String>, Option<Table>)> {
    let run = solve_powered(spec, motor, stations, console)?;
    let problems = run
        .table
        .points
        .iter()
        .filter_map(|p| p.problem().map(|w| format!("V {} m/s: {w}", p.v)))
        .collect();
    let per_station = stations
        .then(|| propbet_report::table::sweep::stations_table(&run.solved()))
        .transpose()?;
    Ok((run.table()?, problems, per_station))
}
