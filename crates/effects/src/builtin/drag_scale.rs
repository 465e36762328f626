//! `drag-scale`: every section's drag times a factor.

use super::*;

/// `drag-scale`: every section's drag times a factor.
#[derive(Debug)]
pub(super) struct DragScale(About);

impl DragScale {
    pub(super) fn new() -> Self {
        Self(About {
            id: "drag-scale",
            params: vec![Param::new(
                "factor",
                "-",
                1.0,
                (0.5, 2.5),
                0.1,
                "multiplies every section's drag (physical bounds: 0.5-2.5: XFOIL's or a wind tunnel's low-Re drag against a real blade's, rough or smooth)",
            ).expecting(0.8, 1.4)],
            hooks: &[Hook::Section],
            explanation: "The sections' profile drag is not the polars': surface roughness (a printed or scanned blade, \
             paint, mould lines), a finite trailing edge, unsteady laminar bubbles and three-dimensional flow \
             that 2-D polars do not hold. Torque (and the hover efficiency) off at every RPM and J alike, thrust \
             barely.",
        })
    }
}

impl Effect for DragScale {
    about!();

    fn drag(
        &self,
        p: &[f64],
        _ctx: &SectionCtx,
        _inner: &dyn SectionAero,
        _d: &DragInput,
        cd: f64,
    ) -> Result<f64, EffectError> {
        Ok(cd * p[0])
    }
}
