//! The per-station solve and the integration of loads at one operating point, exactly as
//! QPROP 1.22 does it (`GVCALC` + `TQCALC`; `../shared/reference/qprop/FORMULATION.md`),
//! made robust: Newton on the wake angle `psi` from QPROP's start, and where Newton fails a
//! bracketed Brent solve on the whole velocity circle, so that every station either converges
//! or says it did not, and no output is ever NaN.
//!
//! Velocity triangle (one unknown, `psi`): with $U_a = V$, $U_t = \Omega r$, $U = |U|$,
//! $$W_a = \tfrac12 U_a + \tfrac12 U\sin\psi,\quad W_t = \tfrac12 U_t + \tfrac12 U\cos\psi,$$
//! induced $v_a = W_a - U_a$, $v_t = U_t - W_t$. Tip factor with $\lambda_w = (r/R)W_a/W_t$,
//! $f = \tfrac B2(1 - r/R)/\lambda_w$ (capped at 20), $F = \tfrac2\pi\arccos e^{-f}$; circulation
//! $\Gamma = v_t\,\tfrac{4\pi r}{B}\,F\sqrt{1 + (4\lambda_w R/(\pi B r))^2}$; residual
//! $\Gamma - \tfrac12 W c\, c_l$.

use argmin::core::{CostFunction, Executor};
use argmin::solver::brent::BrentRoot;
use serde::{Deserialize, Serialize};

use crate::aero::{DragInput, MSQ_MAX};
use crate::fluid::Fluid;
use crate::rotor::{Rotor, Station};

/// QPROP's value of pi (`DATA PI / 3.14159265 /`); it differs from pi by 1e-9 relative, far
/// below QPROP's 4 printed digits, so propbet uses the true value and keeps this for reference.
#[allow(clippy::approx_constant)]
pub const QPROP_PI: f64 = 3.14159265;

/// One operating point: axial speed and rotation rate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OperatingPoint {
    /// Axial (flight) speed [m/s]; negative for reverse flow.
    pub v: f64,
    /// Rotation rate [rad/s], not negative.
    pub omega: f64,
}

impl OperatingPoint {
    /// The point at `rpm` [1/min] and `v` [m/s].
    pub fn from_rpm(v: f64, rpm: f64) -> Self {
        Self {
            v,
            omega: crate::units::rpm_to_omega(rpm),
        }
    }
}

/// Solver settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SolverOptions {
    /// Apply the (modified Prandtl) tip-loss factor F; off sets F = 1.
    pub tip_loss: bool,
    /// Collective blade-angle change added to every station [rad] (QPROP's `Dbeta`).
    pub dbeta: f64,
    /// Newton iterations before the bracketed fallback (QPROP: 20).
    pub max_newton: u32,
    /// Newton convergence on |d psi| [rad] (QPROP: 1e-6).
    pub tol: f64,
    /// Keep the per-station results in [`PointResult::stations`].
    pub keep_stations: bool,
    /// Strength of the tip-loss factor: its exponent `f` is divided by it (1 = QPROP's
    /// modified Prandtl factor; towards 0 the loss vanishes, above 1 it reaches further inboard).
    pub tip_loss_strength: f64,
    /// Strength of a Prandtl hub-loss factor, `f_hub = (B/2) (r - r_hub)/r_hub / tan(phi) / s`
    /// (0 = no hub loss, QPROP's model; 1 = Prandtl's).
    pub hub_loss_strength: f64,
    /// Hub radius the hub-loss factor vanishes at [m].
    pub hub_radius: f64,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            tip_loss: true,
            dbeta: 0.0,
            max_newton: 20,
            tol: 1e-6,
            keep_stations: false,
            tip_loss_strength: 1.0,
            hub_loss_strength: 0.0,
            hub_radius: 0.0,
        }
    }
}

impl SolverOptions {
    /// True when the vectorised path reproduces these options (it has no hub loss).
    pub(crate) fn vector_ok(&self) -> bool {
        self.hub_loss_strength == 0.0
    }

    /// The tip-loss exponent's divisor, or `None` when there is no tip loss.
    pub(crate) fn tip_divisor(&self) -> Option<f64> {
        (self.tip_loss && self.tip_loss_strength > 0.0).then_some(self.tip_loss_strength)
    }
}

/// Prandtl's factor `F = (2/pi) acos(exp(-|k tsr|))` (exponent capped at 20) and its derivative
/// with respect to psi, given `tsr` and d(tsr)/d(psi).
#[inline]
fn prandtl(k: f64, tsr: f64, tsr_p: f64) -> (f64, f64) {
    let sign = if tsr < 0.0 { -1.0 } else { 1.0 };
    let farg = (k * tsr * sign).min(20.0);
    let farg_tsr = k * sign;
    let fexp = (-farg).exp();
    let f = (2.0 / std::f64::consts::PI) * fexp.acos();
    let f_tsr = if fexp < 1.0 {
        (2.0 / std::f64::consts::PI) / (1.0 - fexp * fexp).sqrt() * fexp * farg_tsr
    } else {
        0.0
    };
    (f, f_tsr * tsr_p)
}

/// How a station's solution was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "status")]
pub enum Convergence {
    /// Newton from QPROP's start converged.
    Newton {
        /// Residual evaluations used.
        iterations: u32,
    },
    /// Newton failed; a bracketed Brent solve converged.
    Bracketed {
        /// Brent iterations used.
        iterations: u32,
    },
    /// No root found (for example a bracket that straddles the stall jump of the lift
    /// model); the state with the smallest residual is reported.
    NotConverged,
    /// No flow at the station (V = 0 and no rotation): zero loads.
    NoFlow,
    /// The rotor does not turn: blade-element forces in the undisturbed axial flow, no
    /// induction.
    NoRotation,
    /// Zero chord: no circulation, no loads.
    ZeroChord,
}

impl Convergence {
    /// True unless the station failed to converge.
    pub fn is_ok(&self) -> bool {
        !matches!(self, Convergence::NotConverged)
    }
}

/// The solved state of one station.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StationResult {
    /// Radius [m].
    pub r: f64,
    /// Chord [m].
    pub chord: f64,
    /// Blade angle including the collective change [rad].
    pub beta: f64,
    /// Angle of attack [rad].
    pub alpha: f64,
    /// Lift coefficient [-].
    pub cl: f64,
    /// Drag coefficient [-].
    pub cd: f64,
    /// Chord Reynolds number [-].
    pub re: f64,
    /// Local Mach number W/a (not capped) [-].
    pub mach: f64,
    /// Total relative speed [m/s].
    pub w: f64,
    /// Axial velocity through the disc [m/s].
    pub wa: f64,
    /// Tangential velocity relative to the blade [m/s].
    pub wt: f64,
    /// Axial induced velocity [m/s].
    pub va: f64,
    /// Tangential induced (swirl) velocity [m/s].
    pub vt: f64,
    /// Tip-loss factor F [-].
    pub f_tip: f64,
    /// Local wake advance ratio lambda_w = (r/R) Wa/Wt [-].
    pub lambda_w: f64,
    /// Circulation [m^2/s].
    pub gamma: f64,
    /// Thrust per unit radius, all blades [N/m].
    pub dt_dr: f64,
    /// Torque per unit radius, all blades [N].
    pub dq_dr: f64,
    /// Whether the lift model reported stall.
    pub stalled: bool,
    /// Final residual Gamma - W c cl / 2 [m^2/s].
    pub residual: f64,
    /// The Newton step -residual/(d residual/d psi) at the reported state [rad]: below the
    /// tolerance for a converged station (QPROP does not apply this last step).
    pub dpsi: f64,
    /// How the solution was obtained.
    pub convergence: Convergence,
}

/// Integrated results at one operating point.
///
/// Coefficients use the UIUC convention (CT = T/(rho n^2 D^4), CP = P/(rho n^3 D^5),
/// CQ = Q/(rho n^2 D^5), J = V/(nD)); QPROP's tip-speed coefficients are kept separately.
/// Where a coefficient is undefined (no rotation) it is `None`, never NaN.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PointResult {
    /// Axial speed [m/s].
    pub v: f64,
    /// Rotation rate [rad/s].
    pub omega: f64,
    /// Rotation rate [1/min].
    pub rpm: f64,
    /// Thrust [N].
    pub thrust: f64,
    /// Torque [N m].
    pub torque: f64,
    /// Shaft power Q Omega [W].
    pub power: f64,
    /// Advance ratio J = V/(nD) [-].
    pub j: Option<f64>,
    /// Thrust coefficient T/(rho n^2 D^4) [-].
    pub ct: Option<f64>,
    /// Power coefficient P/(rho n^3 D^5) [-].
    pub cp: Option<f64>,
    /// Torque coefficient Q/(rho n^2 D^5) [-].
    pub cq: Option<f64>,
    /// Propeller efficiency T V / P [-] (0 where P = 0, as QPROP).
    pub eta: f64,
    /// QPROP's advance ratio V/(Omega R) [-].
    pub adv_qprop: Option<f64>,
    /// QPROP's thrust coefficient T/(rho/2 (Omega R)^2 pi R^2) [-].
    pub ct_qprop: Option<f64>,
    /// QPROP's power coefficient Q/(rho/2 (Omega R)^2 pi R^3) [-].
    pub cp_qprop: Option<f64>,
    /// Actuator-disc slipstream velocity increment sqrt(V^2 + 2T/(rho pi R^2)) - V [m/s].
    pub dv: f64,
    /// Thrust-weighted (W^2 c dr) mean lift coefficient [-].
    pub cl_avg: f64,
    /// Thrust-weighted (W^2 c dr) mean drag coefficient [-].
    pub cd_avg: f64,
    /// Number of stations that did not converge.
    pub not_converged: usize,
    /// Per-station states (only with [`SolverOptions::keep_stations`]).
    pub stations: Vec<StationResult>,
}

/// Solves one operating point on the scalar path, station by station: the reference the
/// vectorised path ([`crate::solve_point`], [`crate::Solver`]) is checked against.
///
/// The rotor must satisfy [`Rotor::validate`]; the operating point must be finite with a
/// non-negative rotation rate (the CLI checks user input before this point).
pub fn solve_point_scalar(rotor: &Rotor, fluid: &Fluid, op: OperatingPoint, opts: &SolverOptions) -> PointResult {
    let ctx = context(rotor, fluid, op, opts);
    integrate(
        rotor,
        fluid,
        op,
        opts,
        rotor.stations.iter().map(|st| solve_station(st, &ctx)),
    )
}

/// The context of one operating point for the station solves.
pub(crate) fn context(rotor: &Rotor, fluid: &Fluid, op: OperatingPoint, opts: &SolverOptions) -> Ctx {
    Ctx {
        blades: rotor.blades,
        tip: rotor.tip_radius,
        v: op.v,
        omega: op.omega,
        fluid: *fluid,
        opts: *opts,
    }
}

/// Running sums of a point's station loads (midpoint rule, QPROP `TQCALC`).
#[derive(Debug, Clone, Default)]
pub(crate) struct Sums {
    pub(crate) thrust: f64,
    pub(crate) torque: f64,
    /// Sum of W^2 c dr, and the same weighted by cl and cd (qprop.f cl_avg, cd_avg).
    pub(crate) wsum: f64,
    pub(crate) clsum: f64,
    pub(crate) cdsum: f64,
    pub(crate) not_converged: usize,
}

impl Sums {
    pub(crate) fn add(&mut self, st: &Station, s: &StationResult) {
        self.thrust += s.dt_dr * st.dr;
        self.torque += s.dq_dr * st.dr;
        let wgt = s.w * s.w * st.chord * st.dr;
        self.wsum += wgt;
        self.clsum += wgt * s.cl;
        self.cdsum += wgt * s.cd;
        if !s.convergence.is_ok() {
            self.not_converged += 1;
        }
    }
}

/// Integrates station results into the point result.
pub(crate) fn integrate(
    rotor: &Rotor,
    fluid: &Fluid,
    op: OperatingPoint,
    opts: &SolverOptions,
    results: impl Iterator<Item = StationResult>,
) -> PointResult {
    let mut sums = Sums::default();
    let mut stations = Vec::with_capacity(if opts.keep_stations { rotor.stations.len() } else { 0 });
    for (st, s) in rotor.stations.iter().zip(results) {
        sums.add(st, &s);
        if opts.keep_stations {
            stations.push(s);
        }
    }
    point_result(rotor, fluid, op, &sums, stations)
}

/// Totals and coefficients from the summed loads (qprop.f output block).
pub(crate) fn point_result(
    rotor: &Rotor,
    fluid: &Fluid,
    op: OperatingPoint,
    sums: &Sums,
    stations: Vec<StationResult>,
) -> PointResult {
    let (thrust, torque) = (sums.thrust, sums.torque);
    let rho = fluid.rho;
    let big_r = rotor.tip_radius;
    loads_result(big_r, rho, op, thrust, torque, sums, stations)
}

impl PointResult {
    /// The same solution with other loads at another (logged) rotation rate and density, as a
    /// measurement chain would report it: power, coefficients, efficiency and the slipstream
    /// follow the new values; the station states and mean coefficients stay.
    pub fn with_loads(&self, thrust: f64, torque: f64, omega: f64, rho: f64, tip_radius: f64) -> PointResult {
        let sums = Sums {
            thrust,
            torque,
            wsum: 1.0,
            clsum: self.cl_avg,
            cdsum: self.cd_avg,
            not_converged: self.not_converged,
        };
        let op = OperatingPoint { v: self.v, omega };
        loads_result(tip_radius, rho, op, thrust, torque, &sums, self.stations.clone())
    }
}

fn loads_result(
    big_r: f64,
    rho: f64,
    op: OperatingPoint,
    thrust: f64,
    torque: f64,
    sums: &Sums,
    stations: Vec<StationResult>,
) -> PointResult {
    let power = torque * op.omega;
    let eta = if power != 0.0 { thrust * op.v / power } else { 0.0 };
    let disc = std::f64::consts::PI * big_r * big_r;
    let dv = ((op.v * op.v + 2.0 * thrust / (rho * disc)).max(0.0)).sqrt() - op.v;
    let (j, ct, cp, cq, adv, ctq, cpq) = if op.omega > 0.0 {
        let n = crate::units::omega_to_rev_per_s(op.omega);
        let scale = crate::units::Scales::new(rho, n, 2.0 * big_r);
        let d = 2.0 * big_r;
        let wr = op.omega * big_r;
        let qdisc = 0.5 * rho * wr * wr * disc;
        (
            Some(op.v / (n * d)),
            Some(thrust / scale.thrust),
            Some(power / scale.power),
            Some(torque / scale.torque),
            Some(op.v / wr),
            Some(thrust / qdisc),
            Some(torque / (qdisc * big_r)),
        )
    } else {
        (None, None, None, None, None, None, None)
    };
    let avg = |s: f64| if sums.wsum > 0.0 { s / sums.wsum } else { 0.0 };
    PointResult {
        v: op.v,
        omega: op.omega,
        rpm: crate::units::omega_to_rpm(op.omega),
        thrust,
        torque,
        power,
        j,
        ct,
        cp,
        cq,
        eta,
        adv_qprop: adv,
        ct_qprop: ctq,
        cp_qprop: cpq,
        dv,
        cl_avg: avg(sums.clsum),
        cd_avg: avg(sums.cdsum),
        not_converged: sums.not_converged,
        stations,
    }
}

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
    let beta = st.beta + c.opts.dbeta;
    let ua = c.v;
    let ut = c.omega * st.r;
    let u = (ua * ua + ut * ut).sqrt();
    if u == 0.0 {
        return unloaded(st.r, st.chord, beta, Convergence::NoFlow);
    }
    if c.omega == 0.0 {
        return parked(st, c, beta);
    }
    let psi0 = ua.atan2(ut);
    if st.chord == 0.0 {
        // Gamma = 0 is the exact solution: no induction.
        let e = eval(st, c, beta, ua, ut, u, psi0);
        return finish(st, c, beta, ua, ut, &e, Convergence::ZeroChord);
    }
    let start = psi0.max(beta - st.aero.alpha_zero_lift());
    let mut psi = start;
    for iter in 1..=c.opts.max_newton {
        let e = eval(st, c, beta, ua, ut, u, psi);
        let dpsi = -e.res / e.res_psi;
        if !dpsi.is_finite() || !e.res.is_finite() {
            break;
        }
        let dpsi = dpsi.clamp(-0.1, 0.1);
        if dpsi.abs() < c.opts.tol {
            return finish(st, c, beta, ua, ut, &e, Convergence::Newton { iterations: iter });
        }
        psi += dpsi;
    }
    bracketed(st, c, beta, ua, ut, u, psi0, start)
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
