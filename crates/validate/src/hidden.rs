//! Hidden effects in real measurements: a prop's measured files diagnosed as validate reads
//! them, then again with a known effect added to the measured points
//! ([`propbet_diagnose::inject`]), and whether the ladder finds it with its size.
//!
//! The thrust and torque tares are injected into the files as they are (UIUC's optical RPM and
//! lab air bound the RPM scale and the density ratio, as in any diagnosis of them). The RPM
//! scale and the density are injected into the same points as a stand log whose provenance
//! allows them (an electrical RPM, air nobody wrote down): both ladders of those injections,
//! the clean and the injected one, run with those effects' wide bounds.

use std::sync::Arc;

use propbet_diagnose::discover::{diagnose, Diagnosis};
use propbet_diagnose::inject::{score, Finding, Injected, Injection};
use propbet_diagnose::provenance::Provenance;
use propbet_diagnose::Data;
use propbet_effects::Effect;

use super::{ladder_spec, prepare, Prepared, Sections, ValidateSpec};
use propbet_model::{Model, Result};
use propbet_pipeline::stages;
use propbet_settings::spec::DiagnoseSpec;

/// Whether an injection's ladders run with the files' provenance bounds (the tares) or as a
/// stand log that allows the effect (the RPM scale, the density).
fn with_provenance(effect: Injected) -> bool {
    !matches!(effect, Injected::RpmScale | Injected::Density)
}

/// Each injection on `prop`'s measured files (validate's blade, polars and model), scored
/// against the clean ladder.
pub fn hidden_prop(
    spec: &ValidateSpec,
    prop: &str,
    sections: &Sections,
    injections: &[Injection],
    progress: &propbet_polar::Progress<'_>,
) -> Result<Vec<Finding>> {
    let Prepared {
        dir,
        measured,
        model_spec,
        model,
        ..
    } = prepare(spec, prop, sections, progress)?;
    let dspec = ladder_spec(&model_spec, &measured, &dir);
    hidden_measured(&model, &dspec, injections)
}

/// Each injection on the measured files of `dspec` (a stand log, wind-tunnel files) with
/// `model`, scored against the clean ladder.
pub fn hidden_measured(model: &Model, dspec: &DiagnoseSpec, injections: &[Injection]) -> Result<Vec<Finding>> {
    let batch = stages::load_batch(&dspec.measured)?;
    let wide = stages::candidates(model, dspec)?;
    let mut narrow = wide.clone();
    Provenance::of(&batch.sets).narrow(&mut narrow);
    let (data, dmodel, opts) = stages::diagnosis_inputs(model, dspec, batch.air, &batch.sets, false)?;
    let run = |data: &Data, candidates: &[Arc<dyn Effect>]| -> Result<Diagnosis> {
        Ok(diagnose(&dmodel, data, candidates, &opts)?)
    };
    let mut clean: [Option<Diagnosis>; 2] = [None, None];
    let mut out = Vec::new();
    for inj in injections {
        let provenance = with_provenance(inj.effect);
        let Some((value, injected)) = inj.apply(&data, model.diameter) else {
            continue;
        };
        let candidates = if provenance { &narrow } else { &wide };
        let slot = &mut clean[usize::from(provenance)];
        if slot.is_none() {
            *slot = Some(run(&data, candidates)?);
        }
        let found = run(&injected, candidates)?;
        out.push(score(
            &dmodel,
            &data,
            inj,
            value,
            slot.as_ref().expect("set above"),
            &found,
        )?);
    }
    Ok(out)
}
