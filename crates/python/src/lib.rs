//! `propbet._native`, the Python package's native module: the `propbet` commands run in the
//! interpreter's process (`propbet_cli::execute`, `propbet_cli::api`), with the GIL released
//! while they compute, their errors raised as `propbet.InputError` and a panic, should one
//! happen, as `propbet.InternalError` instead of an abort. The Python side
//! (`python/propbet/__init__.py`) turns keyword arguments into the commands' flags and the
//! tables into pandas DataFrames: nothing is computed twice.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;

use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

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

/// `propbet predict ARGV...` in memory: the sweep table (bytes, CSV or JSON as `--format`
/// says), the per-station table (CSV bytes, when `stations`), and the count of station
/// solutions that did not converge and of the points they are at.
#[pyfunction]
#[allow(clippy::type_complexity)]
fn predict<'py>(
    py: Python<'py>,
    argv: Vec<String>,
    stations: bool,
) -> PyResult<(Bound<'py, PyBytes>, Option<Bound<'py, PyBytes>>, usize, usize)> {
    let t = guarded(py, || propbet_cli::api::predict(&argv, stations))?;
    let body: Vec<u8> = t.body.concat();
    Ok((
        PyBytes::new(py, &body),
        t.stations.as_deref().map(|s| PyBytes::new(py, s)),
        t.failed.0,
        t.failed.1,
    ))
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

/// The module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("InputError", m.py().get_type::<InputError>())?;
    m.add("InternalError", m.py().get_type::<InternalError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(execute, m)?)?;
    m.add_function(wrap_pyfunction!(predict, m)?)?;
    m.add_function(wrap_pyfunction!(stations, m)?)?;
    m.add_function(wrap_pyfunction!(case_stages, m)?)?;
    m.add_function(wrap_pyfunction!(read_measurements, m)?)?;
    Ok(())
}
