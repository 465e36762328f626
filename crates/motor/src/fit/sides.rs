//! Kv from both sides of a step test whose ESC command is logged, each by least squares on the
//! steps at half throttle and above, the duty d read from the command (a linear ESC calibrated
//! to 1000-2000 µs) and the motor's current the supply's over it, $I_m = I_b / d$:
//!
//! - the supply side: the voltage the motor sees, $d V_b = \Omega / K_v + R I_m$ (Kv and R);
//! - the torque side: $I_m = K_t^{-1} Q + I_0$ (Io, and the torque constant's Kv, $1/K_t$,
//!   the check of the supply side's). Its intercept does not move with a torque cell's scale
//!   error, which the supply power's balance turns into a no-load current below zero.
//!
//! A step off the line the others make on the supply side (by more than 4 of their standard
//! deviations and 0.5 % of its voltage: an ESC at full duty before its command, a supply
//! sagging at its current limit) is left out of both, the worst first, at most a third of them.

use super::{t975, Estimate, FitError, FitPoint};

/// The lowest duty the sides are fitted from: below half throttle an ESC's duty strays from
/// its command's line most.
pub const LOWEST_DUTY: f64 = 0.5;

/// The two sides' Kv disagree above this fraction: said so.
pub const DISAGREE: f64 = 0.10;

/// The steps needed on each side (two unknowns and one degree of freedom).
pub const FEWEST: usize = 3;

/// Kv from the supply side and from the torque side.
#[derive(Debug, Clone, PartialEq)]
pub struct Sides {
    /// Kv from the motor's voltage [rpm/V].
    pub kv_rpm: Estimate,
    /// R from the motor's voltage [ohm].
    pub r: Estimate,
    /// The torque side's Kv, 1/Kt [rpm/V].
    pub torque_kv_rpm: Estimate,
    /// Io, the torque side's intercept [A].
    pub io: Estimate,
    /// The steps fitted.
    pub steps: usize,
    /// The ESC commands [µs] of the steps left out (off the supply side's line).
    pub left_out: Vec<f64>,
}

impl Sides {
    /// The torque side's Kv over the supply side's, less 1.
    pub fn disagreement(&self) -> f64 {
        self.torque_kv_rpm.value / self.kv_rpm.value - 1.0
    }
}

/// The duty of a point's ESC command, where at half throttle and above.
pub fn duty(p: &FitPoint) -> Option<f64> {
    let d = (p.esc? - 1000.0) / 1000.0;
    (LOWEST_DUTY..=1.0).contains(&d).then_some(d)
}

/// Least squares of `y` on the columns `x` (rows): coefficients, covariance, residuals; None
/// with too few rows or a singular system.
fn lsq(x: &[Vec<f64>], y: &[f64]) -> Option<super::Ols> {
    let (n, k) = (y.len(), x.first()?.len());
    if n <= k {
        return None;
    }
    let a = nalgebra::DMatrix::from_fn(n, k, |i, j| x[i][j]);
    super::ols_with_rest(&a, &nalgebra::DVector::from_column_slice(y)).ok()
}

/// Kv from both sides, or None where fewer than [`FEWEST`] steps hold an ESC command at half
/// throttle and above. An error where the supply side makes no motor (a negative R or Kv: the
/// duty map is not this ESC's).
pub fn both_sides(points: &[FitPoint]) -> Result<Option<Sides>, FitError> {
    let mut used: Vec<(f64, &FitPoint)> = points.iter().filter_map(|p| Some((duty(p)?, p))).collect();
    let mut left_out = Vec::new();
    let supply = |used: &[(f64, &FitPoint)]| {
        let x: Vec<Vec<f64>> = used.iter().map(|(d, p)| vec![p.omega, p.amps / d]).collect();
        let y: Vec<f64> = used.iter().map(|(d, p)| d * p.volts).collect();
        lsq(&x, &y).map(|f| (f, y))
    };
    let fewest = FEWEST.max(used.len() * 2 / 3);
    // Each step against the line the others make (its voltage off their fit, over 4 of their
    // standard deviations and 0.5 % of its voltage): the worst left out while above 1.
    let (beta, cov) = loop {
        if used.len() < FEWEST {
            return Ok(None);
        }
        let Some(((beta, cov, _), _)) = supply(&used) else {
            return Ok(None);
        };
        if used.len() <= fewest {
            break (beta, cov);
        }
        let score = |i: usize| {
            let mut others = used.clone();
            let (d, p) = others.remove(i);
            let Some(((b, _, res), _)) = supply(&others) else {
                return 0.0;
            };
            let sigma = (res.iter().map(|r| r * r).sum::<f64>() / (res.len() - 2) as f64).sqrt();
            let y = d * p.volts;
            (y - b[0] * p.omega - b[1] * p.amps / d).abs() / (4.0 * sigma).max(0.005 * y.abs())
        };
        let (worst, most) = (0..used.len())
            .map(|i| (i, score(i)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((0, 0.0));
        if most <= 1.0 {
            break (beta, cov);
        }
        left_out.push(used[worst].1.esc.unwrap_or(f64::NAN));
        used.remove(worst);
    };
    let n = used.len();
    let t = t975(n - 2);
    let per_rad = propbet_units::omega_to_rpm(1.0);
    if !(beta[0] > 0.0 && beta[1] > 0.0) {
        return Err(FitError::DutyMap(format!(
            "the motor's voltage at {n} steps of half throttle and above gives {}: the ESC's duty is not \
             (command - 1000 µs) / 1000 µs here",
            if beta[0] > 0.0 {
                format!("R = {:.3} ohm", beta[1])
            } else {
                format!("1/Kv = {:.3e} V s/rad", beta[0])
            }
        )));
    }
    let kv = 1.0 / beta[0];
    let kv_sd = cov[(0, 0)].max(0.0).sqrt() * kv * kv;
    // The torque side, its slope free: 1/Kt.
    let im: Vec<f64> = used.iter().map(|(d, p)| p.amps / d).collect();
    let q: Vec<f64> = used.iter().map(|(_, p)| p.torque).collect();
    let x: Vec<Vec<f64>> = q.iter().map(|q| vec![*q, 1.0]).collect();
    let Some((b, c, _)) = lsq(&x, &im) else {
        return Ok(None);
    };
    let (torque_kv, torque_sd) = (b[0], c[(0, 0)].max(0.0).sqrt());
    let (io, io_sd) = (b[1], c[(1, 1)].max(0.0).sqrt());
    Ok(Some(Sides {
        kv_rpm: Estimate {
            value: kv * per_rad,
            plus_minus: t * kv_sd * per_rad,
        },
        r: Estimate {
            value: beta[1],
            plus_minus: t * cov[(1, 1)].max(0.0).sqrt(),
        },
        torque_kv_rpm: Estimate {
            value: torque_kv * per_rad,
            plus_minus: t * torque_sd * per_rad,
        },
        io: Estimate {
            value: io,
            plus_minus: t * io_sd,
        },
        steps: n,
        left_out,
    }))
}
