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

use serde::{Deserialize, Serialize};

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

/// Where each station's Newton iteration starts.
#[derive(Debug)]
pub enum Psi<'a> {
    /// QPROP's cold start at every station.
    Cold,
    /// The cold start, with the wake angles solved left in the vector, one a station (NaN
    /// where Newton did not give one).
    Record(&'a mut Vec<f64>),
    /// Each station from the wake angle at its index where it is finite (a nearby solve's,
    /// recorded with [`Psi::Record`]), the cold start otherwise or where that fails: the same
    /// roots in fewer iterations, for solves of one point with a model a little apart (the
    /// diagnosis' forward differences).
    From(&'a [f64]),
}

/// [`solve_point_scalar`] with each station's Newton iteration started as `psi` says.
pub fn solve_point_scalar_psi(
    rotor: &Rotor,
    fluid: &Fluid,
    op: OperatingPoint,
    opts: &SolverOptions,
    psi: Psi<'_>,
) -> PointResult {
    let ctx = context(rotor, fluid, op, opts);
    let stations = rotor.stations.iter().enumerate();
    match psi {
        Psi::Cold => solve_point_scalar(rotor, fluid, op, opts),
        Psi::Record(out) => {
            out.clear();
            out.resize(rotor.stations.len(), f64::NAN);
            let solved = stations.map(|(i, st)| {
                let (r, p) = station::solve_station_from(st, &ctx, None);
                out[i] = p.unwrap_or(f64::NAN);
                r
            });
            integrate(rotor, fluid, op, opts, solved)
        }
        Psi::From(start) => {
            let solved = stations.map(|(i, st)| station::solve_station_from(st, &ctx, start.get(i).copied()).0);
            integrate(rotor, fluid, op, opts, solved)
        }
    }
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

mod station;

pub(crate) use station::{solve_station, station_result, Ctx, Eval};
