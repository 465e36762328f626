//! `torque-tare`: the motor's bearing friction and windage on the torque cell.

use super::*;

/// `torque-tare`: the motor's bearing friction and windage on the torque cell.
#[derive(Debug)]
pub(super) struct TorqueTare(About);

impl TorqueTare {
    pub(super) fn new() -> Self {
        Self(About {
            id: "torque-tare",
            params: vec![
                Param::new(
                    "q0",
                    "N m",
                    0.0,
                    (0.0, 0.2),
                    1e-3,
                    "constant torque (bearing friction: never below zero)",
                ),
                Param::new(
                    "q1",
                    "N m s/rad",
                    0.0,
                    (0.0, 1e-4),
                    1e-6,
                    "torque per rad/s (windage, viscous friction: never below zero)",
                ),
            ],
            hooks: &[Hook::Loads],
            explanation: "The torque cell also feels the motor's bearing friction and windage: Q0 + Q1 omega on top \
                 of the propeller's torque. Largest relative error at low RPM, thrust unaffected.",
        })
    }
}

impl Effect for TorqueTare {
    about!();

    fn loads(&self, p: &[f64], point: &PointState, _result: &PointResult, l: &mut Loads) -> Result<(), EffectError> {
        l.torque += p[0] + p[1] * point.omega;
        Ok(())
    }
}
