//! Blade-element/momentum solver with QPROP 1.22's formulation.
//!
//! - [`aero`]: the section-aerodynamics trait and QPROP's parametric airfoil model.
//! - [`rotor`]: rotor and station definitions; QPROP's 25-midpoint spline discretisation.
//! - [`solve`]: the per-station solve (Newton on psi with a bracketed fallback) and loads.
//! - [`sweep`]: parallel sweeps over operating points.
//! - [`spline`]: Drela's derivative-form cubic spline.
//! - [`check`]: physical sense of a solved point (flags for what no propeller does).
//!
//! SI units throughout; angles in radians. This crate reads no files.
#![deny(missing_docs)]

pub mod aero;
pub mod check;
pub mod fluid;
pub mod rotor;
mod simd;
pub mod solve;
pub mod spline;
pub mod sweep;
pub use propbet_units as units;

pub use aero::{DragInput, LiftEval, QpropAirfoil, QpropCoefficients, Rotational, SectionAero};
pub use fluid::Fluid;
pub use rotor::{Discretization, QpropBlade, Rotor, RotorError, Station};
pub use solve::{
    solve_point_scalar, solve_point_scalar_psi, Convergence, OperatingPoint, PointResult, Psi, SolverOptions,
    StationResult,
};
pub use sweep::{grid_omega_j, grid_omega_v, grid_rpm_j, grid_rpm_v, solve_point, solve_points, Solver};
