//! validate's held-out calibration: the ladder fitted to each half of a prop's measurements
//! predicts the other half, with the rung that scores best on the half it was fitted to by
//! validate's own metric.

use rayon::prelude::*;

use propbet_compare::metrics::{halves, window_errors, VALIDATION_J_WINDOW};
use propbet_compare::{AirChoice, ComparedPoint};
use propbet_effects::{parse_spec, Active, Stack};
use propbet_measure::MeasuredSet;

use super::row::{ladder_text, median_p90};
use propbet_model::Model;
use propbet_model::{Error, Result};
use propbet_pipeline::stages;
use propbet_settings::spec::DiagnoseSpec;

/// One half's held-out CT and CP errors and its rung in words.
type HeldOutHalf = (Vec<f64>, Vec<f64>, String);

/// Held out: a ladder fitted to each half of the measurements ([`halves`]) predicts the other
/// half ("after" is scored on those predictions only), with the rung of the half's ladder that
/// scores lowest on the half itself ([`best_rung`]). The CT and CP errors, and each half's
/// rung in words.
pub(super) fn held_out(
    model: &Model,
    dspec: &DiagnoseSpec,
    files: &[std::path::PathBuf],
    air: AirChoice,
    sets: &[MeasuredSet],
    dir: &std::path::Path,
) -> Result<(Vec<f64>, Vec<f64>, [String; 2])> {
    let folds = halves(files, sets);
    // Each half's ladder on its own thread (each spreads its points over the pool too).
    let results: Vec<Option<HeldOutHalf>> = (0..2)
        .into_par_iter()
        .map(|k| {
            let (train, test) = (&folds[k], &folds[1 - k]);
            if train.is_empty() || test.is_empty() {
                return Ok(None);
            }
            let fold_spec = DiagnoseSpec {
                out: dir.join(format!("held_out_{k}")),
                ..dspec.clone()
            };
            let fitted = stages::diagnose_sets(model, &fold_spec, air, train.clone(), false)?;
            let stack = best_rung(model, air, train, &fitted.diagnosis)?;
            let predicted = compare_with(model, air, &stack, test)?;
            let (a, b) = window_errors(&predicted, VALIDATION_J_WINDOW);
            Ok(Some((a, b, ladder_text(&added_effects(model, &stack)))))
        })
        .collect::<Result<_>>()?;
    let (mut ct, mut cp) = (Vec::new(), Vec::new());
    let mut ladders = [String::new(), String::new()];
    for (k, half) in results.into_iter().enumerate() {
        match half {
            None => ladders[k] = "none (a single file: nothing to hold out)".into(),
            Some((a, b, ladder)) => {
                ct.extend(a);
                cp.extend(b);
                ladders[k] = ladder;
            }
        }
    }
    Ok((ct, cp, ladders))
}

/// The rung of a ladder diagnosed on `sets` (the baseline included) that scores lowest on
/// those same points by validate's metric ([`validation_score`]) without raising the ladder's
/// leave-one-RPM-out error ([`carried`]): the calibration validate
/// carries, to the other half of the measurements or to `calibrated/`. The diagnosis ranks by
/// an RMS that the points near zero thrust dominate, which a rung can lower while it raises the
/// median error validate scores (the 9x7.5 SF's whole ladder on its own points: CT 6.5 →
/// 15.5 %).
pub(super) fn best_rung(
    model: &Model,
    air: AirChoice,
    sets: &[MeasuredSet],
    diagnosis: &propbet_diagnose::discover::Diagnosis,
) -> Result<Stack> {
    let mut rungs = rung_stacks(model, diagnosis)?
        .into_iter()
        .map(|s| Ok((validation_score(&compare_with(model, air, &s, sets)?), s)))
        .collect::<Result<Vec<_>>>()?;
    let scores: Vec<f64> = rungs.iter().map(|r| r.0).collect();
    let loro: Vec<Option<f64>> = diagnosis.ladder.iter().map(|r| r.loro_rms).collect();
    Ok(rungs.swap_remove(carried(&scores, &loro)).1)
}

/// The rung carried: the lowest of `scores` (the baseline's first) among the baseline and the
/// rungs that do not raise the ladder's leave-one-RPM-out error (`loro`, the diagnosis's, one
/// per rung) above the baseline's where both have one: a rung that only calibrates to the RPMs
/// it saw is not carried to others.
pub(super) fn carried(scores: &[f64], loro: &[Option<f64>]) -> usize {
    let base = loro.first().copied().flatten();
    let gated: Vec<f64> = scores
        .iter()
        .enumerate()
        .map(|(k, &s)| match (base, loro.get(k).copied().flatten()) {
            (Some(b), Some(l)) if k > 0 && l > b => f64::NAN,
            _ => s,
        })
        .collect();
    lowest(&gated)
}

/// The effects a stack adds to the model's own, as the command line gives them.
pub(super) fn added_effects(model: &Model, stack: &Stack) -> Vec<String> {
    stack.active[model.effects.active.len()..]
        .iter()
        .map(Active::describe)
        .collect()
}

/// The model's own effects and each rung's on top, the baseline's (none) first: the rungs'
/// stacks as the ladder wrote them, the last as the diagnosis's final stack.
fn rung_stacks(model: &Model, d: &propbet_diagnose::discover::Diagnosis) -> Result<Vec<Stack>> {
    let n = d.ladder.len();
    (0..n.max(1))
        .map(|k| {
            let specs: Vec<String> = match k {
                0 => Vec::new(),
                k if k + 1 < n => d.ladder[k].stack.split(" + ").map(str::to_string).collect(),
                _ => d.final_effects(),
            };
            let mut active = model.effects.active.clone();
            for s in &specs {
                let a = parse_spec(s)
                    .and_then(|p| model.registry.resolve(&p))
                    .map_err(|e| Error::about("--effect", e))?;
                active.push(a);
            }
            Ok(Stack { active })
        })
        .collect()
}

/// The comparison of `sets` with the model under `stack`.
fn compare_with(model: &Model, air: AirChoice, stack: &Stack, sets: &[MeasuredSet]) -> Result<Vec<ComparedPoint>> {
    Ok(propbet_compare::compare(
        &propbet_model::solve::setup(model, air, stack.clone()),
        sets,
    )?)
}

/// Validate's metric on a set of compared points: the mean of the CT and CP medians of
/// |predicted/measured − 1| over the points inside the window.
fn validation_score(points: &[ComparedPoint]) -> f64 {
    let (ct, cp) = window_errors(points, VALIDATION_J_WINDOW);
    0.5 * (median_p90(&ct).median + median_p90(&cp).median)
}

/// The index of the lowest score, the first of equals (NaN never lowest); 0 when none is
/// finite.
pub(super) fn lowest(scores: &[f64]) -> usize {
    (0..scores.len()).fold(0, |b, i| {
        if scores[i] < scores[b] || (!scores[b].is_finite() && scores[i].is_finite()) {
            i
        } else {
            b
        }
    })
}
