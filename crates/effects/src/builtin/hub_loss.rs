//! `hub-loss`: Prandtl's factor at the blade root.

use super::*;

/// `hub-loss`: Prandtl's factor at the blade root.
#[derive(Debug)]
pub(super) struct HubLoss(About);

impl HubLoss {
    pub(super) fn new() -> Self {
        Self(About {
            id: "hub-loss",
            params: vec![Param::new(
                "strength",
                "-",
                0.0,
                (0.0, 10.0),
                0.2,
                "0 = no hub loss (the baseline), 1 = Prandtl's hub factor",
            )
            .expecting(0.0, 1.5)],
            hooks: &[Hook::Inflow],
            explanation: "At the blade root the hub and the spinner shed a vortex like the tip does, and the inner \
                 sections carry less load than strip theory gives.",
        })
    }
}

impl Effect for HubLoss {
    about!();

    fn extra_starts(&self) -> Vec<Vec<f64>> {
        vec![vec![1.0]]
    }

    fn inflow(&self, p: &[f64], _point: &PointState, rotor: &Rotor, o: &mut SolverOptions) {
        o.hub_loss_strength = p[0];
        o.hub_radius = rotor.stations.first().map(|s| s.r - 0.5 * s.dr).unwrap_or(0.0);
    }
}
