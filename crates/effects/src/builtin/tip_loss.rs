//! `tip-loss`: the strength of Prandtl's tip-loss factor.

use super::*;

/// `tip-loss`: the strength of Prandtl's tip-loss factor.
#[derive(Debug)]
pub(super) struct TipLoss(About);

impl TipLoss {
    pub(super) fn new() -> Self {
        Self(About {
            id: "tip-loss",
            params: vec![Param::new(
                "strength",
                "-",
                1.0,
                (0.0, 4.0),
                0.2,
                "divides the tip-loss exponent: 1 = Prandtl (the baseline), 0 = no tip loss",
            )
            .expecting(0.7, 1.5)],
            hooks: &[Hook::Inflow],
            explanation:
                "Near the tip air flows round from the pressure to the suction side and the blade loses lift; \
                 Prandtl's factor models it for a helical wake. Measured loads above the model near its limit of \
                 small blade counts, or below it with wide tips, show a different strength.",
        })
    }
}

impl Effect for TipLoss {
    about!();

    fn extra_starts(&self) -> Vec<Vec<f64>> {
        vec![vec![0.3]]
    }

    fn inflow(&self, p: &[f64], _point: &PointState, _rotor: &Rotor, o: &mut SolverOptions) {
        o.tip_loss = true;
        o.tip_loss_strength = p[0];
    }
}
