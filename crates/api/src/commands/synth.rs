//! `propbet synth`: measurements made by the model with hidden effects and noise, written
//! with their answer key.

use std::path::PathBuf;

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
