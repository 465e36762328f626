//! `re-scaling`: a change of the section drag's Reynolds-number exponent.

use super::*;

/// `re-scaling`: a change of the section drag's Reynolds-number exponent.
#[derive(Debug)]
pub(super) struct ReScaling(About);

impl ReScaling {
    pub(super) fn new() -> Self {
        Self(About {
            id: "re-scaling",
            params: vec![Param::new(
                "dexp",
                "-",
                0.0,
                (-1.5, 1.5),
                0.1,
                "added to the drag's Reynolds-number exponent: cd * (Re/REref)^dexp",
            )
            .expecting(-0.5, 0.5)],
            hooks: &[Hook::Section],
            explanation: "At the Reynolds numbers of small propellers (20k-100k) laminar separation bubbles make the \
                 section drag depend on Re more strongly than the polar's exponent says: torque errors that change \
                 with RPM at a fixed advance ratio.",
        })
    }
}

impl Effect for ReScaling {
    about!();

    fn drag(
        &self,
        p: &[f64],
        _ctx: &SectionCtx,
        inner: &dyn SectionAero,
        d: &DragInput,
        cd: f64,
    ) -> Result<f64, EffectError> {
        let re_ref = inner.as_qprop().map_or(RE_SCALING_REF, |q| q.coeffs.re_ref);
        Ok(cd * (d.re.max(1.0) / re_ref).powf(p[0]))
    }
}
