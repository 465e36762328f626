//! A type 1 motor (R, Io, Kv) fitted to what a thrust stand logs: the shaft's speed and
//! torque, and the supply's voltage and current upstream of the ESC.
//!
//! The power the supply gives is the motor's (the ESC taken as lossless; its losses fall into
//! R): $V_b I_b = I_m^2 R + I_m \Omega / K_v$ with $I_m = Q K_v + I_0$. Written in the two
//! combinations a log determines, $a = R K_v^2$ and $b = I_0 / K_v$ (the no-load torque):
//! $$V_b I_b = Q\Omega + b\,\Omega + a\,(Q + b)^2,$$
//! fitted by Gauss-Newton with 95 % intervals from the covariance. The supply side alone
//! cannot separate Kv from R and Io: with the maker's Kv it is fitted so. Where the ESC command
//! is logged, Kv and Io come from both sides of the motor instead ([`sides`]): Kv from the
//! voltage the motor sees, $d V_b = \Omega/K_v + R I_m$, Io from its current against the torque,
//! $I_m = Q/K_t + I_0$, with $I_m = I_b / d$ and the duty $d$ read from the ESC command as a
//! linear ESC calibrated to 1000-2000 µs does (an assumption, said in the fit's notes), over
//! the steps at half throttle and above; the torque side's own constant, $1/K_t$, is the check
//! of Kv, and R stays the supply power's, $a / K_v^2$.
//!
//! The current this model predicts at a point, $I_b = (Q\Omega + b\Omega + a(Q+b)^2)/V_b$,
//! needs a and b only: it is what the held-out check scores.

use thiserror::Error;

use crate::model::Motor;

pub mod sides;

pub use sides::Sides;

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
    /// Kv from both sides of the motor, where the ESC command is logged at 3 steps of half
    /// throttle and above (the check of a given Kv too).
    pub sides: Option<Sides>,
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
    /// Too few steps with an ESC command at half throttle and above to find Kv from.
    #[error("{0} steps with the ESC command at half throttle and above: Kv from the motor's voltage needs at least 3; give the maker's Kv (--kv)")]
    FewDuty(usize),
    /// The motor's voltage at the ESC's duty makes no motor: the duty map is not this ESC's.
    #[error("{0}; give the maker's Kv (--kv)")]
    DutyMap(String),
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
        sides,
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
        sides,
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
    sides: Option<Sides>,
}

/// Type 1: a and b from the supply power over every point; Kv given, or from the motor's
/// voltage at the ESC's duty with Io from its current ([`sides`]).
fn fit_type1(points: &[FitPoint], kv_rpm: Option<f64>) -> Result<Constants, FitError> {
    if points.len() < 4 {
        return Err(FitError::TooFew(points.len()));
    }
    let PowerFit { combos: k, cov, .. } = fit_power(points)?;
    let t = t975(points.len().saturating_sub(2));
    let rpm_per_rad = propbet_units::omega_to_rpm(1.0);
    // Kv [rad/s per V], its standard deviation, and both sides where the command allows them
    // (without the maker's Kv, their Kv and Io are the fit's; with it, they check it).
    let (kv, kv_sd, sides) = match kv_rpm {
        Some(given) => (
            propbet_units::rpm_to_omega(given),
            0.0,
            sides::both_sides(points).ok().flatten(),
        ),
        None => {
            let s = sides::both_sides(points)?.ok_or_else(|| match points.iter().filter_map(sides::duty).count() {
                0 => FitError::NoKv,
                n => FitError::FewDuty(n),
            })?;
            let sd = s.kv_rpm.plus_minus / t975(s.steps - 2) / rpm_per_rad;
            (s.kv_rpm.value / rpm_per_rad, sd, Some(s))
        }
    };
    // The constants of (a, b, c, Kv): Kq = c Kv, R = a / Kq^2, Io = b Kq (the torque side's
    // where Kv is the sides' too).
    let x = [k.a, k.b, k.c, kv];
    let estimate = |g: &dyn Fn([f64; 4]) -> f64| Estimate {
        value: g(x),
        plus_minus: t * propagated(g, x, &cov, kv_sd),
    };
    let kv_est = match (&sides, kv_rpm) {
        (Some(s), None) => s.kv_rpm,
        _ => Estimate {
            value: kv * rpm_per_rad,
            plus_minus: 0.0,
        },
    };
    let source = match (&sides, kv_rpm) {
        (Some(s), None) => KvSource::EscDuty(s.steps),
        _ => KvSource::Given,
    };
    // The torque side's Io where Kv is the sides' and they agree; else the supply power's
    // (which holds the supply's current whatever Kv is).
    let (io, combos) = match sides
        .as_ref()
        .filter(|s| kv_rpm.is_none() && s.disagreement().abs() <= sides::DISAGREE)
    {
        Some(s) => (
            s.io,
            Combos {
                b: s.io.value / kv,
                ..k
            },
        ),
        None => (estimate(&|x| x[1] * x[2] * x[3]), k),
    };
    Ok(Constants {
        r: estimate(&|x| x[0] / (x[2] * x[3]).powi(2)),
        io,
        kv_rpm: kv_est,
        kq_rpm: kv_est,
        source,
        combos,
        sides,
    })
}

/// A least-squares fit: the coefficients, their covariance and the residuals.
type Ols = (Vec<f64>, nalgebra::DMatrix<f64>, Vec<f64>);

/// Ordinary least squares of `y` on the columns of `x` (more rows than columns): the
/// coefficients, their covariance and the residuals.
fn ols_with_rest(x: &nalgebra::DMatrix<f64>, y: &nalgebra::DVector<f64>) -> Result<Ols, FitError> {
    let xtx = x.transpose() * x;
    let inv = xtx
        .try_inverse()
        .filter(|m| m.iter().all(|v| v.is_finite()))
        .ok_or_else(|| FitError::Unphysical("a singular system (every step at one speed and torque)".into()))?;
    let beta = &inv * (x.transpose() * y);
    let res = y - x * &beta;
    let s2 = res.norm_squared() / (y.len() - x.ncols()) as f64;
    Ok((beta.iter().copied().collect(), inv * s2, res.iter().copied().collect()))
}

/// Ordinary least squares of `y` on the columns of `x`: the coefficients and their
/// covariance.
fn ols(x: &nalgebra::DMatrix<f64>, y: &nalgebra::DVector<f64>) -> Result<(Vec<f64>, nalgebra::DMatrix<f64>), FitError> {
    ols_with_rest(x, y).map(|(b, c, _)| (b, c))
}

/// Type 2: the motor's own current from the ESC's duty d (an ideal switch: I_m = I_b / d), at
/// half throttle and above, gives Kq and Io (I_m = Kq Q + Io, a straight line by least
/// squares); the supply power over every point then gives R and Kv (V_b I_b = R I_m^2 +
/// I_m Omega / Kv, linear in R and 1/Kv, each point weighted by its power; Kv given: R alone).
/// The intervals of R and Kv carry those of Kq and Io.
fn fit_type2(points: &[FitPoint], kv_rpm: Option<f64>) -> Result<Constants, FitError> {
    let used: Vec<(f64, f64)> = points
        .iter()
        .filter_map(|p| sides::duty(p).map(|d| (p.amps / d, p.torque)))
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
        sides: None,
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
                FitKind::Type1 => fit_type1(&others, kv_rpm).ok().map(|c| c.combos),
                FitKind::Type2 => fit_type2(&others, kv_rpm).ok().map(|c| c.combos),
            };
            combos.map(|k| predicted_amps(p, &k))
        })
        .collect()
}

#[cfg(test)]
mod tests;
