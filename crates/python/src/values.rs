//! Python's values as the API's requests take them: numbers and lists, the air as a dict.

use propbet_api::{AirRequest, Values};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyString};

/// A number, a list or array of numbers, or the text a flag takes (`4000:8000:1000`), as
/// [`Values`]; None stays None. A bool or a list of texts is a TypeError naming `name`.
pub fn values(name: &str, ob: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Values>> {
    let Some(ob) = ob.filter(|o| !o.is_none()) else {
        return Ok(None);
    };
    if ob.is_instance_of::<PyString>() {
        return Ok(Some(Values::Text(ob.extract()?)));
    }
    if ob.is_instance_of::<PyBool>() {
        return Err(PyTypeError::new_err(format!(
            "{name} = {ob}: a number, a list of numbers or a range's text"
        )));
    }
    if let Ok(x) = ob.extract::<f64>() {
        return Ok(Some(Values::Numbers(vec![x])));
    }
    let Ok(items) = ob.try_iter() else {
        return Err(PyTypeError::new_err(format!(
            "{name} = {}: a number, a list of numbers or a range's text",
            ob.repr()?
        )));
    };
    let mut numbers = Vec::new();
    for (i, item) in items.enumerate() {
        let item = item?;
        if item.is_instance_of::<PyBool>() {
            return Err(PyTypeError::new_err(format!("{name}[{i}] = {item}: not a number")));
        }
        numbers.push(item.extract::<f64>().map_err(|_| {
            PyTypeError::new_err(format!(
                "{name}[{i}] = {}: not a number",
                item.repr().map(|r| r.to_string()).unwrap_or_default()
            ))
        })?);
    }
    Ok(Some(Values::Numbers(numbers)))
}

/// The air of a dict: `{"rho": 1.2}`, or `{"temp": "20C", "pressure": "1013hPa", "humidity":
/// 40}`, and `mu`, `a`. An unknown key is a TypeError naming it.
pub fn air(ob: Option<&Bound<'_, PyDict>>) -> PyResult<AirRequest> {
    let mut air = AirRequest::default();
    let Some(d) = ob else { return Ok(air) };
    for (key, value) in d.iter() {
        let key: String = key.extract()?;
        let number = || -> PyResult<f64> {
            value
                .extract::<f64>()
                .map_err(|_| PyTypeError::new_err(format!("air[{key:?}] = {value}: a number")))
        };
        let text = || -> PyResult<String> {
            if value.is_instance_of::<PyString>() {
                return value.extract();
            }
            number().map(|x| format!("{x}"))
        };
        match key.as_str() {
            "rho" => air.rho = Some(number()?),
            "mu" => air.mu = Some(number()?),
            "a" => air.a = Some(number()?),
            "temp" => air.temp = Some(text()?),
            "pressure" => air.pressure = Some(text()?),
            "humidity" => air.humidity = Some(text()?),
            _ => {
                return Err(crate::boundary::InputError::new_err(format!(
                    "air: unknown key '{key}'; the keys are a, humidity, mu, pressure, rho, temp"
                )))
            }
        }
    }
    Ok(air)
}
