//! A model solved at operating points: the sweep's grid of RPM and J or V checked, each point
//! solved with the model's effects (or others), in order or in parallel chunks; and the setup a
//! comparison solves measured points with. The stages and the band solve through here.

use propbet_bemt::{grid_omega_j, grid_omega_v, Fluid, OperatingPoint, PointResult, Solver};
use propbet_compare::{AirChoice, Setup};
use propbet_effects::Stack;
use propbet_settings::spec::{PredictSpec, SweepAxis};
use rayon::prelude::*;

use crate::Model;
use crate::Result;

/// Most operating points one sweep may hold (RPM values times J or V values): about 200 MB of
/// results, 50 times the largest sweep of the benchmarks.
pub(crate) const MAX_POINTS: usize = 1_000_000;

/// The operating points of a predict spec, for a rotor of tip radius `tip_radius` [m].
pub fn operating_points(spec: &PredictSpec, tip_radius: f64) -> Result<Vec<OperatingPoint>> {
    grid(&spec.omegas, &spec.axis, tip_radius)
}

/// Every rotation speed with every J or V, checked, for a rotor of tip radius `tip_radius` [m].
pub fn grid(omegas: &[f64], axis: &SweepAxis, tip_radius: f64) -> Result<Vec<OperatingPoint>> {
    let other = match axis {
        SweepAxis::J(v) | SweepAxis::V(v) => v.len(),
    };
    let n = omegas.len().saturating_mul(other);
    if n > MAX_POINTS {
        out_of_range!(
            "the sweep has {} RPM values x {other} J or V values = {n} operating points; at most {MAX_POINTS} in one sweep",
            omegas.len()
        );
    }
    if let Some(bad) = omegas.iter().find(|&&w| w > propbet_measure::limits::OMEGA) {
        out_of_range!(
            "--rpm: {} is beyond any small propeller's speed (at most 500000)",
            propbet_units::show(propbet_units::omega_to_rpm(*bad))
        );
    }
    if let Some(bad) = omegas
        .iter()
        .find(|&&w| w > 0.0 && w < propbet_measure::limits::OMEGA_MIN)
    {
        out_of_range!(
            "--rpm: {} is below 1 rpm, where the coefficients divide by almost nothing (0 is allowed: the propeller at rest)",
            propbet_units::show(propbet_units::omega_to_rpm(*bad))
        );
    }
    let speeds = match axis {
        SweepAxis::J(j) => j.iter().any(|j| j.abs() > propbet_measure::limits::ADVANCE_RATIO),
        SweepAxis::V(v) => v.iter().any(|v| v.abs() > propbet_measure::limits::AIRSPEED),
    };
    if speeds {
        out_of_range!(
            "--j / --v: beyond any small propeller's operating range (|J| at most {}, |V| at most {} m/s)",
            propbet_measure::limits::ADVANCE_RATIO,
            propbet_measure::limits::AIRSPEED
        );
    }
    if let Some(bad) = omegas.iter().find(|&&w| w.is_nan() || w < 0.0) {
        out_of_range!(
            "--rpm: rotation speed must not be negative, found {}",
            propbet_settings::values::rpm_text(*bad)
        );
    }
    Ok(match axis {
        SweepAxis::J(j) => {
            if omegas.contains(&0.0) {
                conflict!("--j needs a non-zero --rpm (J = V/(nD) is undefined at 0 rpm)");
            }
            grid_omega_j(omegas, j, tip_radius)
        }
        SweepAxis::V(v) => grid_omega_v(omegas, v),
    })
}

/// Solves `points` with the model (its effects included), in order.
pub fn solve(model: &Model, fluid: &Fluid, points: &[OperatingPoint]) -> Result<Vec<PointResult>> {
    solve_with(model, &model.effects, fluid, points)
}

/// Solves `points` with the model's rotor and `effects` instead of the model's, in order.
pub(crate) fn solve_with(
    model: &Model,
    effects: &Stack,
    fluid: &Fluid,
    points: &[OperatingPoint],
) -> Result<Vec<PointResult>> {
    if effects.is_empty() {
        return Ok(Solver::new(&model.rotor, fluid, &model.opts).solve_many(points));
    }
    points
        .iter()
        .map(|&op| {
            let p = effects.predict(&model.rotor, &model.opts, fluid, model.diameter, op)?;
            Ok(p.result.with_loads(
                p.loads.thrust,
                p.loads.torque,
                op.omega,
                fluid.rho,
                model.rotor.tip_radius,
            ))
        })
        .collect()
}

/// Operating points one parallel task solves at once (the sweeps here, and the predict table
/// that is formatted chunk by chunk as it is solved).
pub const CHUNK: usize = 128;

/// Solves `points` in parallel chunks of [`CHUNK`] (in order).
pub fn sweep(model: &Model, fluid: &Fluid, points: &[OperatingPoint]) -> Result<Vec<PointResult>> {
    sweep_with(model, &model.effects, fluid, points)
}

/// [`sweep`] with `effects` instead of the model's.
pub(crate) fn sweep_with(
    model: &Model,
    effects: &Stack,
    fluid: &Fluid,
    points: &[OperatingPoint],
) -> Result<Vec<PointResult>> {
    let chunks: Vec<Vec<PointResult>> = points
        .par_chunks(CHUNK)
        .map(|c| solve_with(model, effects, fluid, c))
        .collect::<Result<_>>()?;
    Ok(chunks.into_iter().flatten().collect())
}

/// The solver setup of a model for the comparison (with the model's effects or without).
pub fn setup<'a>(model: &'a Model, air: AirChoice, effects: Stack) -> Setup<'a> {
    Setup {
        rotor: &model.rotor,
        diameter: model.diameter,
        opts: model.opts,
        air,
        effects,
    }
}
