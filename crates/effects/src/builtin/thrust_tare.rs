//! `thrust-tare`: the stand's blockage drag in the slipstream.

use super::*;

/// `thrust-tare`: the stand's blockage drag in the slipstream.
#[derive(Debug)]
pub(super) struct ThrustTare(About);

impl ThrustTare {
    pub(super) fn new() -> Self {
        Self(About {
            id: "thrust-tare",
            params: vec![Param::new(
                "k",
                "-",
                0.0,
                (0.0, 0.15),
                0.02,
                "blockage area (CdS) over disc area; thrust - k q_slip pi R^2 (physical bounds: 0-0.15: a drag area is not negative)",
            )],
            hooks: &[Hook::Loads],
            explanation: "The motor, its mount and the stand sit in the slipstream: they take back a drag force \
             proportional to the slipstream's dynamic pressure (1/2 rho (V + dv)^2), so the stand reads \
             less thrust than the propeller makes, about k T when static.",
        })
    }
}

impl Effect for ThrustTare {
    about!();

    fn loads(&self, p: &[f64], point: &PointState, result: &PointResult, l: &mut Loads) -> Result<(), EffectError> {
        let radius = 0.5 * point.diameter;
        let area = PI * radius * radius;
        let vs = point.v + result.dv;
        l.thrust -= p[0] * 0.5 * point.fluid.rho * vs * vs * area;
        Ok(())
    }
}
