//! `post-stall`: Viterna and Corrigan's flat-plate lift and drag beyond stall.

use super::*;

/// `post-stall`: Viterna and Corrigan's flat-plate lift and drag beyond stall.
#[derive(Debug)]
pub(super) struct PostStall(About);

impl PostStall {
    pub(super) fn new() -> Self {
        Self(About {
            id: "post-stall",
            params: vec![Param {
                neutral: None,
                start: 1.2,
                ..Param::new(
                    "cd_max",
                    "-",
                    1.2,
                    (0.3, 2.5),
                    0.1,
                    "Viterna's flat-plate drag at 90 deg (1.11 + 0.018 AR)",
                )
                .expecting(1.0, 2.0)
            }],
            hooks: &[Hook::Section],
            explanation: "Beyond stall the section behaves like a flat plate: Viterna and Corrigan's lift and drag \
                 replace the model's cosine roll-off. Visible only where sections stall (static thrust, low J).",
        })
    }
}

impl Effect for PostStall {
    about!();

    fn lift(
        &self,
        p: &[f64],
        _ctx: &SectionCtx,
        inner: &dyn SectionAero,
        (alpha, _re, msq): (f64, f64, f64),
        base: LiftEval,
    ) -> Result<LiftEval, EffectError> {
        if !base.stalled {
            return Ok(base);
        }
        Ok(match inner.as_qprop().and_then(|q| viterna(q, alpha, msq, p[0])) {
            Some((cl, dcl, _)) => LiftEval {
                cl,
                dcl_dalpha: dcl,
                dcl_dmsq: 0.0,
                ..base
            },
            None => base,
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
        if !d.stalled {
            return Ok(cd);
        }
        let msq = d.mach * d.mach;
        Ok(
            match inner.as_qprop().and_then(|q| viterna(q, d.alpha, msq.min(0.9), p[0])) {
                Some((_, _, cd_v)) => {
                    // The Reynolds-scaled profile drag stays; the stall term is Viterna's.
                    let k = inner.as_qprop().map(|q| q.coeffs);
                    let stall = k.map_or(0.0, |k| 2.0 * (d.alpha - (k.clcd0 - k.cl0) / k.cl_a).sin().powi(2));
                    (cd - stall).max(0.0).max(cd_v)
                }
                None => cd,
            },
        )
    }
}

/// Viterna-Corrigan post-stall lift and drag (and d cl/d alpha) at `alpha` beyond the positive
/// stall of a QPROP section, for flat-plate drag `cd_max`; `None` below stall or for sections
/// without a stall angle.
fn viterna(q: &QpropAirfoil, alpha: f64, msq: f64, cd_max: f64) -> Option<(f64, f64, f64)> {
    let k = &q.coeffs;
    let pg = 1.0 / (1.0 - msq).sqrt();
    let a_s = (k.cl_max / pg - k.cl0) / k.cl_a;
    if !(a_s > 0.02 && a_s < 1.2) || alpha <= a_s {
        return None;
    }
    let a = alpha.min(PI / 2.0);
    let cl_s = k.cl_max;
    let cd_s = q.drag(&DragInput {
        alpha: a_s,
        cl: cl_s,
        stalled: false,
        re: k.re_ref,
        mach: msq.sqrt(),
    });
    let (ss, cs) = a_s.sin_cos();
    let b2 = (cd_s - cd_max * ss * ss) / cs;
    let a1 = 0.5 * cd_max;
    let a2 = (cl_s - cd_max * ss * cs) * ss / (cs * cs);
    let (s, c) = a.sin_cos();
    let cl = a1 * (2.0 * a).sin() + a2 * c * c / s;
    let dcl = if alpha < PI / 2.0 {
        2.0 * a1 * (2.0 * a).cos() - a2 * c * (2.0 * s * s + c * c) / (s * s)
    } else {
        0.0
    };
    let cd = cd_max * s * s + b2 * c;
    Some((cl, dcl, cd))
}
