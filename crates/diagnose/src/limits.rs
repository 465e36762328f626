//! What the data can tell, worked out before any answer, and the answer that respects it.
//!
//! **Signatures.** Each candidate's signature is the Jacobian of the residual rows with
//! respect to its parameters, at its neutral value on top of the baseline (a forward
//! difference of one step of the parameter's scale, towards the inside of its bounds).
//!
//! **What a change must exceed to be seen.** A change of the residual rows is split, load by
//! load (thrust rows, torque rows), into the part a level and trends with RPM and with J make
//! (its least-squares projection on a constant, ln RPM and J) and the rest. The
//! level-and-trend part is the shape of the default model's own error on props of this kind (validate's median
//! error of their family, [`ModelError`]): it must exceed that error to be told from it. The
//! rest must exceed [`Z`] standard errors of the fit's residual RMS over the load's rows and
//! [`REPEATABILITY_FACTOR`] times the measurements' repeatability, where they
//! show it. Where no validated props of this kind exist (a QPROP file, a scan), the model's
//! error is not a term (said as such) and the whole change is judged as the rest.
//! [`Judge::strength`] is the larger of the two ratios: 1 or more is detectable.
//!
//! **Detection limit.** The smallest parameter change from neutral whose signature is
//! detectable: 1 / strength of the unit signature (the change is linear in it to first order).
//!
//! **Telling two apart.** Candidate B imitates A's signature as well as its own parameters
//! allow (least squares); the remainder is what tells them apart, and A can be told from B
//! above the size at which that remainder becomes detectable. A pair whose separating size lies
//! beyond A's physically expected range is one the data cannot separate ([`Tie`]).
//!
//! **The answer** ([`verdict`]). Each effect of the ladder's final stack is judged on its own
//! change of the residual rows (the final stack's residuals against the same stack without it):
//! below the detection limit it is not named; fitted outside its expected range it is a
//! calibration factor (no physics is named; the candidates that make the same change inside
//! their expected ranges are said beside it, its physical stand-ins); where another candidate, inside its bounds,
//! reproduces that change up to an undetectable remainder (the stack's other effects free to
//! move), the answer is the group, with the measurement that would separate them; otherwise it
//! is found physics.

use propbet_effects::Stack;
use serde::Serialize;

use crate::{rms, Data, DiagnoseError, Model, Repeatability};

/// How many times the measured repeatability an effect must change the loads by (the ladder's
/// rule too, [`crate::discover`]).
pub const REPEATABILITY_FACTOR: f64 = 3.0;

/// Standard errors a change must make on a load's rows to be detected against the fit's
/// residual scatter.
pub const Z: f64 = 3.0;

/// How a group names two candidates that reproduce a change together.
pub const PAIR: &str = " + ";

/// The default model's usual error on props of this kind: validate's median errors over the
/// validated props of the same family.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ModelError {
    /// Median relative thrust (CT) error [-].
    pub thrust: f64,
    /// Median relative torque (CP) error [-].
    pub torque: f64,
    /// Validated props it rests on.
    pub props: usize,
    /// The kind of prop, in words ("APC Electric").
    pub kind: &'static str,
}

/// The scatter a change is judged against, load by load.
#[derive(Debug, Clone, Serialize)]
pub struct Noise {
    /// Thrust rows, torque rows.
    pub rows: [usize; 2],
    /// RMS of the final model's residuals on the thrust rows and on the torque rows.
    pub fit_rms: [f64; 2],
    /// The measurements' repeatability, where they show it.
    pub repeatability: Option<f64>,
    /// The default model's usual error on props of this kind (None: no validated props of this
    /// kind; the term is left out, and the report says so).
    pub model_error: Option<ModelError>,
    /// What the rest of a change (beyond a level and trends with RPM and J, where the model's
    /// usual error is a term) must exceed, by load.
    pub shape_threshold: [f64; 2],
    /// The final residuals' correlation between neighbouring points of a file, by load (what
    /// makes the rows count as fewer independent ones).
    pub neighbour_correlation: [f64; 2],
}

/// The smallest detectable size of one parameter.
#[derive(Debug, Clone, Serialize)]
pub struct Limit {
    /// Effect id.
    pub effect: String,
    /// Parameter name.
    pub param: String,
    /// Unit.
    pub unit: String,
    /// The value the change is counted from (neutral, else the start).
    pub reference: f64,
    /// Smallest detectable change of the parameter from `reference` (None: no change within
    /// its bounds is detectable, or the data do not respond to it).
    pub limit: Option<f64>,
    /// The physically expected range.
    pub expected: (f64, f64),
    /// The loads it moves, in words ("thrust", "torque", "thrust and torque").
    pub moves: String,
}

/// Two candidates the data cannot tell apart within the first's physically expected range.
#[derive(Debug, Clone, Serialize)]
pub struct Tie {
    /// The effect imitated.
    pub effect: String,
    /// The candidate that imitates it.
    pub imitated_by: String,
    /// Size of `effect`'s first parameter above which the two are told apart (None: never
    /// within its bounds).
    pub apart_above: Option<f64>,
}

/// What these data can separate, before any answer.
#[derive(Debug, Clone, Serialize)]
pub struct Separability {
    /// The scatter changes are judged against.
    pub noise: Noise,
    /// Every candidate parameter's detection limit.
    pub limits: Vec<Limit>,
    /// The pairs the data cannot separate within physical sizes.
    pub ties: Vec<Tie>,
}

/// How an effect of the ladder is answered.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum AnswerKind {
    /// Found physics: detectable, told apart from every other candidate, inside its expected
    /// range.
    Found,
    /// Detectable, but fitted outside its expected range: a calibration factor, with the
    /// candidates that make the same change inside their expected ranges where there are
    /// (its physical stand-ins, in [`Answer::group`]).
    Calibration,
    /// Detectable, but other candidates reproduce its change: one of a group.
    Group,
    /// Its change is below what these data detect: not named.
    BelowLimit,
}

/// The answer about one effect of the ladder.
#[derive(Debug, Clone, Serialize)]
pub struct Answer {
    /// The ladder's effect (`--effect` form, with its values).
    pub effect: String,
    /// Its id.
    pub id: String,
    /// How it is answered.
    pub kind: AnswerKind,
    /// Its change over the detection threshold (1 or more: detectable).
    pub strength: f64,
    /// The candidates that reproduce its change (its own id first), for a group; for a
    /// calibration factor, those that do inside their expected ranges (empty: none).
    pub group: Vec<String>,
    /// The measurement that would tell the group apart (None without a group).
    pub tell_apart: Option<String>,
}

/// The verdict: the answers, and how much of the residual is within what the model usually
/// misses.
#[derive(Debug, Clone, Serialize)]
pub struct Verdict {
    /// One answer per effect of the ladder's final stack.
    pub answers: Vec<Answer>,
    /// The baseline's RMS thrust and torque errors against the model's usual error on props of
    /// this kind, in words (None without validated props of this kind).
    pub within_model_error: Option<String>,
}

impl Verdict {
    /// The effects named as found physics.
    pub fn physics(&self) -> Vec<&str> {
        self.answers
            .iter()
            .filter(|a| a.kind == AnswerKind::Found)
            .map(|a| a.id.as_str())
            .collect()
    }
}

/// Judges changes of the residual rows of one set of data.
#[derive(Debug, Clone)]
pub struct Judge {
    /// Row kinds (torque or thrust) in [`Data::rows`]' order.
    torque: Vec<bool>,
    /// The thrust rows' and the torque rows' indices.
    load_rows: [Vec<usize>; 2],
    /// On each load's rows, an orthonormal basis of a level and the trends with ln RPM and J:
    /// the shapes of the model's usual error.
    bases: [Vec<Vec<f64>>; 2],
    noise: Noise,
}

impl Judge {
    /// The judge of `data`, whose final model leaves `final_residuals`.
    pub fn new(
        data: &Data,
        final_residuals: &[f64],
        repeatability: Option<&Repeatability>,
        model_error: Option<ModelError>,
    ) -> Self {
        let rows = data.rows();
        let torque: Vec<bool> = rows.iter().map(|r| r.torque).collect();
        let mut counts = [0usize; 2];
        let mut fit_rms = [0.0; 2];
        let mut shape_threshold = [0.0; 2];
        let mut lag = [0.0; 2];
        let mut load_rows: [Vec<usize>; 2] = Default::default();
        let mut bases: [Vec<Vec<f64>>; 2] = Default::default();
        for load in [false, true] {
            let idx: Vec<usize> = (0..rows.len()).filter(|&i| torque[i] == load).collect();
            let k = usize::from(load);
            counts[k] = idx.len();
            let point = |i: usize| &data.obs[rows[i].point];
            bases[k] = level_and_trends_basis(&[
                idx.iter().map(|&i| point(i).rpm().max(1.0).ln()).collect(),
                idx.iter().map(|&i| point(i).j).collect(),
            ]);
            load_rows[k] = idx.clone();
            if idx.is_empty() {
                continue;
            }
            let r: Vec<f64> = idx
                .iter()
                .map(|&i| final_residuals.get(i).copied().unwrap_or(0.0))
                .collect();
            fit_rms[k] = rms(&r);
            // Neighbouring points of one sweep leave errors alike (the model's error is smooth
            // in J): the rows count as fewer independent ones, n (1 - rho) / (1 + rho), with rho
            // the residuals' correlation between neighbours of the same file.
            let files: Vec<usize> = idx.iter().map(|&i| data.obs[rows[i].point].file).collect();
            let rho = neighbour_correlation(&r, &files);
            let n_eff = (idx.len() as f64 * (1.0 - rho) / (1.0 + rho)).max(1.0);
            lag[k] = rho;
            let rep = repeatability.map_or(0.0, |r| REPEATABILITY_FACTOR * r.sd);
            shape_threshold[k] = (Z * fit_rms[k] / n_eff.sqrt()).max(rep).max(1e-9);
        }
        Self {
            torque,
            load_rows,
            bases,
            noise: Noise {
                rows: counts,
                fit_rms,
                repeatability: repeatability.map(|r| r.sd),
                model_error,
                shape_threshold,
                neighbour_correlation: lag,
            },
        }
    }

    /// The scatter it judges against.
    pub fn noise(&self) -> &Noise {
        &self.noise
    }

    /// The effect `id`'s own id and the candidates of `sigs` that reproduce `change`, inside
    /// their bounds, up to an undetectable remainder, with the other effects of the stack
    /// (`stack`: id and current values) free to move within theirs as a refit would (an effect
    /// of the stack among the candidates: a pair fitted together that can stand in for each
    /// other, a density and an RPM scale that cancel, is no answer either). The closest first.
    /// Where no one candidate does, two together that do are a rival too ("a + b"): one effect
    /// standing in for what two did is no more an answer than one for one.
    pub fn group(&self, change: &[f64], id: &str, sigs: &[Signature], stack: &[(&str, &[f64])]) -> Vec<String> {
        self.group_within(change, id, sigs, stack, Reach::Bounds)
    }

    /// [`Judge::group`] with the rivals moving as far as `reach` lets them (the stack's other
    /// effects within their bounds).
    fn group_within(
        &self,
        change: &[f64],
        id: &str,
        sigs: &[Signature],
        stack: &[(&str, &[f64])],
        reach: Reach,
    ) -> Vec<String> {
        let at = |name: &str| stack.iter().find(|(i, _)| *i == name).map(|(_, v)| *v);
        // `change` is what the effect removes from the residual rows (without it minus with
        // it); a rival stands in for it by moving the rows the other way, from its reference
        // towards its bounds: the rows it must make are the negated change.
        let made: Vec<f64> = change.iter().map(|x| -x).collect();
        let rivals: Vec<&Signature> = sigs.iter().filter(|s| s.effect.id() != id).collect();
        // How closely `those` (with the stack's other effects free) reproduce the change.
        let closeness = |those: &[&Signature]| {
            let mut cols = Vec::new();
            for s in those {
                cols.extend(columns(s, at(s.effect.id()), reach));
            }
            for o in &rivals {
                if at(o.effect.id()).is_some() && !those.iter().any(|s| s.effect.id() == o.effect.id()) {
                    cols.extend(columns(o, at(o.effect.id()), Reach::Bounds));
                }
            }
            self.strength(&imitate_by(&made, &cols))
        };
        let mut close: Vec<(f64, String)> = rivals
            .iter()
            .map(|s| (closeness(&[s]), s.effect.id().to_string()))
            .filter(|(st, _)| *st < 1.0)
            .collect();
        if close.is_empty() {
            for (k, a) in rivals.iter().enumerate() {
                for b in &rivals[k + 1..] {
                    let st = closeness(&[a, b]);
                    if st < 1.0 {
                        close.push((st, format!("{}{PAIR}{}", a.effect.id(), b.effect.id())));
                    }
                }
            }
        }
        close.sort_by(|a, b| a.0.total_cmp(&b.0));
        std::iter::once(id.to_string())
            .chain(close.into_iter().map(|c| c.1))
            .collect()
    }

    /// How the change the effect `id` makes is answered, with the group where it is one: below
    /// the limit (nothing named); a calibration factor when its value is `outside` its expected
    /// range, with the candidates that make its change inside their own expected ranges (its
    /// physical stand-ins; none: the group is empty); one of a group where a rival reproduces
    /// it inside its bounds ([`Judge::group`]); else found physics.
    pub fn answer(
        &self,
        change: &[f64],
        id: &str,
        sigs: &[Signature],
        stack: &[(&str, &[f64])],
        outside: bool,
    ) -> (AnswerKind, Vec<String>) {
        if self.strength(change) < 1.0 {
            return (AnswerKind::BelowLimit, Vec::new());
        }
        if outside {
            let stand_ins = self.group_within(change, id, sigs, stack, Reach::Expected);
            return (
                AnswerKind::Calibration,
                if stand_ins.len() > 1 { stand_ins } else { Vec::new() },
            );
        }
        let group = self.group(change, id, sigs, stack);
        if group.len() > 1 {
            (AnswerKind::Group, group)
        } else {
            (AnswerKind::Found, Vec::new())
        }
    }

    /// A change of the residual rows over what these data detect (1 or more: detectable):
    /// the larger, over the loads, of its level-and-trends part over the model's usual error
    /// (or the shape threshold, whichever is larger) and its rest over the shape threshold.
    pub fn strength(&self, change: &[f64]) -> f64 {
        let mut most = 0.0f64;
        for load in [false, true] {
            let k = usize::from(load);
            let idx = &self.load_rows[k];
            if idx.is_empty() {
                continue;
            }
            let c: Vec<f64> = idx.iter().map(|&i| change[i]).collect();
            let t = self.noise.shape_threshold[k];
            let ratio = match self.noise.model_error {
                None => rms(&c) / t,
                Some(m) => {
                    let (fitted, rest) = project(&c, &self.bases[k]);
                    let usual = if load { m.torque } else { m.thrust };
                    (rms(&fitted) / usual.max(t)).max(rms(&rest) / t)
                }
            };
            most = most.max(ratio);
        }
        most
    }
}

/// The correlation of `r` between neighbours with the same `files` entry, in [0, 0.95]
/// (negative correlation counts as none).
fn neighbour_correlation(r: &[f64], files: &[usize]) -> f64 {
    let ss: f64 = r.iter().map(|x| x * x).sum();
    if ss <= 0.0 {
        return 0.0;
    }
    let lagged: f64 = (1..r.len())
        .filter(|&i| files[i] == files[i - 1])
        .map(|i| r[i] * r[i - 1])
        .sum();
    (lagged / ss).clamp(0.0, 0.95)
}

/// An orthonormal basis (modified Gram-Schmidt) of a constant and the trends `x` (each a
/// column over the same rows; one that hardly varies, or repeats the others, is left out).
fn level_and_trends_basis(x: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let n = x.first().map_or(0, Vec::len);
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for col in std::iter::once(vec![1.0; n]).chain(x.iter().cloned()) {
        let scale = col.iter().map(|v| v * v).sum::<f64>().sqrt();
        let mut v = col;
        for b in &basis {
            let d: f64 = v.iter().zip(b).map(|(a, b)| a * b).sum();
            v.iter_mut().zip(b).for_each(|(a, b)| *a -= d * b);
        }
        let norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
        if norm > 1e-6 * scale.max(1e-300) && norm > 1e-9 * (n as f64).sqrt() {
            basis.push(v.into_iter().map(|a| a / norm).collect());
        }
    }
    basis
}

/// Splits `c` into its least-squares fit on the orthonormal `basis` and the rest.
fn project(c: &[f64], basis: &[Vec<f64>]) -> (Vec<f64>, Vec<f64>) {
    let mut fitted = vec![0.0; c.len()];
    for b in basis {
        let d: f64 = c.iter().zip(b).map(|(a, b)| a * b).sum();
        fitted.iter_mut().zip(b).for_each(|(f, b)| *f += d * b);
    }
    let rest = c.iter().zip(&fitted).map(|(a, b)| a - b).collect();
    (fitted, rest)
}

/// Which rows a column moves, in words.
fn moves(judge: &Judge, col: &[f64]) -> String {
    let most = |load: bool| {
        col.iter()
            .zip(&judge.torque)
            .filter(|(_, t)| **t == load)
            .fold(0.0f64, |a, (x, _)| a.max(x.abs()))
    };
    let (t, q) = (most(false), most(true));
    let tiny = 1e-9 * t.max(q);
    match (t > tiny, q > tiny) {
        (true, true) => "thrust and torque".into(),
        (true, false) => "thrust".into(),
        (false, true) => "torque".into(),
        (false, false) => "nothing".into(),
    }
}

/// The detection limits and the ties of `signatures` (on the baseline) under `judge`.
pub fn separability(judge: &Judge, sigs: &[Signature]) -> Separability {
    let mut limits = Vec::new();
    for s in sigs {
        for ((p, r), col) in s.effect.params().iter().zip(&s.reference).zip(&s.columns) {
            let reach = (p.upper - r).abs().max((r - p.lower).abs());
            let limit = col.as_ref().and_then(|c| {
                let st = judge.strength(c);
                (st > 0.0 && 1.0 / st <= reach).then(|| 1.0 / st)
            });
            limits.push(Limit {
                effect: s.effect.id().to_string(),
                param: p.name.clone(),
                unit: p.unit.clone(),
                reference: *r,
                limit,
                expected: p.expected_range(),
                moves: col.as_ref().map_or_else(|| "nothing".into(), |c| moves(judge, c)),
            });
        }
    }
    let mut ties = Vec::new();
    for a in sigs {
        let (Some(Some(col)), Some(p)) = (a.columns.first(), a.effect.params().first()) else {
            continue;
        };
        let r = a.reference[0];
        let (lo, hi) = p.expected_range();
        let span = (hi - r).abs().max((r - lo).abs());
        if judge.strength(col) * span < 1.0 {
            // Not detectable anywhere in its expected range: its limit says so already.
            continue;
        }
        for b in sigs {
            if b.effect.id() == a.effect.id() {
                continue;
            }
            let rest = imitate(col, b, Reach::Free);
            let st = judge.strength(&rest);
            let apart = (st > 0.0).then(|| 1.0 / st);
            if apart.is_none_or(|x| x > span) {
                ties.push(Tie {
                    effect: a.effect.id().to_string(),
                    imitated_by: b.effect.id().to_string(),
                    apart_above: apart.filter(|x| *x <= (p.upper - r).abs().max((r - p.lower).abs())),
                });
            }
        }
    }
    Separability {
        noise: judge.noise.clone(),
        limits,
        ties,
    }
}

/// What these data lack to tell effects apart, if it is a range: forward flight (static points
/// only) or a second RPM range (speeds within a factor 1.5).
pub fn what_the_data_lack(data: &Data) -> Option<String> {
    let (lo, hi) = data
        .obs
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), o| (a.min(o.rpm()), b.max(o.rpm())));
    if data.obs.iter().all(|o| o.j < 0.01) {
        Some("forward-flight sweeps (J above 0)".into())
    } else if hi < 1.5 * lo {
        Some(format!("a second RPM range (these data span {lo:.0}-{hi:.0} rpm)"))
    } else {
        None
    }
}

/// The measurement that would tell the effects `ids` apart (an answer and its closest
/// imitations, first: the first two are looked at), from what each needs and what the data
/// lack.
pub fn tell_apart(data: &Data, ids: &[String]) -> String {
    let ids: Vec<&str> = ids.iter().take(2).flat_map(|i| i.split(PAIR)).collect();
    let has = |id: &str| ids.contains(&id);
    let lo = data.obs.iter().fold(f64::INFINITY, |a, o| a.min(o.rpm()));
    let mut ways = Vec::new();
    if has("torque-tare") {
        ways.push(format!(
            "a static run down to {:.0} rpm (a bearing's torque grows as 1/RPM² against the propeller's) or a run \
             without the propeller",
            (lo / 2.0 / 500.0).round().max(1.0) * 500.0
        ));
    }
    if has("thrust-tare") {
        ways.push(
            "the stand's thrust read with the motor running and the propeller off (the slipstream's drag)".into(),
        );
    }
    if has("rpm-scale") || has("density") {
        ways.push("an optical RPM and a logged air temperature and pressure".into());
    }
    if has("chord-scale") || has("pitch-offset") || has("elastic-twist") {
        ways.push("the blade's chord and angle measured at a few stations".into());
    }
    if ways.is_empty()
        || ids
            .iter()
            .any(|i| i.contains("stall") || i.contains("re-") || *i == "drag-scale")
    {
        ways.extend(what_the_data_lack(data));
    }
    if ways.is_empty() {
        ways.push("repeated points to measure the scatter".into());
    }
    ways.join("; or ")
}

/// The answer about each effect of `final_stack` (the ladder's, leaving `final_residuals`),
/// against the candidates' signatures on the baseline.
pub fn verdict(
    model: &Model,
    data: &Data,
    final_stack: &Stack,
    final_residuals: &[f64],
    baseline_residuals: &[f64],
    judge: &Judge,
    sigs: &[Signature],
) -> Result<Verdict, DiagnoseError> {
    let all: Vec<usize> = (0..data.obs.len()).collect();
    let mut answers = Vec::new();
    for (i, a) in final_stack.active.iter().enumerate() {
        let mut without = final_stack.clone();
        without.active.remove(i);
        let r = model.residuals(data, &without, &all)?;
        // The residual rows this effect removes: its change as the data see it.
        let change: Vec<f64> = r.iter().zip(final_residuals).map(|(x, y)| x - y).collect();
        let id = a.effect.id().to_string();
        let stack: Vec<(&str, &[f64])> = final_stack
            .active
            .iter()
            .map(|x| (x.effect.id(), x.values.as_slice()))
            .collect();
        let outside = a
            .effect
            .params()
            .iter()
            .zip(&a.values)
            .any(|(p, v)| crate::fit::outside_expected(*v, p));
        let (kind, group) = judge.answer(&change, &id, sigs, &stack, outside);
        answers.push(Answer {
            effect: a.describe(),
            tell_apart: (group.len() > 1).then(|| tell_apart(data, &group)),
            id,
            kind,
            strength: judge.strength(&change),
            group,
        });
    }
    let within_model_error = judge.noise.model_error.map(|m| {
        let by_load = |load: bool| -> Vec<f64> {
            baseline_residuals
                .iter()
                .zip(&judge.torque)
                .filter(|(_, t)| **t == load)
                .map(|(x, _)| *x)
                .collect()
        };
        let pct = |x: f64| format!("{:.1} %", 100.0 * x);
        let (t, q) = (rms(&by_load(false)), rms(&by_load(true)));
        let measured_torque = judge.noise.rows[1] > 0;
        let (errors, usual) = if measured_torque {
            (
                format!("thrust {}, torque {} RMS", pct(t), pct(q)),
                format!("{} / {}", pct(m.thrust), pct(m.torque)),
            )
        } else {
            (format!("thrust {} RMS", pct(t)), pct(m.thrust))
        };
        let within = t <= m.thrust && (!measured_torque || q <= m.torque);
        if within {
            format!(
                "The error before any effect ({errors}) is within what the default model usually misses on {} props \
                 ({usual}, {} validated): what is named may be the model's own error",
                m.kind, m.props
            )
        } else {
            format!(
                "Of the error before any effect ({errors}), up to {usual} is what the default model usually misses on \
                 {} props ({} validated)",
                m.kind, m.props
            )
        }
    });
    Ok(Verdict {
        answers,
        within_model_error,
    })
}

mod imitate;
mod signature;
#[cfg(test)]
mod tests;

use imitate::{columns, imitate, imitate_by, Reach};
pub use signature::{signatures, Signature};
