//! `propbet synth`: measurements made by the model with hidden effects and noise, written
//! with their answer key.

use std::path::{Path, PathBuf};

use propbet_pipeline::stages;
pub use propbet_pipeline::stages::SynthFormat;
use propbet_settings::spec::ModelSpec;
use propbet_settings::values::parse_list;

use crate::console::Console;
use crate::files::write_atomic;
use crate::{CommandError, CommandResult as Result};

/// What `propbet synth` is asked, as its flags give it.
pub struct SynthCommand {
    /// The model, its hidden effects among its effects.
    pub model: ModelSpec,
    /// Relative noise on thrust and torque (`1%` or `0.01`).
    pub noise: String,
    /// The files' format.
    pub format: SynthFormat,
    /// RPMs (a list or a range; None: four up to a 150 m/s tip speed).
    pub rpm: Option<String>,
    /// Advance ratios (None: the format's).
    pub j: Option<String>,
    /// Random seed.
    pub seed: u64,
    /// The file (a folder for UIUC's format).
    pub out: PathBuf,
}

/// Runs `propbet synth`.
pub fn synth(c: &SynthCommand, console: &dyn Console) -> Result<bool> {
    let mut answer_path = c.out.as_os_str().to_owned();
    answer_path.push(".answer.json");
    let answer_path = PathBuf::from(answer_path);
    let inputs = c.model.inputs();
    match c.format {
        SynthFormat::Uiuc => crate::files::refuse_inputs_inside(&c.out, &inputs)?,
        _ => crate::files::refuse_outputs_over_inputs(&[&c.out, &answer_path], &inputs)?,
    }
    let m = super::predict::load_model(&c.model, false, console)?;
    let spec = stages::SynthSpec {
        noise: stages::parse_noise(&c.noise)?,
        format: c.format,
        rpms: c.rpm.as_deref().map(|r| parse_list("--rpm", r)).transpose()?,
        js: c.j.as_deref().map(|j| parse_list("--j", j)).transpose()?,
        seed: c.seed,
        prop: c.model.prop.display().to_string(),
        stem: c
            .model
            .prop
            .file_stem()
            .map_or("synth".into(), |s| s.to_string_lossy().replace('_', "-")),
    };
    let made = stages::synth(&spec, &m)?;
    let mut answer_bytes = serde_json::to_vec_pretty(&made.answer)?;
    answer_bytes.push(b'\n');
    match &made.files {
        stages::SynthFiles::Named(files) => {
            std::fs::create_dir_all(&c.out)
                .map_err(|e| CommandError::Message(format!("{}: cannot create the directory: {e}", c.out.display())))?;
            for (name, text) in files {
                write_atomic(&c.out.join(name), &[text.as_bytes()], &inputs)?;
            }
            write_atomic(&c.out.join("answer.json"), &[&answer_bytes], &inputs)?;
        }
        stages::SynthFiles::One(text) => {
            write_atomic(&c.out, &[text.as_bytes()], &inputs)?;
            write_atomic(&answer_path, &[&answer_bytes], &inputs)?;
        }
    }
    console.err(&format!(
        "propbet: {} points ({} RPMs x {} J) with {} and {:.2} % noise -> {}",
        made.points,
        made.plan.rpms.len(),
        made.plan.js.len(),
        made.effects,
        100.0 * spec.noise,
        c.out.display()
    ));
    Ok(true)
}

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
