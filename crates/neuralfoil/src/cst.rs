//! A section's Kulfan (CST) parameters fitted to its coordinates, as NeuralFoil's package fits
//! them (AeroSandbox's `get_kulfan_parameters`, least squares): the coordinates normalised
//! (leading edge, the point farthest from the trailing edge's midpoint, at the origin; chord 1;
//! trailing edge on the x axis), then one linear least-squares problem for 8 Bernstein weights a
//! side on the class function x^0.5 (1 - x), the leading-edge modification and the trailing-edge
//! thickness; solved again without the thickness where it comes out negative. Written here (a
//! few lines over nalgebra's SVD); tested against the package's own fit.

use nalgebra::{DMatrix, DVector};

use crate::Kulfan;

/// How a section's coordinates were moved onto the unit chord before the fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Normalization {
    /// Rotation applied about the leading edge [deg] (counter-clockwise positive): the section's
    /// angle of attack is this much larger than the chord line's.
    pub rotation_deg: f64,
    /// The chord the coordinates had (their units).
    pub chord: f64,
}

/// The fit and what it costs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fit {
    /// The parameters.
    pub kulfan: Kulfan,
    /// How the coordinates were normalised.
    pub normalization: Normalization,
    /// RMS of the fitted surface's distance (in y) from the given points [chord].
    pub rms: f64,
    /// The largest such distance [chord].
    pub max: f64,
}

/// Coordinates that cannot be fitted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    /// Too few points, or points that are not numbers.
    #[error("a section's Kulfan fit needs at least 20 finite points, upper surface then lower, got {0}")]
    Points(usize),
    /// The least-squares problem has no solution.
    #[error("the Kulfan least-squares fit has no solution for these coordinates")]
    Singular,
}

/// Weights a side (NeuralFoil's networks take 8).
const N_WEIGHTS: usize = 8;

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// The coordinates on the unit chord, and how they were moved.
fn normalize(points: &[[f64; 2]]) -> (Vec<[f64; 2]>, Normalization) {
    let (first, last) = (points[0], points[points.len() - 1]);
    let te = [(first[0] + last[0]) / 2.0, (first[1] + last[1]) / 2.0];
    let dist = |p: &[f64; 2]| ((p[0] - te[0]).powi(2) + (p[1] - te[1]).powi(2)).sqrt();
    let (le, chord) = points
        .iter()
        .enumerate()
        .map(|(i, p)| (i, dist(p)))
        .fold((0, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a });
    let (x0, y0) = (points[le][0], points[le][1]);
    let scaled: Vec<[f64; 2]> = points
        .iter()
        .map(|p| [(p[0] - x0) / chord, (p[1] - y0) / chord])
        .collect();
    let (f, l) = (scaled[0], scaled[scaled.len() - 1]);
    let angle = -((f[1] + l[1]) / 2.0).atan2((f[0] + l[0]) / 2.0);
    let (s, c) = angle.sin_cos();
    let rotated = scaled
        .iter()
        .map(|p| [p[0] * c - p[1] * s, p[0] * s + p[1] * c])
        .collect();
    (
        rotated,
        Normalization {
            rotation_deg: angle.to_degrees(),
            chord,
        },
    )
}

/// Least squares by SVD (as numpy's `lstsq`): the solution and the residuals.
fn solve(a: &DMatrix<f64>, b: &DVector<f64>) -> Result<(DVector<f64>, DVector<f64>), FitError> {
    let x = a
        .clone()
        .svd(true, true)
        .solve(b, 1e-14)
        .map_err(|_| FitError::Singular)?;
    if x.iter().any(|v| !v.is_finite()) {
        return Err(FitError::Singular);
    }
    let r = b - a * &x;
    Ok((x, r))
}

/// The coordinates of a Selig `.dat` text as the package reads them: every line of two
/// numbers, nothing repaired (propbet's airfoil reader repairs what it can; the comparison with
/// the package must not).
pub fn selig_points(text: &str) -> Vec<[f64; 2]> {
    text.lines()
        .filter_map(|l| {
            let v: Vec<f64> = l.split_whitespace().filter_map(|t| t.parse().ok()).collect();
            (v.len() == 2).then(|| [v[0], v[1]])
        })
        .collect()
}

/// Fits a section's Kulfan parameters to its coordinates (Selig order: trailing edge, upper
/// surface, leading edge, lower surface, trailing edge).
pub fn fit(points: &[[f64; 2]]) -> Result<Fit, FitError> {
    if points.len() < 20 || points.iter().any(|p| !(p[0].is_finite() && p[1].is_finite())) {
        return Err(FitError::Points(points.len()));
    }
    let (pts, normalization) = normalize(points);
    let n = pts.len();
    let le = pts
        .iter()
        .enumerate()
        .fold((0, f64::INFINITY), |a, (i, p)| if p[0] < a.1 { (i, p[0]) } else { a })
        .0;
    let order = N_WEIGHTS - 1;
    let mut a = DMatrix::<f64>::zeros(n, 2 * N_WEIGHTS + 2);
    let mut b = DVector::<f64>::zeros(n);
    for (row, p) in pts.iter().enumerate() {
        let x = p[0];
        let upper = row <= le;
        let class = x.powf(0.5) * (1.0 - x);
        for k in 0..N_WEIGHTS {
            let s = binomial(order, k) * x.powi(k as i32) * (1.0 - x).powi((order - k) as i32);
            // Lower weights first, then upper, as the package packs them.
            let col = if upper { N_WEIGHTS + k } else { k };
            a[(row, col)] = class * s;
        }
        a[(row, 2 * N_WEIGHTS)] = x * (1.0 - x).max(0.0).powf(N_WEIGHTS as f64 + 0.5);
        a[(row, 2 * N_WEIGHTS + 1)] = if upper { x / 2.0 } else { -x / 2.0 };
        b[row] = p[1];
    }
    let (mut x, mut r) = solve(&a, &b)?;
    let mut te_thickness = x[2 * N_WEIGHTS + 1];
    if te_thickness < 0.0 {
        let a0 = a.columns(0, 2 * N_WEIGHTS + 1).into_owned();
        let (x0, r0) = solve(&a0, &b)?;
        x = x0.push(0.0);
        r = r0;
        te_thickness = 0.0;
    }
    let w = |k: usize| x[k];
    let kulfan = Kulfan {
        lower: std::array::from_fn(w),
        upper: std::array::from_fn(|k| w(N_WEIGHTS + k)),
        leading_edge: x[2 * N_WEIGHTS],
        te_thickness,
    };
    let rms = (r.iter().map(|v| v * v).sum::<f64>() / n as f64).sqrt();
    let max = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    Ok(Fit {
        kulfan,
        normalization,
        rms,
        max,
    })
}
