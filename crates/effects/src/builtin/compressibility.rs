//! `compressibility`: the drag-rise Mach number and the Prandtl-Glauert exponent.

use super::*;

/// QPROP's drag-rise Mach number (qprop.f `MCRIT0`), the baseline of `compressibility`.
const MCRIT0: f64 = propbet_bemt::aero::QPROP_MCRIT;

/// `compressibility`: the drag-rise Mach number and the Prandtl-Glauert exponent.
#[derive(Debug)]
pub(super) struct Compressibility(About);

impl Compressibility {
    pub(super) fn new() -> Self {
        Self(About {
            id: "compressibility",
            params: vec![
                Param {
                    start: 0.6,
                    ..Param::new(
                        "mcrit",
                        "-",
                        MCRIT0,
                        (0.2, 0.95),
                        0.05,
                        "drag-rise Mach number: cd + 10 (M - mcrit)^3 above it (baseline 0.70)",
                    )
                    .expecting(0.5, 0.9)
                },
                Param::new(
                    "pg",
                    "-",
                    1.0,
                    (0.0, 4.0),
                    0.3,
                    "Prandtl-Glauert exponent: cl / (1 - M^2)^(pg/2) (baseline 1)",
                )
                .expecting(0.5, 2.0),
            ],
            hooks: &[Hook::Section],
            explanation:
                "Near the tip the local Mach number reaches 0.3-0.6: lift grows by the Prandtl-Glauert factor \
                 (Karman-Tsien: faster), and the drag rises steeply once shocks form above the critical Mach \
                 number. The error grows with tip Mach, i.e. with RPM at any advance ratio.",
        })
    }
}

impl Effect for Compressibility {
    about!();

    fn extra_starts(&self) -> Vec<Vec<f64>> {
        vec![vec![0.45, 1.0], vec![0.3, 1.0], vec![0.7, 1.5]]
    }

    fn lift(
        &self,
        p: &[f64],
        _ctx: &SectionCtx,
        _inner: &dyn SectionAero,
        (_alpha, _re, msq): (f64, f64, f64),
        base: LiftEval,
    ) -> Result<LiftEval, EffectError> {
        if base.stalled {
            return Ok(base);
        }
        // base = cl_inc / sqrt(1 - M^2); the effect makes the exponent pg/2.
        let f = (1.0 - msq).powf(-(p[1] - 1.0) / 2.0);
        let f_msq = f * (p[1] - 1.0) / 2.0 / (1.0 - msq);
        Ok(LiftEval {
            cl: base.cl * f,
            dcl_dalpha: base.dcl_dalpha * f,
            dcl_dmsq: base.dcl_dmsq * f + base.cl * f_msq,
            ..base
        })
    }

    fn drag(
        &self,
        p: &[f64],
        _ctx: &SectionCtx,
        inner: &dyn SectionAero,
        d: &DragInput,
        cd: f64,
    ) -> Result<f64, EffectError> {
        let rise = |mc: f64| if d.mach > mc { 10.0 * (d.mach - mc).powi(3) } else { 0.0 };
        let base_mcrit = inner.as_qprop().map_or(MCRIT0, |q| q.mcrit);
        Ok(cd - rise(base_mcrit) + rise(p[0]))
    }
}
