//! Section aerodynamics: the [`SectionAero`] trait the solver calls, and QPROP's parametric
//! airfoil model ([`QpropAirfoil`]), the first implementation.
//!
//! The solver only ever asks a section for lift (with the derivatives Newton needs) and, once
//! the station has converged, for drag. A tabulated polar (cl, cd over alpha and Re) plugs in by
//! implementing the same trait.

use serde::{Deserialize, Serialize};

/// Lift of a section at one state, with the derivatives the Newton solve needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LiftEval {
    /// Lift coefficient [-].
    pub cl: f64,
    /// d(cl)/d(alpha) [1/rad].
    pub dcl_dalpha: f64,
    /// d(cl)/d(M^2) [-], zero where the model has no Mach dependence.
    pub dcl_dmsq: f64,
    /// d(cl)/d(Re) [-], zero where the model has no Reynolds dependence.
    pub dcl_dre: f64,
    /// True when alpha is beyond the model's stall limits.
    pub stalled: bool,
}

/// Everything a drag law may depend on, evaluated at the converged state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DragInput {
    /// Angle of attack [rad].
    pub alpha: f64,
    /// Lift coefficient returned by [`SectionAero::lift`] at this state [-].
    pub cl: f64,
    /// Whether [`SectionAero::lift`] reported stall.
    pub stalled: bool,
    /// Chord Reynolds number [-].
    pub re: f64,
    /// Mach number used by the drag law (QPROP: from the capped M^2, at least 1e-8) [-].
    pub mach: f64,
}

/// Aerodynamics of one blade section.
pub trait SectionAero: Send + Sync + std::fmt::Debug {
    /// Lift at angle of attack `alpha` [rad], Reynolds number `re` and squared Mach number
    /// `msq` (already capped by the solver at [`MSQ_MAX`]).
    fn lift(&self, alpha: f64, re: f64, msq: f64) -> LiftEval;
    /// Drag coefficient at a converged state [-].
    fn drag(&self, input: &DragInput) -> f64;
    /// Zero-lift angle of attack [rad]; QPROP starts its Newton iteration at
    /// `psi = beta - alpha_zero_lift` when that exceeds the geometric inflow angle.
    fn alpha_zero_lift(&self) -> f64;
    /// This section as QPROP's parametric model, if it is one: the solver then takes its
    /// vectorised path (eight stations at a time).
    fn as_qprop(&self) -> Option<&QpropAirfoil> {
        None
    }
    /// Reynolds numbers the model has data for (lowest, highest), if it is data at all: a
    /// station solved outside them runs on extrapolated data.
    fn reynolds_range(&self) -> Option<(f64, f64)> {
        None
    }
}

/// Cap on the local M^2 used for Prandtl-Glauert and drag rise (QPROP's `MSQMAX`).
pub const MSQ_MAX: f64 = 0.9;

/// The ten per-station coefficients of a QPROP prop file (SI: lift slope per radian).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct QpropCoefficients {
    /// Lift coefficient at zero angle of attack [-].
    pub cl0: f64,
    /// Lift-curve slope [1/rad].
    pub cl_a: f64,
    /// Negative stall limit of cl [-].
    pub cl_min: f64,
    /// Positive stall limit of cl [-].
    pub cl_max: f64,
    /// Minimum drag coefficient [-].
    pub cd0: f64,
    /// Drag-polar curvature above `clcd0` [-].
    pub cd2u: f64,
    /// Drag-polar curvature below `clcd0` [-].
    pub cd2l: f64,
    /// Lift coefficient at minimum drag [-].
    pub clcd0: f64,
    /// Reynolds number at which the drag polar applies [-].
    pub re_ref: f64,
    /// Reynolds-number scaling exponent of drag [-].
    pub re_exp: f64,
}

impl QpropCoefficients {
    /// QPROP's profile drag at `cl` before the Reynolds factor (FORMULATION.md, drag law):
    /// CD0 + CD2 (cl − CLCD0)², with CD2 = CD2u above CLCD0 and CD2l below. The one copy of
    /// the scalar law: the solver's drag, the polar fit and its tests use it (the vector lanes
    /// of `simd.rs` repeat it in `f64x8`).
    pub fn cd_profile(&self, cl: f64) -> f64 {
        let clb = cl - self.clcd0;
        let cd2 = if cl > self.clcd0 { self.cd2u } else { self.cd2l };
        self.cd0 + cd2 * clb * clb
    }

    /// QPROP's Reynolds-number factor of the drag, (Re/REref)^REexp.
    pub fn re_factor(&self, re: f64) -> f64 {
        (re / self.re_ref).powf(self.re_exp)
    }

    /// The coefficients as an array, in prop-file column order.
    pub fn to_array(&self) -> [f64; 10] {
        [
            self.cl0,
            self.cl_a,
            self.cl_min,
            self.cl_max,
            self.cd0,
            self.cd2u,
            self.cd2l,
            self.clcd0,
            self.re_ref,
            self.re_exp,
        ]
    }

    /// Builds the coefficients from an array in prop-file column order.
    pub fn from_array(a: [f64; 10]) -> Self {
        Self {
            cl0: a[0],
            cl_a: a[1],
            cl_min: a[2],
            cl_max: a[3],
            cd0: a[4],
            cd2u: a[5],
            cd2l: a[6],
            clcd0: a[7],
            re_ref: a[8],
            re_exp: a[9],
        }
    }

    /// Column names in prop-file order.
    pub const NAMES: [&'static str; 10] = [
        "CL0", "CL_a", "CLmin", "CLmax", "CD0", "CD2u", "CD2l", "CLCD0", "REref", "REexp",
    ];
}

/// QPROP's parametric section model (QPROP 1.22 `GVCALC`/`CDFUN`/`DCDFUN`):
///
/// $$c_l = \frac{CL0 + CL_a\,\alpha}{\sqrt{1-M^2}}$$ clipped by a cosine roll-off
/// $c_l = CL_{max}\cos(\alpha - CL0/CL_a)$ beyond `CLmax` (and likewise `CLmin`), and
/// $$c_d = [CD0 + CD2\,(c_l - CLCD0)^2]\,(Re/RE_{ref})^{RE_{exp}} + 10\,(M - M_{crit})^3_{M>M_{crit}}
///        + 2\sin^2(\alpha - \alpha_{CD0})_{stalled}$$
/// with `CD2 = CD2u` above `CLCD0`, `CD2l` below, and $\alpha_{CD0} = (CLCD0 - CL0)/CL_a$.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct QpropAirfoil {
    /// The ten prop-file coefficients.
    pub coeffs: QpropCoefficients,
    /// Critical Mach number of the drag rise [-] (QPROP: always 0.70).
    pub mcrit: f64,
}

/// QPROP's fixed critical Mach number (`MCRIT0` in qprop.f).
pub const QPROP_MCRIT: f64 = 0.70;

/// Smallest Reynolds number the drag law's power scaling is evaluated at; below it (a station
/// with no flow) `(Re/REref)^REexp` would be infinite for negative exponents.
const RE_FLOOR: f64 = 1.0;

impl QpropAirfoil {
    /// The model with QPROP's critical Mach number.
    pub fn new(coeffs: QpropCoefficients) -> Self {
        Self {
            coeffs,
            mcrit: QPROP_MCRIT,
        }
    }
}

impl SectionAero for QpropAirfoil {
    fn lift(&self, alpha: f64, _re: f64, msq: f64) -> LiftEval {
        let k = &self.coeffs;
        let pg = 1.0 / (1.0 - msq).sqrt();
        let cl_inc = k.cl0 + k.cl_a * alpha;
        let cl = cl_inc * pg;
        let limit = if cl > k.cl_max {
            Some(k.cl_max)
        } else if cl < k.cl_min {
            Some(k.cl_min)
        } else {
            None
        };
        match limit {
            // Stall: cosine roll-off about the zero-lift angle, no compressibility factor.
            Some(lim) => {
                let a = alpha - k.cl0 / k.cl_a;
                LiftEval {
                    cl: lim * a.cos(),
                    dcl_dalpha: -lim * a.sin(),
                    dcl_dmsq: 0.0,
                    dcl_dre: 0.0,
                    stalled: true,
                }
            }
            None => LiftEval {
                cl,
                dcl_dalpha: k.cl_a * pg,
                dcl_dmsq: cl_inc * 0.5 * pg / (1.0 - msq),
                dcl_dre: 0.0,
                stalled: false,
            },
        }
    }

    fn drag(&self, q: &DragInput) -> f64 {
        let k = &self.coeffs;
        let mut cd = k.cd_profile(q.cl) * k.re_factor(q.re.max(RE_FLOOR));
        if q.mach > self.mcrit {
            cd += 10.0 * (q.mach - self.mcrit).powi(3);
        }
        if q.stalled {
            let acd0 = (k.clcd0 - k.cl0) / k.cl_a;
            cd += 2.0 * (q.alpha - acd0).sin().powi(2);
        }
        cd
    }

    fn alpha_zero_lift(&self) -> f64 {
        -self.coeffs.cl0 / self.coeffs.cl_a
    }

    fn as_qprop(&self) -> Option<&QpropAirfoil> {
        Some(self)
    }
}

/// Snel's coefficient of rotational augmentation (Snel, Houwink & Bosschers 1994: 3).
pub const SNEL_A: f64 = 3.0;

/// Most of the lift deficit the base model's rotational augmentation restores: half, which
/// Snel's `3 (c/r)^2` reaches at c/r = 0.41. Small propellers have c/r 0.6-1.1 at the root,
/// where the uncapped law restores the whole attached line (cl 2.5-2.8 at 22 deg and Re
/// 15,000-35,000 on the 11x7 E statically). Chosen on the shared props with 1, 0.75, 0.5 and
/// 0.25 measured (`docs/studies/rotational-augmentation.md`); the `stall-delay` effect, which
/// fits `a`, keeps [`snel_fraction`]'s own cap of 1.
pub const SNEL_MAX_FRACTION: f64 = 0.5;

/// Lift of the attached-flow line at `alpha` and its slope, Prandtl-Glauert scaled: QPROP's
/// linear law for a QPROP section, else 2 pi (alpha - alpha_0) through the section's zero-lift
/// angle (thin-airfoil theory, the potential-flow lift Snel's correction restores a part of).
pub fn attached_lift(section: &dyn SectionAero, alpha: f64, msq: f64) -> (f64, f64) {
    let pg = 1.0 / (1.0 - msq).sqrt();
    match section.as_qprop() {
        Some(q) => ((q.coeffs.cl0 + q.coeffs.cl_a * alpha) * pg, q.coeffs.cl_a * pg),
        None => (
            2.0 * std::f64::consts::PI * (alpha - section.alpha_zero_lift()) * pg,
            2.0 * std::f64::consts::PI * pg,
        ),
    }
}

/// Fraction of the lift deficit rotation restores at a station of chord `chord` at radius `r`:
/// Snel's `a (c/r)^2`, at most 1 (the attached-flow line itself: small propellers reach
/// c/r = 0.6 at the root, where Snel's law, made for wind turbines, would pass it).
pub fn snel_fraction(a: f64, chord: f64, r: f64) -> f64 {
    let c_r = chord / r.max(1e-9);
    (a * c_r * c_r).clamp(0.0, 1.0)
}

/// Snel's rotational augmentation of a lift evaluation: `cl + k (cl_att - cl)` wherever the
/// section lifts less than its attached-flow line `(cl_att, dcl_att/dalpha)` on the positive
/// side (stall, laminar separation, thick sections at low Re). The deficit counted is at most
/// `cl_att` itself, so that the correction fades to zero at the line's zero-lift angle and the
/// lift stays continuous in alpha.
pub fn augment_lift(base: LiftEval, attached: (f64, f64), k: f64) -> LiftEval {
    let (lin, lin_a) = attached;
    if k <= 0.0 || lin <= 0.0 || lin <= base.cl {
        return base;
    }
    let (gap, gap_a) = if base.cl >= 0.0 {
        (lin - base.cl, lin_a - base.dcl_dalpha)
    } else {
        (lin, lin_a)
    };
    LiftEval {
        cl: base.cl + k * gap,
        dcl_dalpha: base.dcl_dalpha + k * gap_a,
        ..base
    }
}

/// A section with Snel's rotational augmentation at its station (`k` from [`snel_fraction`]);
/// drag as the section's own.
#[derive(Debug, Clone)]
pub struct Rotational {
    /// The 2-D section.
    pub inner: std::sync::Arc<dyn SectionAero>,
    /// Fraction of the lift deficit restored [-].
    pub k: f64,
}

impl SectionAero for Rotational {
    fn lift(&self, alpha: f64, re: f64, msq: f64) -> LiftEval {
        let base = self.inner.lift(alpha, re, msq);
        augment_lift(base, attached_lift(self.inner.as_ref(), alpha, msq), self.k)
    }

    fn drag(&self, input: &DragInput) -> f64 {
        self.inner.drag(input)
    }

    fn alpha_zero_lift(&self) -> f64 {
        self.inner.alpha_zero_lift()
    }

    fn reynolds_range(&self) -> Option<(f64, f64)> {
        self.inner.reynolds_range()
    }
}

/// A section whose drag is its own times `factor` (the base model's drag factor,
/// `docs/studies/drag-factor.md`); lift as the section's own.
#[derive(Debug, Clone)]
pub struct ScaledDrag {
    /// The section.
    pub inner: std::sync::Arc<dyn SectionAero>,
    /// Drag multiplier [-].
    pub factor: f64,
}

impl SectionAero for ScaledDrag {
    fn lift(&self, alpha: f64, re: f64, msq: f64) -> LiftEval {
        self.inner.lift(alpha, re, msq)
    }

    fn drag(&self, input: &DragInput) -> f64 {
        self.factor * self.inner.drag(input)
    }

    fn alpha_zero_lift(&self) -> f64 {
        self.inner.alpha_zero_lift()
    }

    fn reynolds_range(&self) -> Option<(f64, f64)> {
        self.inner.reynolds_range()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn cam() -> QpropAirfoil {
        // Global coefficients of QPROP's example prop `cam6x3`.
        QpropAirfoil::new(QpropCoefficients::from_array([
            0.5, 5.8, -0.3, 1.2, 0.028, 0.05, 0.05, 0.5, 70000.0, -0.7,
        ]))
    }

    #[test]
    fn lift_linear_range_and_prandtl_glauert() {
        let m = cam();
        let e = m.lift(0.05, 5e4, 0.0);
        assert_relative_eq!(e.cl, 0.5 + 5.8 * 0.05, epsilon = 1e-14);
        assert!(!e.stalled);
        let e = m.lift(0.05, 5e4, 0.36);
        assert_relative_eq!(e.cl, (0.5 + 5.8 * 0.05) / 0.8, epsilon = 1e-14);
        // Derivatives agree with finite differences.
        let h = 1e-7;
        let fd = (m.lift(0.05 + h, 5e4, 0.36).cl - m.lift(0.05 - h, 5e4, 0.36).cl) / (2.0 * h);
        assert_relative_eq!(e.dcl_dalpha, fd, epsilon = 1e-6);
        let fd = (m.lift(0.05, 5e4, 0.36 + h).cl - m.lift(0.05, 5e4, 0.36 - h).cl) / (2.0 * h);
        assert_relative_eq!(e.dcl_dmsq, fd, epsilon = 1e-6);
    }

    #[test]
    fn stall_rolls_off_with_cosine() {
        let m = cam();
        let alpha = 0.3; // (0.5 + 5.8*0.3) = 2.24 > CLmax
        let e = m.lift(alpha, 5e4, 0.0);
        assert!(e.stalled);
        assert_relative_eq!(e.cl, 1.2 * (alpha - 0.5 / 5.8).cos(), epsilon = 1e-14);
        let e = m.lift(-0.3, 5e4, 0.0);
        assert!(e.stalled);
        assert_relative_eq!(e.cl, -0.3 * (-0.3 - 0.5 / 5.8f64).cos(), epsilon = 1e-14);
    }

    #[test]
    fn drag_law_terms() {
        let m = cam();
        let base = DragInput {
            alpha: 0.0,
            cl: 0.8,
            stalled: false,
            re: 70000.0,
            mach: 0.3,
        };
        assert_relative_eq!(m.drag(&base), 0.028 + 0.05 * 0.09, epsilon = 1e-14);
        let low_re = DragInput { re: 35000.0, ..base };
        assert_relative_eq!(
            m.drag(&low_re),
            (0.028 + 0.05 * 0.09) * 0.5f64.powf(-0.7),
            epsilon = 1e-14
        );
        let fast = DragInput { mach: 0.8, ..base };
        assert_relative_eq!(
            m.drag(&fast),
            0.028 + 0.05 * 0.09 + 10.0 * 0.1f64.powi(3),
            epsilon = 1e-12
        );
        let stalled = DragInput {
            stalled: true,
            alpha: 0.4,
            ..base
        };
        assert_relative_eq!(
            m.drag(&stalled),
            0.028 + 0.05 * 0.09 + 2.0 * (0.4f64).sin().powi(2),
            epsilon = 1e-14
        );
        // No flow: finite drag, not infinity.
        assert!(m.drag(&DragInput { re: 0.0, ..base }).is_finite());
    }

    #[test]
    fn rotational_augmentation_restores_part_of_the_deficit_and_stays_continuous() {
        let base = |cl: f64| LiftEval {
            cl,
            dcl_dalpha: 1.0,
            dcl_dmsq: 0.0,
            dcl_dre: 0.0,
            stalled: false,
        };
        // Attached flow (cl on the line) and beyond the line: unchanged.
        assert_eq!(augment_lift(base(0.8), (0.8, 6.0), 0.5).cl, 0.8);
        assert_eq!(augment_lift(base(0.9), (0.8, 6.0), 0.5).cl, 0.9);
        // Half of a 0.4 deficit.
        let e = augment_lift(base(0.6), (1.0, 6.0), 0.5);
        assert_relative_eq!(e.cl, 0.8);
        assert_relative_eq!(e.dcl_dalpha, 3.5);
        // Negative 2-D lift above the line's zero: at most the line's own lift is restored,
        // so the correction vanishes where the line crosses zero.
        assert_relative_eq!(augment_lift(base(-0.2), (0.1, 6.0), 0.5).cl, -0.15);
        assert_eq!(augment_lift(base(-0.2), (-0.1, 6.0), 0.5).cl, -0.2);
        // Snel's fraction: a (c/r)^2, capped at 1 (the line itself).
        assert_relative_eq!(snel_fraction(3.0, 0.02, 0.1), 0.12);
        assert_eq!(snel_fraction(3.0, 0.06, 0.1), 1.0);
        const { assert!(SNEL_MAX_FRACTION > 0.0 && SNEL_MAX_FRACTION < 1.0) };
    }
}
