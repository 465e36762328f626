//! Airfoil fits of one section's points on the unrolled cylinder (or a plane).
//!
//! - [`fit_naca`]: the NACA 4-digit fit of the published photogrammetry method: 7 parameters
//!   (leading-edge position u, w; chord; blade angle; thickness, camber and its position)
//!   found by minimising the point-to-panel distances (Huber loss, so stray points do not
//!   pull), with argmin's Nelder-Mead from the seed that [`crate::section::measure`] gives.
//!   Its chord line (leading edge → trailing edge of the NACA shape) is the section's chord
//!   and blade angle: the farthest-point chord of a cambered section sits off it by the camber
//!   slope at the nose (0.2° at 5 % camber).
//! - [`fit_cst`]: a general shape (Kulfan CST, class function x^0.5 (1 − x), order-5
//!   Bernstein polynomials per surface plus a trailing-edge thickness term) in the NACA fit's
//!   chord frame: blunt trailing edges and non-NACA sections such as E63. Linear least squares.
//!
//! Both report the RMS normal distance of the points to the fitted contour [same unit as
//! the points]. [`Cst::selig`] writes the normalised coordinates XFOIL reads (Selig order:
//! upper trailing edge → leading edge → lower trailing edge, cosine spacing).

use argmin::core::{CostFunction, Executor};
use argmin::solver::neldermead::NelderMead;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use crate::section::SectionShape;
use crate::synth::naca4;

/// Weight of each end term of the NACA fit, as a fraction of the points.
const END_WEIGHT: f64 = 0.01;

/// Points (x, y) of one surface from the leading to the trailing edge.
type Polyline = Vec<(f64, f64)>;

/// Panels per surface of the NACA contour used for distances.
const PANELS: usize = 80;

/// A fitted NACA 4-digit section.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NacaFit {
    /// Leading edge (u, w).
    pub le: (f64, f64),
    /// Chord.
    pub chord: f64,
    /// Blade angle of the chord line [rad] (leading edge at +u and higher w when positive).
    pub beta: f64,
    /// Thickness ratio t/c.
    pub t_c: f64,
    /// Maximum camber / chord.
    pub camber: f64,
    /// Chord position of the maximum camber.
    pub camber_pos: f64,
    /// RMS normal distance of the points to the fitted contour.
    pub rms: f64,
    /// Points used.
    pub points: usize,
    /// The fit's objective (Huber point-to-contour plus end terms, per point).
    pub cost: f64,
}

impl NacaFit {
    /// The same fit with its lengths (leading edge, chord, rms) multiplied by `k`; the
    /// objective is left as it was computed.
    pub fn scaled(&self, k: f64) -> NacaFit {
        NacaFit {
            le: (self.le.0 * k, self.le.1 * k),
            chord: self.chord * k,
            rms: self.rms * k,
            ..*self
        }
    }

    /// The section shape (t/c, camber, camber position), as a seed for a neighbouring station.
    pub fn shape(&self) -> [f64; 3] {
        [self.t_c, self.camber, self.camber_pos]
    }

    /// Normalised section coordinates (x along the chord from the leading edge, y towards the
    /// suction side) of a point (u, w).
    pub fn to_section(&self, p: (f64, f64)) -> (f64, f64) {
        to_section(&[self.le.0, self.le.1, self.chord, self.beta], p)
    }

    /// The 4-digit designation, rounded ("4410").
    pub fn designation(&self) -> String {
        format!(
            "{}{}{:02}",
            (self.camber.abs() * 100.0).round() as i64,
            (self.camber_pos * 10.0).round() as i64,
            (self.t_c * 100.0).round() as i64
        )
    }
}

fn to_section(frame: &[f64], p: (f64, f64)) -> (f64, f64) {
    let (le_u, le_w, c, beta) = (frame[0], frame[1], frame[2], frame[3]);
    let (s, co) = beta.sin_cos();
    let (du, dw) = (p.0 - le_u, p.1 - le_w);
    // Chord direction LE -> TE is (-cos, -sin); suction normal (-sin, cos).
    ((-du * co - dw * s) / c, (-du * s + dw * co) / c)
}

/// The closed NACA contour, upper then lower, each from the leading edge to the trailing edge
/// (PANELS + 1 points, cosine spacing).
fn naca_contour(t: f64, m: f64, p: f64) -> (Polyline, Polyline) {
    let (mut up, mut lo) = (Vec::with_capacity(PANELS + 1), Vec::with_capacity(PANELS + 1));
    for k in 0..=PANELS {
        let x = cosine(k, PANELS);
        let (a, b) = naca4(x, t, m, p);
        up.push(a);
        lo.push(b);
    }
    (up, lo)
}

/// Cosine spacing: 0 at k = 0, 1 at k = n.
fn cosine(k: usize, n: usize) -> f64 {
    0.5 * (1.0 - (std::f64::consts::PI * k as f64 / n as f64).cos())
}

fn seg_dist2(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (x, y) = (a.0 + t * dx - p.0, a.1 + t * dy - p.1);
    x * x + y * y
}

/// Squared distance from a point to two polylines that run from x = 0 to x = 1 with cosine
/// spacing, looking only at the panels near the point's chord position.
fn contour_dist2(p: (f64, f64), sides: [&[(f64, f64)]; 2]) -> f64 {
    let n = sides[0].len() - 1;
    let x = p.0.clamp(0.0, 1.0);
    let k = ((1.0 - 2.0 * x).clamp(-1.0, 1.0).acos() / std::f64::consts::PI * n as f64) as usize;
    let (lo, hi) = (k.saturating_sub(4), (k + 5).min(n));
    let mut best = f64::INFINITY;
    for side in sides {
        for i in lo..hi {
            best = best.min(seg_dist2(p, side[i], side[i + 1]));
        }
        if k < 10 {
            // Near the nose the nearest panel may belong to the other end of the window.
            for i in 0..10.min(n) {
                best = best.min(seg_dist2(p, side[i], side[i + 1]));
            }
        }
    }
    best
}

#[derive(Clone, Copy)]
struct NacaCost<'a> {
    pts: &'a [(f64, f64)],
    /// Seed chord, for the Huber threshold and the scaling of the unknowns.
    c0: f64,
}

impl NacaCost<'_> {
    /// Unknowns scaled to order one: u/c0, w/c0, c/c0, beta, t, m, p.
    fn unpack(&self, x: &[f64]) -> [f64; 7] {
        [x[0] * self.c0, x[1] * self.c0, x[2] * self.c0, x[3], x[4], x[5], x[6]]
    }

    fn distances(&self, q: &[f64; 7]) -> impl Iterator<Item = f64> + '_ {
        let (up, lo) = naca_contour(q[4], q[5], q[6]);
        let q = *q;
        self.pts.iter().map(move |&p| {
            let s = to_section(&q[..4], p);
            contour_dist2(s, [&up, &lo]).sqrt() * q[2]
        })
    }
}

impl CostFunction for NacaCost<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, x: &Vec<f64>) -> Result<f64, argmin::core::Error> {
        let q = self.unpack(x);
        if q[2] <= 0.0 || !(0.003..0.6).contains(&q[4]) || q[5].abs() > 0.15 || !(0.05..0.95).contains(&q[6]) {
            return Ok(f64::INFINITY);
        }
        let delta = 0.005 * self.c0;
        let huber = |d: f64| if d < delta { d * d } else { delta * (2.0 * d - delta) };
        let sum: f64 = self.distances(&q).map(huber).sum();
        // The other way round at the two ends: the model's leading and trailing edge must sit
        // on the points, or the contour could run past them at no cost. Each end weighs as
        // END_WEIGHT of the points.
        let (s, c) = q[3].sin_cos();
        let ends = [(q[0], q[1]), (q[0] - q[2] * c, q[1] - q[2] * s)];
        let end_cost: f64 = ends
            .iter()
            .map(|e| {
                let d2 = self
                    .pts
                    .iter()
                    .map(|p| (p.0 - e.0).powi(2) + (p.1 - e.1).powi(2))
                    .fold(f64::INFINITY, f64::min);
                huber(d2.sqrt())
            })
            .sum();
        Ok((sum + END_WEIGHT * self.pts.len() as f64 * end_cost) / self.pts.len() as f64)
    }
}

/// Fits a NACA 4-digit section to points (u, w), seeded by the measured shape.
pub fn fit_naca(pts: &[(f64, f64)], seed: &SectionShape) -> Option<NacaFit> {
    let own = [seed.t_c, seed.camber, seed.camber_pos];
    fit_naca_from(pts, seed, &[own])
}

/// The same fit started from each of `shapes` (t/c, camber, camber position) in turn, with the
/// position, chord and angle from the measured `seed`; the lowest objective wins. The
/// photogrammetry method seeds each station with its neighbour's fit: a section whose own
/// measure is poor (thin, noisy edges) starts where the blade's shape already is.
pub fn fit_naca_from(pts: &[(f64, f64)], seed: &SectionShape, shapes: &[[f64; 3]]) -> Option<NacaFit> {
    if pts.len() < 8 || seed.chord <= 0.0 {
        return None;
    }
    let c0 = seed.chord;
    let cost = NacaCost { pts, c0 };
    let steps = [0.01, 0.01, 0.01, 0.01, 0.01, 0.01, 0.05];
    let simplex_at = |x: &[f64], f: f64| -> Vec<Vec<f64>> {
        std::iter::once(x.to_vec())
            .chain(steps.iter().enumerate().map(|(i, s)| {
                let mut v = x.to_vec();
                v[i] += s * f;
                v
            }))
            .collect()
    };
    let mut winner: Option<(f64, Vec<f64>)> = None;
    for shape in shapes {
        let mut best = vec![
            seed.le.0 / c0,
            seed.le.1 / c0,
            1.0,
            seed.beta,
            shape[0].clamp(0.01, 0.4),
            shape[1].clamp(-0.1, 0.1),
            shape[2].clamp(0.2, 0.8),
        ];
        let mut value = f64::INFINITY;
        // A restart from the best point shakes Nelder-Mead out of a collapsed simplex.
        for round in 0..2 {
            let simplex = simplex_at(&best, if round == 0 { 1.0 } else { 0.2 });
            let solver = NelderMead::new(simplex).with_sd_tolerance(1e-9).ok()?;
            let res = Executor::new(cost, solver)
                .configure(|s| s.max_iters(1500))
                .run()
                .ok()?;
            best = res.state.best_param.clone()?;
            value = res.state.best_cost;
        }
        if winner.as_ref().is_none_or(|w| value < w.0) {
            winner = Some((value, best));
        }
    }
    let (value, best) = winner?;
    let q = cost.unpack(&best);
    let rms = (cost.distances(&q).map(|d| d * d).sum::<f64>() / pts.len() as f64).sqrt();
    Some(NacaFit {
        le: (q[0], q[1]),
        chord: q[2],
        beta: q[3],
        t_c: q[4],
        camber: q[5],
        camber_pos: q[6],
        rms,
        points: pts.len(),
        cost: value,
    })
}

/// Bernstein order of each CST surface.
pub const CST_ORDER: usize = 5;

/// A CST (Kulfan) section in a chord frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Cst {
    /// Upper-surface Bernstein weights.
    pub upper: Vec<f64>,
    /// Lower-surface weights.
    pub lower: Vec<f64>,
    /// Trailing-edge ordinates of the upper and lower surface (/chord).
    pub te: (f64, f64),
    /// RMS normal distance of the points to the contour [point units].
    pub rms: f64,
    /// Points on the upper and lower surface.
    pub points: (usize, usize),
}

/// A range of chord fractions (from, to).
pub type ChordRange = (f64, f64);

/// The least thickness a written section keeps, per chord at the leading edge, falling
/// linearly to 0 at the trailing edge (a 1.1 deg wedge; real sections are several times
/// thicker everywhere but in the last percent of chord).
pub const TE_WEDGE: f64 = 0.02;

/// The least thickness of a written section at x/c: the [`TE_WEDGE`] wedge, faded out over
/// the first 30 % of chord where every section's thickness rises from 0 at the nose.
fn least_thickness(x: f64) -> f64 {
    TE_WEDGE * (1.0 - x) * (x / 0.3).min(1.0)
}

fn binom(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

fn cst_row(x: f64) -> Vec<f64> {
    let class = x.max(0.0).sqrt() * (1.0 - x);
    (0..=CST_ORDER)
        .map(|i| class * binom(CST_ORDER, i) * x.powi(i as i32) * (1.0 - x).powi((CST_ORDER - i) as i32))
        .collect()
}

impl Cst {
    /// The same fit with its rms distance multiplied by `k` (the shape is per chord).
    pub fn scaled(&self, k: f64) -> Cst {
        Cst {
            rms: self.rms * k,
            ..self.clone()
        }
    }

    fn surface(w: &[f64], te: f64, x: f64) -> f64 {
        cst_row(x).iter().zip(w).map(|(a, b)| a * b).sum::<f64>() + x * te
    }

    /// Upper and lower ordinate at chord fraction x.
    pub fn at(&self, x: f64) -> (f64, f64) {
        (
            Self::surface(&self.upper, self.te.0, x),
            Self::surface(&self.lower, self.te.1, x),
        )
    }

    /// Normalised coordinates in Selig order, `n` points per surface (cosine spacing), as
    /// [`Cst::selig_repaired`] gives them.
    pub fn selig(&self, n: usize) -> Vec<(f64, f64)> {
        self.selig_repaired(n).0
    }

    /// Normalised coordinates in Selig order, `n` points per surface (cosine spacing), and the
    /// chord range (x/c) where the fitted surfaces were moved apart. A noisy scan's fit can
    /// bring the lower surface above the upper near the trailing edge (the contour crosses
    /// itself, and XFOIL cannot panel it): wherever the thickness is below a wedge of
    /// [`TE_WEDGE`] chord falling to 0 at the trailing edge (faded out towards the nose), both
    /// surfaces are set that wedge apart about their middle; a negative trailing-edge gap
    /// closes. Both
    /// surfaces share their x, so a contour with the upper at or above the lower at every x
    /// cannot cross itself.
    pub fn selig_repaired(&self, n: usize) -> (Vec<(f64, f64)>, Option<ChordRange>) {
        let n = n.max(4);
        let mut repaired: Option<(f64, f64)> = None;
        let surfaces: Vec<(f64, f64, f64)> = (0..=n)
            .map(|k| {
                let x = cosine(k, n);
                let (u, l) = self.at(x);
                let least = least_thickness(x);
                if k > 0 && u - l < least {
                    repaired = Some(repaired.map_or((x, x), |r| (r.0.min(x), r.1.max(x))));
                    let m = 0.5 * (u + l);
                    (x, m + 0.5 * least, m - 0.5 * least)
                } else {
                    (x, u, l)
                }
            })
            .collect();
        let mut out = Vec::with_capacity(2 * n + 1);
        out.extend(surfaces.iter().rev().map(|&(x, u, _)| (x, u)));
        out.extend(surfaces.iter().skip(1).map(|&(x, _, l)| (x, l)));
        (out, repaired)
    }

    /// Maximum thickness / chord and its position; maximum camber / chord and its position.
    pub fn thickness_camber(&self) -> ((f64, f64), (f64, f64)) {
        let (mut t, mut c) = ((0.0, 0.0), (0.0f64, 0.0));
        for k in 1..400 {
            let x = k as f64 / 400.0;
            let (u, l) = self.at(x);
            if u - l > t.0 {
                t = (u - l, x);
            }
            let m = 0.5 * (u + l);
            if m.abs() > c.0.abs() {
                c = (m, x);
            }
        }
        (t, c)
    }
}

/// Fits the CST shape to points (u, w) in the chord frame of a NACA fit.
pub fn fit_cst(pts: &[(f64, f64)], frame: &NacaFit) -> Option<Cst> {
    let (up_ref, lo_ref) = naca_contour(frame.t_c, frame.camber, frame.camber_pos);
    let mid = |x: f64| {
        // Camber line of the NACA fit: the middle of the two surfaces at x.
        let k = up_ref.partition_point(|p| p.0 < x).min(PANELS);
        let j = lo_ref.partition_point(|p| p.0 < x).min(PANELS);
        0.5 * (up_ref[k].1 + lo_ref[j].1)
    };
    let (mut up, mut lo) = (Vec::new(), Vec::new());
    for &p in pts {
        let s = frame.to_section(p);
        if !(0.0..=1.0).contains(&s.0) {
            continue;
        }
        if s.1 >= mid(s.0) {
            up.push(s);
        } else {
            lo.push(s);
        }
    }
    let solve = |side: &[(f64, f64)]| -> Option<(Vec<f64>, f64)> {
        if side.len() < CST_ORDER + 3 {
            return None;
        }
        let cols = CST_ORDER + 2;
        // Smoothing rows (neighbouring weights alike, weight 0.01 per point's worth) keep
        // the shape sane where the points leave a gap.
        let lam = 0.01 * (side.len() as f64).sqrt();
        let mut a = DMatrix::zeros(side.len() + CST_ORDER, cols);
        let mut b = DVector::zeros(side.len() + CST_ORDER);
        for (i, &(x, y)) in side.iter().enumerate() {
            for (j, v) in cst_row(x).into_iter().enumerate() {
                a[(i, j)] = v;
            }
            a[(i, cols - 1)] = x;
            b[i] = y;
        }
        for j in 0..CST_ORDER {
            a[(side.len() + j, j)] = lam;
            a[(side.len() + j, j + 1)] = -lam;
        }
        let sol = a.svd(true, true).solve(&b, 1e-12).ok()?;
        let w: Vec<f64> = sol.iter().take(cols - 1).copied().collect();
        Some((w, sol[cols - 1]))
    };
    let (wu, teu) = solve(&up)?;
    let (wl, tel) = solve(&lo)?;
    let mut cst = Cst {
        upper: wu,
        lower: wl,
        te: (teu, tel),
        rms: 0.0,
        points: (up.len(), lo.len()),
    };
    let contour = cst.selig(PANELS);
    let (u_side, l_side): (Vec<_>, Vec<_>) = (
        contour[..=PANELS].iter().rev().copied().collect(),
        contour[PANELS..].to_vec(),
    );
    let n = (up.len() + lo.len()) as f64;
    let ss: f64 = up
        .iter()
        .chain(&lo)
        .map(|&p| contour_dist2(p, [&u_side, &l_side]))
        .sum();
    cst.rms = (ss / n).sqrt() * frame.chord;
    Some(cst)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn naca_points(t: f64, m: f64, p: f64, c: f64, beta: f64, le: (f64, f64)) -> Vec<(f64, f64)> {
        let (s, co) = beta.sin_cos();
        let mut out = Vec::new();
        for k in 0..=60 {
            let x = cosine(k, 60);
            let (a, b) = naca4(x, t, m, p);
            for (xs, ys) in [a, b] {
                out.push((le.0 - c * (xs * co + ys * s), le.1 + c * (-xs * s + ys * co)));
            }
        }
        out
    }

    /// A measured seed near the sections of `naca_points(.., 25.0, 0.35, (7.0, 3.0))`, with
    /// the given shape.
    fn measured(t_c: f64, camber: f64, camber_pos: f64, points: usize) -> SectionShape {
        SectionShape {
            r: 50.0,
            le: (7.3, 3.2),
            te: (-15.0, -5.0),
            chord: 24.0,
            beta: 0.33,
            t_c,
            t_pos: 0.3,
            camber,
            camber_pos,
            points,
        }
    }

    #[test]
    fn naca_fit_recovers_the_section() {
        let pts = naca_points(0.09, 0.04, 0.4, 25.0, 0.35, (7.0, 3.0));
        let seed = measured(0.1, 0.03, 0.5, pts.len());
        let f = fit_naca(&pts, &seed).unwrap();
        assert!((f.beta - 0.35).abs().to_degrees() < 0.01, "{f:?}");
        assert!((f.chord / 25.0 - 1.0).abs() < 1e-3, "{f:?}");
        assert!((f.t_c - 0.09).abs() < 1e-3 && (f.camber - 0.04).abs() < 1e-3, "{f:?}");
        assert!(f.rms < 0.01, "{f:?}");
        assert_eq!(f.designation(), "4409");
        let cst = fit_cst(&pts, &f).unwrap();
        assert!(cst.rms < 0.02, "{cst:?}");
        let ((t, _), (m, xm)) = cst.thickness_camber();
        assert!(
            (t - 0.09).abs() < 2e-3 && (m - 0.04).abs() < 2e-3 && (xm - 0.4).abs() < 0.05,
            "{t} {m} {xm}"
        );
        let sel = cst.selig(80);
        assert_eq!(sel.len(), 161);
        assert!((sel[0].0 - 1.0).abs() < 1e-12 && sel[80].0.abs() < 1e-12 && (sel[160].0 - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_fit_whose_surfaces_cross_at_the_trailing_edge_is_written_apart() {
        // Upper and lower surfaces of a thin section, with the trailing-edge ordinates of a
        // noisy fit: the lower ends 0.4 % chord above the upper.
        let cst = Cst {
            upper: vec![0.12; CST_ORDER + 1],
            lower: vec![-0.02; CST_ORDER + 1],
            te: (-0.004, 0.000),
            rms: 0.0,
            points: (100, 100),
        };
        let (u, l) = cst.at(1.0);
        assert!(u < l);
        let (pts, repaired) = cst.selig_repaired(80);
        let (from, to) = repaired.unwrap();
        assert!(from > 0.8 && to == 1.0, "{from} {to}");
        // Every upper point at or above the lower point at the same x; closed at x = 1.
        for k in 0..=80 {
            let (xu, yu) = pts[80 - k];
            let (xl, yl) = pts[80 + k];
            assert_eq!(xu, xl);
            assert!(yu - yl >= least_thickness(xu) - 1e-12, "x {xu}: {yu} < {yl}");
        }
        assert_eq!(pts[0], pts[160]);
        // A section whose surfaces stay apart is not touched.
        let sound = Cst {
            te: (0.001, -0.001),
            ..cst
        };
        let (p2, r2) = sound.selig_repaired(80);
        assert!(r2.is_none());
        assert_eq!(p2[0].1, sound.at(1.0).0);
    }

    #[test]
    fn the_lowest_objective_of_several_starts_wins() {
        // A thin, strongly cambered section measured as a thick symmetric one.
        let pts = naca_points(0.06, 0.06, 0.4, 25.0, 0.35, (7.0, 3.0));
        let seed = measured(0.2, -0.05, 0.7, pts.len());
        let own = fit_naca(&pts, &seed).unwrap();
        let neighbour = [0.065, 0.055, 0.42];
        let both = fit_naca_from(&pts, &seed, &[[0.2, -0.05, 0.7], neighbour]).unwrap();
        assert!(both.cost <= own.cost, "{} > {}", both.cost, own.cost);
        assert_eq!(both.designation(), "6406", "{both:?}");
        assert!((both.chord / 25.0 - 1.0).abs() < 1e-3, "{both:?}");
    }
}
