//! `transition`: the sections' Ncrit (XFOIL's e^N transition criterion) as a fittable
//! parameter, from polar tables computed at several Ncrit values.
//!
//! The model's sections are the tables at one Ncrit (the default 5). With tables of the same
//! stations and Reynolds-number rungs at other Ncrit values (`propbet polars --ncrit-effect`),
//! the effect moves every station's lift and drag by the difference between the tables at the
//! fitted Ncrit (linear between the two computed levels around it) and the tables at the
//! model's own: `cl + cl_N(alpha, Re) - cl_base(alpha, Re)`, the same for cd. Whatever the
//! model adds on top of its tables (rotational augmentation at the root) stays. Between
//! stations the tables are mixed by radius, as the rotor's own are. Its bounds are the lowest
//! and highest Ncrit computed: beyond them it would be extrapolation, so a fit that ends there
//! "hit its bound".

use std::sync::Arc;

use propbet_bemt::{DragInput, LiftEval, SectionAero};

use crate::{Effect, EffectError, Hook, Param, SectionCtx};

/// The sections of a blade at one Ncrit: models placed at radii [m], ascending.
#[derive(Debug, Clone)]
pub struct Level {
    /// Ncrit of the tables [-].
    pub ncrit: f64,
    /// Radii of the stations that have a model [m], ascending.
    pub r: Vec<f64>,
    /// Their section models.
    pub models: Vec<Arc<dyn SectionAero>>,
}

/// The two entries of the ascending `xs` around `x` and the fraction between them (the end
/// entry beyond the ends).
fn bracket(xs: &[f64], x: f64) -> (usize, usize, f64) {
    let n = xs.len();
    let i = xs.partition_point(|&v| v <= x);
    if i == 0 {
        (0, 0, 0.0)
    } else if i == n {
        (n - 1, n - 1, 0.0)
    } else {
        (i - 1, i, (x - xs[i - 1]) / (xs[i] - xs[i - 1]))
    }
}

/// `eval` at the entries `(i, j)` mixed with fraction `t` (`eval(i)` alone when they are one).
fn between<T>((i, j, t): (usize, usize, f64), eval: impl Fn(usize) -> T, mix: impl Fn(T, T, f64) -> T) -> T {
    let a = eval(i);
    if i == j {
        a
    } else {
        mix(a, eval(j), t)
    }
}

fn mix_drag(a: f64, b: f64, t: f64) -> f64 {
    a + t * (b - a)
}

impl Level {
    fn lift(&self, r: f64, alpha: f64, re: f64, msq: f64) -> LiftEval {
        between(bracket(&self.r, r), |k| self.models[k].lift(alpha, re, msq), mix_lift)
    }

    fn drag(&self, r: f64, input: &DragInput) -> f64 {
        between(bracket(&self.r, r), |k| self.models[k].drag(input), mix_drag)
    }
}

/// `a + f (b - a)` of every derivative.
fn mix_lift(a: LiftEval, b: LiftEval, f: f64) -> LiftEval {
    let m = |x: f64, y: f64| x + f * (y - x);
    LiftEval {
        cl: m(a.cl, b.cl),
        dcl_dalpha: m(a.dcl_dalpha, b.dcl_dalpha),
        dcl_dmsq: m(a.dcl_dmsq, b.dcl_dmsq),
        dcl_dre: m(a.dcl_dre, b.dcl_dre),
        stalled: a.stalled || b.stalled,
    }
}

/// Smallest fraction of the model's drag the effect leaves (tables at two Ncrit values may
/// differ by more than a small drag where one of them separated).
const MIN_DRAG_FRACTION: f64 = 0.2;

/// The `transition` effect: see the module documentation.
#[derive(Debug, Clone)]
pub struct Transition {
    params: [Param; 1],
    /// Ascending in Ncrit; `levels[base]` is the model's own.
    levels: Vec<Level>,
    /// Their Ncrit values.
    ncrits: Vec<f64>,
    base: usize,
}

impl Transition {
    /// The effect from the model's own tables (`base`) and those at other Ncrit values
    /// (at least one, each with at least one station).
    pub fn new(base: Level, others: Vec<Level>) -> Result<Transition, EffectError> {
        let bad = |why: String| Err(EffectError::UserFile(format!("transition effect: {why}")));
        if others.is_empty() {
            return bad("no tables at another Ncrit".into());
        }
        let mut levels = others;
        levels.retain(|l| l.ncrit != base.ncrit);
        if let Some(l) = levels
            .iter()
            .chain(std::iter::once(&base))
            .find(|l| l.models.is_empty() || l.models.len() != l.r.len() || !(l.ncrit.is_finite() && l.ncrit > 0.0))
        {
            return bad(format!(
                "the tables at Ncrit {} have no station or no valid Ncrit",
                l.ncrit
            ));
        }
        let base_ncrit = base.ncrit;
        levels.push(base);
        levels.sort_by(|a, b| a.ncrit.total_cmp(&b.ncrit));
        levels.dedup_by(|a, b| a.ncrit == b.ncrit);
        let base = levels.iter().position(|l| l.ncrit == base_ncrit).unwrap_or(0);
        let (lower, upper) = (levels[0].ncrit, levels[levels.len() - 1].ncrit);
        let computed: Vec<String> = levels.iter().map(|l| crate::fmt_value(l.ncrit)).collect();
        let param = Param::new(
            "ncrit",
            "-",
            base_ncrit,
            (lower, upper),
            0.5,
            &format!(
                "XFOIL's transition amplification ratio of the sections, between the tables computed at Ncrit {} \
                 (lower: a more disturbed flow; Mack: Ncrit = -8.43 - 2.4 ln Tu)",
                computed.join(", ")
            ),
        );
        Ok(Transition {
            params: [param],
            ncrits: levels.iter().map(|l| l.ncrit).collect(),
            levels,
            base,
        })
    }

    /// The Ncrit values of the tables, ascending.
    pub fn ncrits(&self) -> Vec<f64> {
        self.ncrits.clone()
    }

    fn neutral(&self, n: f64) -> bool {
        n == self.levels[self.base].ncrit
    }
}

impl Effect for Transition {
    fn id(&self) -> &str {
        "transition"
    }

    fn params(&self) -> &[Param] {
        &self.params
    }

    fn hooks(&self) -> &[Hook] {
        &[Hook::Section]
    }

    fn explanation(&self) -> &str {
        "Where a small propeller's boundary layers turn turbulent depends on how disturbed the flow is \
         (the blade ahead's wake, the stand, the tunnel): XFOIL's Ncrit. A different Ncrit moves laminar \
         separation bubbles and trailing-edge separation, so lift and drag change most at low Reynolds \
         numbers: errors that change with RPM at a fixed advance ratio and with the angle of attack."
    }

    fn extra_starts(&self) -> Vec<Vec<f64>> {
        // Each computed level: the response is piecewise linear between them.
        self.levels.iter().map(|l| vec![l.ncrit]).collect()
    }

    fn lift(
        &self,
        p: &[f64],
        ctx: &SectionCtx,
        _inner: &dyn SectionAero,
        (alpha, re, msq): (f64, f64, f64),
        base: LiftEval,
    ) -> Result<LiftEval, EffectError> {
        if self.neutral(p[0]) {
            return Ok(base);
        }
        let r = ctx.geom.r;
        let at_n = between(
            bracket(&self.ncrits, p[0]),
            |k| self.levels[k].lift(r, alpha, re, msq),
            mix_lift,
        );
        let own = self.levels[self.base].lift(r, alpha, re, msq);
        Ok(LiftEval {
            cl: base.cl + at_n.cl - own.cl,
            dcl_dalpha: base.dcl_dalpha + at_n.dcl_dalpha - own.dcl_dalpha,
            dcl_dmsq: base.dcl_dmsq + at_n.dcl_dmsq - own.dcl_dmsq,
            dcl_dre: base.dcl_dre + at_n.dcl_dre - own.dcl_dre,
            stalled: base.stalled || at_n.stalled,
        })
    }

    fn drag(
        &self,
        p: &[f64],
        ctx: &SectionCtx,
        _inner: &dyn SectionAero,
        input: &DragInput,
        cd: f64,
    ) -> Result<f64, EffectError> {
        if self.neutral(p[0]) {
            return Ok(cd);
        }
        let r = ctx.geom.r;
        let at_n = between(bracket(&self.ncrits, p[0]), |k| self.levels[k].drag(r, input), mix_drag);
        let own = self.levels[self.base].drag(r, input);
        Ok((cd + at_n - own).max(MIN_DRAG_FRACTION * cd))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{PointState, StationGeom};
    use propbet_bemt::{Fluid, QpropAirfoil, QpropCoefficients};

    fn section(cl0: f64, cd0: f64) -> Arc<dyn SectionAero> {
        Arc::new(QpropAirfoil::new(QpropCoefficients {
            cl0,
            cl_a: 5.8,
            cl_min: -0.5,
            cl_max: 1.3,
            cd0,
            cd2u: 0.05,
            cd2l: 0.05,
            clcd0: 0.3,
            re_ref: 1e5,
            re_exp: -0.5,
        }))
    }

    fn level(ncrit: f64, cl0: [f64; 2], cd0: [f64; 2]) -> Level {
        Level {
            ncrit,
            r: vec![0.05, 0.1],
            models: vec![section(cl0[0], cd0[0]), section(cl0[1], cd0[1])],
        }
    }

    fn ctx(r: f64) -> SectionCtx {
        SectionCtx {
            geom: StationGeom {
                r,
                x: r / 0.125,
                chord: 0.02,
                beta: 0.3,
            },
            point: PointState {
                omega: 500.0,
                v: 0.0,
                fluid: Fluid::default(),
                tip_radius: 0.125,
                blades: 2.0,
                diameter: 0.25,
            },
        }
    }

    fn effect() -> Transition {
        Transition::new(
            level(5.0, [0.5, 0.4], [0.02, 0.02]),
            vec![
                level(9.0, [0.3, 0.2], [0.03, 0.03]),
                level(2.0, [0.6, 0.6], [0.015, 0.01]),
            ],
        )
        .unwrap()
    }

    #[test]
    fn bounds_are_the_computed_levels_and_the_model_is_neutral() {
        let t = effect();
        assert_eq!(t.ncrits(), vec![2.0, 5.0, 9.0]);
        let p = &t.params()[0];
        assert_eq!((p.lower, p.upper, p.neutral), (2.0, 9.0, Some(5.0)));
        let base = section(0.7, 0.01).lift(0.05, 6e4, 0.0);
        let inner = section(0.7, 0.01);
        let same = t
            .lift(&[5.0], &ctx(0.07), inner.as_ref(), (0.05, 6e4, 0.0), base)
            .unwrap();
        assert_eq!(same, base);
    }

    #[test]
    fn lift_and_drag_move_by_the_tables_difference_linear_in_ncrit_and_radius() {
        let t = effect();
        let inner = section(0.7, 0.01);
        let state = (0.05, 1e5, 0.0);
        let base = inner.lift(state.0, state.1, state.2);
        // At Ncrit 9, at the first station: cl0 0.3 against the model's 0.5.
        let l = t.lift(&[9.0], &ctx(0.05), inner.as_ref(), state, base).unwrap();
        assert!((l.cl - (base.cl - 0.2)).abs() < 1e-12, "{l:?}");
        // Halfway to 9 and halfway between the stations: (-0.2 - 0.2)/2 / 2.
        let l = t.lift(&[7.0], &ctx(0.075), inner.as_ref(), state, base).unwrap();
        assert!((l.cl - (base.cl - 0.1)).abs() < 1e-12, "{l:?}");
        // Below the model's Ncrit, towards the level at 2.
        let l = t.lift(&[3.5], &ctx(0.1), inner.as_ref(), state, base).unwrap();
        assert!((l.cl - (base.cl + 0.1)).abs() < 1e-12, "{l:?}");
        let input = DragInput {
            alpha: 0.05,
            cl: base.cl,
            stalled: false,
            re: 1e5,
            mach: 0.0,
        };
        let cd = inner.drag(&input);
        let d9 = t.drag(&[9.0], &ctx(0.05), inner.as_ref(), &input, cd).unwrap();
        assert!((d9 - (cd + 0.01)).abs() < 1e-12, "{d9} {cd}");
        // Never below a fifth of the model's drag.
        let d2 = t.drag(&[2.0], &ctx(0.1), inner.as_ref(), &input, 0.005).unwrap();
        assert!((d2 - 0.001).abs() < 1e-12, "{d2}");
    }

    #[test]
    fn tables_without_stations_are_refused() {
        let empty = Level {
            ncrit: 9.0,
            r: vec![],
            models: vec![],
        };
        let e = Transition::new(level(5.0, [0.5, 0.4], [0.02, 0.02]), vec![empty]).unwrap_err();
        assert!(e.to_string().contains("Ncrit 9"), "{e}");
        assert!(Transition::new(level(5.0, [0.5, 0.4], [0.02, 0.02]), vec![]).is_err());
    }
}
