//! Sweeps: many operating points solved in parallel (rayon). Every point is solved
//! independently from QPROP's cold start, so results do not depend on the order of the points
//! or on the number of threads.

use rayon::prelude::*;

use crate::fluid::Fluid;
use crate::rotor::Rotor;
use crate::simd::{solve_batch, solve_point_prepared, Prepared};
use crate::solve::{solve_point_scalar_psi, OperatingPoint, PointResult, Psi, SolverOptions};

/// Solves one operating point, eight stations at a time in vector lanes where the rotor allows
/// (the same result as [`crate::solve_point_scalar`] to rounding).
///
/// The rotor must satisfy [`Rotor::validate`]; the operating point must be finite with a
/// non-negative rotation rate (the CLI checks user input before this point). For many points
/// use [`solve_points`] or a [`Solver`], which prepare the rotor once.
pub fn solve_point(rotor: &Rotor, fluid: &Fluid, op: OperatingPoint, opts: &SolverOptions) -> PointResult {
    solve_point_prepared(rotor, Prepared::new(rotor).as_ref(), fluid, op, opts)
}

/// A rotor, fluid and options prepared once for solving many operating points (the
/// vectorised path's lane groups are built here).
#[derive(Debug, Clone)]
pub struct Solver<'a> {
    rotor: &'a Rotor,
    prepared: Option<Prepared>,
    fluid: Fluid,
    opts: SolverOptions,
}

impl<'a> Solver<'a> {
    /// Prepares `rotor` (which must satisfy [`Rotor::validate`]).
    pub fn new(rotor: &'a Rotor, fluid: &Fluid, opts: &SolverOptions) -> Self {
        Self {
            rotor,
            prepared: Prepared::new(rotor),
            fluid: *fluid,
            opts: *opts,
        }
    }

    /// The same, solving every point on the scalar reference path (no vector lanes): for
    /// checking the vectorised path against it.
    pub fn scalar(rotor: &'a Rotor, fluid: &Fluid, opts: &SolverOptions) -> Self {
        Self {
            rotor,
            prepared: None,
            fluid: *fluid,
            opts: *opts,
        }
    }

    /// Solves one operating point (same result as [`crate::solve_point`]).
    pub fn solve(&self, op: OperatingPoint) -> PointResult {
        solve_point_prepared(self.rotor, self.prepared.as_ref(), &self.fluid, op, &self.opts)
    }

    /// Solves one operating point with each station's Newton iteration started as `psi` says
    /// ([`crate::solve_point_scalar_psi`]) where the rotor takes the scalar path; on the
    /// vector path every start is the cold one (and nothing is recorded).
    pub fn solve_psi(&self, op: OperatingPoint, psi: Psi<'_>) -> PointResult {
        match (&self.prepared, psi) {
            (None, psi) => solve_point_scalar_psi(self.rotor, &self.fluid, op, &self.opts, psi),
            (Some(_), Psi::Record(out)) => {
                out.clear();
                self.solve(op)
            }
            (Some(_), _) => self.solve(op),
        }
    }

    /// Solves many operating points, in order; eight at a time in vector lanes where possible.
    /// Every point is still solved independently (same iteration from the same start).
    pub fn solve_many(&self, ops: &[OperatingPoint]) -> Vec<PointResult> {
        let mut out = Vec::with_capacity(ops.len());
        let Some(p) = self
            .prepared
            .as_ref()
            .filter(|_| !self.opts.keep_stations && self.opts.vector_ok())
        else {
            out.extend(ops.iter().map(|&op| self.solve(op)));
            return out;
        };
        for chunk in ops.chunks(8) {
            if chunk.iter().all(|op| op.omega > 0.0) {
                out.extend(solve_batch(self.rotor, p, &self.fluid, chunk, &self.opts));
            } else {
                out.extend(chunk.iter().map(|&op| self.solve(op)));
            }
        }
        out
    }
}

/// Solves every point, in parallel, returning results in the order of `points`.
pub fn solve_points(rotor: &Rotor, fluid: &Fluid, points: &[OperatingPoint], opts: &SolverOptions) -> Vec<PointResult> {
    let solver = Solver::new(rotor, fluid, opts);
    points.par_chunks(64).flat_map_iter(|c| solver.solve_many(c)).collect()
}

/// The grid `rpm x v` in QPROP's nesting order (outer RPM, inner V).
pub fn grid_rpm_v(rpms: &[f64], speeds: &[f64]) -> Vec<OperatingPoint> {
    let omegas: Vec<f64> = rpms.iter().map(|&r| crate::units::rpm_to_omega(r)).collect();
    grid_omega_v(&omegas, speeds)
}

/// The grid `omega x V` [rad/s] x [m/s] (outer omega, inner V).
pub fn grid_omega_v(omegas: &[f64], speeds: &[f64]) -> Vec<OperatingPoint> {
    omegas
        .iter()
        .flat_map(|&omega| speeds.iter().map(move |&v| OperatingPoint { v, omega }))
        .collect()
}

/// The grid `rpm x J` (outer RPM, inner J), V = J n D with D = 2 `tip_radius` [m].
pub fn grid_rpm_j(rpms: &[f64], advance_ratios: &[f64], tip_radius: f64) -> Vec<OperatingPoint> {
    let omegas: Vec<f64> = rpms.iter().map(|&r| crate::units::rpm_to_omega(r)).collect();
    grid_omega_j(&omegas, advance_ratios, tip_radius)
}

/// The grid `omega x J` [rad/s] (outer omega, inner J), V = J n D with D = 2 `tip_radius` [m].
pub fn grid_omega_j(omegas: &[f64], advance_ratios: &[f64], tip_radius: f64) -> Vec<OperatingPoint> {
    omegas
        .iter()
        .flat_map(|&omega| {
            advance_ratios.iter().map(move |&j| {
                let n = omega / (2.0 * std::f64::consts::PI);
                OperatingPoint {
                    v: j * n * 2.0 * tip_radius,
                    omega,
                }
            })
        })
        .collect()
}
