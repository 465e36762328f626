//! Which effect is missing: every candidate fitted, scored by held-out error, tested against
//! the noise, ranked; then the greedy ladder.
//!
//! **Held-out error.** k-fold (points shuffled with a fixed seed) and leave-one-RPM-out (when
//! there are at least three RPM groups). Each fold's parameters are refitted by one
//! Gauss-Newton step from the all-data fit on the training rows (exact for parameters that act
//! linearly, such as the tares; first order otherwise), and the held-out points are then
//! solved at those parameters: the held-out residuals are real predictions.
//!
//! **Parsimony and significance.** Candidates are ranked by the BIC form of the held-out error,
//! `n ln(MSE_heldout) + k ln(n)` (n residual rows, k parameters). A candidate is
//! *significant* when the nested F test of its residual sum of squares against the current
//! model's, with the noise variance estimated from its own residuals, gives
//! p < alpha / (number of candidates) (Bonferroni), and its held-out RMS error falls by at
//! least [`MIN_GAIN`] of the current one.
//!
//! **Repeatability.** Where the data repeat themselves (overlapping sweeps at one RPM,
//! repeated steps: [`Data::repeatability`]), a candidate must also change the loads by at
//! least [`REPEATABILITY_FACTOR`] times that scatter (the root of the fall of the squared
//! in-sample RMS error): an effect weaker than the measurements repeat is not found, however
//! small its p value.
//!
//! **Bounds.** Every parameter has physical bounds; a candidate whose fit ends on one, or whose
//! 95 % interval reaches one (other than its neutral value; `fit::on_bound`), is never
//! significant: it "hit its bound", the data want more than it can physically give.
//!
//! **Ladder.** Starting from the baseline, the best significant candidate is added, all
//! parameters of the stack are refitted together, and the remaining candidates are tried on
//! top, until none is significant.

use std::collections::BTreeMap;
use std::sync::Arc;

use nalgebra::{DMatrix, DVector};
use propbet_effects::{Effect, Stack};
use rand::seq::SliceRandom;
use rand::SeedableRng;
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, FisherSnedecor};

use crate::fit::{bounds, fit, stack_at, FitOutcome, FittedParam};
use crate::limits::{self, Judge, ModelError, Separability, Verdict};
use crate::signature::{signatures, Response, Signature};
use crate::{rms, Data, DiagnoseError, Model, Repeatability};

/// Smallest relative fall of the held-out RMS error that counts.
pub const MIN_GAIN: f64 = 0.10;
pub use crate::limits::REPEATABILITY_FACTOR;

/// How a diagnosis is run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Number of folds of the k-fold cross-validation.
    pub folds: usize,
    /// Family-wise significance level.
    pub alpha: f64,
    /// Most effects the ladder adds.
    pub max_steps: usize,
    /// Seed of the fold assignment.
    pub seed: u64,
    /// Whether the residuals' signatures before and after the ladder are found (every
    /// candidate probed on both models): a diagnosis whose ladder alone is wanted (validate's
    /// held-out halves) skips them.
    pub signatures: bool,
    /// The default model's usual error on props of this kind, a term of the detection limits
    /// ([`crate::limits`]; None: no validated props of this kind).
    pub model_error: Option<ModelError>,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            folds: 5,
            alpha: 0.01,
            max_steps: 3,
            seed: 7,
            signatures: true,
            model_error: None,
        }
    }
}

/// One candidate on top of the current stack, fitted and scored.
#[derive(Debug, Clone, Serialize)]
pub struct Scored {
    /// The candidate's id.
    pub id: String,
    /// The physics.
    pub explanation: String,
    /// Every fitted parameter of the stack with it (the candidate's last).
    pub params: Vec<FittedParam>,
    /// In-sample RMS of the residual rows.
    pub rms: f64,
    /// k-fold held-out RMS.
    pub kfold_rms: f64,
    /// The k-fold errors of all rows, of the thrust rows and of the torque rows.
    #[serde(skip)]
    pub(super) kfold_by_load: Option<HeldRms>,
    /// Leave-one-RPM-out held-out RMS (None with fewer than three RPM groups).
    pub loro_rms: Option<f64>,
    /// Relative fall of the k-fold error from the current stack's (of its load's rows alone
    /// for an effect on thrust alone or on torque alone).
    pub gain: f64,
    /// F statistic against the current stack.
    pub f: f64,
    /// Its p value.
    pub p_value: f64,
    /// Significant (see the module documentation).
    pub significant: bool,
    /// Ranking score (lower is better).
    pub score: f64,
    /// Why it could not be fitted, if it could not.
    pub note: Option<String>,
    /// The fit.
    #[serde(skip)]
    pub fit: Option<FitOutcome>,
}

impl Scored {
    /// True when its fit ended on a physical bound: not an answer ([`bound_note`]).
    pub fn hit_bound(&self) -> bool {
        self.fit.as_ref().is_some_and(|f| !f.beyond_bounds().is_empty())
    }
}

/// An effect the ladder did not take, and why.
#[derive(Debug, Clone, Serialize)]
pub struct NotTaken {
    /// The effect's id.
    pub id: String,
    /// Why.
    pub why: String,
}

/// The model at one rung of the ladder.
#[derive(Debug, Clone, Serialize)]
pub struct Rung {
    /// "baseline", then the effect added at this step.
    pub added: String,
    /// The whole stack ("pitch-offset:deg=1.2 + ...").
    pub stack: String,
    /// Its parameters with intervals.
    pub params: Vec<FittedParam>,
    /// In-sample RMS.
    pub rms: f64,
    /// k-fold held-out RMS.
    pub kfold_rms: f64,
    /// Leave-one-RPM-out RMS.
    pub loro_rms: Option<f64>,
    /// p value of the step (None for the baseline).
    pub p_value: Option<f64>,
    /// The thrust error's change with J at fixed RPM with this rung's effects
    /// ([`crate::signature::thrust_trends`]): what an angle or the inflow makes.
    pub thrust_j_trend: Option<f64>,
    /// The thrust error's change with RPM at fixed J: what the sections' Reynolds number makes.
    pub thrust_rpm_trend: Option<f64>,
}

/// Everything a diagnosis finds.
#[derive(Debug, Clone, Serialize)]
pub struct Diagnosis {
    /// Residual rows scored (thrust, and torque where measured).
    pub rows: usize,
    /// Points scored.
    pub points: usize,
    /// The candidates on top of the baseline, best first.
    pub ranking: Vec<Scored>,
    /// The ladder, baseline first.
    pub ladder: Vec<Rung>,
    /// Where the baseline fails, in words (none without [`Options::signatures`]).
    pub before: Vec<Signature>,
    /// What is left after the ladder (none without [`Options::signatures`]).
    pub after: Vec<Signature>,
    /// True when at least one effect is significant.
    pub found: bool,
    /// Residual RMS of the final model: the noise level as far as the model can tell.
    pub noise_estimate: f64,
    /// How well the measurements repeat, where they show it.
    pub repeatability: Option<Repeatability>,
    /// Effects of the refined selection that the rebuilt ladder did not take, with the reason
    /// (on a bound, weaker than the repeatability, or indistinguishable from their absence).
    pub not_taken: Vec<NotTaken>,
    /// Where the answer is one effect: the other significant candidates that explain the data
    /// about as well ([`alike`]): the data cannot tell them apart.
    pub alike: Vec<String>,
    /// The measurement that would tell the alike candidates apart (None without any).
    pub tell_apart: Option<String>,
    /// What these data can separate: the noise, each candidate's detection limit and the
    /// pairs they cannot tell apart ([`crate::limits`]).
    pub separability: Separability,
    /// The answer, respecting it: each effect of the ladder found, one of a group, or below
    /// the detection limit.
    pub verdict: Verdict,
    /// The final stack.
    #[serde(skip)]
    pub final_stack: Stack,
    /// Baseline residual rows.
    #[serde(skip)]
    pub baseline_residuals: Vec<f64>,
    /// Final residual rows.
    #[serde(skip)]
    pub final_residuals: Vec<f64>,
}

impl Diagnosis {
    /// The ladder's final effects as `--effect` arguments ("pitch-offset:deg=1.2").
    pub fn final_effects(&self) -> Vec<String> {
        self.final_stack.active.iter().map(|a| a.describe()).collect()
    }

    /// The first step's candidates whose fits ended on a physical bound while lowering the
    /// held-out error by at least [`MIN_GAIN`]: effects the data want more of than is physical
    /// (a model far from its measurements), best first.
    pub fn bounded_helpful(&self) -> Vec<&Scored> {
        let base = self.ladder.first().map_or(f64::NAN, |r| r.kfold_rms);
        self.ranking
            .iter()
            .filter(|s| s.hit_bound() && s.kfold_rms <= (1.0 - MIN_GAIN) * base)
            .collect()
    }

    /// What the final model leaves unexplained, against how well the measurements repeat:
    /// "2.1 % unexplained, above the 0.6 % the measurements repeat to (14 pairs)".
    pub fn unexplained(&self) -> String {
        let left = 100.0 * self.noise_estimate;
        match &self.repeatability {
            Some(r) if self.noise_estimate > 1.5 * r.sd => format!(
                "{left:.1} % unexplained, above the {:.1} % the measurements repeat to ({} pairs of points at one \
                 operating point): {}",
                100.0 * r.sd,
                r.pairs,
                if self.found {
                    "something the ladder's effects do not describe is still missing"
                } else if !self.bounded_helpful().is_empty() {
                    "no effect within its physical bounds describes it"
                } else {
                    "an effect may be there, but none changes the loads by 3x the repeatability, the least \
                     propbet names"
                }
            ),
            Some(r) => format!(
                "{left:.1} % unexplained, within the {:.1} % the measurements repeat to ({} pairs of points at one \
                 operating point)",
                100.0 * r.sd,
                r.pairs
            ),
            None => format!(
                "{left:.1} % unexplained; the measurements hold no repeated operating point to tell it from their \
                 scatter"
            ),
        }
    }
}

/// Ranks `candidates` on top of the current stack.
fn rank(
    model: &Model,
    data: &Data,
    current: &Evaluated,
    candidates: &[Arc<dyn Effect>],
    f: &Folds,
    alpha: f64,
    rep: Option<&Repeatability>,
) -> Result<Vec<Scored>, DiagnoseError> {
    let m = candidates.len();
    let mut out = candidates
        .iter()
        .map(|c| try_candidate(model, data, current, c, f, alpha / m.max(1) as f64, rep))
        .collect::<Result<Vec<_>, _>>()?;
    out.sort_by(|a, b| a.score.total_cmp(&b.score));
    Ok(out)
}

/// Improves a greedy selection: swaps a chosen effect for an unchosen one while that lowers
/// the score (greedy forward selection can pick an effect that mimics two others), then drops
/// any effect whose removal the F test does not reject.
fn refine(
    model: &Model,
    data: &Data,
    mut chosen: Evaluated,
    candidates: &[Arc<dyn Effect>],
    f: &Folds,
    alpha: f64,
) -> Result<Evaluated, DiagnoseError> {
    for _pass in 0..3 {
        let mut improved = false;
        let current = chosen.effects();
        'swap: for i in 0..current.len() {
            for c in candidates {
                if current.iter().any(|e| e.id() == c.id()) {
                    continue;
                }
                let mut effects = current.clone();
                effects[i] = c.clone();
                let k: usize = effects.iter().map(|e| e.params().len()).sum();
                if chosen.fit.residuals.len() < k + 2 {
                    continue;
                }
                let ev = evaluate(model, data, effects, &chosen.fit.stack, f)?;
                if ev.score() < chosen.score() - 1e-9 * chosen.score().abs()
                    && ev.fit.sse < chosen.fit.sse
                    && ev.fit.beyond_bounds().is_empty()
                {
                    chosen = ev;
                    improved = true;
                    break 'swap;
                }
            }
        }
        if !improved {
            break;
        }
    }
    // Backward: drop effects the data does not need once the others are in; never into a fit
    // that leaves one of the others on a bound.
    loop {
        let current = chosen.effects();
        if current.len() < 2 {
            break;
        }
        let mut drop = None;
        for i in 0..current.len() {
            let mut effects = current.clone();
            let gone = effects.remove(i);
            let ev = evaluate(model, data, effects, &chosen.fit.stack, f)?;
            let (_, p) = f_test(ev.fit.sse, &chosen.fit, gone.params().len());
            if (p >= alpha / current.len() as f64 || ev.kfold <= chosen.kfold) && ev.fit.beyond_bounds().is_empty() {
                drop = Some(ev);
                break;
            }
        }
        match drop {
            Some(ev) => chosen = ev,
            None => break,
        }
    }
    Ok(chosen)
}

/// Which of a rung's options (score, lower is better; whether it can be a rung: inside its
/// bounds, stronger than the repeatability, distinguishable from its absence) the ladder
/// takes: the best that can, else the best of all (which the ladder then refuses, and stops);
/// None without options.
fn rung_choice(options: &[(f64, bool)]) -> Option<usize> {
    let best = |inside_only: bool| {
        (0..options.len())
            .filter(|&i| !inside_only || options[i].1)
            .min_by(|&a, &b| options[a].0.total_cmp(&options[b].0))
    };
    best(true).or_else(|| best(false))
}

/// Most candidates (best of the first step first) whose pairs are all tried: every built-in.
const PAIR_POOL: usize = 14;

/// When the selection holds two effects: every pair of the first step's best candidates
/// (those inside their bounds) is fitted, and a pair that scores better replaces the
/// selection. Greedy steps and single swaps miss a pair whose members each look like a third
/// effect (an RPM error and a torque tare can pass for a thrust tare and a drag change).
fn best_pair(
    model: &Model,
    data: &Data,
    chosen: Evaluated,
    ranking: &[Scored],
    candidates: &[Arc<dyn Effect>],
    f: &Folds,
) -> Result<Evaluated, DiagnoseError> {
    if chosen.fit.stack.active.len() != 2 {
        return Ok(chosen);
    }
    let pool: Vec<Arc<dyn Effect>> = ranking
        .iter()
        .filter(|s| s.fit.is_some() && s.note.is_none())
        .take(PAIR_POOL)
        .filter_map(|s| candidates.iter().find(|c| c.id() == s.id).cloned())
        .collect();
    let mut best = chosen;
    for i in 0..pool.len() {
        for j in i + 1..pool.len() {
            let effects = vec![pool[i].clone(), pool[j].clone()];
            let k: usize = effects.iter().map(|e| e.params().len()).sum();
            if best.fit.residuals.len() < k + 2 {
                continue;
            }
            let ev = evaluate(model, data, effects, &Stack::baseline(), f)?;
            if ev.score() < best.score() - 1e-9 * best.score().abs() && ev.fit.beyond_bounds().is_empty() {
                best = ev;
            }
        }
    }
    Ok(best)
}

/// The first step's significant candidates other than `first` (the ladder's first effect)
/// whose held-out error is within the spread of `first`'s: closer than the measurements'
/// repeatability (where they repeat themselves), or than twice the held-out error's own
/// standard error, rms / sqrt(2 n) over n residual rows (the standard error of an RMS): the two
/// errors are then the same within what the data can resolve.
fn alike(ranking: &[Scored], first: &str, rep: Option<&Repeatability>) -> Vec<String> {
    let Some(a) = ranking.iter().find(|s| s.id == first) else {
        return Vec::new();
    };
    let rows = a.fit.as_ref().map_or(1, |f| f.residuals.len().max(1)) as f64;
    let se = |x: f64| x / (2.0 * rows).sqrt();
    ranking
        .iter()
        .filter(|s| s.id != first && s.significant)
        .filter(|s| {
            let gap = (s.kfold_rms - a.kfold_rms).abs();
            gap < rep.map_or(0.0, |r| r.sd) || gap < 2.0 * se(a.kfold_rms).max(se(s.kfold_rms))
        })
        .map(|s| s.id.clone())
        .collect()
}

/// The measurement that would tell alike candidates apart, from what the data lack: forward
/// flight (static points only), a second RPM range (speeds within a factor 1.5), else logged
/// air and repeated points.
fn tell_apart(data: &Data) -> String {
    limits::what_the_data_lack(data)
        .unwrap_or_else(|| "a logged air temperature and pressure, and repeated points to measure the scatter".into())
}

/// Checks that the measurements are in the propeller's operating range and of its size (the
/// check `compare` warns with: [`propbet_compare::plausible`]).
fn check_overlap(data: &Data, baseline: &[propbet_effects::Loads]) -> Result<(), DiagnoseError> {
    use propbet_compare::plausible::{mismatch, Mismatch};
    let pairs: Vec<(f64, f64)> = data
        .obs
        .iter()
        .zip(baseline)
        .map(|(o, b)| (o.thrust, b.thrust))
        .collect();
    match mismatch(&pairs) {
        None => Ok(()),
        Some(Mismatch::NoThrust(k, n, first)) => {
            let jmax = data.obs.iter().map(|o| o.j).fold(0.0, f64::max);
            let o = &data.obs[first];
            Err(DiagnoseError::NoOverlap(format!(
                "the measurements do not overlap the propeller's operating range: at {k} of {n} points (J up to {jmax:.2}) \
                 the model gives no thrust where the stand measured some (first: {}, {:.0} rpm, V = {:.2} m/s). \
                 Wrong prop file, diameter or airspeed units?",
                o.label,
                o.rpm(),
                o.v
            )))
        }
        Some(m) => Err(DiagnoseError::NoOverlap(m.message())),
    }
}

/// Where between a parameter's reference (its neutral value, or its start) and each bound the
/// signatures probe an effect: spaced by factors of 2 to 4 down to 1/64, since the bounds of some
/// are wide for a small propeller (a friction torque of up to 0.2 N m).
const PROBES: [f64; 5] = [1.0 / 64.0, 1.0 / 16.0, 0.25, 0.5, 1.0];

/// How each of `candidates` not in `base` moves the residual rows on top of it (`r_base` its
/// residual rows): one parameter at a time at [`PROBES`] of the way from its reference to each
/// bound, the others at theirs. A probe the model cannot evaluate is left out.
fn responses(
    model: &Model,
    data: &Data,
    base: &Stack,
    r_base: &[f64],
    candidates: &[Arc<dyn Effect>],
) -> Vec<Response> {
    let all: Vec<usize> = (0..data.obs.len()).collect();
    let mut effects: Vec<Arc<dyn Effect>> = base.active.iter().map(|a| a.effect.clone()).collect();
    let p_base: Vec<f64> = base.active.iter().flat_map(|a| a.values.clone()).collect();
    let mut out = Vec::new();
    for cand in candidates {
        if base.active.iter().any(|a| a.effect.id() == cand.id()) {
            continue;
        }
        let params = cand.params();
        let reference: Vec<f64> = params.iter().map(|p| p.neutral.unwrap_or(p.start)).collect();
        let mut values: Vec<Vec<f64>> = Vec::new();
        for (i, p) in params.iter().enumerate() {
            if p.neutral.is_none() {
                values.push(reference.clone());
            }
            for bound in [p.lower, p.upper] {
                for f in PROBES {
                    let mut v = reference.clone();
                    v[i] += f * (bound - reference[i]);
                    if v[i] != reference[i] {
                        values.push(v);
                    }
                }
            }
        }
        effects.push(cand.clone());
        let probes = values
            .into_iter()
            .filter_map(|v| {
                let mut p = p_base.clone();
                p.extend(v);
                let r = model.residuals(data, &stack_at(&effects, &p), &all).ok()?;
                Some(r.iter().zip(r_base).map(|(a, b)| a - b).collect())
            })
            .collect();
        effects.pop();
        out.push(Response {
            id: cand.id().to_string(),
            probes,
        });
    }
    out
}

/// Runs the diagnosis: ranking on top of the baseline, then the ladder.
pub fn diagnose(
    model: &Model,
    data: &Data,
    candidates: &[Arc<dyn Effect>],
    opts: &Options,
) -> Result<Diagnosis, DiagnoseError> {
    let all: Vec<usize> = (0..data.obs.len()).collect();
    let baseline_loads = model.loads(data, &Stack::baseline(), &all)?;
    check_overlap(data, &baseline_loads)?;
    let f = folds(data, opts.folds, opts.seed);
    let repeatability = data.repeatability();
    let r0 = data.residuals(&all, &baseline_loads);
    let rows = r0.len();
    let base_fit = FitOutcome {
        stack: Stack::baseline(),
        p: Vec::new(),
        sse: r0.iter().map(|x| x * x).sum(),
        jacobian: DMatrix::zeros(rows, 0),
        residuals: r0.clone(),
        sd: Vec::new(),
        evaluations: 1,
        at_bound: Vec::new(),
        stop: crate::fit::Stop::Converged,
    };
    let baseline = Evaluated {
        kfold: rms(&r0),
        kfold_by_load: HeldRms::of(&kinds(data, &r0)),
        loro: f.loro.as_ref().map(|_| rms(&r0)),
        fit: base_fit,
    };
    let mut ladder = vec![baseline.rung(data, None)];
    let mut dropped: Vec<(String, String)> = Vec::new();
    let (ranking, mut current, last_p) = forward(model, data, candidates, &baseline, &f, opts, repeatability.as_ref())?;
    match current.fit.stack.active.len() {
        0 => {}
        1 => ladder.push(current.rung(data, last_p)),
        _ => {
            // Swaps and backward elimination, then the ladder rebuilt along the final set: at
            // each rung the effect of the set that helps most among those whose fit stays inside
            // its bounds (a rung is an answer too: an effect on its bound is none, and the set's
            // others can free it at a later rung); only where every one would end on a bound,
            // the best of them.
            current = rebuild_ladder(
                model,
                data,
                current,
                candidates,
                baseline,
                &ranking,
                &f,
                opts,
                repeatability.as_ref(),
                &mut ladder,
                &mut dropped,
            )?;
        }
    }
    // Alike candidates are looked for where the answer is one effect: a ladder of several is
    // chosen by the joint fit, where a first step's near tie is settled by the steps after it.
    let first_id = (ladder.len() == 2).then(|| ladder[1].added.clone());
    let alike = first_id
        .as_deref()
        .map_or_else(Vec::new, |id| alike(&ranking, id, repeatability.as_ref()));
    let tell_apart = (!alike.is_empty()).then(|| tell_apart(data));
    let final_residuals = current.fit.residuals.clone();
    // What the data can tell, on the baseline's signatures; then the answer that respects it.
    let judge = Judge::new(data, &final_residuals, repeatability.as_ref(), opts.model_error);
    let sigs = limits::signatures(model, data, &Stack::baseline(), &r0, candidates);
    let separability = limits::separability(&judge, &sigs);
    let mut verdict = limits::verdict(model, data, &current.fit.stack, &final_residuals, &r0, &judge, &sigs)?;
    // A one-effect answer with alike candidates (as good held out) is a group too (a
    // calibration factor stays one, whatever imitates it).
    if let ([a], false) = (verdict.answers.as_mut_slice(), alike.is_empty()) {
        if matches!(a.kind, limits::AnswerKind::Found | limits::AnswerKind::Group) {
            // The answer first, then what the ladder found as good held out (the closest
            // rivals), then the rest of the group.
            let rest: Vec<String> = a.group.drain(..).filter(|g| *g != a.id && !alike.contains(g)).collect();
            a.group = std::iter::once(a.id.clone())
                .chain(alike.iter().filter(|g| **g != a.id).cloned())
                .chain(rest)
                .collect();
            a.kind = limits::AnswerKind::Group;
            a.tell_apart = Some(limits::tell_apart(data, &a.group));
        }
    }
    // The candidates' responses on the baseline, and on the final model where the ladder
    // added something (the same ones otherwise).
    let (before, after) = if opts.signatures {
        let first = responses(model, data, &Stack::baseline(), &r0, candidates);
        let last = if current.fit.stack.active.is_empty() {
            first.clone()
        } else {
            responses(model, data, &current.fit.stack, &final_residuals, candidates)
        };
        (signatures(data, &r0, &first), signatures(data, &final_residuals, &last))
    } else {
        (Vec::new(), Vec::new())
    };
    Ok(Diagnosis {
        rows,
        points: data.obs.len(),
        before,
        after,
        found: ladder.len() > 1,
        noise_estimate: rms(&final_residuals),
        repeatability,
        not_taken: dropped.into_iter().map(|(id, why)| NotTaken { id, why }).collect(),
        alike,
        tell_apart,
        separability,
        verdict,
        final_stack: current.fit.stack.clone(),
        ranking,
        ladder,
        baseline_residuals: r0,
        final_residuals,
    })
}

mod candidate;
mod steps;

use candidate::*;
use steps::{forward, rebuild_ladder};

#[cfg(test)]
mod tests;
