//! Polars of every station of a blade: the typed door to `propbet polars`.

use std::path::PathBuf;

use propbet_api::{PolarsRequest, SectionRequest, SweepRequest};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::boundary::guarded;
use crate::model::process;
use crate::values::values;

/// ``propbet polars``: every station's polars of ``geometry`` at its Reynolds and Mach numbers
/// over the operating points, written as a prop file ``out_prop`` and tables ``out_polars``;
/// False when a station has no fit.
#[pyfunction]
#[pyo3(signature = (
    geometry, out_prop, out_polars, *, rpm=None, j=None, v=None, air=None, airfoil=None,
    station_airfoils=None, units=None, thickness=None, sections_from=None, airfoils=None,
    engine=None, ncrit=None, trip=None, alpha=None, panels=None, iter=None, ncrit_effect=Vec::new(),
    neuralfoil_size=None, xfoil=None, cache=None, no_cache=false, quiet=false, xfoil_budget=None
))]
#[allow(clippy::too_many_arguments)]
pub fn polars<'py>(
    py: Python<'py>,
    geometry: PathBuf,
    out_prop: PathBuf,
    out_polars: PathBuf,
    rpm: Option<Bound<'py, PyAny>>,
    j: Option<Bound<'py, PyAny>>,
    v: Option<Bound<'py, PyAny>>,
    air: Option<Bound<'py, PyDict>>,
    airfoil: Option<String>,
    station_airfoils: Option<PathBuf>,
    units: Option<String>,
    thickness: Option<String>,
    sections_from: Option<PathBuf>,
    airfoils: Option<PathBuf>,
    engine: Option<String>,
    ncrit: Option<f64>,
    trip: Option<String>,
    alpha: Option<Bound<'py, PyAny>>,
    panels: Option<u32>,
    iter: Option<u32>,
    ncrit_effect: Vec<f64>,
    neuralfoil_size: Option<String>,
    xfoil: Option<PathBuf>,
    cache: Option<PathBuf>,
    no_cache: bool,
    quiet: bool,
    xfoil_budget: Option<f64>,
) -> PyResult<bool> {
    let request = PolarsRequest {
        geometry,
        units,
        airfoil,
        thickness,
        station_airfoils,
        sections_from,
        airfoils,
        sweep: SweepRequest {
            rpm: values("rpm", rpm.as_ref())?,
            j: values("j", j.as_ref())?,
            v: values("v", v.as_ref())?,
        },
        air: crate::values::air(air.as_ref())?,
        section: SectionRequest {
            process: process(engine, neuralfoil_size, xfoil, cache, no_cache, quiet, xfoil_budget),
            ncrit,
            trip,
            alpha: values("alpha", alpha.as_ref())?,
            panels,
            iter,
        },
        ncrit_effect,
        out_prop,
        out_polars: Some(out_polars),
    };
    guarded(py, move || {
        propbet_api::commands::polar::polars(&request.spec()?, &propbet_cli::Terminal::default())
    })
}

/// ``propbet validate`` on UIUC's measurements, APC's design files and airfoils, into ``out``:
/// its files written; (False when a prop reported problems, validation.md's text,
/// validation.csv's bytes).
#[pyfunction]
#[pyo3(signature = (
    uiuc, pe0, airfoils, out, *, only=None, per3=None, section_model=None, ncrit=None,
    ncrit_effect=Vec::new(), rotation=None, drag_factor=None, trip=None, geometry=None,
    generic_section=None, user_effects=None, engine=None, neuralfoil_size=None, xfoil=None,
    cache=None, no_cache=false, quiet=false, xfoil_budget=None
))]
#[allow(clippy::too_many_arguments)]
pub fn validate(
    py: Python<'_>,
    uiuc: PathBuf,
    pe0: PathBuf,
    airfoils: PathBuf,
    out: PathBuf,
    only: Option<String>,
    per3: Option<PathBuf>,
    section_model: Option<String>,
    ncrit: Option<f64>,
    ncrit_effect: Vec<f64>,
    rotation: Option<String>,
    drag_factor: Option<f64>,
    trip: Option<String>,
    geometry: Option<String>,
    generic_section: Option<String>,
    user_effects: Option<PathBuf>,
    engine: Option<String>,
    neuralfoil_size: Option<String>,
    xfoil: Option<PathBuf>,
    cache: Option<PathBuf>,
    no_cache: bool,
    quiet: bool,
    xfoil_budget: Option<f64>,
) -> PyResult<(bool, String, Bound<'_, pyo3::types::PyBytes>)> {
    let request = propbet_api::commands::validate::ValidateRequest {
        uiuc,
        pe0,
        airfoils,
        only,
        out,
        section: propbet_api::SectionRequest {
            process: process(engine, neuralfoil_size, xfoil, cache, no_cache, quiet, xfoil_budget),
            ncrit,
            trip,
            ..Default::default()
        },
        section_model,
        per3,
        ncrit_effect,
        rotation,
        drag_factor,
        geometry,
        generic_section,
        user_effects,
    };
    let (ok, written) = guarded(py, move || {
        let (spec, props, generic) = request.spec()?;
        propbet_api::commands::validate::validate(&spec, &props, generic.as_ref(), &propbet_cli::Terminal::default())
    })?;
    Ok((ok, written.markdown, pyo3::types::PyBytes::new(py, &written.csv)))
}
