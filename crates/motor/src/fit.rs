//! A type 1 motor (R, Io, Kv) fitted to what a thrust stand logs: the shaft's speed and
//! torque, and the supply's voltage and current upstream of the ESC.
//!
//! The power the supply gives is the motor's (the ESC taken as lossless; its losses fall into
//! R): $V_b I_b = I_m^2 R + I_m \Omega / K_v$ with $I_m = Q K_v + I_0$. Written in the two
//! combinations a log determines, $a = R K_v^2$ and $b = I_0 / K_v$ (the no-load torque):
//! $$V_b I_b = Q\Omega + b\,\Omega + a\,(Q + b)^2,$$
//! fitted by Gauss-Newton with 95 % intervals from the covariance. The supply side alone
//! cannot separate Kv from R and Io; Kv comes either from the user (a maker's number) or from
//! the voltage the motor sees, $d V_b = I_m R + \Omega/K_v = (a (Q + b) + \Omega)/K_v$, with
//! the duty $d$ read from the ESC command as a linear ESC calibrated to 1000-2000 µs does
//! (an assumption, said in the fit's notes), over the steps at half throttle and above.
//!
//! The current this model predicts at a point, $I_b = (Q\Omega + b\Omega + a(Q+b)^2)/V_b$,
//! needs a and b only: it is what the held-out check scores.

use thiserror::Error;

use crate::model::Motor;

/// One steady point of a stand log.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitPoint {
    /// Rotation rate [rad/s].
    pub omega: f64,
    /// Shaft torque [N m] (positive driving the propeller).
    pub torque: f64,
    /// Supply voltage [V].
    pub volts: f64,
    /// Supply current [A].
    pub amps: f64,
    /// ESC command [µs], when logged.
    pub esc: Option<f64>,
}

/// A value and its 95 % interval half-width.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// The value.
    pub value: f64,
    /// Half-width of its 95 % interval.
    pub plus_minus: f64,
}

/// Where Kv came from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KvSource {
    /// Given by the user.
    Given,
    /// From the voltage the motor sees at the ESC's duty (the points used).
    EscDuty(usize),
}

/// The fitted motor.
#[derive(Debug, Clone, PartialEq)]
pub struct MotorFit {
    /// Winding (and ESC) resistance [ohm].
    pub r: Estimate,
    /// No-load current [A].
    pub io: Estimate,
    /// Kv [rpm/V].
    pub kv_rpm: Estimate,
    /// Kq [rpm/V], fitted on its own (type 2); None where it is Kv (type 1).
    pub kq_rpm: Option<Estimate>,
    /// Where Kv came from.
    pub kv_source: KvSource,
    /// RMS relative error of the supply current over the points fitted.
    pub rms_current: f64,
    /// The points fitted.
    pub points: usize,
    /// The motor.
    pub motor: Motor,
}

/// Why a fit cannot be made.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FitError {
    /// Too few points with speed, torque, voltage and current.
    #[error("{0} points with speed, torque, voltage and current: a motor fit needs at least 4")]
    TooFew(usize),
    /// Type 2 with too few steps at half throttle and above.
    #[error("{0} steps with the ESC command at half throttle and above: a fit of Kq needs at least 4 (the motor's own current is known there)")]
    TooFewDuty(usize),
    /// Type 2 without the ESC command: the motor's own voltage and current are not known.
    #[error("a fit of Kq needs the ESC command (the motor's own voltage and current, at half throttle and above); the log has none there")]
    NoDuty,
    /// No Kv: neither given nor an ESC command logged.
    #[error("the log has no ESC command at half throttle or above to find Kv from; give the maker's Kv")]
    NoKv,
    /// The fitted constants are not a motor's.
    #[error("the fit gives {0}: the log's electrical columns do not describe a DC motor here")]
    Unphysical(String),
}

/// Student-t's 97.5 % point for `dof` degrees of freedom (Abramowitz & Stegun 26.7.5, the
/// Cornish-Fisher series to 1/dof^2, within 1 % from 3 degrees of freedom).
fn t975(dof: usize) -> f64 {
    let z: f64 = 1.959_964;
    let n = dof.max(1) as f64;
    z + (z.powi(3) + z) / (4.0 * n) + (5.0 * z.powi(5) + 16.0 * z.powi(3) + 3.0 * z) / (96.0 * n * n)
}

/// Which motor a fit makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FitKind {
    /// QPROP's type 1: R, Io, Kv (the torque constant the back-EMF's, Kq = Kv).
    #[default]
    Type1,
    /// QPROP's type 2 with a torque constant of its own: R, Io, Kv, Kq (tau, Io1, Io2, R2 zero).
    /// Kq/Kv above 1 is shaft power the supply pays for beyond the winding's and the no-load
    /// losses: the ESC's and the iron's losses that grow with the power.
    Type2,
}

/// The combinations of the constants that the supply power determines: a = R Kq^2,
/// b = Io / Kq (the no-load torque) and c = Kq / Kv (1 for type 1), in
/// $V_b I_b = c\,(Q\Omega + b\,\Omega) + a\,(Q + b)^2$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Combos {
    /// R Kq^2.
    pub a: f64,
    /// Io / Kq.
    pub b: f64,
    /// Kq / Kv.
    pub c: f64,
}

/// The supply power the model gives at a point.
fn power(p: &FitPoint, k: &Combos) -> f64 {
    k.c * (p.torque * p.omega + k.b * p.omega) + k.a * (p.torque + k.b).powi(2)
}

/// The supply current the fitted combinations predict at a point.
pub fn predicted_amps(p: &FitPoint, k: &Combos) -> f64 {
    power(p, k) / p.volts
}

/// The power fit of a type 1 motor: the combinations, their covariance (a, b, c; c is 1 and
/// its row and column zero), the RMS relative residual.
#[derive(Debug, Clone, PartialEq)]
pub struct PowerFit {
    /// The combinations.
    pub combos: Combos,
    /// Their covariance, in the order a, b, c.
    pub cov: [[f64; 3]; 3],
    /// RMS of the residuals relative to each point's measured power.
    pub rms: f64,
}

/// Gauss-Newton on the combinations a and b of a type 1 motor (c = 1), residuals relative to
/// each point's measured power.
pub fn fit_power(points: &[FitPoint]) -> Result<PowerFit, FitError> {
    let n = 2;
    if points.len() < n + 2 {
        return Err(FitError::TooFew(points.len()));
    }
    let mut k = Combos { a: 0.0, b: 0.0, c: 1.0 };
    let mut out = PowerFit {
        combos: k,
        cov: [[0.0; 3]; 3],
        rms: 0.0,
    };
    for _ in 0..100 {
        let mut jac = nalgebra::DMatrix::<f64>::zeros(points.len(), n);
        let mut res = nalgebra::DVector::<f64>::zeros(points.len());
        for (row, p) in points.iter().enumerate() {
            let measured = p.volts * p.amps;
            let w = 1.0 / measured.abs().max(1e-9);
            res[row] = (power(p, &k) - measured) * w;
            let d = [(p.torque + k.b).powi(2), k.c * p.omega + 2.0 * k.a * (p.torque + k.b)];
            for (col, x) in d.iter().enumerate() {
                jac[(row, col)] = x * w;
            }
        }
        let jtj = jac.transpose() * &jac;
        let Some(inv) = jtj.clone().try_inverse().filter(|m| m.iter().all(|x| x.is_finite())) else {
            return Err(FitError::Unphysical(
                "a singular system (every point at one speed and torque)".into(),
            ));
        };
        let step = &inv * (jac.transpose() * &res);
        k.a -= step[0];
        k.b -= step[1];
        let ss = res.norm_squared();
        let s2 = ss / (points.len() - n) as f64;
        out.combos = k;
        for r in 0..n {
            for c in 0..n {
                out.cov[r][c] = inv[(r, c)] * s2;
            }
        }
        out.rms = (ss / points.len() as f64).sqrt();
        let scale = [k.a, k.b];
        if (0..n).all(|i| step[i].abs() <= 1e-12 * scale[i].abs().max(1e-12)) {
            break;
        }
    }
    Ok(out)
}

/// The slope through the origin of the ESC's voltage against the back-EMF's speed: d V_b =
/// x / Kv with x = a (Q + b) / c + Omega (I_m R = a (Q + b) / Kq), over the steps at half
/// throttle and above; the slope, its standard deviation from the scatter, and the points used.
fn duty_slope(points: &[FitPoint], k: &Combos) -> Option<(f64, f64, usize)> {
    let used: Vec<(f64, f64)> = points
        .iter()
        .filter_map(|p| {
            let d = (p.esc? - 1000.0) / 1000.0;
            (0.5..=1.0)
                .contains(&d)
                .then_some((k.a * (p.torque + k.b) / k.c + p.omega, d * p.volts))
        })
        .collect();
    if used.len() < 2 {
        return None;
    }
    let sxx: f64 = used.iter().map(|(x, _)| x * x).sum();
    let slope = used.iter().map(|(x, y)| x * y).sum::<f64>() / sxx;
    let ss: f64 = used.iter().map(|(x, y)| (y - slope * x).powi(2)).sum();
    Some((slope, (ss / (used.len() - 1) as f64 / sxx).sqrt(), used.len()))
}

/// The standard deviation of `g` at `x` (a, b, c, Kv) under the covariance `cov` of (a, b, c)
/// and Kv's own standard deviation, independent: the delta method with a numerical gradient.
fn propagated(g: &dyn Fn([f64; 4]) -> f64, x: [f64; 4], cov: &[[f64; 3]; 3], kv_sd: f64) -> f64 {
    let grad: Vec<f64> = (0..4)
        .map(|i| {
            let h = 1e-6 * x[i].abs().max(1e-9);
            let mut up = x;
            up[i] += h;
            (g(up) - g(x)) / h
        })
        .collect();
    let mut var = grad[3] * grad[3] * kv_sd * kv_sd;
    for r in 0..3 {
        for c in 0..3 {
            var += grad[r] * grad[c] * cov[r][c];
        }
    }
    var.max(0.0).sqrt()
}

/// Fits R, Io and Kv (and Kq for [`FitKind::Type2`]) to `points`; `kv_rpm` the maker's Kv when
/// given.
pub fn fit_motor(points: &[FitPoint], kv_rpm: Option<f64>, kind: FitKind) -> Result<MotorFit, FitError> {
    let fit = match kind {
        FitKind::Type1 => fit_type1(points, kv_rpm)?,
        FitKind::Type2 => fit_type2(points, kv_rpm)?,
    };
    let Constants {
        r,
        io,
        kv_rpm,
        kq_rpm,
        source,
        combos,
    } = fit;
    if io.value < 0.0 {
        return Err(FitError::Unphysical(format!(
            "a negative no-load current, Io = {:.3} A",
            io.value
        )));
    }
    let motor = match kind {
        FitKind::Type1 => Motor::dc1(r.value, io.value, kv_rpm.value),
        FitKind::Type2 => Motor::from_params(2, &[r.value, io.value, kv_rpm.value, kq_rpm.value, 0.0, 0.0, 0.0, 0.0]),
    }
    .map_err(|e| FitError::Unphysical(e.to_string()))?;
    let rms_current = (points
        .iter()
        .map(|p| (predicted_amps(p, &combos) / p.amps - 1.0).powi(2))
        .sum::<f64>()
        / points.len() as f64)
        .sqrt();
    Ok(MotorFit {
        r,
        io,
        kv_rpm,
        kq_rpm: (kind == FitKind::Type2).then_some(kq_rpm),
        kv_source: source,
        rms_current,
        points: points.len(),
        motor,
    })
}

/// A fit's constants with their 95 % intervals, and the combinations that predict the supply
/// current.
struct Constants {
    r: Estimate,
    io: Estimate,
    kv_rpm: Estimate,
    kq_rpm: Estimate,
    source: KvSource,
    combos: Combos,
}

/// Type 1: a and b from the supply power over every point, Kv given or from the duty's slope.
fn fit_type1(points: &[FitPoint], kv_rpm: Option<f64>) -> Result<Constants, FitError> {
    let PowerFit { combos: k, cov, .. } = fit_power(points)?;
    let t = t975(points.len().saturating_sub(2));
    // Kv [rad/s per V] and its standard deviation.
    let (kv, kv_sd, source) = match kv_rpm {
        Some(given) => (propbet_units::rpm_to_omega(given), 0.0, KvSource::Given),
        None => {
            let (slope, scatter, used) = duty_slope(points, &k).ok_or(FitError::NoKv)?;
            // The combinations' own uncertainty, carried through the slope.
            let of = |x: [f64; 4]| {
                duty_slope(
                    points,
                    &Combos {
                        a: x[0],
                        b: x[1],
                        c: x[2],
                    },
                )
                .map_or(slope, |s| s.0)
            };
            let from_combos = propagated(&of, [k.a, k.b, k.c, 0.0], &cov, 0.0);
            let slope_sd = (scatter * scatter + from_combos * from_combos).sqrt();
            (1.0 / slope, slope_sd / (slope * slope), KvSource::EscDuty(used))
        }
    };
    // The constants of (a, b, c, Kv): Kq = c Kv, R = a / Kq^2, Io = b Kq.
    let x = [k.a, k.b, k.c, kv];
    let rpm_per_rad = propbet_units::omega_to_rpm(1.0);
    let estimate = |g: &dyn Fn([f64; 4]) -> f64, unit: f64| Estimate {
        value: g(x) * unit,
        plus_minus: t * propagated(g, x, &cov, kv_sd) * unit,
    };
    let kv_rpm = Estimate {
        value: kv * rpm_per_rad,
        plus_minus: t * kv_sd * rpm_per_rad,
    };
    Ok(Constants {
        r: estimate(&|x| x[0] / (x[2] * x[3]).powi(2), 1.0),
        io: estimate(&|x| x[1] * x[2] * x[3], 1.0),
        kv_rpm,
        kq_rpm: kv_rpm,
        source,
        combos: k,
    })
}

/// Ordinary least squares of `y` on the columns of `x`: the coefficients and their
/// covariance.
fn ols(x: &nalgebra::DMatrix<f64>, y: &nalgebra::DVector<f64>) -> Result<(Vec<f64>, nalgebra::DMatrix<f64>), FitError> {
    let xtx = x.transpose() * x;
    let inv = xtx
        .try_inverse()
        .filter(|m| m.iter().all(|v| v.is_finite()))
        .ok_or_else(|| FitError::Unphysical("a singular system (every step at one speed and torque)".into()))?;
    let beta = &inv * (x.transpose() * y);
    let res = y - x * &beta;
    let s2 = res.norm_squared() / (y.len() - x.ncols()) as f64;
    Ok((beta.iter().copied().collect(), inv * s2))
}

/// Type 2: the motor's own current from the ESC's duty d (an ideal switch: I_m = I_b / d), at
/// half throttle and above, gives Kq and Io (I_m = Kq Q + Io, a straight line by least
/// squares); the supply power over every point then gives R and Kv (V_b I_b = R I_m^2 +
/// I_m Omega / Kv, linear in R and 1/Kv, each point weighted by its power; Kv given: R alone).
/// The intervals of R and Kv carry those of Kq and Io.
fn fit_type2(points: &[FitPoint], kv_rpm: Option<f64>) -> Result<Constants, FitError> {
    let used: Vec<(f64, f64)> = points
        .iter()
        .filter_map(|p| {
            let d = (p.esc? - 1000.0) / 1000.0;
            (0.5..=1.0).contains(&d).then_some((p.amps / d, p.torque))
        })
        .collect();
    if used.is_empty() {
        return Err(FitError::NoDuty);
    }
    if points.len() < 4 {
        return Err(FitError::TooFew(points.len()));
    }
    if used.len() < 4 {
        return Err(FitError::TooFewDuty(used.len()));
    }
    let n = used.len();
    let currents = nalgebra::DVector::from_iterator(n, used.iter().map(|u| u.0));
    let torque = nalgebra::DMatrix::from_fn(n, 2, |i, j| if j == 0 { used[i].1 } else { 1.0 });
    let (kq_io, cov_q) = ols(&torque, &currents)?;
    let given = kv_rpm.map(propbet_units::rpm_to_omega);
    // R and 1/Kv from the supply power, for a Kq and an Io.
    let power_fit = |kq: f64, io: f64| -> Result<(Vec<f64>, nalgebra::DMatrix<f64>), FitError> {
        let m = points.len();
        let w = |p: &FitPoint| 1.0 / (p.volts * p.amps).abs().max(1e-9);
        let im = |p: &FitPoint| kq * p.torque + io;
        match given {
            Some(kv) => {
                let y = nalgebra::DVector::from_iterator(
                    m,
                    points.iter().map(|p| (p.volts * p.amps - im(p) * p.omega / kv) * w(p)),
                );
                ols(
                    &nalgebra::DMatrix::from_fn(m, 1, |i, _| im(&points[i]).powi(2) * w(&points[i])),
                    &y,
                )
            }
            None => {
                let y = nalgebra::DVector::from_iterator(m, points.iter().map(|p| p.volts * p.amps * w(p)));
                let x = nalgebra::DMatrix::from_fn(m, 2, |i, j| {
                    let p = &points[i];
                    w(p) * if j == 0 { im(p).powi(2) } else { im(p) * p.omega }
                });
                ols(&x, &y)
            }
        }
    };
    let (kq, io) = (kq_io[0], kq_io[1]);
    let (b, cov_p) = power_fit(kq, io)?;
    // The sensitivities of R and 1/Kv to Kq and Io, for their share of the interval.
    let steps = [1e-6 * kq.abs().max(1e-9), 1e-6 * io.abs().max(1e-9)];
    let mut grad = vec![[0.0; 2]; b.len()];
    for (j, h) in steps.iter().enumerate() {
        let (kq2, io2) = if j == 0 { (kq + h, io) } else { (kq, io + h) };
        let b2 = power_fit(kq2, io2)?.0;
        for (k, g) in grad.iter_mut().enumerate() {
            g[j] = (b2[k] - b[k]) / h;
        }
    }
    let sd = |k: usize| {
        let g = grad[k];
        let carried = g[0] * g[0] * cov_q[(0, 0)] + 2.0 * g[0] * g[1] * cov_q[(0, 1)] + g[1] * g[1] * cov_q[(1, 1)];
        (cov_p[(k, k)] + carried).max(0.0).sqrt()
    };
    let (kv, kv_sd, source) = match given {
        Some(kv) => (kv, 0.0, KvSource::Given),
        None => (1.0 / b[1], sd(1) / (b[1] * b[1]), KvSource::EscDuty(n)),
    };
    let (r, r_sd) = (b[0], sd(0));
    let t = t975(n - 2);
    let rpm_per_rad = propbet_units::omega_to_rpm(1.0);
    let est = |value: f64, sd: f64| Estimate {
        value,
        plus_minus: t * sd,
    };
    Ok(Constants {
        r: est(r, r_sd),
        io: est(io, cov_q[(1, 1)].max(0.0).sqrt()),
        kv_rpm: est(kv * rpm_per_rad, kv_sd * rpm_per_rad),
        kq_rpm: est(kq * rpm_per_rad, cov_q[(0, 0)].max(0.0).sqrt() * rpm_per_rad),
        source,
        combos: Combos {
            a: r * kq * kq,
            b: io / kq,
            c: kq / kv,
        },
    })
}

/// The current predicted at each point with the fit made on the other steps (leave one step
/// out, Kv as the fit found it, `kv_rpm` when given); `step` names each point's step. Points
/// whose step leaves too few others are None.
pub fn held_out_amps(points: &[FitPoint], step: &[usize], kv_rpm: Option<f64>, kind: FitKind) -> Vec<Option<f64>> {
    points
        .iter()
        .zip(step)
        .map(|(p, s)| {
            let others: Vec<FitPoint> = points
                .iter()
                .zip(step)
                .filter(|(_, t)| *t != s)
                .map(|(q, _)| *q)
                .collect();
            let combos = match kind {
                FitKind::Type1 => fit_power(&others).ok().map(|f| f.combos),
                FitKind::Type2 => fit_type2(&others, kv_rpm).ok().map(|c| c.combos),
            };
            combos.map(|k| predicted_amps(p, &k))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn t_quantiles_are_students() {
        // Tables: t(0.975; 5) = 2.571, t(0.975; 30) = 2.042, infinity 1.960.
        assert!((t975(5) - 2.571).abs() < 0.03, "{}", t975(5));
        assert!((t975(30) - 2.042).abs() < 0.005);
        assert!((t975(100_000) - 1.960).abs() < 0.001);
    }

    /// `m` at `volts` on a propeller of Q = c w^2: its speed and its torque and current there.
    fn on_quadratic_prop(m: &Motor, volts: f64, c: f64) -> (f64, crate::model::MotorPoint) {
        let (mut lo, mut hi) = (0.0, m.free_speed(volts).unwrap());
        for _ in 0..200 {
            let w = 0.5 * (lo + hi);
            if c * w * w < m.at(w, volts).torque {
                lo = w;
            } else {
                hi = w;
            }
        }
        let w = 0.5 * (lo + hi);
        (w, m.at(w, volts))
    }

    /// A generated step log of `m` on a propeller Q = c w^2 (a 7 A load at full throttle) at 12 V through an ideal ESC,
    /// five samples per step, each reading with `noise` relative Gaussian noise.
    fn generated(m: &Motor, noise: f64, seed: u64) -> Vec<FitPoint> {
        let mut state = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        let mut uniform = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
        };
        let mut gauss = move || (-2.0 * uniform().ln()).sqrt() * (2.0 * std::f64::consts::PI * uniform()).cos();
        let vb = 12.0;
        let mut out = Vec::new();
        for k in 3..=10 {
            let d = k as f64 / 10.0;
            let (w, at) = on_quadratic_prop(m, d * vb, 2e-8);
            for _ in 0..5 {
                out.push(FitPoint {
                    omega: w * (1.0 + noise * gauss()),
                    torque: at.torque * (1.0 + noise * gauss()),
                    volts: vb * (1.0 + noise * gauss()),
                    amps: d * at.amps * (1.0 + noise * gauss()),
                    esc: Some(1000.0 + 1000.0 * d),
                });
            }
        }
        out
    }

    #[test]
    fn generated_logs_with_one_percent_noise_give_their_constants_within_the_intervals() {
        let m = Motor::dc1(0.12, 0.9, 1400.0).unwrap();
        let truth = [0.12, 0.9, 1400.0];
        let mut inside = [0usize; 3];
        let runs = 40;
        for seed in 0..runs {
            let f = fit_motor(&generated(&m, 0.01, seed), None, FitKind::Type1).unwrap();
            for (k, e) in [f.r, f.io, f.kv_rpm].iter().enumerate() {
                if (e.value - truth[k]).abs() <= e.plus_minus {
                    inside[k] += 1;
                }
                // The intervals say something: under a third of the value.
                assert!(e.plus_minus < 0.34 * truth[k], "seed {seed}: {k} {e:?}");
            }
        }
        // 95 % intervals: at least 34 of 40 (a binomial 95 % of 40 falls below 34 with
        // probability 1.6 %).
        eprintln!("intervals holding R, Io, Kv: {inside:?} of {runs}");
        for (k, n) in inside.iter().enumerate() {
            assert!(*n >= 34, "parameter {k}: {n} of {runs} intervals hold the truth");
        }
    }

    #[test]
    fn a_type_2_fit_finds_a_torque_constant_of_its_own_within_its_interval() {
        // Kq 10 % above Kv: the supply pays 10 % more than the shaft power's share.
        let m = Motor::from_params(2, &[0.12, 0.9, 1400.0, 1540.0, 0.0, 0.0, 0.0, 0.0]).unwrap();
        let truth = [0.12, 0.9, 1400.0, 1540.0];
        let mut inside = [0usize; 4];
        let mut inside_given = 0;
        let runs = 40;
        for seed in 0..runs {
            let f = fit_motor(&generated(&m, 0.01, seed), None, FitKind::Type2).unwrap();
            let kq = f.kq_rpm.expect("type 2 fits Kq");
            for (k, e) in [f.r, f.io, f.kv_rpm, kq].iter().enumerate() {
                if (e.value - truth[k]).abs() <= e.plus_minus {
                    inside[k] += 1;
                }
            }
            // Kq and Io are told apart well; R and Kv trade against each other on a
            // propeller's load (the current and the speed rise together): wide, but holding.
            assert!(
                kq.plus_minus < 0.03 * truth[3] && f.io.plus_minus < 0.15 * truth[1],
                "seed {seed}: {kq:?} {:?}",
                f.io
            );
            assert_eq!(f.motor.kind, crate::MotorKind::Dc2);
            // With the maker's Kv, R is found as well as type 1 finds it.
            let given = fit_motor(&generated(&m, 0.01, seed), Some(1400.0), FitKind::Type2).unwrap();
            if (given.r.value - truth[0]).abs() <= given.r.plus_minus {
                inside_given += 1;
            }
            assert!(given.r.plus_minus < 0.34 * truth[0], "seed {seed}: {:?}", given.r);
        }
        assert!(inside_given >= 34, "R with Kv given: {inside_given} of {runs}");
        eprintln!("intervals holding R, Io, Kv, Kq: {inside:?} of {runs}");
        for (k, n) in inside.iter().enumerate() {
            assert!(*n >= 34, "parameter {k}: {n} of {runs} intervals hold the truth");
        }
        // A type 1 fit of the same logs cannot hold both: it puts the extra power in R and Io.
        let one = fit_motor(&generated(&m, 0.0, 1), None, FitKind::Type1).unwrap();
        assert!(one.rms_current > 1e-4, "{}", one.rms_current);
        let two = fit_motor(&generated(&m, 0.0, 1), None, FitKind::Type2).unwrap();
        assert!(two.rms_current < 1e-9, "{}", two.rms_current);
        assert!((two.kq_rpm.unwrap().value / 1540.0 - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_noiseless_log_gives_its_motor_back() {
        let m = Motor::dc1(0.12, 0.9, 1400.0).unwrap();
        let vb = 12.0;
        let points: Vec<FitPoint> = (5..=10)
            .map(|k| {
                let d = k as f64 / 10.0;
                let (w, at) = on_quadratic_prop(&m, d * vb, 2e-9);
                FitPoint {
                    omega: w,
                    torque: at.torque,
                    volts: vb,
                    amps: d * at.amps,
                    esc: Some(1000.0 + 1000.0 * d),
                }
            })
            .collect();
        let f = fit_motor(&points, None, FitKind::Type1).unwrap();
        assert!((f.r.value / 0.12 - 1.0).abs() < 1e-6, "{:?}", f.r);
        assert!((f.io.value / 0.9 - 1.0).abs() < 1e-6, "{:?}", f.io);
        assert!((f.kv_rpm.value / 1400.0 - 1.0).abs() < 1e-6, "{:?}", f.kv_rpm);
        assert!(f.rms_current < 1e-9);
        let given = fit_motor(&points, Some(1400.0), FitKind::Type1).unwrap();
        assert!((given.r.value / 0.12 - 1.0).abs() < 1e-6);
        assert!(matches!(
            fit_motor(&points[..3], None, FitKind::Type1),
            Err(FitError::TooFew(3))
        ));
        let no_esc: Vec<FitPoint> = points.iter().map(|p| FitPoint { esc: None, ..*p }).collect();
        assert_eq!(fit_motor(&no_esc, None, FitKind::Type1), Err(FitError::NoKv));
    }
}
