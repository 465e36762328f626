//! `stall-delay`: Snel's rotational augmentation of the inner sections' lift.

use super::*;

/// `stall-delay`: Snel's rotational augmentation of the inner sections' lift.
#[derive(Debug)]
pub(super) struct StallDelay(About);

impl StallDelay {
    pub(super) fn new() -> Self {
        Self(About {
            id: "stall-delay",
            params: vec![Param::new(
                "a",
                "-",
                0.0,
                (0.0, 12.0),
                0.5,
                "Snel's coefficient: cl + a (c/r)^2 (cl_attached - cl) where the section lifts less than its attached-flow line (Snel: 3)",
            ).expecting(0.0, 6.0)],
            hooks: &[Hook::Section],
            explanation: "Rotation delays stall near the root: centrifugal pumping thins the boundary layer and \
             the inner sections keep lifting beyond the 2-D stall angle (Snel et al. 1994). Visible at low \
             advance ratio, where the inner sections stall.",
        })
    }
}

impl Effect for StallDelay {
    about!();

    fn extra_starts(&self) -> Vec<Vec<f64>> {
        vec![vec![3.0]]
    }

    fn lift(
        &self,
        p: &[f64],
        ctx: &SectionCtx,
        inner: &dyn SectionAero,
        (alpha, _re, msq): (f64, f64, f64),
        base: LiftEval,
    ) -> Result<LiftEval, EffectError> {
        Ok(augment_lift(
            base,
            attached_lift(inner, alpha, msq),
            snel_fraction(p[0], ctx.geom.chord, ctx.geom.r),
        ))
    }
}
