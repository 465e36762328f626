//! A propeller's model as the commands read it: a prop file as it is, or a blade file without
//! section coefficients (APC's PE0, a UIUC table, a blade table) with its polars computed over
//! the operating points a command needs; what a person is told of it is returned, not printed.

use propbet_model::Model;
use propbet_settings::spec::{MeasuredSpec, ModelSpec, SweepAxis};

use crate::command_error::refuse;
use crate::CommandResult as Result;

/// A model, and what a person is told of how it was read.
pub struct Loaded {
    /// The model.
    pub model: Model,
    /// For a blade file without coefficients, what its polars are, in a sentence ("polars of
    /// NAME: ...").
    pub polars: Option<String>,
    /// The prop file's warnings, or the polar cache's.
    pub warnings: Vec<String>,
}

/// The model `spec` names; a blade file without coefficients has its polars computed over the
/// operating points `points` gives (the command's), `progress` told of each polar done.
pub fn load(
    spec: &ModelSpec,
    points: impl FnOnce() -> Result<(Vec<f64>, SweepAxis)>,
    keep_stations: bool,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Loaded> {
    if spec.design.is_none() {
        let model = prop_file(spec, keep_stations)?;
        let warnings = model.loaded.warnings.clone();
        return Ok(Loaded {
            model,
            polars: None,
            warnings,
        });
    }
    let (omegas, axis) = points()?;
    let Some((model, polars)) = propbet_pipeline::stages::design_model(spec, omegas, axis, keep_stations, progress)?
    else {
        refuse!("{}: not a blade file without coefficients", spec.prop.display());
    };
    // What the polars are, in a line (the exported file's fidelity is no question here).
    let name = spec
        .prop
        .file_name()
        .map_or_else(|| spec.prop.display().to_string(), |n| n.to_string_lossy().into());
    let brief: Vec<String> = propbet_report::polar::brief(&polars)
        .into_iter()
        .filter(|l| !l.starts_with("the exported QPROP file"))
        .collect();
    Ok(Loaded {
        model,
        polars: Some(format!("polars of {name}: {}", brief.join("; "))),
        warnings: polars.cache_warning.into_iter().collect(),
    })
}

/// The model of a QPROP prop file (its warnings in `loaded.warnings`); a blade file without
/// section coefficients is refused.
pub fn prop_file(spec: &ModelSpec, keep_stations: bool) -> Result<Model> {
    if spec.design.is_some() {
        refuse!(
            "{}: a blade file without section coefficients; this command reads QPROP prop files only",
            spec.prop.display()
        );
    }
    Ok(Model::load(spec, keep_stations)?)
}

/// The operating points a blade file's polars cover for a comparison: the measured range.
pub fn cover(measured: &MeasuredSpec) -> Result<(Vec<f64>, SweepAxis)> {
    let (omegas, js) = propbet_pipeline::stages::cover(measured)?;
    Ok((omegas, SweepAxis::J(js)))
}
