//! Reduction of XFOIL polars to QPROP's ten coefficients.
//!
//! QPROP's section law (`propbet_bemt::aero::QpropAirfoil`) is a straight lift line clipped at
//! CLmin/CLmax, and a drag polar of two half-parabolas in cl about CLCD0, scaled by
//! (Re/REref)^REexp. Real low-Re polars are not that shape everywhere: a thin, highly cambered
//! section (E63 at 4-6 % and Re 2e4-1e5) has its drag minimum near cl = 1.2, laminar bubbles
//! bend the lift line, and XFOIL fails at many positive angles inboard. A fit over the whole
//! polar then describes angles the blade never sees and misses the ones it does. So:
//!
//! 1. the **linear range** grows outward from the angle the blade works at (or the middle of the
//!    attached range) while one straight line still fits every point within 0.025 in cl;
//! 2. CL0 and CL_a come from a weighted line fit over it, the weights [`AlphaWeights`] saying
//!    which angles the blade sees; Prandtl-Glauert is taken out, because QPROP puts it back;
//! 3. CD0, CD2u, CD2l come from a weighted least-squares fit of the *relative* drag error over
//!    the linear range for each trial CLCD0 (a fine grid over its cl), keeping the best;
//! 4. REexp from the drag ratio at equal cl between polars at other Re;
//! 5. the residuals over the linear range are reported, and [`QpropFit::unfit`] says in words
//!    when the parametric law does not describe XFOIL's polar where the blade works.

use propbet_bemt::QpropCoefficients;
use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::table::Polar;

/// Placeholder lift and Reynolds terms for evaluating the drag law alone (only its drag terms
/// are read).
fn drag_only() -> QpropCoefficients {
    QpropCoefficients {
        cl0: 0.0,
        cl_a: 2.0 * std::f64::consts::PI,
        cl_min: -1.0,
        cl_max: 1.0,
        cd0: 0.0,
        cd2u: 0.0,
        cd2l: 0.0,
        clcd0: 0.0,
        re_ref: 1.0,
        re_exp: 0.0,
    }
}

/// Lift tolerance of the linear range: every point within this of one straight line.
pub const LINEAR_RANGE_CL_TOL: f64 = 0.025;
/// Largest lift error of an acceptable fit over the linear range.
pub const FIT_CL_TOL: f64 = 0.03;
/// Largest relative drag error of an acceptable fit over the linear range.
pub const FIT_CD_REL_TOL: f64 = 0.10;

/// Physical bounds of QPROP's coefficients for a small propeller's section, in prop-file order
/// (CL0, CL_a [/rad], CLmin, CLmax, CD0, CD2u, CD2l, CLCD0, -, REexp). Lift slope: thin-airfoil
/// theory gives 2 pi = 6.28 /rad, XFOIL at Re 2e4-2e5 between about 4 and 7; laminar bubbles
/// and short linear ranges give fits outside 3..7.5 that QPROP then applies at every angle.
/// CL0 of a section up to 8 % camber stays below 1 (thin-airfoil CL0 = 4 pi camber = 1.0 at
/// 8 %). CD2 curvatures of measured low-Re polars are 0.005-0.5; CD0 0.005-0.2; REexp between
/// -1 (laminar separation) and 0.
pub const BOUNDS: [(f64, f64); 10] = [
    (-0.5, 1.0),
    (3.0, 7.5),
    (-1.5, 0.0),
    (0.3, 2.0),
    (0.005, 0.2),
    (0.0, 1.0),
    (0.0, 1.0),
    (-0.5, 1.5),
    (0.0, f64::INFINITY),
    (-1.0, 0.0),
];

/// Clamps coefficients to [`BOUNDS`]; one sentence for each clamped (the fallback named).
pub fn bound(c: &mut QpropCoefficients) -> Vec<String> {
    let mut a = c.to_array();
    let mut said = Vec::new();
    for (k, (lo, hi)) in BOUNDS.iter().enumerate() {
        let v = a[k];
        if !(v >= *lo && v <= *hi) {
            let to = if v.is_nan() { 0.5 * (lo + hi) } else { v.clamp(*lo, *hi) };
            said.push(format!(
                "{} {v:.4} is outside the physical {lo}..{hi}: set to {to} in the exported prop file (fallback)",
                QpropCoefficients::NAMES[k],
            ));
            a[k] = to;
        }
    }
    *c = QpropCoefficients::from_array(a);
    said
}

/// Which angles of attack matter, and how much.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum AlphaWeights {
    /// Every angle alike.
    Uniform,
    /// Gaussian bumps of width `sigma_deg` around each angle the blade works at (from the
    /// solver), averaged, on a floor of 0.05 so that no converged point is ignored entirely.
    Around {
        /// Angles of attack seen by the section [deg].
        alphas_deg: Vec<f64>,
        /// Width of each bump [deg].
        sigma_deg: f64,
    },
}

impl AlphaWeights {
    /// Weight of angle `alpha_deg`.
    pub fn weight(&self, alpha_deg: f64) -> f64 {
        match self {
            AlphaWeights::Uniform => 1.0,
            AlphaWeights::Around { alphas_deg, sigma_deg } => {
                0.05 + alphas_deg
                    .iter()
                    .map(|a| (-0.5 * ((alpha_deg - a) / sigma_deg).powi(2)).exp())
                    .sum::<f64>()
                    / alphas_deg.len().max(1) as f64
            }
        }
    }

    fn centre(&self) -> Option<f64> {
        match self {
            AlphaWeights::Uniform => None,
            AlphaWeights::Around { alphas_deg, .. } if !alphas_deg.is_empty() => {
                Some(alphas_deg.iter().sum::<f64>() / alphas_deg.len() as f64)
            }
            AlphaWeights::Around { .. } => None,
        }
    }
}

/// Fit residual at one XFOIL point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FitResidual {
    /// Angle of attack [deg].
    pub alpha_deg: f64,
    /// XFOIL's lift coefficient [-].
    pub cl_xfoil: f64,
    /// The fitted law's lift coefficient [-].
    pub cl_fit: f64,
    /// XFOIL's drag coefficient [-].
    pub cd_xfoil: f64,
    /// The fitted law's drag coefficient [-].
    pub cd_fit: f64,
    /// Whether the point is in the linear range.
    pub linear: bool,
}

/// QPROP coefficients fitted to polars, with how well they fit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QpropFit {
    /// The ten coefficients (CL_a per radian).
    pub coeffs: QpropCoefficients,
    /// The linear range [deg].
    pub linear_range_deg: [f64; 2],
    /// Points in the linear range.
    pub linear_points: usize,
    /// Largest |cl error| over the linear range [-].
    pub cl_max_error: f64,
    /// Weighted RMS cl error over the linear range [-].
    pub cl_rms_error: f64,
    /// Largest relative cd error over the linear range [-].
    pub cd_max_rel_error: f64,
    /// Weighted RMS relative cd error over the linear range [-].
    pub cd_rms_rel_error: f64,
    /// Whether REexp came from polars at other Re (otherwise the default was kept).
    pub re_exp_fitted: bool,
    /// Residuals at every converged point of the attached range.
    pub residuals: Vec<FitResidual>,
    /// Why the parametric law does not describe this section where the blade works (empty:
    /// it does).
    pub unfit: Vec<String>,
    /// Other remarks (limits taken from the last converged point, defaults kept).
    pub notes: Vec<String>,
}

/// Polars that cannot be reduced.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FitError {
    /// No polar given.
    #[error("no polar to fit")]
    NoPolar,
    /// Too few converged points in the attached range of the polar at `re`.
    #[error("the polar at Re = {re:.0} has {found} converged points before stall; at least 3 are needed")]
    TooFewPoints {
        /// Reynolds number of the polar.
        re: f64,
        /// Points found.
        found: usize,
    },
}

/// The linear range of the attached points `pts`, grown from the working angle (the weights'
/// centre), the tolerance widened where XFOIL's curve is too wavy for five points on a line
/// (very low Re).
fn linear_range(pts: &[crate::table::PolarPoint], weights: &AlphaWeights) -> Grown {
    let seed_alpha = weights
        .centre()
        .unwrap_or(0.5 * (pts[0].alpha_deg + pts[pts.len() - 1].alpha_deg));
    let seed = (0..pts.len())
        .min_by(|&i, &j| {
            (pts[i].alpha_deg - seed_alpha)
                .abs()
                .total_cmp(&(pts[j].alpha_deg - seed_alpha).abs())
        })
        .unwrap_or(0)
        .clamp(1, pts.len() - 2);
    let mut grown = grow_linear(pts, seed, LINEAR_RANGE_CL_TOL);
    for tol in [2.0 * LINEAR_RANGE_CL_TOL, 4.0 * LINEAR_RANGE_CL_TOL] {
        if grown.members.len() >= 5 {
            break;
        }
        let wider = grow_linear(pts, seed, tol);
        if wider.members.len() > grown.members.len() {
            grown = wider;
        }
    }
    grown
}

/// The two-parabola drag law of the linear range: the CLCD0 of least weighted error on a grid
/// over its cl, and CD0, CD2u, CD2l there.
fn drag_polar(lin: &[crate::table::PolarPoint], weights: &AlphaWeights) -> (f64, [f64; 3]) {
    let cl_lo = lin.iter().map(|p| p.cl).fold(f64::INFINITY, f64::min);
    let cl_hi = lin.iter().map(|p| p.cl).fold(f64::NEG_INFINITY, f64::max);
    let rows: Vec<(f64, f64, f64)> = lin.iter().map(|p| (p.cl, p.cd, weights.weight(p.alpha_deg))).collect();
    let mut best: Option<(f64, [f64; 3])> = None;
    let mut best_obj = f64::INFINITY;
    const GRID: usize = 200;
    for k in 0..=GRID {
        let c = cl_lo + (cl_hi - cl_lo) * k as f64 / GRID as f64;
        if let Some((obj, coef)) = drag_fit(&rows, c) {
            if obj < best_obj {
                best_obj = obj;
                best = Some((c, coef));
            }
        }
    }
    best.unwrap_or_else(|| {
        let cd_min = rows.iter().map(|r| r.1).fold(f64::INFINITY, f64::min);
        (cl_lo, [cd_min, 0.0, 0.0])
    })
}

/// The Reynolds-number exponent at equal cl and whether it was fitted: `default_re_exp`, noted,
/// where no other polar overlaps the centre's cl.
fn re_exponent(
    polars: &[Polar],
    centre: &Polar,
    lin: &[crate::table::PolarPoint],
    weights: &AlphaWeights,
    default_re_exp: f64,
    notes: &mut Vec<String>,
) -> (f64, bool) {
    let (sxy, sxx) = re_sums(polars, centre, lin, weights);
    let re_exp_fitted = sxx > 0.0;
    let re_exp = if re_exp_fitted { sxy / sxx } else { default_re_exp };
    if !re_exp_fitted {
        notes.push(format!(
            "REexp = {default_re_exp} kept: no polar at another Re overlaps this one's cl"
        ));
    }
    (re_exp, re_exp_fitted)
}

/// The weighted sums of the Reynolds-number exponent's least squares: ln(cd ratio) against
/// ln(Re ratio) of the other polars at the linear range's cl.
fn re_sums(polars: &[Polar], centre: &Polar, lin: &[crate::table::PolarPoint], weights: &AlphaWeights) -> (f64, f64) {
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for other in polars.iter().filter(|p| (p.re / centre.re - 1.0).abs() > 1e-6) {
        let x = (other.re / centre.re).ln();
        for p in lin {
            if let Some(cd_o) = other.cd_at_cl(p.cl) {
                let w = weights.weight(p.alpha_deg);
                sxy += w * x * (cd_o / p.cd).ln();
                sxx += w * x * x;
            }
        }
    }
    (sxy, sxx)
}

/// The fit's errors over the linear range: cl's largest and weighted RMS, cd's relative largest
/// and weighted RMS.
fn fit_errors(residuals: &[FitResidual], weights: &AlphaWeights) -> [f64; 4] {
    let in_lin: Vec<&FitResidual> = residuals.iter().filter(|r| r.linear).collect();
    let wsum: f64 = in_lin.iter().map(|r| weights.weight(r.alpha_deg)).sum();
    let cl_max_error = in_lin.iter().map(|r| (r.cl_fit - r.cl_xfoil).abs()).fold(0.0, f64::max);
    let cd_max_rel_error = in_lin
        .iter()
        .map(|r| (r.cd_fit / r.cd_xfoil - 1.0).abs())
        .fold(0.0, f64::max);
    let cl_rms_error = (in_lin
        .iter()
        .map(|r| weights.weight(r.alpha_deg) * (r.cl_fit - r.cl_xfoil).powi(2))
        .sum::<f64>()
        / wsum)
        .sqrt();
    let cd_rms_rel_error = (in_lin
        .iter()
        .map(|r| weights.weight(r.alpha_deg) * (r.cd_fit / r.cd_xfoil - 1.0).powi(2))
        .sum::<f64>()
        / wsum)
        .sqrt();
    [cl_max_error, cl_rms_error, cd_max_rel_error, cd_rms_rel_error]
}

/// CLmin and CLmax: XFOIL's extreme converged cl over the attached points `pts` (`lo..=hi` of
/// the centre polar's), noted where one is the polar's first or last point, not a stall.
fn cl_limits(
    pts: &[crate::table::PolarPoint],
    centre: &Polar,
    lo: usize,
    hi: usize,
    notes: &mut Vec<String>,
) -> (f64, f64) {
    let cl_max = pts.iter().map(|p| p.cl).fold(f64::NEG_INFINITY, f64::max);
    let cl_min = pts.iter().map(|p| p.cl).fold(f64::INFINITY, f64::min);
    let all = &centre.points;
    if hi == all.len() - 1 {
        notes.push(format!(
            "CLmax = {cl_max:.3} is the last converged point (alpha {} deg), not a stall the polars resolved",
            all[hi].alpha_deg
        ));
    }
    if lo == 0 {
        notes.push(format!(
            "CLmin = {cl_min:.3} is the first converged point (alpha {} deg), not a stall the polars resolved",
            all[0].alpha_deg
        ));
    }
    (cl_min, cl_max)
}

/// What the linear range and the fit's errors say: into `unfit` (the law does not follow
/// XFOIL) and `notes` (points left out).
fn fit_verdict(
    grown: &Grown,
    pts: &[crate::table::PolarPoint],
    range: [f64; 2],
    linear_points: usize,
    [cl_max_error, cd_max_rel_error]: [f64; 2],
    unfit: &mut Vec<String>,
    notes: &mut Vec<String>,
) {
    if grown.tol > LINEAR_RANGE_CL_TOL {
        unfit.push(format!(
            "the polars' lift curve is straight only within {:.2} in cl near the working angle",
            grown.tol
        ));
    }
    if !grown.skipped.is_empty() {
        notes.push(format!(
            "points at alpha {} deg left out of the lift line as outliers",
            grown
                .skipped
                .iter()
                .map(|&k| format!("{}", pts[k].alpha_deg))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    if range[1] - range[0] < 4.0 || linear_points < 4 {
        unfit.push(format!(
            "the lift curve is straight only over alpha {:.1}..{:.1} deg ({} points)",
            range[0], range[1], linear_points
        ));
    }
    if cl_max_error > FIT_CL_TOL {
        unfit.push(format!(
            "the lift line misses the polars by up to {cl_max_error:.3} in cl over the linear range"
        ));
    }
    if cd_max_rel_error > FIT_CD_REL_TOL {
        unfit.push(format!(
            "the two-parabola drag law misses the polars by up to {:.0} % over the linear range",
            cd_max_rel_error * 100.0
        ));
    }
}

/// Where the blade works outside the linear range, or where XFOIL did not converge near the
/// angles it works at.
fn working_angle_notes(weights: &AlphaWeights, range: [f64; 2], centre: &Polar) -> Vec<String> {
    let mut unfit = Vec::new();
    if let AlphaWeights::Around { alphas_deg, .. } = weights {
        let outside: Vec<f64> = alphas_deg
            .iter()
            .copied()
            .filter(|a| *a < range[0] - 0.5 || *a > range[1] + 0.5)
            .collect();
        if !outside.is_empty() {
            let (lo, hi) = outside
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &a| (l.min(a), h.max(a)));
            unfit.push(format!(
                "the blade works at alpha {lo:.1}..{hi:.1} deg at {} of its {} operating points, outside the linear range {:.1}..{:.1} deg",
                outside.len(),
                alphas_deg.len(),
                range[0],
                range[1]
            ));
        }
        let failed = alphas_deg
            .iter()
            .filter(|a| centre.unconverged_deg.iter().any(|u| (*u - **a).abs() < 1.0))
            .count();
        if failed > 0 {
            unfit.push(format!(
                "XFOIL did not converge within 1 deg of the angle the blade works at, at {failed} of its {} operating points",
                alphas_deg.len()
            ));
        }
    }
    unfit
}

/// The Reynolds-number exponent of the drag where a single polar cannot give one: -0.5, a
/// laminar boundary layer's skin friction (Blasius, cf ~ Re^-0.5).
pub const DEFAULT_RE_EXP: f64 = -0.5;

/// Fits QPROP's coefficients to `polars` (any order; the one nearest `re_ref` in ln Re gives
/// lift and drag, the others REexp). `default_re_exp` is kept when there is a single polar.
pub fn fit_qprop(
    polars: &[Polar],
    re_ref: f64,
    weights: &AlphaWeights,
    default_re_exp: f64,
) -> Result<QpropFit, FitError> {
    let centre = polars
        .iter()
        .min_by(|a, b| {
            (a.re.ln() - re_ref.ln())
                .abs()
                .total_cmp(&(b.re.ln() - re_ref.ln()).abs())
        })
        .ok_or(FitError::NoPolar)?;
    let too_few = |found| FitError::TooFewPoints { re: centre.re, found };
    let (lo, hi) = centre.attached_range().ok_or(too_few(centre.points.len()))?;
    let pts = &centre.points[lo..=hi];
    if pts.len() < 3 {
        return Err(too_few(pts.len()));
    }
    let mut notes = Vec::new();
    let mut unfit = Vec::new();

    // 1. Linear range, grown from the working angle.
    let grown = linear_range(pts, weights);
    let members = grown.members.clone();
    let lin: Vec<crate::table::PolarPoint> = members.iter().map(|&k| pts[k]).collect();
    let lin = &lin[..];
    let range = [lin[0].alpha_deg, lin[lin.len() - 1].alpha_deg];

    // 2. Lift line, weighted.
    let xs: Vec<(f64, f64, f64)> = lin
        .iter()
        .map(|p| (p.alpha_deg, p.cl, weights.weight(p.alpha_deg)))
        .collect();
    let (mut cl0_m, mut slope_deg) = line_fit(&xs);
    if slope_deg <= 0.0 {
        // No rising line anywhere: take the secant across the attached range.
        let (a, b) = (pts[0], pts[pts.len() - 1]);
        slope_deg = (b.cl - a.cl) / (b.alpha_deg - a.alpha_deg);
        cl0_m = a.cl - slope_deg * a.alpha_deg;
        unfit.push("the polars' lift does not rise with alpha near the working angle; CL_a is the secant across the attached range".into());
    }
    let beta = (1.0 - centre.mach * centre.mach).max(0.1).sqrt();
    let cl_fit = |alpha_deg: f64| cl0_m + slope_deg * alpha_deg;

    // 3. Drag polar: best CLCD0 on a grid over the linear range's cl.
    let (clcd0, [cd0, cd2u, cd2l]) = drag_polar(lin, weights);
    // The law as the solver evaluates it (its Reynolds factor is 1 at the centre polar).
    let law = QpropCoefficients {
        cd0,
        cd2u,
        cd2l,
        clcd0,
        ..drag_only()
    };
    let cd_fit = |cl: f64| law.cd_profile(cl);

    // 4. Reynolds-number exponent from the other polars, at equal cl.
    let (re_exp, re_exp_fitted) = re_exponent(polars, centre, lin, weights, default_re_exp, &mut notes);

    // Limits: XFOIL's extreme converged cl.
    let (cl_min, cl_max) = cl_limits(pts, centre, lo, hi, &mut notes);

    // 5. Residuals and verdict.
    let residuals: Vec<FitResidual> = pts
        .iter()
        .enumerate()
        .map(|(i, p)| FitResidual {
            alpha_deg: p.alpha_deg,
            cl_xfoil: p.cl,
            cl_fit: cl_fit(p.alpha_deg),
            cd_xfoil: p.cd,
            cd_fit: cd_fit(p.cl),
            linear: members.contains(&i),
        })
        .collect();
    let [cl_max_error, cl_rms_error, cd_max_rel_error, cd_rms_rel_error] = fit_errors(&residuals, weights);
    fit_verdict(
        &grown,
        pts,
        range,
        lin.len(),
        [cl_max_error, cd_max_rel_error],
        &mut unfit,
        &mut notes,
    );
    unfit.extend(working_angle_notes(weights, range, centre));
    let mut coeffs = QpropCoefficients {
        cl0: cl0_m * beta,
        cl_a: slope_deg.to_degrees() * beta,
        cl_min,
        cl_max,
        cd0,
        cd2u,
        cd2l,
        clcd0,
        re_ref: centre.re,
        re_exp,
    };
    unfit.extend(bound(&mut coeffs));
    Ok(QpropFit {
        coeffs,
        linear_range_deg: range,
        linear_points: lin.len(),
        cl_max_error,
        cl_rms_error,
        cd_max_rel_error,
        cd_rms_rel_error,
        re_exp_fitted,
        residuals,
        unfit,
        notes,
    })
}

/// A linear range: the points on the line, the isolated outliers skipped inside it, the
/// tolerance used.
#[derive(Debug, Clone)]
struct Grown {
    members: Vec<usize>,
    skipped: Vec<usize>,
    tol: f64,
}

/// Grows a range of points that one straight line fits within `tol`, from the three around
/// `seed`, a point at a time on the side that fits better. A single point that does not fit,
/// with the next one beyond it fitting, is skipped as an outlier (XFOIL's odd point on another
/// solution branch), as long as outliers stay under a fifth of the points.
fn grow_linear(pts: &[crate::table::PolarPoint], seed: usize, tol: f64) -> Grown {
    let max_dev = |members: &[usize]| {
        let xs: Vec<(f64, f64, f64)> = members.iter().map(|&k| (pts[k].alpha_deg, pts[k].cl, 1.0)).collect();
        let (c0, c1) = line_fit(&xs);
        xs.iter().map(|&(x, y, _)| (y - c0 - c1 * x).abs()).fold(0.0, f64::max)
    };
    let mut members: Vec<usize> = vec![seed - 1, seed, seed + 1];
    let mut skipped = Vec::new();
    let (mut lo, mut hi) = (seed - 1, seed + 1);
    loop {
        // Candidates: (point added, point skipped, new lo, new hi).
        let pick = |cands: Vec<(usize, Option<usize>, usize, usize)>| {
            cands
                .into_iter()
                .map(|c| {
                    let mut m = members.clone();
                    m.push(c.0);
                    m.sort_unstable();
                    let d = max_dev(&m);
                    (m, c.1, c.2, c.3, d)
                })
                .filter(|c| c.4 <= tol)
                .min_by(|a, b| a.4.total_cmp(&b.4))
        };
        let mut near = Vec::new();
        if lo > 0 {
            near.push((lo - 1, None, lo - 1, hi));
        }
        if hi + 1 < pts.len() {
            near.push((hi + 1, None, lo, hi + 1));
        }
        let mut best = pick(near);
        let room = (skipped.len() + 1) * 5 <= members.len() + 1;
        if best.is_none() && room {
            let mut far = Vec::new();
            if lo > 1 {
                far.push((lo - 2, Some(lo - 1), lo - 2, hi));
            }
            if hi + 2 < pts.len() {
                far.push((hi + 2, Some(hi + 1), lo, hi + 2));
            }
            best = pick(far);
        }
        match best {
            Some((m, skip, nlo, nhi, _)) => {
                members = m;
                skipped.extend(skip);
                lo = nlo;
                hi = nhi;
            }
            None => break,
        }
    }
    Grown { members, skipped, tol }
}

/// Weighted least-squares line `y = c0 + c1 x` through `(x, y, w)`.
fn line_fit(p: &[(f64, f64, f64)]) -> (f64, f64) {
    let sw: f64 = p.iter().map(|q| q.2).sum();
    let mx = p.iter().map(|q| q.2 * q.0).sum::<f64>() / sw;
    let my = p.iter().map(|q| q.2 * q.1).sum::<f64>() / sw;
    let sxx: f64 = p.iter().map(|q| q.2 * (q.0 - mx).powi(2)).sum();
    let sxy: f64 = p.iter().map(|q| q.2 * (q.0 - mx) * (q.1 - my)).sum();
    let c1 = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    (my - c1 * mx, c1)
}

/// Drag law for a fixed CLCD0 `c`: minimises sum w (cd_fit / cd - 1)^2 over (CD0, CD2u, CD2l)
/// with CD0 > 0 and both CD2 >= 0. A side with fewer than two points takes the other side's
/// curvature. Returns the objective and the coefficients.
fn drag_fit(rows: &[(f64, f64, f64)], c: f64) -> Option<(f64, [f64; 3])> {
    let up = rows.iter().filter(|r| r.0 > c).count();
    let down = rows.len() - up;
    let basis = |cl: f64, tie_up: bool, tie_down: bool| -> [f64; 3] {
        let d2 = (cl - c).powi(2);
        let (u, l) = if cl > c { (d2, 0.0) } else { (0.0, d2) };
        // A tied side's column is merged into the other one.
        match (tie_up, tie_down) {
            (true, _) => [1.0, 0.0, u + l],
            (_, true) => [1.0, u + l, 0.0],
            _ => [1.0, u, l],
        }
    };
    let (tie_up, tie_down) = (up < 2, down < 2 && up >= 2);
    let mut active = [true, !tie_up, !tie_down];
    for _ in 0..3 {
        let mut ata = [[0.0; 3]; 3];
        let mut atb = [0.0; 3];
        for &(cl, cd, w) in rows {
            let b = basis(cl, tie_up, tie_down);
            let s = w / (cd * cd);
            for i in 0..3 {
                atb[i] += s * b[i] * cd;
                for j in 0..3 {
                    ata[i][j] += s * b[i] * b[j];
                }
            }
        }
        for i in (0..3).filter(|&i| !active[i]) {
            for (j, row) in ata.iter_mut().enumerate() {
                row[i] = 0.0;
                if j == i {
                    row.fill(0.0);
                    row[i] = 1.0;
                }
            }
            atb[i] = 0.0;
        }
        let x = solve3(ata, atb)?;
        if x[0] <= 0.0 {
            return None;
        }
        let negative: Vec<usize> = (1..3).filter(|&i| active[i] && x[i] < 0.0).collect();
        if negative.is_empty() {
            let coef = match (tie_up, tie_down) {
                (true, _) => [x[0], x[2], x[2]],
                (_, true) => [x[0], x[1], x[1]],
                _ => [x[0], x[1], x[2]],
            };
            let obj = rows
                .iter()
                .map(|&(cl, cd, w)| {
                    let b = basis(cl, tie_up, tie_down);
                    w * ((x[0] * b[0] + x[1] * b[1] + x[2] * b[2]) / cd - 1.0).powi(2)
                })
                .sum();
            return Some((obj, coef));
        }
        for i in negative {
            active[i] = false;
        }
    }
    None
}

/// Solves a 3x3 system (LU with partial pivoting); `None` when singular.
fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let m = nalgebra::Matrix3::from_fn(|i, j| a[i][j]);
    let x = m.lu().solve(&nalgebra::Vector3::from(b))?;
    x.iter().all(|v| v.is_finite()).then(|| [x[0], x[1], x[2]])
}

#[cfg(test)]
mod tests;
