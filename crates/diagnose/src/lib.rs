//! Model discovery: where the model fails, which physical effect is missing, and by how much
//! the error falls when it is added.
//!
//! - [`Data`]: the scored measured points of a comparison, as residual rows (relative thrust
//!   and torque errors, with compare's 5 %-of-maximum floor).
//! - [`fit`]: a bounded Levenberg-Marquardt fit of effect parameters, with confidence intervals.
//! - [`discover`]: every candidate fitted and scored by held-out error (k-fold and
//!   leave-one-RPM-out), an F test against the noise, a parsimony penalty, the ranking and the
//!   greedy ladder.
//! - [`limits`]: what the data can tell (detection limits, effects they cannot separate) and
//!   the verdict that respects it.
//! - [`signature`]: residual patterns in words.
//! - [`synth`]: measurements made by the model with hidden effects and noise.
#![deny(missing_docs)]

pub mod discover;
pub mod fit;
pub mod inject;
pub mod limits;
pub mod provenance;

pub mod signature;
pub mod synth;

use propbet_bemt::{Fluid, OperatingPoint, Psi, Rotor, SolverOptions};
use propbet_compare::{metrics::rpm_group, ComparedPoint, RELATIVE_FLOOR};
use propbet_effects::{EffectError, Loads, Stack};
use rayon::prelude::*;
use serde::Serialize;
use thiserror::Error;

/// What can go wrong in a diagnosis.
#[derive(Debug, Error)]
pub enum DiagnoseError {
    /// An effect failed (a user formula).
    #[error(transparent)]
    Effect(#[from] EffectError),
    /// Not enough data.
    #[error("{0}")]
    TooFew(String),
    /// The measurements do not fit the propeller.
    #[error("{0}")]
    NoOverlap(String),
}

/// The model the effects are added to.
#[derive(Debug, Clone)]
pub struct Model<'a> {
    /// The rotor.
    pub rotor: &'a Rotor,
    /// Solver options (baseline).
    pub opts: SolverOptions,
    /// Propeller diameter [m].
    pub diameter: f64,
    /// Effects always applied (the user's `--effect`s), before the ones being fitted.
    pub fixed: Stack,
}

/// One scored measured point.
#[derive(Debug, Clone, Serialize)]
pub struct Observation {
    /// Index in the comparison's points.
    pub index: usize,
    /// Index of its measurement file.
    pub file: usize,
    /// Label ("line 12", "ESC 1300 µs").
    pub label: String,
    /// Logged rotation rate [rad/s].
    pub omega: f64,
    /// Airspeed [m/s].
    pub v: f64,
    /// Advance ratio (logged RPM).
    pub j: f64,
    /// Air assumed.
    #[serde(skip)]
    pub fluid: Fluid,
    /// Measured thrust [N].
    pub thrust: f64,
    /// Measured torque [N m], if measured.
    pub torque: Option<f64>,
    /// RPM group key (compare's grouping).
    pub rpm_group: i64,
    /// Its name ("6000 rpm").
    pub rpm_name: String,
    /// Tip Mach number.
    pub mach_tip: f64,
}

impl Observation {
    /// RPM as logged.
    pub fn rpm(&self) -> f64 {
        propbet_units::omega_to_rpm(self.omega)
    }
}

/// The scored points and how their residuals are scaled.
#[derive(Debug, Clone)]
pub struct Data {
    /// The points.
    pub obs: Vec<Observation>,
    /// Thrust residual floor [N] (5 % of the largest |thrust|).
    pub thrust_floor: f64,
    /// Torque residual floor [N m].
    pub torque_floor: f64,
}

/// The residual rows of one point: (point, is_torque).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Row {
    /// Index in [`Data::obs`].
    pub point: usize,
    /// Torque (else thrust).
    pub torque: bool,
}

impl Data {
    /// The scored points of a comparison: those the reader did not flag, inside the window
    /// (below `window` times their file's measured zero-thrust J,
    /// [`propbet_compare::metrics::in_window`]).
    pub fn from_points(points: &[ComparedPoint], window: f64) -> Result<Self, DiagnoseError> {
        let mut obs = Vec::new();
        let inside = propbet_compare::metrics::in_window(points, window);
        for (index, p) in points.iter().enumerate() {
            let Some(thrust) = p.measured.thrust.filter(|_| p.scored() && inside[index]) else {
                continue;
            };
            let (key, name) = rpm_group(p);
            obs.push(Observation {
                index,
                file: p.file,
                label: p.label.clone(),
                omega: propbet_units::rpm_to_omega(p.rpm),
                v: p.v,
                j: p.j,
                fluid: p.air.fluid,
                thrust,
                torque: p.measured.torque,
                rpm_group: key,
                rpm_name: name,
                mach_tip: p.mach_tip,
            });
        }
        if obs.len() < 3 {
            return Err(DiagnoseError::TooFew(format!(
                "only {} scored point(s) in the measurements: a diagnosis needs at least 3 (more than the parameters it fits)",
                obs.len()
            )));
        }
        let max_t = obs.iter().fold(0.0f64, |a, o| a.max(o.thrust.abs()));
        let max_q = obs.iter().filter_map(|o| o.torque).fold(0.0f64, |a, q| a.max(q.abs()));
        Ok(Self {
            obs,
            thrust_floor: (RELATIVE_FLOOR * max_t).max(1e-12),
            torque_floor: (RELATIVE_FLOOR * max_q).max(1e-12),
        })
    }

    /// The residual rows, in order.
    pub fn rows(&self) -> Vec<Row> {
        let mut rows = Vec::with_capacity(2 * self.obs.len());
        for (i, o) in self.obs.iter().enumerate() {
            rows.push(Row {
                point: i,
                torque: false,
            });
            if o.torque.is_some() {
                rows.push(Row { point: i, torque: true });
            }
        }
        rows
    }

    /// Residual rows of the points `which` given their predicted loads (same order).
    pub fn residuals(&self, which: &[usize], loads: &[Loads]) -> Vec<f64> {
        let mut r = Vec::with_capacity(2 * which.len());
        for (&i, l) in which.iter().zip(loads) {
            let o = &self.obs[i];
            r.push((l.thrust - o.thrust) / o.thrust.abs().max(self.thrust_floor));
            if let Some(q) = o.torque {
                r.push((l.torque - q) / q.abs().max(self.torque_floor));
            }
        }
        r
    }
}

impl Model<'_> {
    /// Predicted loads of the points `which` with the effects of `stack` (in parallel).
    pub fn loads(&self, data: &Data, stack: &Stack, which: &[usize]) -> Result<Vec<Loads>, EffectError> {
        let stack = self.with_fixed(stack);
        which
            .par_iter()
            .map(|&i| self.predict(&stack, &data.obs[i], Psi::Cold))
            .collect()
    }

    /// Predicted loads of every point with the effects of `stack`, `psi` holding a vector of
    /// wake angles a point: recorded there when `near` is false, each station's Newton
    /// iteration started from them when true (for a model a little apart from the one
    /// recorded: the forward differences of a fit; [`propbet_bemt::Psi`]).
    pub fn loads_near(
        &self,
        data: &Data,
        stack: &Stack,
        psi: &mut [Vec<f64>],
        near: bool,
    ) -> Result<Vec<Loads>, EffectError> {
        let stack = self.with_fixed(stack);
        data.obs
            .par_iter()
            .zip(psi.par_iter_mut())
            .map(|(o, psi)| {
                let start = if near { Psi::From(psi) } else { Psi::Record(psi) };
                self.predict(&stack, o, start)
            })
            .collect()
    }

    /// The model's own effects under `stack`'s.
    fn with_fixed<'s>(&self, stack: &'s Stack) -> std::borrow::Cow<'s, Stack> {
        if self.fixed.is_empty() {
            std::borrow::Cow::Borrowed(stack)
        } else {
            let mut active = self.fixed.active.clone();
            active.extend(stack.active.iter().cloned());
            std::borrow::Cow::Owned(Stack { active })
        }
    }

    fn predict(&self, stack: &Stack, o: &Observation, psi: Psi<'_>) -> Result<Loads, EffectError> {
        stack
            .predict_psi(
                self.rotor,
                &self.opts,
                &o.fluid,
                self.diameter,
                OperatingPoint { v: o.v, omega: o.omega },
                psi,
            )
            .map(|p| p.loads)
    }

    /// Residual rows of the points `which` with `stack`.
    pub fn residuals(&self, data: &Data, stack: &Stack, which: &[usize]) -> Result<Vec<f64>, EffectError> {
        Ok(data.residuals(which, &self.loads(data, stack, which)?))
    }

    /// Residual rows of every point with `stack`, the solves' wake angles recorded in or
    /// started from `psi` ([`Model::loads_near`]).
    pub fn residuals_near(
        &self,
        data: &Data,
        stack: &Stack,
        psi: &mut [Vec<f64>],
        near: bool,
    ) -> Result<Vec<f64>, EffectError> {
        let all: Vec<usize> = (0..data.obs.len()).collect();
        Ok(data.residuals(&all, &self.loads_near(data, stack, psi, near)?))
    }
}

/// How well the measurements repeat, estimated from the data themselves: pairs of points
/// taken at the same operating point in two sweeps (overlapping J sweeps at one RPM, the second
/// interpolated in J) or repeated within one file.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Repeatability {
    /// Relative standard deviation of one point's thrust (and torque, where measured) [-].
    pub sd: f64,
    /// Pairs of points it is estimated from.
    pub pairs: usize,
}

/// Largest RPM difference of two points taken as the same operating point (UIUC's sweeps at
/// "5000 rpm" run at 4,997 and 5,018).
const SAME_RPM: f64 = 0.03;
/// Widest J interval a point of another sweep is interpolated across.
const MAX_J_GAP: f64 = 0.1;
/// Pairs whose thrust is below this fraction of the largest are left out (near zero thrust a
/// relative difference says nothing).
const PAIR_THRUST_FLOOR: f64 = 0.25;

impl Data {
    /// The repeatability of these measurements, if they hold at least three pairs of points at
    /// the same operating point (`None` otherwise: nothing to estimate it from).
    pub fn repeatability(&self) -> Option<Repeatability> {
        let max_t = self.obs.iter().fold(0.0f64, |a, o| a.max(o.thrust.abs()));
        // Loads over rho omega^2: the coefficients up to the diameter, which is common.
        let norm = |o: &Observation, x: f64| x / (o.fluid.rho * o.omega * o.omega);
        let big = |o: &Observation| o.thrust > PAIR_THRUST_FLOOR * max_t;
        let mut d2 = Vec::new();
        let mut files: Vec<usize> = self.obs.iter().map(|o| o.file).collect();
        files.sort_unstable();
        files.dedup();
        for (ia, &fa) in files.iter().enumerate() {
            let a_pts: Vec<&Observation> = self.obs.iter().filter(|o| o.file == fa && big(o)).collect();
            // Repeated points within one file.
            for (k, a) in a_pts.iter().enumerate() {
                for b in &a_pts[k + 1..] {
                    if (a.omega / b.omega - 1.0).abs() < 0.01 && (a.j - b.j).abs() < 0.005 {
                        interpolated_pair(a, b, b, 0.0, norm, &mut d2);
                    }
                }
            }
            for &fb in &files[ia + 1..] {
                let mut b_pts: Vec<&Observation> = self.obs.iter().filter(|o| o.file == fb).collect();
                b_pts.sort_by(|x, y| x.j.total_cmp(&y.j));
                for a in &a_pts {
                    let near: Vec<&&Observation> = b_pts
                        .iter()
                        .filter(|b| (b.omega / a.omega - 1.0).abs() < SAME_RPM)
                        .collect();
                    if a.j < 0.01 {
                        // Static: the nearest static point of the other file at the same RPM.
                        if let Some(b) = near.iter().find(|b| b.j < 0.01 && big(b)) {
                            interpolated_pair(a, b, b, 0.0, norm, &mut d2);
                        }
                        continue;
                    }
                    if let Some(w) = near.windows(2).find(|w| w[0].j <= a.j && a.j <= w[1].j) {
                        let (b0, b1) = (w[0], w[1]);
                        if b1.j - b0.j <= MAX_J_GAP && b1.j > b0.j && big(b0) && big(b1) {
                            let t = (a.j - b0.j) / (b1.j - b0.j);
                            interpolated_pair(a, b0, b1, t, norm, &mut d2);
                        }
                    }
                }
            }
        }
        (d2.len() >= 3).then(|| Repeatability {
            // Each pair's difference holds two points' scatter.
            sd: (d2.iter().sum::<f64>() / (2.0 * d2.len() as f64)).sqrt(),
            pairs: d2.len(),
        })
    }
}

/// Squared relative differences of thrust (and torque) of `a` and the point interpolated
/// between `b0` and `b1` (`b0 = b1`, `t = 0` for a point measured again).
fn interpolated_pair(
    a: &Observation,
    b0: &Observation,
    b1: &Observation,
    t: f64,
    norm: impl Fn(&Observation, f64) -> f64,
    d2: &mut Vec<f64>,
) {
    let lerp = |x: f64, y: f64| x + t * (y - x);
    let rel = |x: f64, y: f64| (x / y - 1.0).powi(2);
    d2.push(rel(norm(a, a.thrust), lerp(norm(b0, b0.thrust), norm(b1, b1.thrust))));
    if let (Some(qa), Some(q0), Some(q1)) = (a.torque, b0.torque, b1.torque) {
        d2.push(rel(norm(a, qa), lerp(norm(b0, q0), norm(b1, q1))));
    }
}

/// Root mean square.
pub fn rms(r: &[f64]) -> f64 {
    if r.is_empty() {
        0.0
    } else {
        (r.iter().map(|x| x * x).sum::<f64>() / r.len() as f64).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A static-air point of file `file` at `rpm` and `j` measuring `thrust` (no torque): the
    /// tests' point (`limits`' too).
    pub(crate) fn obs(file: usize, rpm: f64, j: f64, thrust: f64) -> Observation {
        Observation {
            index: 0,
            file,
            label: String::new(),
            omega: propbet_units::rpm_to_omega(rpm),
            v: 0.0,
            j,
            fluid: Fluid::QPROP_DEFAULT,
            thrust,
            torque: None,
            rpm_group: rpm as i64,
            rpm_name: String::new(),
            mach_tip: 0.1,
        }
    }

    #[test]
    fn repeatability_comes_from_points_at_one_operating_point() {
        // Two sweeps at 5000 rpm: the second's thrust 2 % above the first's, J nodes offset by
        // half a step (interpolated); a third sweep at 8000 rpm pairs with neither.
        let mut v = Vec::new();
        for k in 0..6 {
            let j = 0.1 + 0.05 * f64::from(k);
            v.push(obs(0, 5000.0, j, 10.0 - 10.0 * j));
            let j2 = j + 0.025;
            v.push(obs(1, 5000.0, j2, 1.02 * (10.0 - 10.0 * j2)));
            v.push(obs(2, 8000.0, j, 30.0 - 30.0 * j));
        }
        let data = Data {
            obs: v,
            thrust_floor: 0.5,
            torque_floor: 1e-12,
        };
        let r = data.repeatability().expect("overlapping sweeps");
        // Every pair differs by 2 % (linear thrust: interpolation is exact): the first sweep's
        // point over the second's is 1/1.02, sd = that difference / sqrt 2. Points below a
        // quarter of the largest thrust (the 8000 rpm sweep's) are left out.
        assert!((r.sd - (1.0 - 1.0 / 1.02) / 2f64.sqrt()).abs() < 1e-9, "{r:?}");
        assert!(r.pairs >= 3, "{r:?}");
        // One sweep alone repeats nothing.
        let single = Data {
            obs: data.obs.iter().filter(|o| o.file == 0).cloned().collect(),
            ..data.clone()
        };
        assert!(single.repeatability().is_none());
    }
}
