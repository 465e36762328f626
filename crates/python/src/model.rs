//! The propeller model and what is asked of it: predictions, the file's stations, measured
//! files, comparisons and diagnoses, each from typed values (no command line).

use std::path::PathBuf;

use propbet_api::{
    AirSpec, DiagnoseRequest, MeasuredRequest, ModelRequest, ModelSpec, PredictSpec, ProcessRequest, SweepAxis,
    SweepRequest, TableFormat,
};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};

use crate::boundary::{columns, guarded};
use crate::values::values;

/// The polar engine's keyword arguments (every function that may make polars takes them) as
/// a request.
#[allow(clippy::too_many_arguments)]
pub(crate) fn process(
    engine: Option<String>,
    neuralfoil_size: Option<String>,
    xfoil: Option<PathBuf>,
    cache: Option<PathBuf>,
    no_cache: bool,
    quiet: bool,
    budget: Option<f64>,
) -> ProcessRequest {
    ProcessRequest {
        engine,
        neuralfoil_size,
        xfoil,
        cache,
        no_cache,
        quiet,
        budget,
    }
}

/// A propeller model: a blade file, how it is read and what is added to it. Made with the
/// keyword arguments of ``propbet predict``'s model (``units``, ``qprop_compat``, ``dbeta``
/// [deg], ``rotation``, ``drag_factor``, ``effects``, ``user_effects``, ``polars``; for a blade
/// file without coefficients ``airfoil``, ``sections_from``, ``airfoils``, ``engine``, ...);
/// a bad value raises ``InputError`` naming it.
#[pyclass(module = "propbet._native", frozen)]
pub struct Model {
    /// What was asked (None for a case's model, made by its case file).
    pub(crate) request: Option<ModelRequest>,
    pub(crate) spec: ModelSpec,
    /// A case's sweep and air.
    pub(crate) case: Option<(Vec<f64>, SweepAxis, AirSpec)>,
}

impl Model {
    fn of(py: Python<'_>, request: ModelRequest) -> PyResult<Model> {
        let r = request.clone();
        let spec = guarded(py, move || r.spec())?;
        Ok(Model {
            request: Some(request),
            spec,
            case: None,
        })
    }
}

#[pymethods]
impl Model {
    #[new]
    #[pyo3(signature = (
        prop, *, units=None, qprop_compat=false, no_tip_loss=false, dbeta=0.0, rotation=None,
        drag_factor=None, effects=Vec::new(), user_effects=None, polars=None, airfoil=None,
        sections_from=None, airfoils=None, engine=None, neuralfoil_size=None, xfoil=None,
        cache=None, no_cache=false, quiet=false, xfoil_budget=None
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        prop: PathBuf,
        units: Option<String>,
        qprop_compat: bool,
        no_tip_loss: bool,
        dbeta: f64,
        rotation: Option<String>,
        drag_factor: Option<f64>,
        effects: Vec<String>,
        user_effects: Option<PathBuf>,
        polars: Option<PathBuf>,
        airfoil: Option<String>,
        sections_from: Option<PathBuf>,
        airfoils: Option<PathBuf>,
        engine: Option<String>,
        neuralfoil_size: Option<String>,
        xfoil: Option<PathBuf>,
        cache: Option<PathBuf>,
        no_cache: bool,
        quiet: bool,
        xfoil_budget: Option<f64>,
    ) -> PyResult<Model> {
        Model::of(
            py,
            ModelRequest {
                prop,
                dbeta_deg: dbeta,
                units,
                qprop_compat,
                no_tip_loss,
                polars,
                rotation,
                drag_factor,
                effects,
                user_effects,
                airfoil,
                sections_from,
                airfoils,
                process: process(engine, neuralfoil_size, xfoil, cache, no_cache, quiet, xfoil_budget),
            },
        )
    }

    /// The blade file the predictions read.
    #[getter]
    fn prop(&self) -> PathBuf {
        self.spec.prop.clone()
    }

    /// The tabulated polars that replace the file's coefficients, if any.
    #[getter]
    fn polars(&self) -> Option<PathBuf> {
        self.spec.polars.clone()
    }

    /// The same model on another prop file and its tabulated polars (``propbet polars``'s
    /// outputs): the rest as asked.
    fn with_tables(&self, py: Python<'_>, prop: PathBuf, polars: PathBuf) -> PyResult<Model> {
        let mut m = match &self.request {
            Some(r) => Model::of(
                py,
                ModelRequest {
                    prop,
                    polars: Some(polars),
                    airfoil: None,
                    sections_from: None,
                    ..r.clone()
                },
            )?,
            // A case's model: its settings are the case file's, kept as they are.
            None => Model {
                request: None,
                spec: ModelSpec {
                    prop,
                    polars: Some(polars),
                    design: None,
                    ..self.spec.clone()
                },
                case: None,
            },
        };
        m.case = self.case.clone();
        Ok(m)
    }

    fn __repr__(&self) -> String {
        format!("Model({:?})", self.spec.prop.display().to_string())
    }
}

/// Performance over every RPM with every J (or V; static without either), as columns: the
/// sweep's and (with ``stations``) the per-station table's, and the count of station
/// solutions that did not converge and of the points they are at. Without ``rpm`` a case's
/// model sweeps the case's points.
#[pyfunction]
#[pyo3(signature = (model, rpm=None, j=None, v=None, air=None, effects=Vec::new(), band=false, stations=false))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub fn predict<'py>(
    py: Python<'py>,
    model: &Model,
    rpm: Option<Bound<'py, PyAny>>,
    j: Option<Bound<'py, PyAny>>,
    v: Option<Bound<'py, PyAny>>,
    air: Option<Bound<'py, PyDict>>,
    effects: Vec<String>,
    band: bool,
    stations: bool,
) -> PyResult<(Vec<Bound<'py, PyTuple>>, Option<Vec<Bound<'py, PyTuple>>>, usize, usize)> {
    let sweep = SweepRequest {
        rpm: values("rpm", rpm.as_ref())?,
        j: values("j", j.as_ref())?,
        v: values("v", v.as_ref())?,
    };
    let asked_air = air.as_ref().map(|a| crate::values::air(Some(a))).transpose()?;
    let case = if sweep.rpm.is_none() { model.case.clone() } else { None };
    if case.is_some() && (sweep.j.is_some() || sweep.v.is_some()) {
        return Err(crate::boundary::InputError::new_err("j and v: give rpm with them"));
    }
    let mut spec = model.spec.clone();
    spec.effects.extend(effects);
    let (table, per_station, (failed, at)) = guarded(py, move || {
        let (omegas, axis, case_air) = match case {
            Some(c) => c,
            None => {
                let (omegas, axis) = sweep.spec()?;
                (omegas, axis, AirSpec::default())
            }
        };
        let air = match asked_air {
            Some(a) => a.spec()?,
            None => case_air,
        };
        let spec = PredictSpec {
            model: spec,
            omegas,
            axis,
            air,
            format: TableFormat::Csv,
            out: None,
            stations: None,
            band,
        };
        propbet_api::commands::predict::columns(&spec, stations, &propbet_cli::Terminal::default())
    })?;
    Ok((
        columns(py, table)?,
        per_station.map(|t| columns(py, t)).transpose()?,
        failed,
        at,
    ))
}

/// The model's blade file's rows in SI, as CSV bytes (``propbet prop``'s reading).
#[pyfunction]
pub fn stations<'py>(py: Python<'py>, model: &Model) -> PyResult<Bound<'py, PyBytes>> {
    let spec = model.spec.clone();
    let t = guarded(py, move || {
        propbet_api::commands::prop::stations(&spec, &propbet_cli::Terminal::default())
    })?;
    Ok(PyBytes::new(py, &t))
}

/// The model of a case directory: its scan and polars stages run into ``out`` as ``propbet
/// run`` runs them, its prediction's model, sweep and air; and the polars stage's blade and
/// sections (geometry, airfoil, station airfoils), if it has one.
#[pyfunction]
#[allow(clippy::type_complexity)]
pub fn case_model(
    py: Python<'_>,
    case: PathBuf,
    out: PathBuf,
) -> PyResult<(Model, Option<(PathBuf, Option<String>, Option<PathBuf>)>)> {
    let (predict, polars) = guarded(py, move || {
        propbet_api::commands::run::case_prediction(
            &case,
            &out,
            &ProcessRequest::default(),
            &propbet_cli::Terminal::default(),
        )
    })?;
    let spec = predict.model;
    Ok((
        Model {
            request: None,
            spec,
            case: Some((predict.omegas, predict.axis, predict.air)),
        },
        polars,
    ))
}

/// Measured files as ``compare`` reads them: the points and the dropped rows (CSV bytes).
#[pyfunction]
#[pyo3(signature = (files, poles=None, rpm_source=None, atmosphere=None, rho=None, columns=None))]
pub fn read_measurements<'py>(
    py: Python<'py>,
    files: Vec<PathBuf>,
    poles: Option<u32>,
    rpm_source: Option<String>,
    atmosphere: Option<String>,
    rho: Option<f64>,
    columns: Option<PathBuf>,
) -> PyResult<(Bound<'py, PyBytes>, Bound<'py, PyBytes>)> {
    let request = measured_request(files, poles, rpm_source, atmosphere, rho, columns);
    let (points, dropped) = guarded(py, move || {
        let spec = request.spec()?;
        propbet_api::outputs::measured::tables(&spec)
    })?;
    Ok((PyBytes::new(py, &points), PyBytes::new(py, &dropped)))
}

/// The measured files and how to read them, as the keyword arguments give them.
pub(crate) fn measured_request(
    files: Vec<PathBuf>,
    poles: Option<u32>,
    rpm_source: Option<String>,
    atmosphere: Option<String>,
    rho: Option<f64>,
    columns: Option<PathBuf>,
) -> MeasuredRequest {
    MeasuredRequest {
        files,
        poles,
        rpm_source,
        atmosphere,
        rho,
        columns,
    }
}

/// ``propbet compare``: the model against the measured files, its files written into
/// ``out``: whether it ran clean (False when it reported problems), and metrics.json,
/// summary.json and points.csv as it wrote them (bytes, not read back).
#[pyfunction]
#[pyo3(signature = (
    model, files, out, *, per3=None, qprop_output=None, motor=None, poles=None, rpm_source=None,
    atmosphere=None, rho=None, columns=None
))]
#[allow(clippy::too_many_arguments)]
pub fn compare<'py>(
    py: Python<'py>,
    model: &Model,
    files: Vec<PathBuf>,
    out: PathBuf,
    per3: Option<PathBuf>,
    qprop_output: Option<PathBuf>,
    motor: Option<PathBuf>,
    poles: Option<u32>,
    rpm_source: Option<String>,
    atmosphere: Option<String>,
    rho: Option<f64>,
    columns: Option<PathBuf>,
) -> PyResult<(bool, Bytes<'py>, Bytes<'py>, Bytes<'py>)> {
    let model = model.spec.clone();
    let measured = measured_request(files, poles, rpm_source, atmosphere, rho, columns);
    let (ok, w) = guarded(py, move || {
        let spec = propbet_api::CompareSpec {
            model,
            measured: measured.spec()?,
            per3,
            qprop_output,
            motor,
            out,
        };
        propbet_api::commands::compare::compare(&spec, &propbet_cli::Terminal::default())
    })?;
    Ok((
        ok,
        PyBytes::new(py, &w.metrics),
        PyBytes::new(py, &w.summary),
        PyBytes::new(py, &w.points),
    ))
}

/// ``propbet diagnose``: which effect is missing, its files written into ``out``: whether it
/// ran clean (False when it reported problems), and diagnosis.json and summary.json as it
/// wrote them (bytes, not read back).
#[pyfunction]
#[pyo3(signature = (
    model, files, out, *, effects=None, folds=None, max_steps=None, window=None, poles=None,
    rpm_source=None, atmosphere=None, rho=None, columns=None
))]
#[allow(clippy::too_many_arguments)]
pub fn diagnose<'py>(
    py: Python<'py>,
    model: &Model,
    files: Vec<PathBuf>,
    out: PathBuf,
    effects: Option<Vec<String>>,
    folds: Option<usize>,
    max_steps: Option<usize>,
    window: Option<f64>,
    poles: Option<u32>,
    rpm_source: Option<String>,
    atmosphere: Option<String>,
    rho: Option<f64>,
    columns: Option<PathBuf>,
) -> PyResult<(bool, Bytes<'py>, Bytes<'py>)> {
    let model = model.spec.clone();
    let measured = measured_request(files, poles, rpm_source, atmosphere, rho, columns);
    let request = DiagnoseRequest {
        effects,
        folds,
        max_steps,
        window,
    };
    let (ok, w) = guarded(py, move || {
        let spec = request.spec(model, measured.spec()?, out)?;
        propbet_api::commands::diagnose::diagnose(&spec, &propbet_cli::Terminal::default())
    })?;
    Ok((ok, PyBytes::new(py, &w.diagnosis), PyBytes::new(py, &w.summary)))
}

/// ``propbet run`` of a case directory (None: the shipped default case) into ``out``: its
/// files written; False when a stage reported problems.
#[pyfunction]
#[pyo3(signature = (
    case, out, *, verbose=false, inputs_anywhere=false, engine=None, neuralfoil_size=None,
    xfoil=None, cache=None, no_cache=false, quiet=false, xfoil_budget=None
))]
#[allow(clippy::too_many_arguments)]
pub fn run<'py>(
    py: Python<'py>,
    case: Option<PathBuf>,
    out: PathBuf,
    verbose: bool,
    inputs_anywhere: bool,
    engine: Option<String>,
    neuralfoil_size: Option<String>,
    xfoil: Option<PathBuf>,
    cache: Option<PathBuf>,
    no_cache: bool,
    quiet: bool,
    xfoil_budget: Option<f64>,
) -> PyResult<RunOutput<'py>> {
    let process = process(engine, neuralfoil_size, xfoil, cache, no_cache, quiet, xfoil_budget);
    let (ok, f) = guarded(py, move || {
        let request = propbet_api::commands::run::RunRequest {
            case,
            out: Some(out),
            xfoil: process.spec()?,
            verbose,
            inputs_anywhere,
        };
        propbet_api::commands::run::run(&request, &propbet_cli::Terminal::default())
    })?;
    let bytes = |b: Option<Vec<u8>>| b.map(|b| PyBytes::new(py, &b));
    Ok((
        ok,
        PyBytes::new(py, &f.summary),
        bytes(f.sweep),
        bytes(f.points),
        bytes(f.diagnosis),
    ))
}

/// A run's answer to Python: clean, then summary.json, sweep.csv, points.csv and
/// diagnosis.json as written (None where the case has no such stage).
type RunOutput<'py> = (
    bool,
    Bytes<'py>,
    Option<Bytes<'py>>,
    Option<Bytes<'py>>,
    Option<Bytes<'py>>,
);

/// A file's contents as a command wrote them, for Python.
type Bytes<'py> = Bound<'py, PyBytes>;

/// ``propbet scan`` of a scan file into ``out``: ``settings`` the scan's settings as JSON
/// (a case's ``[geometry]`` keys: ``units``, ``stations``, ``blade_colour``, ...); an unknown
/// key is a TypeError naming it. False when a station could not be measured or fitted.
#[pyfunction]
#[pyo3(signature = (path, out, settings, *, reference=None, name=None))]
pub fn scan(
    py: Python<'_>,
    path: PathBuf,
    out: PathBuf,
    settings: &str,
    reference: Option<PathBuf>,
    name: Option<String>,
) -> PyResult<bool> {
    let settings: propbet_api::ScanSettings = serde_json::from_str(settings)
        .map_err(|e| pyo3::exceptions::PyTypeError::new_err(format!("from_scan(): {e}")))?;
    guarded(py, move || {
        let spec = propbet_api::ScanSpec {
            input: path,
            options: settings.options()?,
            reference,
            name,
            out,
        };
        propbet_api::commands::scan::run(&spec, &propbet_cli::Terminal::default())
    })
}
