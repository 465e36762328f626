//! A section model that interpolates XFOIL's polars directly (instead of QPROP's parametric
//! law): cl and cd linear in alpha and linear in ln Re between polars, with a post-stall
//! extension to +-180 deg and Prandtl-Glauert from each polar's own Mach number.
//!
//! Every polar is resampled once onto a uniform grid of [`STEP_DEG`] over -180..180 deg, so that
//! a lookup is an index computation instead of a search (the solver asks for lift a few
//! hundred times per operating point and station). Polars at XFOIL's usual whole or half
//! degrees are reproduced exactly; between the points of a finer user grid the table is the
//! linear interpolant of the grid's nodes.
//!
//! Past the last converged point on each side the curves blend, over 20 deg, from the last
//! point's cl and cd to a flat plate (cl = CDmax sin a cos a, cd = CDmax sin^2 a), CDmax = 1.3
//! (the Viterna-Corrigan value 1.11 + 0.018 AR for an aspect ratio near 10); a blade solved
//! there is marked stalled. Outside the polars' Re range cl is held and cd scaled by
//! (Re/Re_edge)^REexp with REexp from the two outermost polars (0 with a single polar).
//!
//! Between input stations the rotor gets a table of its own ([`TabulatedAero::blend`]): the
//! two neighbours' curves mixed by radius at every Reynolds number either of them has.

use std::f64::consts::PI;
use std::sync::Arc;

use propbet_bemt::{DragInput, LiftEval, Rotor, SectionAero};

use crate::table::Polar;

/// Drag coefficient of a flat plate broadside to the flow, used by the post-stall extension.
pub const CD_MAX: f64 = 1.3;
/// Angle over which the extension blends from the last converged point to the flat plate [deg].
const BLEND_DEG: f64 = 20.0;
/// Spacing of the uniform alpha grid every polar is resampled onto [deg].
pub const STEP_DEG: f64 = 0.25;
/// Nodes of the grid: -180..=180 deg.
const NODES: usize = (360.0 / STEP_DEG) as usize + 1;

/// One polar as interpolation tables on the uniform grid over -180..180 deg.
#[derive(Debug, Clone, PartialEq)]
struct Curve {
    re: f64,
    mach: f64,
    cl: Vec<f64>,
    cd: Vec<f64>,
    /// Converged range [rad]; outside it the section is stalled (extension).
    converged: [f64; 2],
}

/// Linear interpolation of `(x, y)` (x ascending) at `a`, clamped to the ends.
fn lerp_table(x: &[f64], y: &[f64], a: f64) -> f64 {
    let i = x.partition_point(|&v| v <= a).clamp(1, x.len() - 1);
    let t = ((a - x[i - 1]) / (x[i] - x[i - 1])).clamp(0.0, 1.0);
    y[i - 1] + t * (y[i] - y[i - 1])
}

/// Angle of grid node `k` [rad].
fn node(k: usize) -> f64 {
    (-180.0 + STEP_DEG * k as f64).to_radians()
}

impl Curve {
    fn new(p: &Polar) -> Option<Curve> {
        if p.points.len() < 2 {
            return None;
        }
        let first = p.points[0];
        let last = p.points[p.points.len() - 1];
        let mut alpha = Vec::new();
        let mut cl = Vec::new();
        let mut cd = Vec::new();
        // Skin friction stays when the plate is edgewise to the flow (near +-180 deg).
        let cd_floor = p.points.iter().map(|q| q.cd).fold(f64::INFINITY, f64::min);
        let extension = |a_s: f64, cl_s: f64, cd_s: f64, a: f64| -> (f64, f64) {
            let f = ((a - a_s).abs() / BLEND_DEG.to_radians()).min(1.0);
            let f = f * f * (3.0 - 2.0 * f);
            let (s, c) = a.sin_cos();
            let (cl_fp, cd_fp) = (CD_MAX * s * c, CD_MAX * s * s);
            (
                (1.0 - f) * cl_s + f * cl_fp,
                ((1.0 - f) * cd_s + f * cd_fp).max(cd_floor),
            )
        };
        let a_lo = first.alpha_deg.to_radians();
        let a_hi = last.alpha_deg.to_radians();
        // The extension at grid nodes beyond the converged range, at least half a step from
        // its ends; the converged points themselves as XFOIL gave them.
        let margin = 0.5 * STEP_DEG;
        for k in 0..NODES {
            let deg = -180.0 + STEP_DEG * k as f64;
            if deg < first.alpha_deg - margin {
                let (l, d) = extension(a_lo, first.cl, first.cd, deg.to_radians());
                alpha.push(deg.to_radians());
                cl.push(l);
                cd.push(d);
            }
        }
        for q in &p.points {
            alpha.push(q.alpha_deg.to_radians());
            cl.push(q.cl);
            cd.push(q.cd);
        }
        for k in 0..NODES {
            let deg = -180.0 + STEP_DEG * k as f64;
            if deg > last.alpha_deg + margin {
                let (l, d) = extension(a_hi, last.cl, last.cd, deg.to_radians());
                alpha.push(deg.to_radians());
                cl.push(l);
                cd.push(d);
            }
        }
        Some(Curve {
            re: p.re,
            mach: p.mach,
            cl: (0..NODES).map(|k| lerp_table(&alpha, &cl, node(k))).collect(),
            cd: (0..NODES).map(|k| lerp_table(&alpha, &cd, node(k))).collect(),
            converged: [a_lo, a_hi],
        })
    }

    /// Indices of the grid nodes inside the converged range.
    fn converged_indices(&self) -> impl Iterator<Item = usize> + '_ {
        (0..NODES).filter(|&k| node(k) >= self.converged[0] - 1e-12 && node(k) <= self.converged[1] + 1e-12)
    }

    /// (cl, dcl/dalpha, cd) at `a` in [-pi, pi].
    fn eval(&self, a: f64) -> (f64, f64, f64) {
        let h = STEP_DEG.to_radians();
        let x = (a + PI) / h;
        let i = (x.floor().max(0.0) as usize).min(NODES - 2);
        let t = (x - i as f64).clamp(0.0, 1.0);
        let slope = (self.cl[i + 1] - self.cl[i]) / h;
        (
            self.cl[i] + t * (self.cl[i + 1] - self.cl[i]),
            slope,
            self.cd[i] + t * (self.cd[i + 1] - self.cd[i]),
        )
    }

    /// `(1 - t) a + t b` node by node; Re geometric, Mach and the converged range linear.
    fn mix(a: &Curve, b: &Curve, t: f64) -> Curve {
        let m = |x: f64, y: f64| x + t * (y - x);
        Curve {
            re: (m(a.re.ln(), b.re.ln())).exp(),
            mach: m(a.mach, b.mach),
            cl: a.cl.iter().zip(&b.cl).map(|(&x, &y)| m(x, y)).collect(),
            cd: a.cd.iter().zip(&b.cd).map(|(&x, &y)| m(x, y)).collect(),
            converged: [m(a.converged[0], b.converged[0]), m(a.converged[1], b.converged[1])],
        }
    }
}

/// Polars of one section at several Reynolds numbers, as a [`SectionAero`].
#[derive(Debug, Clone, PartialEq)]
pub struct TabulatedAero {
    curves: Vec<Curve>,
    res: Vec<f64>,
    /// ln of `res` (the solver asks for lift hundreds of times a point: one log per call).
    ln_res: Vec<f64>,
    alpha_zero_lift: f64,
    re_exp_outside: f64,
}

impl TabulatedAero {
    /// Builds the model from polars of one section (polars with fewer than two converged points
    /// are skipped; `None` when none is left).
    pub fn new(polars: &[Polar]) -> Option<TabulatedAero> {
        let mut usable: Vec<&Polar> = polars.iter().filter(|p| p.points.len() >= 2).collect();
        usable.sort_by(|a, b| a.re.total_cmp(&b.re));
        usable.dedup_by(|a, b| a.re == b.re);
        let curves: Vec<Curve> = usable.iter().filter_map(|p| Curve::new(p)).collect();
        if curves.is_empty() {
            return None;
        }
        let alpha_zero_lift = zero_lift(&curves[curves.len() / 2]);
        let re_exp_outside = if curves.len() >= 2 {
            let (a, b) = (&curves[0], &curves[curves.len() - 1]);
            let cd_min = |c: &Curve| c.converged_indices().map(|i| c.cd[i]).fold(f64::INFINITY, f64::min);
            let e = (cd_min(b) / cd_min(a)).ln() / (b.re / a.re).ln();
            // A converged range narrower than one grid step has no minimum: no trend then.
            if e.is_finite() {
                e
            } else {
                0.0
            }
        } else {
            0.0
        };
        Some(Self::from_curves(curves, alpha_zero_lift, re_exp_outside))
    }

    fn from_curves(curves: Vec<Curve>, alpha_zero_lift: f64, re_exp_outside: f64) -> TabulatedAero {
        TabulatedAero {
            res: curves.iter().map(|c| c.re).collect(),
            ln_res: curves.iter().map(|c| c.re.ln()).collect(),
            curves,
            alpha_zero_lift,
            re_exp_outside,
        }
    }

    /// Reynolds numbers of the polars, ascending.
    pub fn reynolds_numbers(&self) -> &[f64] {
        &self.res
    }

    /// The curve this model uses at `re` (outside the range: the end curve, drag scaled).
    fn curve_at(&self, re: f64) -> Curve {
        let (i, j, t, _) = self.bracket(re);
        let mut c = Curve::mix(&self.curves[i], &self.curves[j], t);
        if let Some(e) = self.edge(re) {
            let f = (re / e).powf(self.re_exp_outside);
            c.cd.iter_mut().for_each(|d| *d *= f);
        }
        c.re = re;
        c
    }

    /// The end of the Re range `re` lies beyond, if it does.
    fn edge(&self, re: f64) -> Option<f64> {
        let (lo, hi) = (self.res[0], self.res[self.res.len() - 1]);
        (re < lo).then_some(lo).or((re > hi).then_some(hi))
    }

    /// The model of a section between two others: `(1 - f) a + f b` at every Reynolds number
    /// of either (`f` clamped to [0, 1]).
    pub fn blend(a: &TabulatedAero, b: &TabulatedAero, f: f64) -> TabulatedAero {
        let f = f.clamp(0.0, 1.0);
        let mut res: Vec<f64> = a.res.iter().chain(&b.res).copied().collect();
        res.sort_by(f64::total_cmp);
        res.dedup_by(|x, y| (*x / *y - 1.0).abs() < 1e-9);
        let curves = res
            .iter()
            .map(|&re| Curve {
                re,
                ..Curve::mix(&a.curve_at(re), &b.curve_at(re), f)
            })
            .collect();
        let m = |x: f64, y: f64| x + f * (y - x);
        Self::from_curves(
            curves,
            m(a.alpha_zero_lift, b.alpha_zero_lift),
            m(a.re_exp_outside, b.re_exp_outside),
        )
    }

    /// The two polars around `re` and the fraction between them, linear in ln Re (clamped to
    /// the ends: `table::re_bracket` with the logs kept).
    fn bracket(&self, re: f64) -> (usize, usize, f64, f64) {
        let n = self.res.len();
        let lr = re.ln();
        // NaN Re (no flow) takes the first polar.
        if n == 1 || lr.is_nan() || lr <= self.ln_res[0] {
            return (0, 0, 0.0, lr);
        }
        if lr >= self.ln_res[n - 1] {
            return (n - 1, n - 1, 0.0, lr);
        }
        let i = self.ln_res.iter().position(|&x| x > lr).unwrap_or(n - 1).max(1);
        let t = (lr - self.ln_res[i - 1]) / (self.ln_res[i] - self.ln_res[i - 1]);
        (i - 1, i, t, lr)
    }

    fn at(&self, alpha: f64, re: f64) -> (f64, f64, f64, f64, f64, bool) {
        let a = wrap(alpha);
        let (i, j, t, _) = self.bracket(re);
        let (ci, cj) = (&self.curves[i], &self.curves[j]);
        let (li, si, di) = ci.eval(a);
        let (lj, sj, dj) = cj.eval(a);
        let cl = li + t * (lj - li);
        let slope = si + t * (sj - si);
        let mut cd = di + t * (dj - di);
        let dcl_dre = if i != j {
            (lj - li) / (re * (self.ln_res[j] - self.ln_res[i]))
        } else {
            0.0
        };
        if let Some(e) = self.edge(re) {
            cd *= (re / e).powf(self.re_exp_outside);
        }
        let mach = ci.mach + t * (cj.mach - ci.mach);
        let lo = ci.converged[0] + t * (cj.converged[0] - ci.converged[0]);
        let hi = ci.converged[1] + t * (cj.converged[1] - ci.converged[1]);
        (cl, slope, cd, dcl_dre, mach, a < lo || a > hi)
    }
}

impl SectionAero for TabulatedAero {
    fn lift(&self, alpha: f64, re: f64, msq: f64) -> LiftEval {
        let (cl, slope, _, dcl_dre, mach, stalled) = self.at(alpha, re);
        let beta_t = (1.0 - mach * mach).sqrt();
        let one_m = (1.0 - msq).max(1e-6);
        let factor = beta_t / one_m.sqrt();
        LiftEval {
            cl: cl * factor,
            dcl_dalpha: slope * factor,
            // d/dM^2 of beta_t (1 - M^2)^(-1/2) = beta_t / 2 (1 - M^2)^(-3/2).
            dcl_dmsq: 0.5 * cl * factor / one_m,
            dcl_dre: dcl_dre * factor,
            stalled,
        }
    }

    fn drag(&self, input: &DragInput) -> f64 {
        self.at(input.alpha, input.re).2
    }

    fn alpha_zero_lift(&self) -> f64 {
        self.alpha_zero_lift
    }

    fn reynolds_range(&self) -> Option<(f64, f64)> {
        Some((self.res[0], self.res[self.res.len() - 1]))
    }
}

/// Zero-lift angle of a curve: the crossing in its converged range, else where its lift line
/// through the converged nodes would cross.
fn zero_lift(c: &Curve) -> f64 {
    let idx: Vec<usize> = c.converged_indices().collect();
    for w in idx.windows(2) {
        let (i, j) = (w[0], w[1]);
        if c.cl[i] <= 0.0 && c.cl[j] >= 0.0 && c.cl[j] > c.cl[i] {
            return node(i) - c.cl[i] * (node(j) - node(i)) / (c.cl[j] - c.cl[i]);
        }
    }
    let (Some(&i), Some(&j)) = (idx.first(), idx.last()) else {
        return 0.0;
    };
    let slope = (c.cl[j] - c.cl[i]) / (node(j) - node(i));
    if slope > 0.0 {
        node(i) - c.cl[i] / slope
    } else {
        0.0
    }
}

fn wrap(a: f64) -> f64 {
    if (-PI..=PI).contains(&a) {
        a
    } else {
        (a + PI).rem_euclid(2.0 * PI) - PI
    }
}

/// Puts section models given at radii `r` (ascending) onto the rotor's stations: at a station
/// between two of them, [`TabulatedAero::blend`] of the two by radius; beyond the ends, the
/// end model.
pub fn apply_to_rotor(rotor: &mut Rotor, r: &[f64], models: &[TabulatedAero]) {
    assert_eq!(r.len(), models.len(), "one section model per radius");
    let models: Vec<Arc<TabulatedAero>> = models.iter().cloned().map(Arc::new).collect();
    for st in &mut rotor.stations {
        let i = r.partition_point(|&x| x <= st.r);
        st.aero = if i == 0 {
            models[0].clone()
        } else if i == r.len() {
            models[r.len() - 1].clone()
        } else {
            let f = (st.r - r[i - 1]) / (r[i] - r[i - 1]);
            Arc::new(TabulatedAero::blend(&models[i - 1], &models[i], f))
        };
    }
}
#[cfg(test)]
mod tests {
    use super::*;

    fn polar(re: f64, cd_scale: f64) -> Polar {
        Polar::from_law(re, -6, 12, |alpha| {
            (0.4 + 0.1 * alpha, cd_scale * (0.012 + 0.0004 * alpha * alpha))
        })
    }

    #[test]
    fn reproduces_the_polar_and_interpolates_in_re() {
        let t = TabulatedAero::new(&[polar(5e4, 1.2), polar(2e5, 1.0)]).unwrap();
        let l = t.lift(4f64.to_radians(), 5e4, 0.0);
        assert!((l.cl - 0.8).abs() < 1e-12, "{l:?}");
        assert!((l.dcl_dalpha - 0.1f64.to_degrees()).abs() < 1e-9);
        assert!(!l.stalled);
        let d = |re: f64| {
            t.drag(&DragInput {
                alpha: 0.0,
                cl: 0.4,
                stalled: false,
                re,
                mach: 0.0,
            })
        };
        assert!((d(5e4) - 0.0144).abs() < 1e-12);
        assert!((d(1e5) - 0.012 * 1.1).abs() < 1e-12, "halfway in ln Re");
        // Outside the Re range drag follows the polars' own Re trend.
        assert!(d(4e5) < d(2e5) && d(2.5e4) > d(5e4));
        assert!((t.alpha_zero_lift() - (-4f64).to_radians()).abs() < 1e-9);
    }

    #[test]
    fn blending_mixes_by_radius_at_every_reynolds_number_of_either() {
        let a = TabulatedAero::new(&[polar(5e4, 1.2), polar(2e5, 1.0)]).unwrap();
        let b = TabulatedAero::new(&[polar(1e5, 1.5)]).unwrap();
        let m = TabulatedAero::blend(&a, &b, 0.25);
        assert_eq!(m.reynolds_numbers(), &[5e4, 1e5, 2e5]);
        assert_eq!(m.reynolds_range(), Some((5e4, 2e5)));
        let drag = |t: &TabulatedAero, re: f64| {
            t.drag(&DragInput {
                alpha: 2f64.to_radians(),
                cl: 0.6,
                stalled: false,
                re,
                mach: 0.0,
            })
        };
        for re in [5e4, 7e4, 1e5, 1.5e5, 2e5] {
            let want = 0.75 * drag(&a, re) + 0.25 * drag(&b, re);
            // Between its own nodes the blend is linear in ln Re, the parts are not.
            let tol = if [5e4, 1e5, 2e5].contains(&re) { 1e-12 } else { 2e-4 };
            assert!((drag(&m, re) - want).abs() < tol, "Re {re}: {} vs {want}", drag(&m, re));
        }
        let (only_a, a_with_a) = (TabulatedAero::blend(&a, &b, 0.0), TabulatedAero::blend(&a, &a, 0.7));
        for re in [3e4, 6e4, 1e5, 3e5] {
            assert!((drag(&only_a, re) - drag(&a, re)).abs() < 1e-12);
            assert!((drag(&a_with_a, re) - drag(&a, re)).abs() < 1e-12);
        }
    }

    #[test]
    fn off_grid_angles_are_linear_between_grid_nodes() {
        let t = TabulatedAero::new(&[polar(1e5, 1.0)]).unwrap();
        let l = |deg: f64| t.lift(deg.to_radians(), 1e5, 0.0).cl;
        assert!((l(3.1) - (0.4 + 0.31)).abs() < 1e-12);
        assert!((l(-6.0) - (-0.2)).abs() < 1e-12);
    }

    #[test]
    fn post_stall_goes_to_a_flat_plate_and_is_continuous() {
        let t = TabulatedAero::new(&[polar(1e5, 1.0)]).unwrap();
        let mut prev = t.lift(-PI, 1e5, 0.0).cl;
        for k in -1799..=1800 {
            let a = f64::from(k).to_radians() / 10.0;
            let l = t.lift(a, 1e5, 0.0);
            assert!((l.cl - prev).abs() < 0.05, "jump at {} deg", f64::from(k) / 10.0);
            prev = l.cl;
            let d = t.drag(&DragInput {
                alpha: a,
                cl: l.cl,
                stalled: l.stalled,
                re: 1e5,
                mach: 0.0,
            });
            assert!((0.012 - 1e-12..=CD_MAX + 1e-9).contains(&d), "cd {d} at {a}");
        }
        let l90 = t.lift(PI / 2.0, 1e5, 0.0);
        assert!(l90.stalled && l90.cl.abs() < 1e-9);
        let cd90 = t.drag(&DragInput {
            alpha: PI / 2.0,
            cl: 0.0,
            stalled: true,
            re: 1e5,
            mach: 0.0,
        });
        assert!((cd90 - CD_MAX).abs() < 1e-9);
        // Angles beyond +-180 wrap.
        assert!((t.lift(3.0 * PI / 2.0, 1e5, 0.0).cl - t.lift(-PI / 2.0, 1e5, 0.0).cl).abs() < 1e-9);
    }

    #[test]
    fn prandtl_glauert_relative_to_the_polar_mach() {
        let t = TabulatedAero::new(&[polar(1e5, 1.0)]).unwrap();
        let l0 = t.lift(0.0, 1e5, 0.0);
        let l = t.lift(0.0, 1e5, 0.36);
        assert!((l.cl - l0.cl / 0.8).abs() < 1e-12);
        // d cl / d M^2 by finite difference.
        let h = 1e-6;
        let fd = (t.lift(0.0, 1e5, 0.36 + h).cl - t.lift(0.0, 1e5, 0.36 - h).cl) / (2.0 * h);
        assert!((fd - l.dcl_dmsq).abs() < 1e-6, "{fd} vs {}", l.dcl_dmsq);
    }
}
