//! The propeller on its motor: each (driver, airspeed) point solved where the motor's torque
//! meets the model's (QPROP's `qprop PROP MOTOR V RPM Volt ...` drivers), with the model's
//! effects, in QPROP's order (the driver outer, the airspeed inner).

use std::path::Path;

use propbet_bemt::{Fluid, OperatingPoint, PointResult};
use propbet_motor::{operate, Drive, MotorFile, OperateError, Powered, PropLoads, Supply, SupplyPoint};
use rayon::prelude::*;

use crate::model::Model;
use crate::{read_text, Error, Result};

/// Reads a QPROP motor file (its constants checked: a bad one names its line and value).
pub fn read_motor(path: &Path) -> Result<MotorFile> {
    let text = read_text(path)?;
    propbet_motor::parse_motor(&text).map_err(|e| Error::input(path, e.to_string()))
}

/// One point of a powered sweep: its driver and airspeed, and the operating point or why
/// there is none.
#[derive(Debug, Clone)]
pub struct PoweredPoint {
    /// What set the point.
    pub drive: Drive,
    /// Airspeed [m/s].
    pub v: f64,
    /// The motor's side and the propeller's full result, or why the motor and the propeller
    /// have no common operating point.
    pub outcome: std::result::Result<(Powered, PointResult), String>,
    /// With a battery and ESC: what they do at the point, or why they cannot give it.
    pub supply: Option<std::result::Result<SupplyPoint, String>>,
}

/// The fastest a propeller is searched at: a tip speed of 1.5 times the speed of sound.
pub fn omega_ceiling(model: &Model, fluid: &Fluid) -> f64 {
    (1.5 * fluid.a / model.rotor.tip_radius).min(propbet_units::operating::OMEGA_MAX)
}

/// Every driver at every airspeed (the driver outer), on `motor` (and `supply`, the battery
/// and ESC, when given), in parallel.
pub fn powered(
    model: &Model,
    fluid: &Fluid,
    motor: &propbet_motor::Motor,
    supply: Option<&Supply>,
    drives: &[Drive],
    speeds: &[f64],
) -> Result<Vec<PoweredPoint>> {
    let ceiling = omega_ceiling(model, fluid);
    let pairs: Vec<(Drive, f64)> = drives
        .iter()
        .flat_map(|&d| speeds.iter().map(move |&v| (d, v)))
        .collect();
    if pairs.is_empty() {
        crate::nothing!("no operating point: give at least one driver value and one airspeed");
    }
    pairs
        .par_iter()
        .map(|&(drive, v)| {
            let at = |omega: f64| -> Result<PointResult> {
                let mut r = crate::stages::solve(model, fluid, &[OperatingPoint { v, omega }])?;
                r.pop()
                    .ok_or_else(|| Error::Nothing("the solver returned no point".into()))
            };
            let mut loads = |omega: f64| {
                at(omega).map(|p| PropLoads {
                    thrust: p.thrust,
                    torque: p.torque,
                })
            };
            let outcome = match operate(motor, drive, ceiling, &mut loads) {
                Ok(p) => Ok((p, at(p.omega)?)),
                Err(OperateError::Prop(e)) => return Err(e),
                Err(e @ OperateError::NoSolution { .. }) => Err(e.to_string()),
            };
            let supply = match (&outcome, supply) {
                (Ok((p, _)), Some(s)) => Some(s.at(p.volts, p.amps)),
                _ => None,
            };
            Ok(PoweredPoint {
                drive,
                v,
                outcome,
                supply,
            })
        })
        .collect()
}
