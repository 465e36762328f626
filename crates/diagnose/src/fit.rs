//! Bounded Levenberg-Marquardt fit of effect parameters to the residual rows.
//!
//! Parameters are scaled by each one's typical change ([`propbet_effects::Param::scale`]); a
//! parameter on a bound that the descent pushes outwards is held there while the others step
//! (an active set), and a step that leaves the bounds is projected back onto them; the
//! Jacobian is a forward difference of 1 % of the scale (the solver converges to 1e-6 in the
//! wake angle, far below that). Bounded least-squares crates exist (`rmpfit`, a port of
//! MINPACK's MPFIT with box constraints; `ganesh`); this one is kept because it is tailored to
//! the diagnosis: scaled parameters, a stop on the relative fall of the SSE at the solver's
//! accuracy, and the Jacobian reused for the covariance and the folds' Gauss-Newton refits.
//! nalgebra does the linear algebra. The iteration ([`levenberg_marquardt`]) works on any
//! residual function and says why it stopped ([`Stop`]).
//!
//! Confidence intervals are 1.96 standard deviations from the covariance
//! s^2 (J^T J)^-1 with s^2 = SSE/(rows - parameters), computed by SVD so that a parameter the
//! data cannot see (for example a drag-rise Mach number above every local Mach number) gets
//! an infinite interval rather than a failure.

use std::sync::Arc;

use nalgebra::{DMatrix, DVector};
use propbet_effects::{Active, Effect, Stack};
use serde::Serialize;

use crate::{Data, DiagnoseError, Model};

/// A fitted set of effects.
#[derive(Debug, Clone)]
pub struct FitOutcome {
    /// The effects with their fitted values.
    pub stack: Stack,
    /// All parameter values, effect after effect.
    pub p: Vec<f64>,
    /// Residual rows at the fit (all points).
    pub residuals: Vec<f64>,
    /// d(residual)/d(parameter) at the fit [rows x parameters].
    pub jacobian: DMatrix<f64>,
    /// Sum of squared residuals.
    pub sse: f64,
    /// One standard deviation of each parameter (infinite where the data cannot see it).
    pub sd: Vec<f64>,
    /// Model evaluations (all points) used.
    pub evaluations: usize,
    /// Parameters that ended on a bound.
    pub at_bound: Vec<bool>,
    /// Why the iteration stopped.
    pub stop: Stop,
}

/// Why a bounded Levenberg-Marquardt iteration stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Stop {
    /// The SSE fell by less than 1e-10 of itself, or the step by less than 1e-6 of the scales.
    Converged,
    /// No damped step lowered the SSE (a minimum at the resolution of the model).
    NoDescent,
    /// Every step was projected back onto the point: the minimum lies beyond a bound.
    AtBound,
    /// The iteration limit was reached first.
    IterationLimit,
}

/// A residual function (its second argument: the call is a forward difference).
type Residuals<'a, E> = dyn FnMut(&[f64], bool) -> Result<Vec<f64>, E> + 'a;

/// The result of [`levenberg_marquardt`].
#[derive(Debug, Clone)]
pub struct LmResult {
    /// Parameters at the end.
    pub p: Vec<f64>,
    /// Residuals there.
    pub residuals: Vec<f64>,
    /// Jacobian there (forward differences).
    pub jacobian: DMatrix<f64>,
    /// Sum of squared residuals there.
    pub sse: f64,
    /// Why it stopped.
    pub stop: Stop,
    /// Parameters on a bound at the end.
    pub at_bound: Vec<bool>,
}

/// Bounded Levenberg-Marquardt on `residuals(p)`, from `start` (clamped into the bounds), in
/// coordinates scaled by `scale`; a parameter on a bound the descent pushes against is held
/// there, and a step leaving the box [`lo`, `hi`] is projected onto it.
/// The Jacobian is a forward difference of 1 % of each scale (backward at an upper bound).
pub fn levenberg_marquardt<E>(
    mut residuals: impl FnMut(&[f64]) -> Result<Vec<f64>, E>,
    start: &[f64],
    lo: &[f64],
    hi: &[f64],
    scale: &[f64],
) -> Result<LmResult, E> {
    levenberg_marquardt_near(|p: &[f64], _near: bool| residuals(p), start, lo, hi, scale)
}

/// [`levenberg_marquardt`] on a residual function told, by its second argument, whether a
/// call is one of the Jacobian's forward differences: parameters a hundredth of a scale from
/// those of the call before the differences (the last call with `false`), whose solves can
/// start from that call's.
pub fn levenberg_marquardt_near<E>(
    mut residuals: impl FnMut(&[f64], bool) -> Result<Vec<f64>, E>,
    start: &[f64],
    lo: &[f64],
    hi: &[f64],
    scale: &[f64],
) -> Result<LmResult, E> {
    let k = start.len();
    let mut p: Vec<f64> = start.iter().enumerate().map(|(i, &v)| v.clamp(lo[i], hi[i])).collect();
    let mut r = residuals(&p, false)?;
    let mut s = sse(&r);
    let mut lambda = 1e-3;
    let jac_of = |residuals: &mut Residuals<'_, E>, p: &[f64], r: &[f64]| {
        let mut j = DMatrix::zeros(r.len(), p.len());
        for c in 0..p.len() {
            let mut h = 0.01 * scale[c];
            if p[c] + h > hi[c] {
                h = -h;
            }
            let mut q = p.to_vec();
            q[c] += h;
            let rq = residuals(&q, true)?;
            for (i, (a, b)) in rq.iter().zip(r).enumerate() {
                j[(i, c)] = (a - b) / h;
            }
        }
        Ok::<_, E>(j)
    };
    let mut jac = jac_of(&mut residuals, &p, &r)?;
    let mut jac_at_p = true;
    let mut stop = Stop::IterationLimit;
    for _iter in 0..40 {
        if !jac_at_p {
            jac = jac_of(&mut residuals, &p, &r)?;
            jac_at_p = true;
        }
        // Scaled coordinates x = p / scale.
        let jx = DMatrix::from_fn(jac.nrows(), k, |i, c| jac[(i, c)] * scale[c]);
        let a = jx.transpose() * &jx;
        let g = jx.transpose() * DVector::from_column_slice(&r);
        // A parameter on a bound that the descent pushes outwards is held there and the step
        // solved for the others (an active set): projecting the full step instead leaves the
        // others with a step meant for a point outside the box, and the damping then creeps.
        let held: Vec<bool> = (0..k)
            .map(|c| (p[c] <= lo[c] && g[c] > 0.0) || (p[c] >= hi[c] && g[c] < 0.0))
            .collect();
        let mut g = g;
        for c in (0..k).filter(|&c| held[c]) {
            g[c] = 0.0;
        }
        let mut accepted = None;
        let mut projected = false;
        for _try in 0..10 {
            let mut m = a.clone();
            for d in 0..k {
                m[(d, d)] += lambda * a[(d, d)].max(1e-12);
            }
            for c in (0..k).filter(|&c| held[c]) {
                m.row_mut(c).fill(0.0);
                m.column_mut(c).fill(0.0);
                m[(c, c)] = 1.0;
            }
            let Some(dx) = m
                .clone()
                .cholesky()
                .map(|c| c.solve(&(-&g)))
                .or_else(|| m.lu().solve(&(-&g)))
            else {
                lambda *= 10.0;
                continue;
            };
            let q: Vec<f64> = (0..k).map(|c| (p[c] + dx[c] * scale[c]).clamp(lo[c], hi[c])).collect();
            if q == p {
                projected = true;
                break;
            }
            let rq = residuals(&q, false)?;
            let sq = sse(&rq);
            if sq < s {
                lambda = (lambda / 5.0).max(1e-10);
                let step = (0..k).map(|c| ((q[c] - p[c]) / scale[c]).abs()).fold(0.0, f64::max);
                accepted = Some((q, rq, sq, step));
                break;
            }
            lambda *= 5.0;
        }
        let Some((q, rq, sq, step)) = accepted else {
            stop = if projected { Stop::AtBound } else { Stop::NoDescent };
            break;
        };
        let gain = s - sq;
        p = q;
        r = rq;
        s = sq;
        jac_at_p = false;
        if gain <= 1e-10 * s + 1e-16 || step < 1e-6 {
            stop = Stop::Converged;
            break;
        }
    }
    if !jac_at_p {
        jac = jac_of(&mut residuals, &p, &r)?;
    }
    let at_bound = (0..k)
        .map(|c| {
            let tol = bound_tolerance(lo[c], hi[c], scale[c]);
            (p[c] - lo[c]).abs() < tol || (hi[c] - p[c]).abs() < tol
        })
        .collect();
    Ok(LmResult {
        p,
        residuals: r,
        jacobian: jac,
        sse: s,
        stop,
        at_bound,
    })
}

/// One fitted parameter, for the report and the JSON.
#[derive(Debug, Clone, Serialize)]
pub struct FittedParam {
    /// Effect id.
    pub effect: String,
    /// Parameter name.
    pub name: String,
    /// Unit.
    pub unit: String,
    /// Value.
    pub value: f64,
    /// Half-width of the 95 % interval (None: the data cannot determine it).
    pub ci95: Option<f64>,
    /// True when it ended on one of its physical bounds or its 95 % interval reaches one
    /// ([`on_bound`]; other than its neutral value: a friction torque of zero is no torque
    /// tare, not one that wants to be negative).
    pub at_bound: bool,
    /// The value at which the effect changes nothing, if it has one.
    pub neutral: Option<f64>,
    /// The range a physical cause would give ([`propbet_effects::Param::expected_range`]).
    pub expected: (f64, f64),
    /// The 95 % interval holds the neutral value: the data cannot tell the effect from its
    /// absence.
    pub holds_neutral: bool,
    /// The value lies outside the expected range: a calibration factor, not found physics.
    pub outside_expected: bool,
}

/// Whether a fitted parameter sits on one of its physical bounds: the fit ended on it
/// (`lm_at_bound`, within [`AT_BOUND_FRACTION`] of the range), or its 95 % interval (1.96 `sd`,
/// where the data determine it) reaches it, so that the data cannot tell the value from the
/// bound (the 9x4.7 SF's chord-scale 0.8536 ± 0.0063 against its bound 0.85). A bound that is
/// the parameter's neutral value does not count (an interval reaching a friction torque of zero
/// says the effect may be absent, which its significance test judges), nor does a value that
/// is the neutral one.
pub fn on_bound(value: f64, sd: Option<f64>, lm_at_bound: bool, p: &propbet_effects::Param) -> bool {
    let tol = bound_tolerance(p.lower, p.upper, p.scale);
    let neutral = |x: f64| p.neutral.is_some_and(|n| (x - n).abs() < tol);
    if neutral(value) {
        return false;
    }
    lm_at_bound
        || sd.is_some_and(|sd| {
            [p.lower, p.upper]
                .into_iter()
                .any(|b| b.is_finite() && !neutral(b) && (value - b).abs() < 1.96 * sd)
        })
}

/// Whether a fitted value's 95 % interval (`ci95`, its half-width; None where the data do not
/// determine it) holds the parameter's neutral value: the data cannot tell the effect from its
/// absence; an undetermined interval does too. A parameter without a neutral value never does.
pub fn holds_neutral(value: f64, ci95: Option<f64>, p: &propbet_effects::Param) -> bool {
    match (p.neutral, ci95) {
        (None, _) => false,
        (Some(n), Some(c)) => (value - n).abs() <= c,
        (Some(_), None) => true,
    }
}

/// Whether a fitted value lies outside the parameter's physically expected range.
pub fn outside_expected(value: f64, p: &propbet_effects::Param) -> bool {
    let (lo, hi) = p.expected_range();
    let tol = bound_tolerance(p.lower, p.upper, p.scale);
    value < lo - tol || value > hi + tol
}

/// How close to a bound a fitted value counts as on it: a thousandth of the parameter's range.
/// A bounded fit pressing against a bound can stop just short of it (a tip loss of 0.002 in
/// [0, 4], whose refit with a warm start then sat on 0); a 1e-9 tolerance let such a fit pass
/// as inside. An unbounded side keeps the tight tolerance.
pub const AT_BOUND_FRACTION: f64 = 1e-3;

fn bound_tolerance(lo: f64, hi: f64, scale: f64) -> f64 {
    let range = hi - lo;
    if range.is_finite() {
        AT_BOUND_FRACTION * range
    } else {
        1e-9 * scale
    }
}

impl FitOutcome {
    /// The parameters with their intervals.
    pub fn params(&self) -> Vec<FittedParam> {
        let mut out = Vec::new();
        let mut k = 0;
        for a in &self.stack.active {
            for p in a.effect.params() {
                let sd = self.sd[k];
                // An interval many times wider than the physical range says the data do not
                // determine the parameter (hub-loss 0 ± 1.03e5 on a static step test).
                let range = p.upper - p.lower;
                let determined = sd.is_finite() && (!range.is_finite() || 1.96 * sd <= 10.0 * range);
                out.push(FittedParam {
                    effect: a.effect.id().to_string(),
                    name: p.name.clone(),
                    unit: p.unit.clone(),
                    value: self.p[k],
                    ci95: determined.then_some(1.96 * sd),
                    at_bound: on_bound(self.p[k], determined.then_some(sd), self.at_bound[k], p),
                    neutral: p.neutral,
                    expected: p.expected_range(),
                    holds_neutral: holds_neutral(self.p[k], determined.then_some(1.96 * sd), p),
                    outside_expected: outside_expected(self.p[k], p),
                });
                k += 1;
            }
        }
        out
    }
}

impl FitOutcome {
    /// The parameters that ended on a physical bound (not their neutral value): the data want
    /// more than the effect can physically give.
    pub fn beyond_bounds(&self) -> Vec<FittedParam> {
        self.params().into_iter().filter(|p| p.at_bound).collect()
    }
}

/// The stack of `effects` at the flat parameter vector `p`.
pub fn stack_at(effects: &[Arc<dyn Effect>], p: &[f64]) -> Stack {
    let mut k = 0;
    let active = effects
        .iter()
        .map(|e| {
            let n = e.params().len();
            let values = p[k..k + n].to_vec();
            k += n;
            Active {
                effect: e.clone(),
                values,
            }
        })
        .collect();
    Stack { active }
}

/// Lower bounds, upper bounds and scales of the effects' parameters, flat.
pub fn bounds(effects: &[Arc<dyn Effect>]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let ps: Vec<_> = effects.iter().flat_map(|e| e.params().to_vec()).collect();
    (
        ps.iter().map(|p| p.lower).collect(),
        ps.iter().map(|p| p.upper).collect(),
        ps.iter().map(|p| p.scale).collect(),
    )
}

fn sse(r: &[f64]) -> f64 {
    r.iter().map(|x| x * x).sum()
}

/// Fits every parameter of `effects` to all points of `data`, from `start` (flat).
pub fn fit(
    model: &Model,
    data: &Data,
    effects: &[Arc<dyn Effect>],
    start: &[f64],
) -> Result<FitOutcome, DiagnoseError> {
    let (lo, hi, scale) = bounds(effects);
    let mut evaluations = 0;
    // The wake angles of the last solve that was not a forward difference: the differences'
    // solves start from them (the same roots in about two Newton steps instead of three).
    let mut psi = vec![Vec::new(); data.obs.len()];
    let lm = levenberg_marquardt_near(
        |p: &[f64], near: bool| {
            evaluations += 1;
            model.residuals_near(data, &stack_at(effects, p), &mut psi, near)
        },
        start,
        &lo,
        &hi,
        &scale,
    )?;
    let k = start.len();
    let dof = (lm.residuals.len() as f64 - k as f64).max(1.0);
    let sd = covariance_sd(&lm.jacobian, lm.sse / dof);
    Ok(FitOutcome {
        stack: stack_at(effects, &lm.p),
        p: lm.p,
        residuals: lm.residuals,
        jacobian: lm.jacobian,
        sse: lm.sse,
        sd,
        evaluations,
        at_bound: lm.at_bound,
        stop: lm.stop,
    })
}

/// Standard deviations from s^2 (J^T J)^+ (SVD pseudo-inverse; infinite for directions the
/// data does not constrain).
fn covariance_sd(jac: &DMatrix<f64>, s2: f64) -> Vec<f64> {
    let k = jac.ncols();
    if k == 0 {
        return Vec::new();
    }
    // Column scaling makes the conditioning test meaningful across units.
    let norms: Vec<f64> = (0..k).map(|c| jac.column(c).norm()).collect();
    let js = DMatrix::from_fn(jac.nrows(), k, |i, c| {
        if norms[c] > 0.0 {
            jac[(i, c)] / norms[c]
        } else {
            0.0
        }
    });
    let svd = (js.transpose() * &js).svd(true, true);
    let smax = svd.singular_values.max();
    let (Some(u), Some(vt)) = (svd.u.as_ref(), svd.v_t.as_ref()) else {
        return vec![f64::INFINITY; k];
    };
    (0..k)
        .map(|c| {
            if norms[c] == 0.0 {
                return f64::INFINITY;
            }
            let mut var = 0.0;
            for (m, &sv) in svd.singular_values.iter().enumerate() {
                if sv <= 1e-10 * smax {
                    if u[(c, m)].abs() > 1e-6 {
                        return f64::INFINITY;
                    }
                    continue;
                }
                var += u[(c, m)] * vt[(m, c)] / sv;
            }
            (s2 * var).sqrt() / norms[c]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// y = a exp(-b x) at ten points, exact.
    fn decay(a: f64, b: f64) -> (Vec<f64>, Vec<f64>) {
        let x: Vec<f64> = (0..10).map(|i| 0.3 * i as f64).collect();
        let y = x.iter().map(|x| a * (-b * x).exp()).collect();
        (x, y)
    }

    fn residuals<'a>(x: &'a [f64], y: &'a [f64]) -> impl FnMut(&[f64]) -> Result<Vec<f64>, ()> + 'a {
        move |p: &[f64]| Ok(x.iter().zip(y).map(|(x, y)| p[0] * (-p[1] * x).exp() - y).collect())
    }

    #[test]
    fn a_bounded_fit_recovers_a_known_truth() {
        let (x, y) = decay(2.0, 0.7);
        let r = levenberg_marquardt(residuals(&x, &y), &[1.0, 0.2], &[0.0, 0.0], &[5.0, 5.0], &[1.0, 1.0]).unwrap();
        assert_eq!(r.stop, Stop::Converged);
        assert!((r.p[0] - 2.0).abs() < 1e-6 && (r.p[1] - 0.7).abs() < 1e-6, "{:?}", r.p);
        assert!(r.sse < 1e-12);
        assert_eq!(r.at_bound, vec![false, false]);
        // The start is clamped into the box.
        let r = levenberg_marquardt(residuals(&x, &y), &[9.0, -1.0], &[0.0, 0.0], &[5.0, 5.0], &[1.0, 1.0]).unwrap();
        assert!((r.p[0] - 2.0).abs() < 1e-6, "{:?}", r.p);
    }

    #[test]
    fn an_active_bound_is_reported() {
        // The truth b = 0.7 lies above the upper bound 0.5: b ends on it, a compensates.
        let (x, y) = decay(2.0, 0.7);
        let r = levenberg_marquardt(residuals(&x, &y), &[1.0, 0.2], &[0.0, 0.0], &[5.0, 0.5], &[1.0, 1.0]).unwrap();
        assert_eq!(r.p[1], 0.5, "{:?}", r.p);
        assert_eq!(r.at_bound, vec![false, true]);
        assert!(
            matches!(r.stop, Stop::AtBound | Stop::Converged | Stop::NoDescent),
            "{:?}",
            r.stop
        );
        assert!(r.sse > 1e-4);
    }

    #[test]
    fn a_parameter_held_on_its_bound_lets_the_others_converge() {
        // y = a + b x over x in [10, 11], whose free fit wants a < 0: with a >= 0 the answer is
        // a = 0, b = sum(x y) / sum(x^2). a and b are nearly collinear here: a step projected
        // back onto the box creeps (the iteration limit), one with a held on its bound does not.
        let x: Vec<f64> = (0..11).map(|i| 10.0 + 0.1 * i as f64).collect();
        let y: Vec<f64> = x.iter().map(|x| -3.0 + 1.5 * x + 0.01 * (7.0 * x).sin()).collect();
        let mut calls = 0;
        let line = |p: &[f64]| {
            calls += 1;
            Ok::<_, ()>(x.iter().zip(&y).map(|(x, y)| p[0] + p[1] * x - y).collect::<Vec<_>>())
        };
        let r = levenberg_marquardt(line, &[1.0, 1.0], &[0.0, -10.0], &[10.0, 10.0], &[1.0, 0.1]).unwrap();
        let b = x.iter().zip(&y).map(|(x, y)| x * y).sum::<f64>() / x.iter().map(|x| x * x).sum::<f64>();
        assert_eq!(r.p[0], 0.0, "{:?}", r.p);
        assert!((r.p[1] - b).abs() < 1e-6 * b, "{:?} against b = {b}", r.p);
        assert_ne!(r.stop, Stop::IterationLimit);
        assert!(calls < 60, "{calls} evaluations");
    }

    /// A truth a hair inside the box (less than a thousandth of the range from the bound) is
    /// on the bound: the fit presses against it (a tip loss of 0.002 in [0, 4]); one a percent
    /// of the range inside is not.
    #[test]
    fn a_fit_a_thousandth_of_its_range_from_a_bound_is_on_it() {
        let (x, y) = decay(2.0, 0.4996);
        let r = levenberg_marquardt(residuals(&x, &y), &[1.0, 0.2], &[0.0, 0.0], &[5.0, 0.5], &[1.0, 1.0]).unwrap();
        assert!((r.p[1] - 0.4996).abs() < 1e-6, "{:?}", r.p);
        assert_eq!(r.at_bound, vec![false, true]);
        let (x, y) = decay(2.0, 0.495);
        let r = levenberg_marquardt(residuals(&x, &y), &[1.0, 0.2], &[0.0, 0.0], &[5.0, 0.5], &[1.0, 1.0]).unwrap();
        assert_eq!(r.at_bound, vec![false, false]);
    }

    #[test]
    fn a_fit_whose_interval_reaches_a_bound_is_on_it() {
        let chord = propbet_effects::Param::new("factor", "-", 1.0, (0.85, 1.15), 0.05, "");
        // The 9x4.7 SF's chord-scale: 0.8536 ± 0.0063 (1.96 sd) reaches 0.85; ± 0.003 does not.
        assert!(on_bound(0.8536, Some(0.0063 / 1.96), false, &chord));
        assert!(!on_bound(0.8536, Some(0.003 / 1.96), false, &chord));
        // Undetermined (no interval): only the fit's own end counts.
        assert!(!on_bound(0.8536, None, false, &chord));
        assert!(on_bound(0.85, None, true, &chord));
        // A friction torque whose lower bound is its neutral 0: an interval reaching 0 is not
        // "on its bound", nor is the neutral value itself; the upper bound still counts.
        let q0 = propbet_effects::Param::new("q0", "N m", 0.0, (0.0, 0.5), 0.01, "");
        assert!(!on_bound(0.0052, Some(0.01), false, &q0));
        assert!(!on_bound(0.0, None, true, &q0));
        assert!(on_bound(0.49, Some(0.01), false, &q0));
    }

    #[test]
    fn the_iteration_limit_is_reported_and_errors_pass_through() {
        // A residual that falls by a fixed fraction at every step without end: 1/(1 + p) is
        // halved by each Gauss-Newton step (p -> 2p + 1), so forty steps never converge.
        let r = levenberg_marquardt(
            |p: &[f64]| Ok::<_, ()>(vec![1.0 / (1.0 + p[0])]),
            &[0.0],
            &[0.0],
            &[1e300],
            &[1.0],
        )
        .unwrap();
        assert_eq!(r.stop, Stop::IterationLimit, "{:?}", r.p);
        let e = levenberg_marquardt(|_: &[f64]| Err::<Vec<f64>, _>("boom"), &[0.0], &[-1.0], &[1.0], &[1.0]);
        assert_eq!(e.unwrap_err(), "boom");
    }

    #[test]
    fn covariance_of_a_line_fit() {
        // y = p0 + p1 x at x = 0..4 with residual variance s2: var(p1) = s2 / sum (x - mean)^2.
        let jac = DMatrix::from_fn(5, 2, |i, c| if c == 0 { 1.0 } else { i as f64 });
        let sd = covariance_sd(&jac, 0.04);
        assert!((sd[1] - (0.04f64 / 10.0).sqrt()).abs() < 1e-12, "{sd:?}");
        // A parameter the data cannot see gets an infinite deviation.
        let blind = DMatrix::from_fn(5, 2, |i, c| if c == 0 { 1.0 } else { 0.0 * i as f64 });
        assert!(covariance_sd(&blind, 0.04)[1].is_infinite());
    }
}
