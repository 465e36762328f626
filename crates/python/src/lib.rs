//! `propbet._native`, the Python package's native module: the `propbet` commands run in the
//! interpreter's process (`propbet_cli::execute`, `propbet_cli::api`), with the GIL released
//! while they compute, their errors raised as `propbet.InputError` and a panic, should one
//! happen, as `propbet.InternalError` instead of an abort. The Python side
//! (`python/propbet/__init__.py`) turns keyword arguments into the commands' flags and the
//! tables into pandas DataFrames: nothing is computed twice.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;

use propbet_cli::columns::{Column, Table};
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyTuple};

pyo3::create_exception!(
    propbet,
    InputError,
    PyException,
    "Bad input: a file, value or option propbet cannot use (the command line's exit status 2), with the \
     message naming the file, line or value."
);
pyo3::create_exception!(
    propbet,
    InternalError,
    PyException,
    "A fault of propbet's own (a Rust panic caught at the boundary): please report it with the input."
);

/// Runs `f` without the GIL; its error becomes an `InputError` (the message as the command
/// line prints it), a panic an `InternalError`.
fn guarded<T, E>(py: Python<'_>, f: impl FnOnce() -> Result<T, E> + Send) -> PyResult<T>
where
    T: Send,
    E: std::fmt::Display + Send,
{
    match py.detach(|| catch_unwind(AssertUnwindSafe(f))) {
        Ok(Ok(v)) => Ok(v),
        Ok(Err(e)) => Err(InputError::new_err(format!("{e:#}"))),
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a panic without a message".into());
            Err(InternalError::new_err(format!("propbet: internal error: {what}")))
        }
    }
}

/// Runs `propbet ARGV...` as the command line does (files written where its flags say);
/// returns True when done, False when done with problems it reported (exit status 1).
#[pyfunction]
fn execute(py: Python<'_>, argv: Vec<String>) -> PyResult<bool> {
    guarded(py, || {
        propbet_cli::execute(std::iter::once("propbet".to_string()).chain(argv))
    })
}

/// `propbet predict ARGV...` in memory: the sweep table and (when `stations`) the per-station
/// table, each a list of columns `(name, kind, values)` in the CSV's order (kind "f8" and
/// "i8": the numbers as native-endian bytes, "b1": one byte each, "str": a list of texts), and
/// the count of station solutions that did not converge and of the points they are at.
#[pyfunction]
#[allow(clippy::type_complexity)]
fn predict<'py>(
    py: Python<'py>,
    argv: Vec<String>,
    stations: bool,
) -> PyResult<(Vec<Bound<'py, PyTuple>>, Option<Vec<Bound<'py, PyTuple>>>, usize, usize)> {
    let (sweep, per_station, (failed, at)) = guarded(py, || propbet_cli::api::predict(&argv, stations))?;
    Ok((
        columns(py, sweep)?,
        per_station.map(|t| columns(py, t)).transpose()?,
        failed,
        at,
    ))
}

/// A table's columns for Python.
fn columns(py: Python<'_>, t: Table) -> PyResult<Vec<Bound<'_, PyTuple>>> {
    t.names
        .into_iter()
        .zip(t.columns)
        .map(|(name, c)| {
            let (kind, values): (&str, Bound<'_, PyAny>) = match c {
                Column::Num(v) => ("f8", PyBytes::new(py, &bytes(&v, |x| x.to_ne_bytes())).into_any()),
                Column::Int(v) => ("i8", PyBytes::new(py, &bytes(&v, |x| x.to_ne_bytes())).into_any()),
                Column::Bool(v) => ("b1", PyBytes::new(py, &bytes(&v, |x| [u8::from(*x)])).into_any()),
                Column::Text(v) => ("str", v.into_pyobject(py)?.into_any()),
            };
            PyTuple::new(
                py,
                [
                    name.into_pyobject(py)?.into_any(),
                    kind.into_pyobject(py)?.into_any(),
                    values,
                ],
            )
        })
        .collect()
}

/// Values as bytes, one after another.
fn bytes<T, const N: usize>(values: &[T], each: impl Fn(&T) -> [u8; N]) -> Vec<u8> {
    values.iter().flat_map(each).collect()
}

/// A number as propbet's tables write it (7 significant digits).
#[pyfunction]
fn format_number(v: f64) -> String {
    propbet_cli::api::format_number(v)
}

/// A prop file's rows (`propbet prop ARGV...`) in SI, as CSV bytes.
#[pyfunction]
fn stations<'py>(py: Python<'py>, argv: Vec<String>) -> PyResult<Bound<'py, PyBytes>> {
    let t = guarded(py, || propbet_cli::api::stations(&argv))?;
    Ok(PyBytes::new(py, &t))
}

/// The command lines of the stages `propbet run CASE -o OUT` runs, in order.
#[pyfunction]
fn case_stages(py: Python<'_>, case: PathBuf, out: PathBuf) -> PyResult<Vec<Vec<String>>> {
    guarded(py, || propbet_cli::api::case_stages(&case, &out))
}

/// Measured files read with `compare`'s measurement flags: the points and the dropped rows
/// (CSV bytes each).
#[pyfunction]
fn read_measurements<'py>(py: Python<'py>, argv: Vec<String>) -> PyResult<(Bound<'py, PyBytes>, Bound<'py, PyBytes>)> {
    let (points, dropped) = guarded(py, || propbet_cli::api::measurements(&argv))?;
    Ok((PyBytes::new(py, &points), PyBytes::new(py, &dropped)))
}

/// The flags of a `propbet` command as (keyword, kind): `switch`, `number`, `many`, `text`
/// (`propbet_cli::api::flags_of`), for checking keyword arguments at the call.
#[pyfunction]
fn flags(py: Python<'_>, command: String) -> PyResult<Vec<(String, &'static str)>> {
    guarded(py, || propbet_cli::api::flags_of(&command))
}

/// The module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("InputError", m.py().get_type::<InputError>())?;
    m.add("InternalError", m.py().get_type::<InternalError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(execute, m)?)?;
    m.add_function(wrap_pyfunction!(predict, m)?)?;
    m.add_function(wrap_pyfunction!(format_number, m)?)?;
    m.add_function(wrap_pyfunction!(stations, m)?)?;
    m.add_function(wrap_pyfunction!(case_stages, m)?)?;
    m.add_function(wrap_pyfunction!(read_measurements, m)?)?;
    m.add_function(wrap_pyfunction!(flags, m)?)?;
    Ok(())
}
