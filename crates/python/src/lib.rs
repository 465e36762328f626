//! `propbet._native`, the Python package's native module: propbet's typed API in the
//! interpreter's process. Keyword arguments become the API's requests ([`propbet_api`]), never
//! a command line; the API's commands run them (`propbet_api::commands`, telling the terminal
//! what the binary tells it) and the results come back as columns, with the GIL released
//! while they compute, errors raised as `propbet.InputError` naming the value and a panic,
//! should one happen, as `propbet.InternalError` instead of an abort. The Python side
//! (`python/propbet/__init__.py`) makes the columns pandas DataFrames: nothing is computed
//! twice.

mod boundary;
mod model;
mod motor;
mod polars;
mod values;

use boundary::{guarded, InputError, InternalError};
use pyo3::prelude::*;

/// Runs `propbet ARGV...` as the command line does (files written where its flags say);
/// returns True when done, False when done with problems it reported (exit status 1).
#[pyfunction]
fn execute(py: Python<'_>, argv: Vec<String>) -> PyResult<bool> {
    guarded(py, || {
        propbet_cli::execute(std::iter::once("propbet".to_string()).chain(argv))
    })
}

/// A number as propbet's tables write it (7 significant digits).
#[pyfunction]
fn format_number(v: f64) -> String {
    propbet_report::table::text(v)
}

/// The module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("InputError", m.py().get_type::<InputError>())?;
    m.add("InternalError", m.py().get_type::<InternalError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(execute, m)?)?;
    m.add_function(wrap_pyfunction!(format_number, m)?)?;
    m.add_class::<model::Model>()?;
    m.add_function(wrap_pyfunction!(model::predict, m)?)?;
    m.add_function(wrap_pyfunction!(model::stations, m)?)?;
    m.add_function(wrap_pyfunction!(model::case_model, m)?)?;
    m.add_function(wrap_pyfunction!(model::read_measurements, m)?)?;
    m.add_function(wrap_pyfunction!(model::compare, m)?)?;
    m.add_function(wrap_pyfunction!(model::diagnose, m)?)?;
    m.add_function(wrap_pyfunction!(model::run, m)?)?;
    m.add_function(wrap_pyfunction!(model::scan, m)?)?;
    m.add_function(wrap_pyfunction!(polars::polars, m)?)?;
    m.add_function(wrap_pyfunction!(polars::validate, m)?)?;
    m.add_class::<motor::Motor>()?;
    m.add_class::<motor::Battery>()?;
    m.add_function(wrap_pyfunction!(motor::powered, m)?)?;
    m.add_function(wrap_pyfunction!(motor::fit_motor, m)?)?;
    m.add_function(wrap_pyfunction!(motor::compare_props, m)?)?;
    Ok(())
}
