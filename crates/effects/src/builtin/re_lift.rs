//! `re-lift`: section lift times (Re/1e5)^n.

use super::*;

/// `re-lift`: section lift times (Re/1e5)^n.
#[derive(Debug)]
pub(super) struct ReLift(About);

impl ReLift {
    pub(super) fn new() -> Self {
        Self(About {
            id: "re-lift",
            params: vec![Param::new(
                "n",
                "-",
                0.0,
                (-0.4, 0.4),
                0.02,
                "section lift times (Re/1e5)^n (physical bounds: +-0.4, lift halving or doubling over a decade at most)",
            ).expecting(-0.2, 0.2)],
            hooks: &[Hook::Section],
            explanation: "At 20k-100k the sections' lift depends on Reynolds number (laminar separation and bubbles \
             thin as Re grows) more or less than the polars say: thrust errors that change with RPM at a fixed \
             advance ratio, torque following through the induced power.",
        })
    }
}

impl Effect for ReLift {
    about!();

    fn lift(
        &self,
        p: &[f64],
        _ctx: &SectionCtx,
        _inner: &dyn SectionAero,
        (_alpha, re, _msq): (f64, f64, f64),
        base: LiftEval,
    ) -> Result<LiftEval, EffectError> {
        let f = (re.max(1.0) / RE_SCALING_REF).powf(p[0]);
        Ok(LiftEval {
            cl: base.cl * f,
            dcl_dalpha: base.dcl_dalpha * f,
            dcl_dmsq: base.dcl_dmsq * f,
            dcl_dre: base.dcl_dre * f + base.cl * f * p[0] / re.max(1.0),
            ..base
        })
    }
}
