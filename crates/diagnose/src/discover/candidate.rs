//! One candidate tried on top of the current stack: the cross-validation folds (k random
//! folds and the RPM groups), the held-out score of a fit, the F test against the stack
//! without it, and the notes that keep it from being an answer (too weak, neutral value inside
//! its interval, on a bound, outside its expected range).

use super::*;

/// Point indices of the k folds and the RPM groups.
pub(super) struct Folds {
    pub(super) kfold: Vec<Vec<usize>>,
    pub(super) loro: Option<Vec<Vec<usize>>>,
}

pub(super) fn folds(data: &Data, k: usize, seed: u64) -> Folds {
    let groups: Vec<i64> = data.obs.iter().map(|o| o.rpm_group).collect();
    folds_of(&groups, k, seed)
}

/// k folds of the points (shuffled with `seed`) and, with three or more RPM groups, one fold
/// per group; `groups[i]` is point i's RPM group.
pub(super) fn folds_of(groups: &[i64], k: usize, seed: u64) -> Folds {
    let n = groups.len();
    let mut idx: Vec<usize> = (0..n).collect();
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    idx.shuffle(&mut rng);
    let k = k.clamp(2, n.max(2));
    let mut kfold = vec![Vec::new(); k];
    for (i, p) in idx.into_iter().enumerate() {
        kfold[i % k].push(p);
    }
    kfold.retain(|f| !f.is_empty());
    let mut by_group: BTreeMap<i64, Vec<usize>> = BTreeMap::new();
    for (i, &g) in groups.iter().enumerate() {
        by_group.entry(g).or_default().push(i);
    }
    let loro = (by_group.len() >= 3).then(|| by_group.into_values().collect());
    Folds { kfold, loro }
}

/// Held-out RMS errors: of all residual rows, and of the thrust rows and the torque rows alone
/// (what an effect on one of the two loads is judged on).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct HeldRms {
    pub(super) all: f64,
    /// Thrust rows, torque rows.
    pub(super) by_load: [f64; 2],
}

impl HeldRms {
    /// The RMS errors of residual rows of kinds `torque`.
    pub(super) fn of(rows: &[(bool, f64)]) -> Self {
        let pick = |t: bool| -> Vec<f64> { rows.iter().filter(|r| r.0 == t).map(|r| r.1).collect() };
        let all: Vec<f64> = rows.iter().map(|r| r.1).collect();
        Self {
            all: rms(&all),
            by_load: [rms(&pick(false)), rms(&pick(true))],
        }
    }

    /// The held-out error an effect is judged on: of its load's rows alone (`load`: Some(true)
    /// for an effect on torque alone), else of all rows.
    pub(super) fn on(&self, load: Option<bool>) -> f64 {
        load.map_or(self.all, |t| self.by_load[usize::from(t)])
    }
}

/// The rows of `data` as (is torque, residual) pairs, `residuals` in [`Data::rows`]' order.
pub(super) fn kinds(data: &Data, residuals: &[f64]) -> Vec<(bool, f64)> {
    data.rows().iter().zip(residuals).map(|(r, x)| (r.torque, *x)).collect()
}

/// The load an effect of the last `k_new` parameters of `fit` acts on alone: Some(true) when
/// its parameters move no thrust row (a torque tare), Some(false) when they move no torque row
/// (a thrust tare), None when they move both.
pub(super) fn load_of(data: &Data, fit: &FitOutcome, k_new: usize) -> Option<bool> {
    let rows = data.rows();
    let k = fit.jacobian.ncols();
    if k_new == 0 || k < k_new || fit.jacobian.nrows() != rows.len() {
        return None;
    }
    let mut most = [0.0f64; 2];
    for (i, r) in rows.iter().enumerate() {
        for c in k - k_new..k {
            let m = &mut most[usize::from(r.torque)];
            *m = m.max(fit.jacobian[(i, c)].abs());
        }
    }
    let tiny = 1e-9 * most[0].max(most[1]);
    if most[0] <= tiny && most[1] > tiny {
        Some(true)
    } else if most[1] <= tiny && most[0] > tiny && rows.iter().any(|r| r.torque) {
        Some(false)
    } else {
        None
    }
}

/// Held-out RMS over `folds`: one Gauss-Newton refit per fold on the other points' rows, then
/// the held-out points solved at the refitted parameters.
pub(super) fn held_out(
    model: &Model,
    data: &Data,
    effects: &[Arc<dyn Effect>],
    f: &FitOutcome,
    folds: &[Vec<usize>],
) -> Result<HeldRms, DiagnoseError> {
    let rows = data.rows();
    let k = f.p.len();
    let (lo, hi, scale) = bounds(effects);
    let mut held = Vec::with_capacity(rows.len());
    for fold in folds {
        let mut out = vec![false; data.obs.len()];
        for &i in fold {
            out[i] = true;
        }
        if k == 0 {
            held.extend(
                rows.iter()
                    .zip(&f.residuals)
                    .filter(|(r, _)| out[r.point])
                    .map(|(r, x)| (r.torque, *x)),
            );
            continue;
        }
        let train: Vec<usize> = (0..rows.len()).filter(|&i| !out[rows[i].point]).collect();
        let j = DMatrix::from_fn(train.len(), k, |i, c| f.jacobian[(train[i], c)] * scale[c]);
        let r = DVector::from_iterator(train.len(), train.iter().map(|&i| f.residuals[i]));
        let a = j.transpose() * &j;
        let g = j.transpose() * r;
        let dx = a
            .svd(true, true)
            .solve(&(-g), 1e-10)
            .unwrap_or_else(|_| DVector::zeros(k));
        let p: Vec<f64> = (0..k)
            .map(|c| (f.p[c] + dx[c] * scale[c]).clamp(lo[c], hi[c]))
            .collect();
        let r = model.residuals(data, &stack_at(effects, &p), fold)?;
        let kinds = fold
            .iter()
            .flat_map(|&i| std::iter::once(false).chain(data.obs[i].torque.map(|_| true)));
        held.extend(kinds.zip(r));
    }
    Ok(HeldRms::of(&held))
}

pub(super) fn score(rows: usize, heldout_rms: f64, k: usize) -> f64 {
    let n = rows as f64;
    n * (heldout_rms * heldout_rms).max(1e-300).ln() + k as f64 * n.ln()
}

pub(super) fn all_starts(e: &Arc<dyn Effect>) -> Vec<Vec<f64>> {
    let mut s = vec![e.params().iter().map(|p| p.start).collect::<Vec<_>>()];
    s.extend(e.extra_starts());
    s
}

/// A set of effects fitted together, with its held-out errors.
#[derive(Clone)]
pub(super) struct Evaluated {
    pub(super) fit: FitOutcome,
    pub(super) kfold: f64,
    /// The k-fold errors of the thrust rows and of the torque rows.
    pub(super) kfold_by_load: HeldRms,
    pub(super) loro: Option<f64>,
}

impl Evaluated {
    /// The effects of the fitted stack, in order.
    pub(super) fn effects(&self) -> Vec<Arc<dyn Effect>> {
        self.fit.stack.active.iter().map(|a| a.effect.clone()).collect()
    }

    /// Ranking score (lower is better).
    pub(super) fn score(&self) -> f64 {
        score(self.fit.residuals.len(), self.kfold, self.fit.p.len())
    }

    /// The ladder's rung for this model ("baseline" when it has no effect).
    pub(super) fn rung(&self, data: &Data, p_value: Option<f64>) -> Rung {
        let (thrust_j_trend, thrust_rpm_trend) = crate::signature::thrust_trends(data, &self.fit.residuals);
        Rung {
            thrust_j_trend,
            thrust_rpm_trend,
            added: self
                .fit
                .stack
                .active
                .last()
                .map_or("baseline".into(), |a| a.effect.id().to_string()),
            stack: self.fit.stack.describe(),
            params: self.fit.params(),
            rms: rms(&self.fit.residuals),
            kfold_rms: self.kfold,
            loro_rms: self.loro,
            p_value,
        }
    }
}

/// Fits `effects` together: parameters of effects in `warm` start from their values there; the
/// one effect that is not starts from the best of its start vectors (by the initial error).
pub(super) fn evaluate(
    model: &Model,
    data: &Data,
    effects: Vec<Arc<dyn Effect>>,
    warm: &Stack,
    f: &Folds,
) -> Result<Evaluated, DiagnoseError> {
    let all: Vec<usize> = (0..data.obs.len()).collect();
    let mut starts: Vec<Vec<f64>> = vec![Vec::new()];
    for e in &effects {
        let options = match warm.active.iter().find(|a| a.effect.id() == e.id()) {
            Some(a) => vec![a.values.clone()],
            None => all_starts(e),
        };
        starts = starts
            .iter()
            .flat_map(|s| {
                options.iter().map(move |o| {
                    let mut v = s.clone();
                    v.extend(o);
                    v
                })
            })
            .collect();
    }
    let mut best: Option<(f64, Vec<f64>)> = None;
    if starts.len() == 1 {
        best = starts.pop().map(|s| (0.0, s));
    } else {
        for s in starts {
            let r = model.residuals(data, &stack_at(&effects, &s), &all)?;
            let e = r.iter().map(|x| x * x).sum::<f64>();
            if best.as_ref().is_none_or(|b| e < b.0) {
                best = Some((e, s));
            }
        }
    }
    let start = best.map(|b| b.1).unwrap_or_default();
    let fitted = fit(model, data, &effects, &start)?;
    let kfold = held_out(model, data, &effects, &fitted, &f.kfold)?;
    let loro = match &f.loro {
        Some(g) => Some(held_out(model, data, &effects, &fitted, g)?.all),
        None => None,
    };
    Ok(Evaluated {
        fit: fitted,
        kfold: kfold.all,
        kfold_by_load: kfold,
        loro,
    })
}

/// p value of the nested F test of `full` against `reduced` (which lacks `k` parameters).
pub(super) fn f_test(reduced_sse: f64, full: &FitOutcome, k: usize) -> (f64, f64) {
    f_test_rows(reduced_sse, full.sse, full.residuals.len(), full.p.len(), k)
}

/// [`f_test`] of sums of squares over `rows` residual rows, the full model fitting `params`.
fn f_test_rows(reduced_sse: f64, s1: f64, rows: usize, params: usize, k: usize) -> (f64, f64) {
    let dof = rows.saturating_sub(params).max(1);
    let fstat = if s1 > 0.0 {
        ((reduced_sse - s1) / k.max(1) as f64) / (s1 / dof as f64)
    } else if reduced_sse > 0.0 {
        f64::INFINITY
    } else {
        0.0
    };
    let p = if fstat.is_infinite() {
        0.0
    } else if fstat > 0.0 {
        FisherSnedecor::new(k.max(1) as f64, dof as f64).map_or(1.0, |d| d.sf(fstat))
    } else {
        1.0
    };
    (fstat, p)
}

/// [`f_test`] on the rows of one load (`load`, [`load_of`]); on all rows for None.
pub(super) fn f_test_on(
    data: &Data,
    reduced: &FitOutcome,
    full: &FitOutcome,
    k: usize,
    load: Option<bool>,
) -> (f64, f64) {
    let Some(t) = load else {
        return f_test(reduced.sse, full, k);
    };
    let sse = |f: &FitOutcome| -> (f64, usize) {
        let on: Vec<f64> = kinds(data, &f.residuals)
            .into_iter()
            .filter(|r| r.0 == t)
            .map(|r| r.1)
            .collect();
        (on.iter().map(|x| x * x).sum(), on.len())
    };
    let ((s0, _), (s1, n)) = (sse(reduced), sse(full));
    f_test_rows(s0, s1, n, full.p.len(), k)
}

pub(super) fn try_candidate(
    model: &Model,
    data: &Data,
    current: &Evaluated,
    cand: &Arc<dyn Effect>,
    f: &Folds,
    p_max: f64,
    rep: Option<&Repeatability>,
) -> Result<Scored, DiagnoseError> {
    let mut effects = current.effects();
    effects.push(cand.clone());
    let k_new = cand.params().len();
    let k = current.fit.p.len() + k_new;
    let rows = current.fit.residuals.len();
    let base = Scored {
        id: cand.id().to_string(),
        explanation: cand.explanation().to_string(),
        params: Vec::new(),
        rms: f64::NAN,
        kfold_rms: f64::NAN,
        kfold_by_load: None,
        loro_rms: None,
        gain: 0.0,
        f: 0.0,
        p_value: 1.0,
        significant: false,
        score: f64::INFINITY,
        note: None,
        fit: None,
    };
    if rows < k + 2 || k_new == 0 {
        let names: Vec<String> = cand.params().iter().map(|p| p.name.clone()).collect();
        return Ok(Scored {
            note: Some(format!(
                "too few points to fit {} ({}): {rows} residual(s) (thrust and torque per point) for {k} parameter(s) in all; \
                 at least {} are needed",
                cand.id(),
                names.join(", "),
                k + 2
            )),
            ..base
        });
    }
    let ev = evaluate(model, data, effects, &current.fit.stack, f)?;
    // An effect on one load alone is judged on that load's rows: the other load's error, which
    // it cannot change, would dilute its gain, its F statistic and its size.
    let load = load_of(data, &ev.fit, k_new);
    let (fstat, p_value) = f_test_on(data, &current.fit, &ev.fit, k_new, load);
    let before = current.kfold_by_load.on(load);
    let gain = if before > 0.0 {
        1.0 - ev.kfold_by_load.on(load) / before
    } else {
        0.0
    };
    let note = refusal(data, &current.fit, &ev.fit, rep, load);
    let significant = p_value < p_max && gain >= MIN_GAIN && note.is_none();
    Ok(Scored {
        note,
        params: ev.fit.params(),
        rms: rms(&ev.fit.residuals),
        kfold_rms: ev.kfold,
        kfold_by_load: Some(ev.kfold_by_load),
        loro_rms: ev.loro,
        gain,
        f: fstat,
        p_value,
        significant,
        score: ev.score(),
        fit: Some(ev.fit),
        ..base
    })
}

/// The words for an effect that changes the loads less than [`REPEATABILITY_FACTOR`] times
/// the measurements' repeatability.
pub(super) fn weak_note(size: f64, r: &Repeatability) -> String {
    format!(
        "changes the loads by {:.1} %, less than {REPEATABILITY_FACTOR} times the {:.1} % the measurements repeat to",
        100.0 * size,
        100.0 * r.sd
    )
}

/// True when a one-parameter effect's 95 % interval holds its neutral value (`own`: the
/// effect's own fitted parameters): the data cannot tell the effect from its absence, and it
/// is not added. An effect of several parameters is judged by the nested F test of all of them
/// together (its parameters' separate intervals are wide where they are correlated: a
/// friction torque's q0 and q1).
pub(super) fn neutral_held(own: &[FittedParam]) -> bool {
    matches!(own, [p] if p.neutral.is_some() && p.holds_neutral)
}

/// The words for [`neutral_held`].
pub(super) fn neutral_note(own: &[FittedParam]) -> String {
    let list: Vec<String> = own
        .iter()
        .filter(|p| p.neutral.is_some())
        .map(|p| match p.ci95 {
            Some(c) => format!(
                "{} = {} ± {}",
                p.name,
                propbet_effects::fmt_value(p.value),
                propbet_effects::fmt_value(c)
            ),
            None => format!(
                "{} = {} (not determined by the data)",
                p.name,
                propbet_effects::fmt_value(p.value)
            ),
        })
        .collect();
    format!(
        "its 95 % interval holds its neutral value ({}): the data cannot tell it from its absence",
        list.join(", ")
    )
}

/// Why the effect `next` adds on top of `prev` cannot be an answer, if it cannot: its fit
/// ends on a bound, it changes the loads less than [`REPEATABILITY_FACTOR`] times the measured
/// repeatability, or its interval holds its neutral value. One set of tests for a candidate of
/// the ranking and for a rung of the rebuilt ladder; `load` as in [`load_of`].
pub(super) fn refusal(
    data: &Data,
    prev: &FitOutcome,
    next: &FitOutcome,
    rep: Option<&Repeatability>,
    load: Option<bool>,
) -> Option<String> {
    let params = next.params();
    let beyond: Vec<FittedParam> = params.iter().filter(|p| p.at_bound).cloned().collect();
    if !beyond.is_empty() {
        return Some(bound_note(&beyond));
    }
    // The size on the effect's own load's rows (all rows for an effect on both).
    let on = |f: &FitOutcome| HeldRms::of(&kinds(data, &f.residuals)).on(load);
    let size = (on(prev).powi(2) - on(next).powi(2)).max(0.0).sqrt();
    if let Some(r) = rep.filter(|r| size < REPEATABILITY_FACTOR * r.sd) {
        return Some(weak_note(size, r));
    }
    let own = &params[prev.p.len()..];
    neutral_held(own).then(|| neutral_note(own))
}

/// The words for a fit that ended on physical bounds.
pub fn bound_note(beyond: &[FittedParam]) -> String {
    let list: Vec<String> = beyond
        .iter()
        .map(|p| match p.ci95 {
            Some(c) => {
                // The interval to two significant digits.
                let decimals = (1 - c.abs().max(1e-12).log10().floor() as i32).max(0) as usize;
                format!("{}:{} = {:.4} ± {:.*}", p.effect, p.name, p.value, decimals, c)
            }
            None => format!("{}:{} = {:.4}", p.effect, p.name, p.value),
        })
        .collect();
    format!(
        "hit its bound ({}): the data want more than this effect can physically give; not an answer",
        list.join(", ")
    )
}
