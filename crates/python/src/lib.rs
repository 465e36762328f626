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

/// What to expect of a prediction of the prop whose file is `name` before any measurement, from
/// the validation shipped with propbet: the sentence `predict` prints, and the numbers of its
/// APC family or maker line (None where the validation holds none of its kind).
#[pyfunction]
#[pyo3(signature = (name=None))]
fn expected_accuracy(py: Python<'_>, name: Option<String>) -> PyResult<Bound<'_, pyo3::types::PyDict>> {
    use propbet_api::compare::expected;
    use pyo3::types::PyDictMethods;
    let table = expected::shipped();
    let d = pyo3::types::PyDict::new(py);
    d.set_item("sentence", expected::sentence(name.as_deref(), &table))?;
    let group = expected::group_of(name.as_deref(), &table);
    d.set_item("group", group.map(|e| expected::family_words(&e.family)))?;
    d.set_item("props", group.map(|e| e.props))?;
    d.set_item("ct_median", group.map(|e| e.ct_median))?;
    d.set_item("cp_median", group.map(|e| e.cp_median))?;
    d.set_item("band_ct_inside", group.map(|e| e.band_ct_inside))?;
    d.set_item("band_cp_inside", group.map(|e| e.band_cp_inside))?;
    Ok(d)
}

/// The module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("InputError", m.py().get_type::<InputError>())?;
    m.add("InternalError", m.py().get_type::<InternalError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(execute, m)?)?;
    m.add_function(wrap_pyfunction!(format_number, m)?)?;
    m.add_function(wrap_pyfunction!(expected_accuracy, m)?)?;
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
