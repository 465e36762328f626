//! `propbet prop`: a blade file as propbet reads it, its stations as QPROP discretises them,
//! and the file written back as QPROP 1.22 reads it.

use std::path::Path;

use propbet_settings::spec::ModelSpec;

use crate::console::Console;
use crate::CommandResult as Result;

/// The blade file's model as `propbet prop` shows it, of a model's spec (its file, units and
/// reading): a QPROP file as it is; APC's PE0, a UIUC table or a blade table as its stations
/// with QPROP's generic coefficients (the polars of `predict` replace them).
pub fn prop_model(spec: &ModelSpec, console: &dyn Console) -> Result<propbet_model::Model> {
    let spec = ModelSpec {
        units: spec.units,
        qprop_compat: spec.qprop_compat,
        ..ModelSpec::prop(spec.prop.clone())
    };
    let opts = propbet_model::design::DesignOptions {
        units: spec.units,
        ..Default::default()
    };
    match propbet_model::design::read_design(&spec.prop, &opts)? {
        Some(d) => Ok(propbet_model::Model::from_loaded(
            &ModelSpec { units: None, ..spec },
            d.geometry,
            false,
        )?),
        None => super::predict::load_model(&spec, false, console),
    }
}

/// Runs `propbet prop`: the file's stations as QPROP discretises them; written back
/// normalised to `write`.
pub fn prop(spec: &ModelSpec, write: Option<&Path>, console: &dyn Console) -> Result<bool> {
    let model = prop_model(spec, console)?;
    let (loaded, rotor) = (&model.loaded, &model.rotor);
    console.out(&format!("name: {}", loaded.file.name));
    console.out(&format!("blades: {}", rotor.blades));
    console.out(&format!("tip radius: {:.6} m", rotor.tip_radius));
    console.out(&format!("input rows: {}", loaded.file.rows.len()));
    console.out("# computational stations (QPROP discretisation)");
    console.out("r_m,dr_m,chord_m,beta_deg");
    for s in &rotor.stations {
        console.out(&format!(
            "{:.6},{:.6},{:.6},{:.4}",
            s.r,
            s.dr,
            s.chord,
            s.beta.to_degrees()
        ));
    }
    if let Some(out) = write {
        crate::console::emit(
            console,
            Some(out),
            &[crate::qprop::write_prop(&loaded.file.as_qprop_reads())],
            &[spec.prop.as_path()],
        )?;
    }
    Ok(true)
}

/// A blade file's rows as `propbet prop` reads them (the spec's file, units and reading), in
/// SI: radius, chord, blade angle and the ten QPROP section coefficients of each row (a row's
/// own, or the file's global ones), as a table (CSV).
pub fn stations(spec: &ModelSpec, console: &dyn Console) -> Result<Vec<u8>> {
    let model = prop_model(spec, console)?;
    Ok(propbet_report::table::stations::csv(&model.loaded.file)?)
}
