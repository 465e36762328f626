//! One station's solve, as QPROP's `GVCALC` does it (Newton on the wake angle `psi`), with the
//! bracketed Brent solve on the whole velocity circle where Newton fails, and the loads at the
//! solved state (`TQCALC`): every station converges or says it did not, never NaN.

use argmin::core::{CostFunction, Executor};
use argmin::solver::brent::BrentRoot;

use super::{prandtl, Convergence, SolverOptions, StationResult};
use crate::aero::{DragInput, MSQ_MAX};
use crate::fluid::Fluid;
use crate::rotor::Station;

/// Everything about the operating point a station solve needs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ctx {
    pub(crate) blades: f64,
    pub(crate) tip: f64,
    pub(crate) v: f64,
    pub(crate) omega: f64,
    pub(crate) fluid: Fluid,
    pub(crate) opts: SolverOptions,
}

/// The state at one value of psi, with d(residual)/d(psi).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Eval {
    pub(crate) res: f64,
    pub(crate) res_psi: f64,
    pub(crate) wa: f64,
    pub(crate) wt: f64,
    pub(crate) w: f64,
    pub(crate) msq: f64,
    pub(crate) alpha: f64,
    pub(crate) cl: f64,
    pub(crate) stalled: bool,
    pub(crate) f_tip: f64,
    pub(crate) lambda_w: f64,
    pub(crate) gamma: f64,
}

/// Residual and its analytic derivative at `psi` (QPROP `GVCALC`, one Newton pass).
#[inline]
fn eval(st: &Station, c: &Ctx, beta: f64, ua: f64, ut: f64, u: f64, psi: f64) -> Eval {
    let (sinp, cosp) = psi.sin_cos();
    let wa = 0.5 * ua + 0.5 * u * sinp;
    let wa_p = 0.5 * u * cosp;
    let wt = 0.5 * ut + 0.5 * u * cosp;
    let wt_p = -0.5 * u * sinp;

    // Modified Prandtl factor and wake advance ratio. QPROP leaves F = 1 when Wa = 0; we do
    // the same when Wt = 0 (no finite helix), and use |f| for reverse flow, where QPROP's
    // acos(exp(-f)) would be NaN.
    let (f_tip, f_p, adw, adw_p) = if wa != 0.0 && wt != 0.0 {
        let tsr = wt / wa * c.tip / st.r;
        let tsr_p = (wt_p * c.tip / st.r - tsr * wa_p) / wa;
        let (mut f, mut f_p) = match c.opts.tip_divisor() {
            Some(s) => prandtl(0.5 * c.blades * (1.0 - st.r / c.tip) / s, tsr, tsr_p),
            None => (1.0, 0.0),
        };
        let (s_h, r_h) = (c.opts.hub_loss_strength, c.opts.hub_radius);
        if s_h > 0.0 && r_h > 0.0 && st.r > r_h {
            // 1/tan(phi) = tsr r/R.
            let k = 0.5 * c.blades * (st.r - r_h) / r_h * st.r / c.tip / s_h;
            let (h, h_p) = prandtl(k, tsr, tsr_p);
            (f, f_p) = (f * h, f_p * h + f * h_p);
        }
        (f, f_p, 1.0 / tsr, -tsr_p / (tsr * tsr))
    } else {
        (1.0, 0.0, 0.0, 0.0)
    };

    let vt = ut - wt;
    let vt_p = -wt_p;
    let qbi = 4.0 / c.blades;
    let pi_r = std::f64::consts::PI * st.r;
    let pir = (pi_r * pi_r + (qbi * c.tip * adw).powi(2)).sqrt();
    let pir_p = (qbi * c.tip).powi(2) * adw / pir * adw_p;
    let gamma = qbi * f_tip * vt * pir;
    let gam_p = qbi * (f_tip * vt_p + f_p * vt) * pir + qbi * f_tip * vt * pir_p;

    let wsq = wa * wa + wt * wt;
    let w = wsq.sqrt();
    let w_p = (wa * wa_p + wt * wt_p) / w;
    let alpha = beta - wa.atan2(wt);
    let alpha_p = (-wt * wa_p + wa * wt_p) / wsq;
    let a2 = c.fluid.a * c.fluid.a;
    let (msq, msq_p) = if wsq / a2 > MSQ_MAX {
        (MSQ_MAX, 0.0)
    } else {
        (wsq / a2, 2.0 * w * w_p / a2)
    };
    let re = c.fluid.rho * w * st.chord / c.fluid.mu;
    let re_p = c.fluid.rho * st.chord * w_p / c.fluid.mu;
    let lift = st.aero.lift(alpha, re, msq);
    let cl_p = lift.dcl_dalpha * alpha_p + lift.dcl_dmsq * msq_p + lift.dcl_dre * re_p;
    let res = gamma - 0.5 * st.chord * lift.cl * w;
    let res_p = gam_p - 0.5 * st.chord * (lift.cl * w_p + cl_p * w);
    Eval {
        res,
        res_psi: res_p,
        wa,
        wt,
        w,
        msq,
        alpha,
        cl: lift.cl,
        stalled: lift.stalled,
        f_tip,
        lambda_w: adw,
        gamma,
    }
}

pub(crate) fn solve_station(st: &Station, c: &Ctx) -> StationResult {
    solve_station_from(st, c, None).0
}

/// [`solve_station`] with Newton started from `warm` where it is given and finite (the wake
/// angle of a nearby solve): the same root in fewer iterations. A warm start that does not
/// converge falls back to the cold solve. Also returns the wake angle Newton converged at
/// (None where the station needed no iteration or the bracketed solve).
pub(crate) fn solve_station_from(st: &Station, c: &Ctx, warm: Option<f64>) -> (StationResult, Option<f64>) {
    let beta = st.beta + c.opts.dbeta;
    let ua = c.v;
    let ut = c.omega * st.r;
    let u = (ua * ua + ut * ut).sqrt();
    if u == 0.0 {
        return (unloaded(st.r, st.chord, beta, Convergence::NoFlow), None);
    }
    if c.omega == 0.0 {
        return (parked(st, c, beta), None);
    }
    let psi0 = ua.atan2(ut);
    if st.chord == 0.0 {
        // Gamma = 0 is the exact solution: no induction.
        let e = eval(st, c, beta, ua, ut, u, psi0);
        return (finish(st, c, beta, ua, ut, &e, Convergence::ZeroChord), None);
    }
    let triangle = Triangle { beta, ua, ut, u };
    if let Some(found) = warm.filter(|w| w.is_finite()).and_then(|w| newton(st, c, &triangle, w)) {
        return found;
    }
    let start = psi0.max(beta - st.aero.alpha_zero_lift());
    newton(st, c, &triangle, start).unwrap_or_else(|| (bracketed(st, c, beta, ua, ut, u, psi0, start), None))
}

/// A station's twist and velocity triangle at one operating point.
#[derive(Clone, Copy)]
struct Triangle {
    beta: f64,
    ua: f64,
    ut: f64,
    u: f64,
}

/// QPROP's Newton iteration on psi from `start`: the result and its psi, None where it fails.
fn newton(st: &Station, c: &Ctx, t: &Triangle, start: f64) -> Option<(StationResult, Option<f64>)> {
    let Triangle { beta, ua, ut, u } = *t;
    let mut psi = start;
    for iter in 1..=c.opts.max_newton {
        let e = eval(st, c, beta, ua, ut, u, psi);
        let dpsi = -e.res / e.res_psi;
        if !dpsi.is_finite() || !e.res.is_finite() {
            return None;
        }
        let dpsi = dpsi.clamp(-0.1, 0.1);
        if dpsi.abs() < c.opts.tol {
            let r = finish(st, c, beta, ua, ut, &e, Convergence::Newton { iterations: iter });
            return Some((r, Some(psi)));
        }
        psi += dpsi;
    }
    None
}

/// Guaranteed-convergence fallback (after Ning 2014): sample the residual around the whole
/// velocity circle psi in (psi0 - pi, psi0 + pi), where W vanishes only at the ends, take the
/// sign change nearest QPROP's Newton start, and solve it with Brent's method.
#[allow(clippy::too_many_arguments)]
fn bracketed(st: &Station, c: &Ctx, beta: f64, ua: f64, ut: f64, u: f64, psi0: f64, start: f64) -> StationResult {
    const SAMPLES: usize = 90;
    let pi = std::f64::consts::PI;
    let step = 2.0 * pi / SAMPLES as f64;
    let grid: Vec<(f64, Eval)> = (0..SAMPLES)
        .map(|k| {
            let psi = psi0 - pi + (k as f64 + 0.5) * step;
            (psi, eval(st, c, beta, ua, ut, u, psi))
        })
        .collect();
    let mut best: Option<(f64, f64, f64)> = None; // (distance to start, lo, hi)
    for pair in grid.windows(2) {
        let (p0, e0) = pair[0];
        let (p1, e1) = pair[1];
        if e0.res.is_finite() && e1.res.is_finite() && (e0.res <= 0.0) != (e1.res <= 0.0) {
            let d = (0.5 * (p0 + p1) - start).abs();
            if best.is_none_or(|b| d < b.0) {
                best = Some((d, p0, p1));
            }
        }
    }
    let smallest = |grid: &[(f64, Eval)]| {
        grid.iter()
            .filter(|(_, e)| e.res.is_finite())
            .min_by(|a, b| a.1.res.abs().total_cmp(&b.1.res.abs()))
            .map(|(_, e)| *e)
    };
    if let Some((_, lo, hi)) = best {
        let problem = Residual {
            f: &|p: f64| eval(st, c, beta, ua, ut, u, p).res,
        };
        let solver = BrentRoot::new(lo, hi, 1e-13);
        let run = Executor::new(problem, solver)
            .configure(|s| s.param(0.5 * (lo + hi)).max_iters(200))
            .run();
        if let Ok(out) = run {
            let iterations = out.state.iter as u32;
            if let Some(&p) = out.state.best_param.as_ref() {
                let e = eval(st, c, beta, ua, ut, u, p);
                let scale = e.gamma.abs() + 0.5 * st.chord * (e.cl * e.w).abs() + f64::MIN_POSITIVE;
                if e.res.is_finite() && e.res.abs() <= 1e-8 * scale {
                    return finish(st, c, beta, ua, ut, &e, Convergence::Bracketed { iterations });
                }
            }
        }
    }
    match smallest(&grid) {
        Some(e) => finish(st, c, beta, ua, ut, &e, Convergence::NotConverged),
        None => unloaded(st.r, st.chord, beta, Convergence::NotConverged),
    }
}

/// The residual as an argmin problem.
struct Residual<'a> {
    f: &'a dyn Fn(f64) -> f64,
}

impl CostFunction for Residual<'_> {
    type Param = f64;
    type Output = f64;
    fn cost(&self, p: &f64) -> Result<f64, argmin::core::Error> {
        Ok((self.f)(*p))
    }
}

/// Drag and loads at a solved state (QPROP `TQCALC`).
pub(crate) fn finish(st: &Station, c: &Ctx, beta: f64, ua: f64, ut: f64, e: &Eval, conv: Convergence) -> StationResult {
    let re = c.fluid.rho * e.w * st.chord / c.fluid.mu;
    let mach_drag = e.msq.sqrt().max(1e-8);
    let cd = st.aero.drag(&DragInput {
        alpha: e.alpha,
        cl: e.cl,
        stalled: e.stalled,
        re,
        mach: mach_drag,
    });
    station_result(st, c, beta, ua, ut, e, re, cd, conv)
}

/// The station's result from its solved state, Reynolds number and drag: loads (QPROP
/// `TQCALC`), induced velocities, and the no-NaN check. Shared by the scalar and vector paths.
#[allow(clippy::too_many_arguments)]
pub(crate) fn station_result(
    st: &Station,
    c: &Ctx,
    beta: f64,
    ua: f64,
    ut: f64,
    e: &Eval,
    re: f64,
    cd: f64,
    conv: Convergence,
) -> StationResult {
    let hrc = 0.5 * c.fluid.rho * st.chord;
    let fa = hrc * e.w * (e.cl * e.wt - cd * e.wa);
    let ft = hrc * e.w * (e.cl * e.wa + cd * e.wt);
    let out = StationResult {
        r: st.r,
        chord: st.chord,
        beta,
        alpha: e.alpha,
        cl: e.cl,
        cd,
        re,
        mach: e.w / c.fluid.a,
        w: e.w,
        wa: e.wa,
        wt: e.wt,
        va: e.wa - ua,
        vt: ut - e.wt,
        f_tip: e.f_tip,
        lambda_w: e.lambda_w,
        gamma: e.gamma,
        dt_dr: c.blades * fa,
        dq_dr: c.blades * ft * st.r,
        stalled: e.stalled,
        residual: e.res,
        dpsi: if e.res_psi != 0.0 { -e.res / e.res_psi } else { 0.0 },
        convergence: conv,
    };
    sanitize(out)
}

/// A non-rotating rotor in axial flow: section forces in the undisturbed flow, no induction.
fn parked(st: &Station, c: &Ctx, beta: f64) -> StationResult {
    let wa = c.v;
    let w = wa.abs();
    let alpha = beta - wa.atan2(0.0);
    let msq = (w * w / (c.fluid.a * c.fluid.a)).min(MSQ_MAX);
    let re = c.fluid.rho * w * st.chord / c.fluid.mu;
    let lift = st.aero.lift(alpha, re, msq);
    let e = Eval {
        res: 0.0,
        res_psi: 0.0,
        wa,
        wt: 0.0,
        w,
        msq,
        alpha,
        cl: lift.cl,
        stalled: lift.stalled,
        f_tip: 1.0,
        lambda_w: 0.0,
        gamma: 0.0,
    };
    finish(st, c, beta, c.v, 0.0, &e, Convergence::NoRotation)
}

fn unloaded(r: f64, chord: f64, beta: f64, conv: Convergence) -> StationResult {
    StationResult {
        r,
        chord,
        beta,
        alpha: 0.0,
        cl: 0.0,
        cd: 0.0,
        re: 0.0,
        mach: 0.0,
        w: 0.0,
        wa: 0.0,
        wt: 0.0,
        va: 0.0,
        vt: 0.0,
        f_tip: 1.0,
        lambda_w: 0.0,
        gamma: 0.0,
        dt_dr: 0.0,
        dq_dr: 0.0,
        stalled: false,
        residual: 0.0,
        dpsi: 0.0,
        convergence: conv,
    }
}

/// Last line of defence for the no-NaN guarantee: a station whose state is not finite is
/// reported unloaded and not converged rather than poisoning the integrals.
fn sanitize(s: StationResult) -> StationResult {
    let values = [
        s.alpha, s.cl, s.cd, s.re, s.mach, s.w, s.wa, s.wt, s.va, s.vt, s.f_tip, s.lambda_w, s.gamma, s.dt_dr, s.dq_dr,
        s.residual, s.dpsi,
    ];
    if values.iter().all(|v| v.is_finite()) {
        s
    } else {
        unloaded(s.r, s.chord, s.beta, Convergence::NotConverged)
    }
}
