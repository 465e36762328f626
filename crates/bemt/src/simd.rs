//! The vectorised station solve: eight stations at a time in `f64x8` lanes (crate `wide`), for
//! rotors whose sections all use QPROP's parametric model.
//!
//! It is the same computation as [`crate::solve`]'s scalar `eval` and Newton loop (QPROP's
//! start, step limit and exit), lane by lane. A lane that does not converge within the Newton
//! budget, or meets anything non-finite, is solved again by the scalar path, which has the
//! bracketed fallback; so are whole points without rotation or with a zero-chord station.
//! Results agree with the scalar path to rounding (the vector transcendental functions differ
//! from libm's in the last bits).

use wide::f64x8;

/// Stations per vector.
const LANES: usize = 8;

use crate::fluid::Fluid;
use crate::rotor::Rotor;
use crate::solve::{
    context, finish, integrate, solve_station, Convergence, Ctx, Eval, OperatingPoint, PointResult, SolverOptions,
    StationResult,
};

/// One vector's worth of stations' constants.
#[derive(Debug, Clone)]
struct Group {
    /// Station indices of the lanes (padding lanes repeat the last station).
    index: [usize; 8],
    /// Lanes that are real stations.
    lanes: usize,
    r: f64x8,
    chord: f64x8,
    beta: f64x8,
    cl0: f64x8,
    cl_a: f64x8,
    cl_min: f64x8,
    cl_max: f64x8,
    /// CL0 / CL_a [rad].
    a0: f64x8,
}

/// A rotor prepared for the vectorised path.
#[derive(Debug, Clone)]
pub(crate) struct Prepared {
    groups: Vec<Group>,
}

impl Prepared {
    /// `None` when some station is not QPROP's model or has zero chord.
    pub(crate) fn new(rotor: &Rotor) -> Option<Self> {
        let n = rotor.stations.len();
        if n == 0 {
            return None;
        }
        let mut models = Vec::with_capacity(n);
        for s in &rotor.stations {
            if s.chord <= 0.0 {
                return None;
            }
            models.push(*s.aero.as_qprop()?);
        }
        let groups = (0..n.div_ceil(LANES))
            .map(|g| {
                let index: [usize; 8] = std::array::from_fn(|k| (LANES * g + k).min(n - 1));
                let lane = |f: &dyn Fn(usize) -> f64| f64x8::new(index.map(f));
                Group {
                    index,
                    lanes: (n - LANES * g).min(LANES),
                    r: lane(&|i| rotor.stations[i].r),
                    chord: lane(&|i| rotor.stations[i].chord),
                    beta: lane(&|i| rotor.stations[i].beta),
                    cl0: lane(&|i| models[i].coeffs.cl0),
                    cl_a: lane(&|i| models[i].coeffs.cl_a),
                    cl_min: lane(&|i| models[i].coeffs.cl_min),
                    cl_max: lane(&|i| models[i].coeffs.cl_max),
                    a0: lane(&|i| models[i].coeffs.cl0 / models[i].coeffs.cl_a),
                }
            })
            .collect();
        Some(Self { groups })
    }
}

/// Solves one point, vectorised where `prepared` allows.
pub(crate) fn solve_point_prepared(
    rotor: &Rotor,
    prepared: Option<&Prepared>,
    fluid: &Fluid,
    op: OperatingPoint,
    opts: &SolverOptions,
) -> PointResult {
    let ctx = context(rotor, fluid, op, opts);
    match prepared {
        Some(p) if op.omega > 0.0 => {
            let mut results: Vec<Option<StationResult>> = vec![None; rotor.stations.len()];
            for g in &p.groups {
                solve_group(rotor, g, &ctx, &mut results);
            }
            let all = results
                .into_iter()
                .zip(&rotor.stations)
                .map(|(r, st)| r.unwrap_or_else(|| solve_station(st, &ctx)));
            integrate(rotor, fluid, op, opts, all)
        }
        _ => integrate(
            rotor,
            fluid,
            op,
            opts,
            rotor.stations.iter().map(|st| solve_station(st, &ctx)),
        ),
    }
}

/// Vector state at one psi per lane (see `solve::eval`).
struct VEval {
    res: f64x8,
    res_psi: f64x8,
    wa: f64x8,
    wt: f64x8,
    w: f64x8,
    msq: f64x8,
    alpha: f64x8,
    cl: f64x8,
    stalled: f64x8,
    f_tip: f64x8,
    lambda_w: f64x8,
    gamma: f64x8,
}

#[inline]
fn select(mask: f64x8, yes: f64x8, no: f64x8) -> f64x8 {
    mask.bitselect(yes, no)
}

#[allow(clippy::too_many_arguments)]
#[inline]
fn veval(g: &Group, c: &Ctx, beta: f64x8, ua: f64x8, ut: f64x8, u: f64x8, psi0: f64x8, psi: f64x8) -> VEval {
    let zero = f64x8::splat(0.0);
    let one = f64x8::splat(1.0);
    let half = f64x8::splat(0.5);
    let two_pi = f64x8::splat(2.0 / std::f64::consts::PI);
    let tip = f64x8::splat(c.tip);
    let (sinp, cosp) = psi.sin_cos();
    let wa = half * ua + half * u * sinp;
    let wa_p = half * u * cosp;
    let wt = half * ut + half * u * cosp;
    let wt_p = -(half * u * sinp);

    let valid = wa.simd_ne(zero) & wt.simd_ne(zero);
    let wa_s = select(valid, wa, one);
    let wt_s = select(valid, wt, one);
    let tr = tip / g.r;
    let tsr = wt_s / wa_s * tr;
    let tsr_p = (wt_p * tr - tsr * wa_p) / wa_s;
    let (f, f_p) = if c.opts.tip_loss {
        let k = f64x8::splat(0.5 * c.blades) * (one - g.r / tip);
        let sign = select(tsr.simd_lt(zero), f64x8::splat(-1.0), one);
        let farg = (k * tsr * sign).min(f64x8::splat(20.0));
        let farg_tsr = k * sign;
        let fexp = (-farg).exp();
        let f = two_pi * fexp.acos();
        let below = fexp.simd_lt(one);
        let denom = select(below, one - fexp * fexp, one).sqrt();
        let f_tsr = select(below, two_pi / denom * fexp * farg_tsr, zero);
        (f, f_tsr * tsr_p)
    } else {
        (one, zero)
    };
    let f_tip = select(valid, f, one);
    let f_p = select(valid, f_p, zero);
    let adw = select(valid, one / tsr, zero);
    let adw_p = select(valid, -tsr_p / (tsr * tsr), zero);

    let vt = ut - wt;
    let vt_p = -wt_p;
    let qbi = f64x8::splat(4.0 / c.blades);
    let pi_r = f64x8::splat(std::f64::consts::PI) * g.r;
    let qr = qbi * tip;
    let pir = (pi_r * pi_r + (qr * adw) * (qr * adw)).sqrt();
    let pir_p = qr * qr * adw / pir * adw_p;
    let gamma = qbi * f_tip * vt * pir;
    let gam_p = qbi * (f_tip * vt_p + f_p * vt) * pir + qbi * f_tip * vt * pir_p;

    let wsq = wa * wa + wt * wt;
    let w = wsq.sqrt();
    let w_p = (wa * wa_p + wt * wt_p) / w;
    // The velocity circle passes through the origin (psi = psi0 + pi), so by the inscribed
    // angle theorem the inflow angle atan2(Wa, Wt) is (psi + psi0)/2 for |psi - psi0| < pi,
    // which saves an atan2 per lane and iteration.
    let inside = (psi - psi0).abs().simd_lt(f64x8::splat(std::f64::consts::PI));
    let phi = if inside.all() {
        half * (psi + psi0)
    } else {
        wa.atan2(wt)
    };
    let alpha = beta - phi;
    let alpha_p = (-(wt * wa_p) + wa * wt_p) / wsq;
    let a2 = f64x8::splat(c.fluid.a * c.fluid.a);
    let msq_raw = wsq / a2;
    let capped = msq_raw.simd_gt(f64x8::splat(crate::aero::MSQ_MAX));
    let msq = select(capped, f64x8::splat(crate::aero::MSQ_MAX), msq_raw);
    let msq_p = select(capped, zero, f64x8::splat(2.0) * w * w_p / a2);

    let pg = one / (one - msq).sqrt();
    let cl_inc = g.cl0 + g.cl_a * alpha;
    let cl_lin = cl_inc * pg;
    let cl_lin_p = g.cl_a * pg * alpha_p + cl_inc * half * pg / (one - msq) * msq_p;
    let hi = cl_lin.simd_gt(g.cl_max);
    let lo = cl_lin.simd_lt(g.cl_min);
    let stalled = hi | lo;
    let (cl, cl_p) = if stalled.any() {
        let lim = select(hi, g.cl_max, g.cl_min);
        let (s, co) = (alpha - g.a0).sin_cos();
        (
            select(stalled, lim * co, cl_lin),
            select(stalled, -(lim * s) * alpha_p, cl_lin_p),
        )
    } else {
        (cl_lin, cl_lin_p)
    };
    let res = gamma - half * g.chord * cl * w;
    let res_psi = gam_p - half * g.chord * (cl * w_p + cl_p * w);
    VEval {
        res,
        res_psi,
        wa,
        wt,
        w,
        msq,
        alpha,
        cl,
        stalled,
        f_tip,
        lambda_w: adw,
        gamma,
    }
}

fn lane(e: &VEval, k: usize) -> Eval {
    Eval {
        res: e.res.to_array()[k],
        res_psi: e.res_psi.to_array()[k],
        wa: e.wa.to_array()[k],
        wt: e.wt.to_array()[k],
        w: e.w.to_array()[k],
        msq: e.msq.to_array()[k],
        alpha: e.alpha.to_array()[k],
        cl: e.cl.to_array()[k],
        stalled: e.stalled.to_array()[k].to_bits() != 0,
        f_tip: e.f_tip.to_array()[k],
        lambda_w: e.lambda_w.to_array()[k],
        gamma: e.gamma.to_array()[k],
    }
}

/// QPROP's Newton iteration on a group of stations at once; converged lanes are finished and stored
/// in `out`, the others are left `None` for the scalar path.
fn solve_group(rotor: &Rotor, g: &Group, c: &Ctx, out: &mut [Option<StationResult>]) {
    let beta = g.beta + f64x8::splat(c.opts.dbeta);
    let ua = f64x8::splat(c.v);
    let ut = f64x8::splat(c.omega) * g.r;
    let u = (ua * ua + ut * ut).sqrt();
    let psi0 = ua.atan2(ut);
    let mut psi = psi0.max(beta + g.a0);
    let tol = c.opts.tol;
    let mut done = [false; 8];
    // Padding lanes are stopped from the start.
    let mut stop: [bool; LANES] = std::array::from_fn(|k| k >= g.lanes);
    for iter in 1..=c.opts.max_newton {
        let e = veval(g, c, beta, ua, ut, u, psi0, psi);
        let dpsi_raw = -e.res / e.res_psi;
        let dpsi = dpsi_raw.max(f64x8::splat(-0.1)).min(f64x8::splat(0.1));
        let raw = dpsi_raw.to_array();
        let res = e.res.to_array();
        let step = dpsi.to_array();
        let mut new_psi = psi.to_array();
        for k in 0..LANES {
            if stop[k] {
                continue;
            }
            if !raw[k].is_finite() || !res[k].is_finite() {
                stop[k] = true; // scalar path takes over
            } else if step[k].abs() < tol {
                stop[k] = true;
                done[k] = true;
                let i = g.index[k];
                let ua_k = c.v;
                let ut_k = c.omega * rotor.stations[i].r;
                let beta_k = rotor.stations[i].beta + c.opts.dbeta;
                out[i] = Some(finish(
                    &rotor.stations[i],
                    c,
                    beta_k,
                    ua_k,
                    ut_k,
                    &lane(&e, k),
                    Convergence::Newton { iterations: iter },
                ));
            } else {
                new_psi[k] += step[k];
            }
        }
        if stop.iter().all(|&s| s) {
            break;
        }
        psi = f64x8::new(new_psi);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aero::QpropCoefficients;
    use crate::rotor::{Discretization, QpropBlade};

    /// QPROP's example prop (cam6x3), with per-station coefficient variation so that lanes
    /// differ in every constant.
    fn rotor() -> Rotor {
        let r: Vec<f64> = [0.75, 1.0, 1.5, 2.0, 2.5, 2.875, 3.0]
            .iter()
            .map(|x| x * 0.0254)
            .collect();
        let chord = [0.66, 0.69, 0.63, 0.55, 0.44, 0.30, 0.19]
            .iter()
            .map(|x| x * 0.0254)
            .collect();
        let beta = [27.5f64, 22.0, 15.2, 10.2, 6.5, 4.6, 4.2]
            .iter()
            .map(|x| x.to_radians())
            .collect();
        let coeffs = (0..7)
            .map(|i| {
                let f = i as f64 / 6.0;
                QpropCoefficients::from_array([
                    0.4 + 0.2 * f,
                    5.8,
                    -0.3,
                    1.1 + 0.2 * f,
                    0.028,
                    0.05,
                    0.04,
                    0.5,
                    7e4,
                    -0.7,
                ])
            })
            .collect();
        QpropBlade {
            blades: 2.0,
            tip_radius: 0.0762,
            r,
            chord,
            beta,
            coeffs,
        }
        .to_rotor(Discretization::default())
        .unwrap()
    }

    #[test]
    fn vector_and_scalar_paths_agree() {
        let rotor = rotor();
        let prepared = Prepared::new(&rotor).unwrap();
        assert_eq!(prepared.groups.len(), 25usize.div_ceil(LANES));
        let fluid = Fluid::default();
        let mut worst: f64 = 0.0;
        for rpm in [1500.0, 6000.0, 14000.0, 30000.0, 60000.0] {
            for v in [-8.0, 0.0, 3.0, 11.0, 25.0, 45.0] {
                for dbeta in [-6.0f64, 0.0, 9.0] {
                    let opts = SolverOptions {
                        dbeta: dbeta.to_radians(),
                        keep_stations: true,
                        ..Default::default()
                    };
                    let op = OperatingPoint::from_rpm(v, rpm);
                    let a = solve_point_prepared(&rotor, Some(&prepared), &fluid, op, &opts);
                    let b = solve_point_prepared(&rotor, None, &fluid, op, &opts);
                    assert_eq!(a.not_converged, b.not_converged, "rpm {rpm} v {v} dbeta {dbeta}");
                    for (x, y) in [(a.thrust, b.thrust), (a.torque, b.torque), (a.cl_avg, b.cl_avg)] {
                        let scale = b.thrust.abs() + b.torque.abs() / rotor.tip_radius + 1e-12;
                        worst = worst.max((x - y).abs() / scale);
                    }
                    for (s, t) in a.stations.iter().zip(&b.stations) {
                        assert_eq!(s.stalled, t.stalled);
                        assert!(
                            (s.alpha - t.alpha).abs() < 1e-9,
                            "rpm {rpm} v {v}: {} vs {}",
                            s.alpha,
                            t.alpha
                        );
                    }
                }
            }
        }
        assert!(worst < 1e-9, "worst relative difference {worst}");
    }
}
