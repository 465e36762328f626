//! Bounded Levenberg-Marquardt fit of effect parameters to the residual rows.
//!
//! Parameters are scaled by each one's typical change ([`propbet_effects::Param::scale`]); a
//! step that leaves the bounds is projected back onto them; the Jacobian is a forward
//! difference of 1 % of the scale (the solver converges to 1e-6 in the wake angle, far below
//! that). No crate at hand does bounded LM (argmin has none; `levenberg-marquardt` has no
//! bounds), so it is written here, with nalgebra for the linear algebra.
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
    /// True when it ended on a bound.
    pub at_bound: bool,
}

impl FitOutcome {
    /// The parameters with their intervals.
    pub fn params(&self) -> Vec<FittedParam> {
        let mut out = Vec::new();
        let mut k = 0;
        for a in &self.stack.active {
            for p in a.effect.params() {
                let sd = self.sd[k];
                out.push(FittedParam {
                    effect: a.effect.id().to_string(),
                    name: p.name.clone(),
                    unit: p.unit.clone(),
                    value: self.p[k],
                    ci95: sd.is_finite().then_some(1.96 * sd),
                    at_bound: self.at_bound[k],
                });
                k += 1;
            }
        }
        out
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

struct Problem<'a> {
    model: &'a Model<'a>,
    data: &'a Data,
    effects: &'a [Arc<dyn Effect>],
    all: Vec<usize>,
    lo: Vec<f64>,
    hi: Vec<f64>,
    scale: Vec<f64>,
    evaluations: usize,
}

impl Problem<'_> {
    fn residuals(&mut self, p: &[f64]) -> Result<Vec<f64>, DiagnoseError> {
        self.evaluations += 1;
        Ok(self.model.residuals(self.data, &stack_at(self.effects, p), &self.all)?)
    }

    fn jacobian(&mut self, p: &[f64], r: &[f64]) -> Result<DMatrix<f64>, DiagnoseError> {
        let mut j = DMatrix::zeros(r.len(), p.len());
        for k in 0..p.len() {
            let mut h = 0.01 * self.scale[k];
            if p[k] + h > self.hi[k] {
                h = -h;
            }
            let mut q = p.to_vec();
            q[k] += h;
            let rq = self.residuals(&q)?;
            for (i, (a, b)) in rq.iter().zip(r).enumerate() {
                j[(i, k)] = (a - b) / h;
            }
        }
        Ok(j)
    }
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
    let mut pr = Problem {
        model,
        data,
        effects,
        all: (0..data.obs.len()).collect(),
        lo,
        hi,
        scale,
        evaluations: 0,
    };
    let k = start.len();
    let mut p: Vec<f64> = start
        .iter()
        .enumerate()
        .map(|(i, &v)| v.clamp(pr.lo[i], pr.hi[i]))
        .collect();
    let mut r = pr.residuals(&p)?;
    let mut s = sse(&r);
    let mut lambda = 1e-3;
    let mut jac = pr.jacobian(&p, &r)?;
    let mut jac_at_p = true;
    for _iter in 0..40 {
        if !jac_at_p {
            jac = pr.jacobian(&p, &r)?;
            jac_at_p = true;
        }
        // Scaled coordinates x = p / scale.
        let jx = DMatrix::from_fn(jac.nrows(), k, |i, c| jac[(i, c)] * pr.scale[c]);
        let a = jx.transpose() * &jx;
        let g = jx.transpose() * DVector::from_column_slice(&r);
        let mut accepted = None;
        for _try in 0..10 {
            let mut m = a.clone();
            for d in 0..k {
                m[(d, d)] += lambda * a[(d, d)].max(1e-12);
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
            let q: Vec<f64> = (0..k)
                .map(|c| (p[c] + dx[c] * pr.scale[c]).clamp(pr.lo[c], pr.hi[c]))
                .collect();
            if q == p {
                break;
            }
            let rq = pr.residuals(&q)?;
            let sq = sse(&rq);
            if sq < s {
                lambda = (lambda / 5.0).max(1e-10);
                let step = (0..k).map(|c| ((q[c] - p[c]) / pr.scale[c]).abs()).fold(0.0, f64::max);
                accepted = Some((q, rq, sq, step));
                break;
            }
            lambda *= 5.0;
        }
        let Some((q, rq, sq, step)) = accepted else {
            break;
        };
        let gain = s - sq;
        p = q;
        r = rq;
        s = sq;
        jac_at_p = false;
        if gain <= 1e-10 * s + 1e-16 || step < 1e-6 {
            break;
        }
    }
    if !jac_at_p {
        jac = pr.jacobian(&p, &r)?;
    }
    let dof = (r.len() as f64 - k as f64).max(1.0);
    let s2 = s / dof;
    let sd = covariance_sd(&jac, s2);
    let at_bound = (0..k)
        .map(|c| (p[c] - pr.lo[c]).abs() < 1e-9 * pr.scale[c] || (pr.hi[c] - p[c]).abs() < 1e-9 * pr.scale[c])
        .collect();
    Ok(FitOutcome {
        stack: stack_at(effects, &p),
        p,
        residuals: r,
        jacobian: jac,
        sse: s,
        sd,
        evaluations: pr.evaluations,
        at_bound,
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
