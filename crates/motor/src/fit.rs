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

/// The supply power the model gives at a point with combinations (a, b).
fn power(p: &FitPoint, a: f64, b: f64) -> f64 {
    p.torque * p.omega + b * p.omega + a * (p.torque + b).powi(2)
}

/// The supply current the fitted combinations (a, b) predict at a point.
pub fn predicted_amps(p: &FitPoint, ab: (f64, f64)) -> f64 {
    power(p, ab.0, ab.1) / p.volts
}

/// The power fit: (a, b), their covariance, the RMS relative residual.
pub type PowerFit = ((f64, f64), [[f64; 2]; 2], f64);

/// Gauss-Newton on (a, b), residuals relative to each point's measured power; returns the
/// estimates, their covariance and the RMS relative residual.
pub fn fit_power(points: &[FitPoint]) -> Result<PowerFit, FitError> {
    if points.len() < 4 {
        return Err(FitError::TooFew(points.len()));
    }
    let (mut a, mut b) = (0.0, 0.0);
    let mut cov = [[0.0; 2]; 2];
    let mut rms = 0.0;
    for _ in 0..50 {
        let (mut jtj, mut jtr, mut ss) = ([[0.0; 2]; 2], [0.0; 2], 0.0);
        for p in points {
            let measured = p.volts * p.amps;
            let w = 1.0 / measured.abs().max(1e-9);
            let r = (power(p, a, b) - measured) * w;
            let j = [(p.torque + b).powi(2) * w, (p.omega + 2.0 * a * (p.torque + b)) * w];
            for i in 0..2 {
                jtr[i] += j[i] * r;
                for k in 0..2 {
                    jtj[i][k] += j[i] * j[k];
                }
            }
            ss += r * r;
        }
        let det = jtj[0][0] * jtj[1][1] - jtj[0][1] * jtj[1][0];
        if det.abs() < 1e-300 {
            return Err(FitError::Unphysical(
                "a singular system (every point at one speed and torque)".into(),
            ));
        }
        let inv = [[jtj[1][1] / det, -jtj[0][1] / det], [-jtj[1][0] / det, jtj[0][0] / det]];
        let step = [
            inv[0][0] * jtr[0] + inv[0][1] * jtr[1],
            inv[1][0] * jtr[0] + inv[1][1] * jtr[1],
        ];
        a -= step[0];
        b -= step[1];
        let s2 = ss / (points.len() - 2) as f64;
        cov = [[inv[0][0] * s2, inv[0][1] * s2], [inv[1][0] * s2, inv[1][1] * s2]];
        rms = (ss / points.len() as f64).sqrt();
        if step[0].abs() <= 1e-12 * a.abs().max(1e-12) && step[1].abs() <= 1e-12 * b.abs().max(1e-12) {
            break;
        }
    }
    Ok(((a, b), cov, rms))
}

/// Fits R, Io and Kv to `points`; `kv_rpm` the maker's Kv when given.
pub fn fit_motor(points: &[FitPoint], kv_rpm: Option<f64>) -> Result<MotorFit, FitError> {
    let ((a, b), cov, _) = fit_power(points)?;
    let t = t975(points.len().saturating_sub(2));
    // Kv [rad/s per V] and its standard deviation.
    let (kv, kv_sd, source) = match kv_rpm {
        Some(k) => (propbet_units::rpm_to_omega(k), 0.0, KvSource::Given),
        None => {
            // d V_b = x / kv with x = a (Q + b) + Omega: the slope 1/kv through the origin,
            // its scatter about the line and, propagated, the uncertainty of a and b in x.
            let slope_of = |a: f64, b: f64| -> Option<(f64, f64, usize)> {
                let used: Vec<(f64, f64)> = points
                    .iter()
                    .filter_map(|p| {
                        let d = (p.esc? - 1000.0) / 1000.0;
                        (0.5..=1.0)
                            .contains(&d)
                            .then_some((a * (p.torque + b) + p.omega, d * p.volts))
                    })
                    .collect();
                if used.len() < 2 {
                    return None;
                }
                let sxx: f64 = used.iter().map(|(x, _)| x * x).sum();
                let slope = used.iter().map(|(x, y)| x * y).sum::<f64>() / sxx;
                let ss: f64 = used.iter().map(|(x, y)| (y - slope * x).powi(2)).sum();
                Some((slope, (ss / (used.len() - 1) as f64 / sxx).sqrt(), used.len()))
            };
            let (slope, scatter, n) = slope_of(a, b).ok_or(FitError::NoKv)?;
            let (da, db) = (1e-6 * a.abs().max(1e-9), 1e-6 * b.abs().max(1e-9));
            let g = [
                (slope_of(a + da, b).map_or(slope, |s| s.0) - slope) / da,
                (slope_of(a, b + db).map_or(slope, |s| s.0) - slope) / db,
            ];
            let from_ab = g[0] * g[0] * cov[0][0] + 2.0 * g[0] * g[1] * cov[0][1] + g[1] * g[1] * cov[1][1];
            let slope_sd = (scatter * scatter + from_ab.max(0.0)).sqrt();
            (1.0 / slope, slope_sd / (slope * slope), KvSource::EscDuty(n))
        }
    };
    let (a_sd, b_sd) = (cov[0][0].max(0.0).sqrt(), cov[1][1].max(0.0).sqrt());
    let r = a / (kv * kv);
    let r_sd = ((a_sd / (kv * kv)).powi(2) + (2.0 * r / kv * kv_sd).powi(2)).sqrt();
    let io = b * kv;
    let io_sd = ((b_sd * kv).powi(2) + (b * kv_sd).powi(2)).sqrt();
    let rpm_per_rad = propbet_units::omega_to_rpm(1.0);
    let motor = Motor::dc1(r, io.max(0.0), kv * rpm_per_rad).map_err(|e| FitError::Unphysical(e.to_string()))?;
    if io < 0.0 {
        return Err(FitError::Unphysical(format!(
            "a negative no-load current, Io = {io:.3} A"
        )));
    }
    let rms_current = (points
        .iter()
        .map(|p| (predicted_amps(p, (a, b)) / p.amps - 1.0).powi(2))
        .sum::<f64>()
        / points.len() as f64)
        .sqrt();
    let kv_rpm_sd = kv_sd * rpm_per_rad;
    Ok(MotorFit {
        r: Estimate {
            value: r,
            plus_minus: t * r_sd,
        },
        io: Estimate {
            value: io,
            plus_minus: t * io_sd,
        },
        kv_rpm: Estimate {
            value: kv * rpm_per_rad,
            plus_minus: t * kv_rpm_sd,
        },
        kv_source: source,
        rms_current,
        points: points.len(),
        motor,
    })
}

/// The current predicted at each point with the fit made on the other steps (leave one step
/// out); `step` names each point's step. Points whose step leaves too few others are None.
pub fn held_out_amps(points: &[FitPoint], step: &[usize]) -> Vec<Option<f64>> {
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
            fit_power(&others).ok().map(|(ab, _, _)| predicted_amps(p, ab))
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
            let f = fit_motor(&generated(&m, 0.01, seed), None).unwrap();
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
        let f = fit_motor(&points, None).unwrap();
        assert!((f.r.value / 0.12 - 1.0).abs() < 1e-6, "{:?}", f.r);
        assert!((f.io.value / 0.9 - 1.0).abs() < 1e-6, "{:?}", f.io);
        assert!((f.kv_rpm.value / 1400.0 - 1.0).abs() < 1e-6, "{:?}", f.kv_rpm);
        assert!(f.rms_current < 1e-9);
        let given = fit_motor(&points, Some(1400.0)).unwrap();
        assert!((given.r.value / 0.12 - 1.0).abs() < 1e-6);
        assert!(matches!(fit_motor(&points[..3], None), Err(FitError::TooFew(3))));
        let no_esc: Vec<FitPoint> = points.iter().map(|p| FitPoint { esc: None, ..*p }).collect();
        assert_eq!(fit_motor(&no_esc, None), Err(FitError::NoKv));
    }
}
