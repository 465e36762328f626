//! The vectorised station solve: eight stations at a time in `f64x8` lanes (crate `wide`), for
//! rotors whose sections all use QPROP's parametric model.
//!
//! It is the same computation as [`crate::solve`]'s scalar `eval`, Newton loop (QPROP's
//! start, step limit and exit), drag law and loads, lane by lane. A lane that does not
//! converge within the Newton budget, or meets anything non-finite, is solved again by the
//! scalar path, which has the bracketed fallback; so are whole points without rotation or with
//! a zero-chord station, and a remainder of one or two stations after the last full group.
//! Results agree with the scalar path to rounding (the vector transcendental functions differ
//! from libm's in the last bits; `tests::vector_and_scalar_paths_agree` bounds it at 1e-9).

use wide::f64x8;

/// Stations per vector.
const LANES: usize = 8;

use crate::fluid::Fluid;
use crate::rotor::Rotor;
use crate::solve::{
    context, point_result, solve_station, station_result, Convergence, Ctx, Eval, OperatingPoint, PointResult,
    SolverOptions, StationResult, Sums,
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
    dr: f64x8,
    cd0: f64x8,
    cd2u: f64x8,
    cd2l: f64x8,
    clcd0: f64x8,
    re_ref: f64x8,
    re_exp: f64x8,
    mcrit: f64x8,
    /// (CLCD0 - CL0) / CL_a [rad].
    acd0: f64x8,
    /// R / r [-].
    tip_over_r: f64x8,
    /// B/2 (1 - r/R), the tip factor's f per unit tip-speed ratio [-].
    f_per_tsr: f64x8,
    /// pi r [m].
    pi_r: f64x8,
}

/// A rotor prepared for the vectorised path.
#[derive(Debug, Clone)]
pub(crate) struct Prepared {
    groups: Vec<Group>,
    /// Stations left over after the last full group when they are too few to fill a vector
    /// economically (a lane group costs about as much as three scalar solves); solved by the
    /// scalar path.
    scalar: Vec<usize>,
    /// One group per station with that station in every lane, for solving eight operating
    /// points at once ([`solve_batch`]).
    per_station: Vec<Group>,
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
        // A remainder of one or two stations is cheaper on the scalar path than in a vector.
        let rem = n % LANES;
        let vector_n = if rem > 0 && rem <= 2 && n > LANES { n - rem } else { n };
        let group = |index: [usize; LANES], lanes: usize| {
            let lane = |f: &dyn Fn(usize) -> f64| f64x8::new(index.map(f));
            Group {
                index,
                lanes,
                r: lane(&|i| rotor.stations[i].r),
                chord: lane(&|i| rotor.stations[i].chord),
                beta: lane(&|i| rotor.stations[i].beta),
                cl0: lane(&|i| models[i].coeffs.cl0),
                cl_a: lane(&|i| models[i].coeffs.cl_a),
                cl_min: lane(&|i| models[i].coeffs.cl_min),
                cl_max: lane(&|i| models[i].coeffs.cl_max),
                a0: lane(&|i| models[i].coeffs.cl0 / models[i].coeffs.cl_a),
                dr: lane(&|i| rotor.stations[i].dr),
                cd0: lane(&|i| models[i].coeffs.cd0),
                cd2u: lane(&|i| models[i].coeffs.cd2u),
                cd2l: lane(&|i| models[i].coeffs.cd2l),
                clcd0: lane(&|i| models[i].coeffs.clcd0),
                re_ref: lane(&|i| models[i].coeffs.re_ref),
                re_exp: lane(&|i| models[i].coeffs.re_exp),
                mcrit: lane(&|i| models[i].mcrit),
                acd0: lane(&|i| (models[i].coeffs.clcd0 - models[i].coeffs.cl0) / models[i].coeffs.cl_a),
                tip_over_r: lane(&|i| rotor.tip_radius / rotor.stations[i].r),
                f_per_tsr: lane(&|i| 0.5 * rotor.blades * (1.0 - rotor.stations[i].r / rotor.tip_radius)),
                pi_r: lane(&|i| std::f64::consts::PI * rotor.stations[i].r),
            }
        };
        let groups = (0..vector_n.div_ceil(LANES))
            .map(|g| {
                let index: [usize; LANES] = std::array::from_fn(|k| (LANES * g + k).min(vector_n - 1));
                group(index, (vector_n - LANES * g).min(LANES))
            })
            .collect();
        let per_station = (0..n).map(|i| group([i; LANES], LANES)).collect();
        Some(Self {
            groups,
            scalar: (vector_n..n).collect(),
            per_station,
        })
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
        Some(p) if op.omega > 0.0 && opts.vector_ok() => {
            let mut sums = Sums::default();
            let mut stations: Vec<Option<StationResult>> = if opts.keep_stations {
                vec![None; rotor.stations.len()]
            } else {
                Vec::new()
            };
            for g in &p.groups {
                solve_group(rotor, g, &ctx, &mut sums, &mut stations);
            }
            for &i in &p.scalar {
                let st = &rotor.stations[i];
                let s = solve_station(st, &ctx);
                sums.add(st, &s);
                if opts.keep_stations {
                    stations[i] = Some(s);
                }
            }
            let stations = stations.into_iter().flatten().collect();
            point_result(rotor, fluid, op, &sums, stations)
        }
        _ => crate::solve::solve_point_scalar(rotor, fluid, op, opts),
    }
}

/// Solves up to eight operating points at once, one station at a time with the points in
/// the lanes: neighbouring points need about as many Newton iterations as each other, so less
/// work is wasted on lanes that already converged than with the stations in the lanes. Each
/// lane runs exactly the per-station computation of [`solve_point_prepared`]; loads are summed
/// station by station per point.
///
/// Needs every `ops[k].omega > 0` and `!opts.keep_stations`; `ops.len()` must be 1..=8.
pub(crate) fn solve_batch(
    rotor: &Rotor,
    p: &Prepared,
    fluid: &Fluid,
    ops: &[OperatingPoint],
    opts: &SolverOptions,
) -> Vec<PointResult> {
    let n = ops.len();
    assert!((1..=LANES).contains(&n), "a batch holds 1 to {LANES} points");
    let zero = f64x8::splat(0.0);
    let ctxs: Vec<Ctx> = ops.iter().map(|&op| context(rotor, fluid, op, opts)).collect();
    let v = f64x8::new(std::array::from_fn(|k| ops[k.min(n - 1)].v));
    let omega = f64x8::new(std::array::from_fn(|k| ops[k.min(n - 1)].omega));
    let real = f64x8::new(std::array::from_fn(|k| if k < n { 1.0 } else { 0.0 })).simd_ne(zero);
    let (mut thrust, mut torque, mut wsum, mut clsum, mut cdsum) = (zero, zero, zero, zero, zero);
    let mut extra: Vec<Sums> = vec![Sums::default(); n];
    for (i, g) in p.per_station.iter().enumerate() {
        let out = solve_lanes(g, &ctxs[0], v, omega * g.r, real);
        let c = out.conv;
        thrust += select(c, out.dt_dr * g.dr, zero);
        torque += select(c, out.dq_dr * g.dr, zero);
        wsum += select(c, out.wgt, zero);
        clsum += select(c, out.wgt * out.fin.cl, zero);
        cdsum += select(c, out.wgt * out.cd, zero);
        let conv = c.to_bitmask();
        for (k, ctx) in ctxs.iter().enumerate() {
            if conv & (1 << k) == 0 {
                let st = &rotor.stations[i];
                extra[k].add(st, &solve_station(st, ctx));
            }
        }
    }
    let (thrust, torque, wsum, clsum, cdsum) = (
        thrust.to_array(),
        torque.to_array(),
        wsum.to_array(),
        clsum.to_array(),
        cdsum.to_array(),
    );
    (0..n)
        .map(|k| {
            let e = &extra[k];
            let sums = Sums {
                thrust: thrust[k] + e.thrust,
                torque: torque[k] + e.torque,
                wsum: wsum[k] + e.wsum,
                clsum: clsum[k] + e.clsum,
                cdsum: cdsum[k] + e.cdsum,
                not_converged: e.not_converged,
            };
            point_result(rotor, fluid, ops[k], &sums, Vec::new())
        })
        .collect()
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
    let (sinp, cosp) = psi.sin_cos();
    let wa = half * ua + half * u * sinp;
    let wa_p = half * u * cosp;
    let wt = half * ut + half * u * cosp;
    let wt_p = -(half * u * sinp);

    let valid = wa.simd_ne(zero) & wt.simd_ne(zero);
    let wa_s = select(valid, wa, one);
    let wt_s = select(valid, wt, one);
    let inv_wa = one / wa_s;
    let tsr = wt_s * inv_wa * g.tip_over_r;
    let tsr_p = (wt_p * g.tip_over_r - tsr * wa_p) * inv_wa;
    let (f, f_p) = if let Some(strength) = c.opts.tip_divisor() {
        let sign = select(tsr.simd_lt(zero), f64x8::splat(-1.0), one);
        let farg_tsr = g.f_per_tsr * sign / f64x8::splat(strength);
        let farg = (farg_tsr * tsr).min(f64x8::splat(20.0));
        let fexp = (-farg).exp();
        let f = two_pi * fexp.acos();
        let below = fexp.simd_lt(one);
        let denom = select(below, one - fexp * fexp, one).sqrt();
        let f_tsr = select(below, two_pi * fexp * farg_tsr / denom, zero);
        (f, f_tsr * tsr_p)
    } else {
        (one, zero)
    };
    let f_tip = select(valid, f, one);
    let f_p = select(valid, f_p, zero);
    let inv_tsr = one / tsr;
    let adw = select(valid, inv_tsr, zero);
    let adw_p = select(valid, -tsr_p * inv_tsr * inv_tsr, zero);

    let vt = ut - wt;
    let vt_p = -wt_p;
    let qbi = f64x8::splat(4.0 / c.blades);
    let qr = f64x8::splat(4.0 / c.blades * c.tip);
    let qra = qr * adw;
    let pir = (g.pi_r * g.pi_r + qra * qra).sqrt();
    let pir_p = qr * qra * adw_p / pir;
    let gamma = qbi * f_tip * vt * pir;
    let gam_p = qbi * ((f_tip * vt_p + f_p * vt) * pir + f_tip * vt * pir_p);

    let wsq = wa * wa + wt * wt;
    let w = wsq.sqrt();
    let inv_w = one / w;
    let w_p = (wa * wa_p + wt * wt_p) * inv_w;
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
    let alpha_p = (wa * wt_p - wt * wa_p) * (inv_w * inv_w);
    let inv_a2 = f64x8::splat(1.0 / (c.fluid.a * c.fluid.a));
    let msq_raw = wsq * inv_a2;
    let capped = msq_raw.simd_gt(f64x8::splat(crate::aero::MSQ_MAX));
    let msq = select(capped, f64x8::splat(crate::aero::MSQ_MAX), msq_raw);
    let msq_p = select(capped, zero, f64x8::splat(2.0) * w * w_p * inv_a2);

    let pg = one / (one - msq).sqrt();
    let cl_inc = g.cl0 + g.cl_a * alpha;
    let cl_lin = cl_inc * pg;
    // d(PG)/d(M^2) = PG^3 / 2.
    let cl_lin_p = g.cl_a * pg * alpha_p + cl_inc * half * pg * pg * pg * msq_p;
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

impl VEval {
    fn zero() -> Self {
        let z = f64x8::splat(0.0);
        Self {
            res: z,
            res_psi: z,
            wa: z,
            wt: z,
            w: z,
            msq: z,
            alpha: z,
            cl: z,
            stalled: z,
            f_tip: z,
            lambda_w: z,
            gamma: z,
        }
    }

    /// Takes `other`'s lanes where `mask` is set.
    fn blend(&mut self, mask: f64x8, other: &VEval) {
        self.res = select(mask, other.res, self.res);
        self.res_psi = select(mask, other.res_psi, self.res_psi);
        self.wa = select(mask, other.wa, self.wa);
        self.wt = select(mask, other.wt, self.wt);
        self.w = select(mask, other.w, self.w);
        self.msq = select(mask, other.msq, self.msq);
        self.alpha = select(mask, other.alpha, self.alpha);
        self.cl = select(mask, other.cl, self.cl);
        self.stalled = select(mask, other.stalled, self.stalled);
        self.f_tip = select(mask, other.f_tip, self.f_tip);
        self.lambda_w = select(mask, other.lambda_w, self.lambda_w);
        self.gamma = select(mask, other.gamma, self.gamma);
    }
}

/// What the lanes of one vector solve produce: the converged state and its drag and loads.
struct LaneOut {
    /// Lanes that converged with finite loads.
    conv: f64x8,
    fin: VEval,
    iterations: f64x8,
    re: f64x8,
    cd: f64x8,
    dt_dr: f64x8,
    dq_dr: f64x8,
    /// W^2 c dr, the weight of the cl and cd averages.
    wgt: f64x8,
}

/// QPROP's Newton iteration on eight lanes at once (stations of one point, or one station at
/// eight points: `ua`, `ut` and the constants in `g` are per lane), then drag (QPROP CDFUN +
/// DCDFUN) and loads (TQCALC) at the converged states. `real` marks the lanes to solve.
fn solve_lanes(g: &Group, c: &Ctx, ua: f64x8, ut: f64x8, real: f64x8) -> LaneOut {
    let zero = f64x8::splat(0.0);
    let half = f64x8::splat(0.5);
    let beta = g.beta + f64x8::splat(c.opts.dbeta);
    let u = (ua * ua + ut * ut).sqrt();
    let psi0 = ua.atan2(ut);
    let mut psi = psi0.max(beta + g.a0);
    let tol = f64x8::splat(c.opts.tol);
    let mut active = real;
    let mut conv = zero.simd_ne(zero);
    let mut iterations = zero;
    let mut fin = VEval::zero();
    for iter in 1..=c.opts.max_newton {
        let e = veval(g, c, beta, ua, ut, u, psi0, psi);
        let dpsi_raw = -e.res / e.res_psi;
        let finite = dpsi_raw.is_finite() & e.res.is_finite();
        let dpsi = dpsi_raw.max(f64x8::splat(-0.1)).min(f64x8::splat(0.1));
        let newly = active & finite & dpsi.abs().simd_lt(tol);
        if newly.any() {
            fin.blend(newly, &e);
            iterations = select(newly, f64x8::splat(iter as f64), iterations);
            conv |= newly;
        }
        // Lanes that converged or met a non-finite value stop; the latter go to the scalar path.
        active = active & finite & !newly;
        if !active.any() {
            break;
        }
        psi = select(active, psi + dpsi, psi);
    }

    let rho = f64x8::splat(c.fluid.rho);
    let re = rho * fin.w * g.chord / f64x8::splat(c.fluid.mu);
    let mach = fin.msq.sqrt().max(f64x8::splat(1e-8));
    let fac = (re.max(f64x8::splat(1.0)) / g.re_ref).powf_simd(g.re_exp);
    let clb = fin.cl - g.clcd0;
    let cd2 = select(fin.cl.simd_gt(g.clcd0), g.cd2u, g.cd2l);
    let mut cd = (g.cd0 + cd2 * clb * clb) * fac;
    let dm = mach - g.mcrit;
    cd += select(mach.simd_gt(g.mcrit), f64x8::splat(10.0) * dm * dm * dm, zero);
    let stalled = fin.stalled.simd_ne(zero);
    if (stalled & conv).any() {
        let sa = (fin.alpha - g.acd0).sin_cos().0;
        cd += select(stalled, f64x8::splat(2.0) * sa * sa, zero);
    }
    let hrc = half * rho * g.chord;
    let fa = hrc * fin.w * (fin.cl * fin.wt - cd * fin.wa);
    let ft = hrc * fin.w * (fin.cl * fin.wa + cd * fin.wt);
    let blades = f64x8::splat(c.blades);
    let dt_dr = blades * fa;
    let dq_dr = blades * ft * g.r;
    let conv = conv & dt_dr.is_finite() & dq_dr.is_finite() & cd.is_finite();
    let wgt = fin.w * fin.w * g.chord * g.dr;
    LaneOut {
        conv,
        fin,
        iterations,
        re,
        cd,
        dt_dr,
        dq_dr,
        wgt,
    }
}

/// The stations of one point in groups of eight: sums of the converged lanes, the scalar path
/// for the others. With `stations` non-empty, each station's result is stored there.
fn solve_group(rotor: &Rotor, g: &Group, c: &Ctx, sums: &mut Sums, stations: &mut [Option<StationResult>]) {
    let zero = f64x8::splat(0.0);
    let real = f64x8::new(std::array::from_fn(|k| if k < g.lanes { 1.0 } else { 0.0 })).simd_ne(zero);
    let ua = f64x8::splat(c.v);
    let ut = f64x8::splat(c.omega) * g.r;
    let out = solve_lanes(g, c, ua, ut, real);
    let LaneOut {
        conv,
        ref fin,
        iterations,
        re,
        cd,
        dt_dr,
        dq_dr,
        wgt,
    } = out;
    // The sums use the vector loads; a kept station's loads are recomputed by
    // `station_result` from the same state with the same formula.
    sums.thrust += select(conv, dt_dr * g.dr, zero).reduce_add();
    sums.torque += select(conv, dq_dr * g.dr, zero).reduce_add();
    sums.wsum += select(conv, wgt, zero).reduce_add();
    sums.clsum += select(conv, wgt * fin.cl, zero).reduce_add();
    sums.cdsum += select(conv, wgt * cd, zero).reduce_add();

    let conv_lanes = conv.to_bitmask();
    let keep = !stations.is_empty();
    for k in 0..g.lanes {
        let i = g.index[k];
        let st = &rotor.stations[i];
        if conv_lanes & (1 << k) == 0 {
            let s = solve_station(st, c);
            sums.add(st, &s);
            if keep {
                stations[i] = Some(s);
            }
        } else if keep {
            let a = |v: f64x8| v.to_array()[k];
            let e = Eval {
                res: a(fin.res),
                res_psi: a(fin.res_psi),
                wa: a(fin.wa),
                wt: a(fin.wt),
                w: a(fin.w),
                msq: a(fin.msq),
                alpha: a(fin.alpha),
                cl: a(fin.cl),
                stalled: fin.stalled.to_bitmask() & (1 << k) != 0,
                f_tip: a(fin.f_tip),
                lambda_w: a(fin.lambda_w),
                gamma: a(fin.gamma),
            };
            let conv = Convergence::Newton {
                iterations: a(iterations) as u32,
            };
            let beta = st.beta + c.opts.dbeta;
            stations[i] = Some(station_result(st, c, beta, c.v, c.omega * st.r, &e, a(re), a(cd), conv));
        }
    }
}

#[cfg(test)]
mod tests;
