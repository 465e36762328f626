//! The boundary between Python and Rust: propbet's errors as Python's exceptions, a panic
//! caught, the GIL released while propbet computes, tables handed over as columns.

use std::panic::{catch_unwind, AssertUnwindSafe};

use propbet_report::table::columns::{Column, Table};
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
pub(crate) fn guarded<T, E>(py: Python<'_>, f: impl FnOnce() -> Result<T, E> + Send) -> PyResult<T>
where
    T: Send,
    E: Into<Box<dyn std::error::Error + Send + Sync>> + Send,
{
    match py.detach(|| catch_unwind(AssertUnwindSafe(f))) {
        Ok(Ok(v)) => Ok(v),
        Ok(Err(e)) => Err(InputError::new_err(propbet_api::with_causes(&*e.into()))),
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

/// A table's columns for Python: each `(name, kind, values)` in the CSV's order (kind "f8"
/// and "i8": the numbers as native-endian bytes, "b1": one byte each, "str": a list of texts).
pub(crate) fn columns(py: Python<'_>, t: Table) -> PyResult<Vec<Bound<'_, PyTuple>>> {
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
