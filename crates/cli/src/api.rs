//! The commands' results in memory, for a program that runs propbet in its own process (the
//! Python package): typed specs in ([`propbet_api`]'s requests make them), the same tables as
//! the files the commands write out, returned instead of written. No command line is built or
//! read here.

use std::path::{Path, PathBuf};

use anyhow::{bail, Result};
use propbet_pipeline::spec::{ModelSpec, PredictSpec, StageSpec};

/// `propbet predict`'s tables as columns ([`propbet_api::outputs::predict::columns`]): the sweep's, the
/// per-station table's when `stations`, and the count of station solutions that did not
/// converge and of the points they are at.
pub fn predict(
    spec: &PredictSpec,
    stations: bool,
) -> Result<(
    propbet_report::table::columns::Table,
    Option<propbet_report::table::columns::Table>,
    (usize, usize),
)> {
    let model = crate::predict::load_model_at(&spec.model, || Ok((spec.omegas.clone(), spec.axis.clone())), stations)?;
    Ok(propbet_api::outputs::predict::columns(spec, &model, stations)?)
}

/// The prediction of a case directory, as `propbet run` makes it into `out`: its scan and
/// polars stages run (their files written under `out`, as the run writes them), and its
/// prediction's spec returned (the model those stages made, the case's sweep and air), with the
/// polars stage's blade and sections (geometry, airfoil, station airfoils) where it has one.
#[allow(clippy::type_complexity)]
pub fn case_prediction(
    dir: &Path,
    out: &Path,
    xfoil: &propbet_api::ProcessRequest,
) -> Result<(PredictSpec, Option<(PathBuf, Option<String>, Option<PathBuf>)>)> {
    let case = propbet_pipeline::case::read_case(dir)?;
    let plan = case.plan(dir, out, &xfoil.spec()?)?;
    let mut sections = None;
    for stage in plan.stages() {
        match &stage {
            // Their problems are on the terminal, as each command prints them.
            StageSpec::Scan(spec) => {
                crate::scan::run_spec(spec)?;
            }
            StageSpec::Polars(spec) => {
                for p in std::iter::once(spec.out_prop.as_path()).chain(spec.out_polars.as_deref()) {
                    crate::run::create_parent(p)?;
                }
                sections = Some((
                    spec.geometry.clone(),
                    spec.airfoil.clone(),
                    spec.station_airfoils.clone(),
                ));
                crate::polar::run_polars_spec(spec)?;
            }
            StageSpec::Predict(spec) => return Ok((spec.clone(), sections)),
            _ => {}
        }
    }
    bail!("{}: the case has no prediction stage", dir.display())
}

/// A blade file's rows as `propbet prop` reads them (the spec's file, units and reading), in
/// SI: radius, chord, blade angle and the ten QPROP section coefficients of each row (a row's
/// own, or the file's global ones), as a table (CSV).
pub fn stations(spec: &ModelSpec) -> Result<Vec<u8>> {
    let model = crate::prop::load_spec(spec)?;
    Ok(propbet_report::table::stations::csv(&model.loaded.file)?)
}

/// `propbet predict --motor` in memory (its format and output files aside): the powered
/// table's columns, each point without an operating point with the reason, and with
/// `stations` the per-station table of every operating point found. `motor` is the motor
/// itself (`spec.motor`, its file, is not read).
pub fn powered(
    spec: &propbet_pipeline::spec::PoweredSpec,
    motor: &propbet_api::motor::MotorFile,
    stations: bool,
) -> Result<(
    propbet_report::table::columns::Table,
    Vec<String>,
    Option<propbet_report::table::columns::Table>,
)> {
    let run = crate::powered::solve(spec, motor, stations)?;
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

/// `propbet compare-props` in memory (the battery and ESC as `battery`'s text says them;
/// airspeeds [m/s] of the full-throttle curves, None: the command's): props.csv's columns and the answer's sentences.
pub fn compare_props(
    models: &[(String, ModelSpec)],
    motor: &propbet_api::motor::MotorFile,
    supply: &propbet_api::motor::Supply,
    battery: &str,
    hover: f64,
    speeds: Option<Vec<f64>>,
    air: &propbet_pipeline::spec::AirSpec,
) -> Result<(propbet_report::table::columns::Table, Vec<String>)> {
    let speeds = speeds.unwrap_or_else(crate::compare_props::default_speeds);
    let props = crate::compare_props::side(models, &motor.motor, supply, hover, &speeds, air)?;
    Ok((
        crate::compare_props::table(&props, hover)?,
        crate::compare_props::answer(&props, &motor.name, battery, hover),
    ))
}

/// `propbet compare` of a spec: its files written; whether it ran clean (false when it
/// reported problems) and the contents of metrics.json, summary.json and points.csv.
pub fn compare(spec: &propbet_pipeline::spec::CompareSpec) -> Result<(bool, crate::compare::Written)> {
    crate::compare::run_spec(spec)
}

/// `propbet diagnose` of a spec: its files written; whether it ran clean (false when it
/// reported problems) and the contents of diagnosis.json and summary.json.
pub fn diagnose(spec: &propbet_pipeline::spec::DiagnoseSpec) -> Result<(bool, crate::diagnose::Written)> {
    crate::diagnose::run_spec(spec)
}

/// `propbet run` of a case directory (None: the shipped default case) into `out` (None:
/// `run_<case>`): its files written; false when a stage reported problems; and what it wrote
/// that a caller reads as data.
pub fn run(
    case: Option<PathBuf>,
    out: Option<PathBuf>,
    xfoil: &propbet_api::ProcessRequest,
    verbose: bool,
    inputs_anywhere: bool,
) -> Result<(bool, crate::run::RunFiles)> {
    crate::run::run_request(&crate::run::RunRequest {
        case,
        out,
        xfoil: xfoil.spec()?,
        verbose,
        inputs_anywhere,
    })
}

/// `propbet scan` of a scan file into `out` with these settings (a case's `[geometry]` keys):
/// its files written; false when a station could not be measured or fitted.
pub fn scan(
    input: PathBuf,
    settings: &propbet_api::settings::scan::ScanSettings,
    reference: Option<PathBuf>,
    name: Option<String>,
    out: PathBuf,
) -> Result<bool> {
    let spec = propbet_pipeline::spec::ScanSpec {
        input,
        options: settings.options()?,
        reference,
        name,
        out,
    };
    crate::scan::run_spec(&spec)
}

/// `propbet polars` of a spec: its prop file and tables written; false when a station has
/// no fit (kept from the geometry file, and reported).
pub fn polars(spec: &propbet_pipeline::spec::PolarsSpec) -> Result<bool> {
    crate::polar::run_polars_spec(spec)
}

pub use crate::engine::XfoilProcess;
pub use crate::validate::{ValidateArgs, Written as ValidateWritten};
pub use propbet_api::settings::{NCRIT, SECTION_MODEL};
pub use propbet_validate::DEFAULT_GENERIC_SECTION;

/// `propbet validate` of its arguments, typed: its files written; false when a prop reported
/// problems; the table as it wrote it.
pub fn validate(args: &ValidateArgs) -> Result<(bool, ValidateWritten)> {
    propbet_api::settings::SECTION_MODEL.choose(&args.section_model)?;
    crate::validate::run(args)
}
