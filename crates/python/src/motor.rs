//! The motor, the battery, and the propeller on them: the operating points, a motor fitted to
//! stand logs, propellers side by side.

use std::path::PathBuf;

use propbet_api::{DriveRequest, SweepRequest};
use propbet_api::{MotorFile, Supply};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use crate::boundary::{columns, guarded};
use crate::model::Model;
use crate::values::values;

/// A motor as QPROP models it: type 1 (R, Io, Kv) or type 2 (R0, Io0, Kv, Kq, tau, Io1, Io2,
/// R2). ``Motor(r, io, kv)`` makes a type 1 [ohm, A, rpm/V]; :meth:`from_file` reads a QPROP
/// motor file.
#[pyclass(module = "propbet._native", frozen)]
pub struct Motor {
    pub(crate) file: MotorFile,
}

#[pymethods]
impl Motor {
    #[new]
    #[pyo3(signature = (r, io, kv, *, name="motor".to_string()))]
    fn new(py: Python<'_>, r: f64, io: f64, kv: f64, name: String) -> PyResult<Motor> {
        let file = guarded(py, move || propbet_api::motor(&name, 1, &[r, io, kv]))?;
        Ok(Motor { file })
    }

    /// A QPROP motor file, read as QPROP 1.22 reads it.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<Motor> {
        let file = guarded(py, move || propbet_api::read_motor(&path))?;
        Ok(Motor { file })
    }

    /// The motor's name (the file's first line).
    #[getter]
    fn name(&self) -> String {
        self.file.name.clone()
    }

    /// QPROP's motor type: 1 or 2.
    #[getter]
    fn kind(&self) -> i64 {
        self.file.motor.kind.index()
    }

    /// The parameters in the file's order (type 1: R [ohm], Io [A], Kv [rpm/V]).
    #[getter]
    fn params(&self) -> Vec<f64> {
        self.file.params.clone()
    }

    /// Winding resistance [ohm] (type 2: R0).
    #[getter]
    fn r(&self) -> f64 {
        self.file.motor.r0
    }

    /// No-load current [A] (type 2: Io0).
    #[getter]
    fn io(&self) -> f64 {
        self.file.motor.io0
    }

    /// Speed constant [rpm/V].
    #[getter]
    fn kv(&self) -> f64 {
        self.file.motor.kv_rpm
    }

    /// The motor as a QPROP motor file (text QPROP 1.22 reads).
    fn text(&self) -> String {
        propbet_api::motor_text(&self.file)
    }

    fn __repr__(&self) -> String {
        format!(
            "Motor({:?}, type {}, {:?})",
            self.file.name,
            self.kind(),
            self.file.params
        )
    }
}

/// A battery of cells through an ESC: ``Battery("3S,2200mAh,R=5mOhm")`` (cells in series, then
/// any of capacity, per-cell resistance ``R``, open-circuit volts per cell ``V``, ``cutoff``,
/// ``usable``; LiPo defaults), ``esc_ohms`` the ESC's resistance [ohm].
#[pyclass(module = "propbet._native", frozen)]
pub struct Battery {
    pub(crate) text: String,
    pub(crate) supply: Supply,
}

#[pymethods]
impl Battery {
    #[new]
    #[pyo3(signature = (spec, *, esc_ohms=0.005))]
    fn new(py: Python<'_>, spec: String, esc_ohms: f64) -> PyResult<Battery> {
        let text = spec.clone();
        let supply = guarded(py, move || propbet_api::supply(&spec, esc_ohms))?;
        Ok(Battery { text, supply })
    }

    /// Cells in series.
    #[getter]
    fn cells(&self) -> u32 {
        self.supply.battery.cells
    }

    /// Open-circuit voltage of the pack [V].
    #[getter]
    fn volts(&self) -> f64 {
        self.supply.battery.cell_volts * f64::from(self.supply.battery.cells)
    }

    /// Capacity [mAh] (0: not given).
    #[getter]
    fn capacity_mah(&self) -> f64 {
        1000.0 * self.supply.battery.capacity_ah
    }

    /// Internal resistance of a cell [ohm].
    #[getter]
    fn cell_ohms(&self) -> f64 {
        self.supply.battery.cell_ohms
    }

    /// The lowest loaded cell voltage allowed [V].
    #[getter]
    fn cutoff_volts(&self) -> f64 {
        self.supply.battery.cutoff_volts
    }

    /// The fraction of the capacity used before landing.
    #[getter]
    fn usable(&self) -> f64 {
        self.supply.battery.usable
    }

    /// The ESC's resistance [ohm].
    #[getter]
    fn esc_ohms(&self) -> f64 {
        self.supply.esc_ohms
    }

    fn __repr__(&self) -> String {
        format!("Battery({:?}, esc_ohms={})", self.text, self.supply.esc_ohms)
    }
}

/// The model on a motor at each voltage, current, thrust, RPM or throttle (one of them) and
/// airspeed: the powered table's columns, each point without an operating point, and with
/// `stations` the per-station table's columns of every operating point found.
#[pyfunction]
#[pyo3(signature = (
    model, motor, *, volts=None, amps=None, thrust=None, rpm=None, throttle=None, battery=None,
    v=None, air=None, band=false, stations=false
))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub fn powered<'py>(
    py: Python<'py>,
    model: &Model,
    motor: &Motor,
    volts: Option<Bound<'py, PyAny>>,
    amps: Option<Bound<'py, PyAny>>,
    thrust: Option<Bound<'py, PyAny>>,
    rpm: Option<Bound<'py, PyAny>>,
    throttle: Option<Bound<'py, PyAny>>,
    battery: Option<PyRef<'py, Battery>>,
    v: Option<Bound<'py, PyAny>>,
    air: Option<Bound<'py, PyDict>>,
    band: bool,
    stations: bool,
) -> PyResult<(Vec<Bound<'py, PyTuple>>, Vec<String>, Option<Vec<Bound<'py, PyTuple>>>)> {
    let drive = DriveRequest {
        volts: values("volts", volts.as_ref())?,
        amps: values("amps", amps.as_ref())?,
        thrust: values("thrust", thrust.as_ref())?,
        rpm: values("rpm", rpm.as_ref())?,
        throttle: values("throttle", throttle.as_ref())?,
    };
    let speeds = SweepRequest {
        v: values("v", v.as_ref())?,
        ..SweepRequest::default()
    };
    let air = crate::values::air(air.as_ref())?;
    let supply = battery.map(|b| b.supply);
    let spec = model.spec.clone();
    let m = motor.file.clone();
    let (table, problems, per_station) = guarded(py, move || {
        let drives = drive.drives(supply.as_ref())?;
        let speeds = speeds.airspeeds()?;
        let spec = propbet_api::PoweredSpec {
            model: spec,
            motor: m.name.clone().into(),
            drives,
            supply,
            speeds,
            air: air.spec()?,
            format: propbet_api::TableFormat::Csv,
            out: None,
            stations: None,
            band,
        };
        propbet_api::commands::predict::powered_columns(&spec, &m, stations, &propbet_cli::Terminal::default())
    })?;
    let per_station = per_station.map(|t| columns(py, t)).transpose()?;
    Ok((columns(py, table)?, problems, per_station))
}

/// A type 1 motor (type 2 with ``kq``: Kq fitted on its own) fitted to stand logs that carry
/// speed, torque, voltage and current (``kv`` the maker's, or from the ESC command's duty):
/// the motor, its file's text, a summary (constants with their 95 % half-widths, errors,
/// notes) and the fitted steps' columns.
#[pyfunction]
#[pyo3(signature = (files, *, kv=None, kq=false, name=None, poles=None, rpm_source=None, atmosphere=None, rho=None, columns=None))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub fn fit_motor<'py>(
    py: Python<'py>,
    files: Vec<PathBuf>,
    kv: Option<f64>,
    kq: bool,
    name: Option<String>,
    poles: Option<u32>,
    rpm_source: Option<String>,
    atmosphere: Option<String>,
    rho: Option<f64>,
    columns: Option<PathBuf>,
) -> PyResult<(Motor, String, Bound<'py, PyDict>, Vec<Bound<'py, PyTuple>>)> {
    let request = crate::model::measured_request(files, poles, rpm_source, atmosphere, rho, columns);
    let (f, steps) = guarded(py, move || {
        propbet_api::outputs::motor::fit(&request.spec()?, kv, kq, name)
    })?;
    let m = &f.fit.fit;
    let summary = PyDict::new(py);
    summary.set_item("r", (m.r.value, m.r.plus_minus))?;
    summary.set_item("io", (m.io.value, m.io.plus_minus))?;
    summary.set_item("kv", (m.kv_rpm.value, m.kv_rpm.plus_minus))?;
    summary.set_item("kq", m.kq_rpm.map(|k| (k.value, k.plus_minus)))?;
    summary.set_item(
        "kv_from",
        match m.kv_source {
            propbet_api::KvSource::Given => "given",
            propbet_api::KvSource::EscDuty(_) => "esc_duty",
        },
    )?;
    summary.set_item(
        "torque_kv",
        m.sides
            .as_ref()
            .map(|s| (s.torque_kv_rpm.value, s.torque_kv_rpm.plus_minus)),
    )?;
    summary.set_item("steps", m.points)?;
    summary.set_item("rms_current", m.rms_current)?;
    summary.set_item("held_out_median", f.fit.held_out_median)?;
    summary.set_item("notes", f.fit.notes.clone())?;
    summary.set_item("misses", f.fit.misses.clone())?;
    summary.set_item("lines", f.lines.to_vec())?;
    Ok((
        Motor { file: f.file },
        f.text,
        summary,
        crate::boundary::columns(py, steps)?,
    ))
}

/// Propellers side by side on one motor and battery, ranked by g/W at ``hover`` thrust [N]:
/// props.csv's columns and the answer's sentences.
#[pyfunction]
#[pyo3(signature = (models, motor, battery, hover, *, v=None, air=None))]
pub fn compare_props<'py>(
    py: Python<'py>,
    models: Vec<(String, PyRef<'py, Model>)>,
    motor: &Motor,
    battery: &Battery,
    hover: f64,
    v: Option<Bound<'py, PyAny>>,
    air: Option<Bound<'py, PyDict>>,
) -> PyResult<(Vec<Bound<'py, PyTuple>>, Vec<String>)> {
    let models: Vec<(String, propbet_api::ModelSpec)> = models.into_iter().map(|(n, m)| (n, m.spec.clone())).collect();
    let speeds = values("v", v.as_ref())?;
    let air = crate::values::air(air.as_ref())?;
    let (file, text, supply) = (motor.file.clone(), battery.text.clone(), battery.supply);
    let (table, answer) = guarded(py, move || {
        let speeds = speeds.map(|v| v.numbers("v")).transpose()?;
        propbet_api::commands::motor::compare_props_columns(
            &models,
            &file,
            &supply,
            &text,
            hover,
            speeds,
            &air.spec()?,
            &propbet_cli::Terminal::default(),
        )
    })?;
    Ok((columns(py, table)?, answer))
}
