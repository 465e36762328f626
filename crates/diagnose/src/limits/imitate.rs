//! How well one candidate's signature (with others beside it) reproduces a change of the
//! residual rows: bounded least squares by coordinate descent.

use super::Signature;

/// How far a parameter may move when it imitates a change.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Reach {
    /// Without bounds (the table of ties).
    Free,
    /// To its physical bounds.
    Bounds,
    /// To its physically expected range (a physical stand-in for a calibration factor).
    Expected,
}

/// `sig`'s columns with how far each parameter may move: from `at` (its current values; its
/// reference where None) as far as `reach` lets it.
pub(super) fn columns<'a>(sig: &'a Signature, at: Option<&[f64]>, reach: Reach) -> Vec<(&'a [f64], f64, f64)> {
    sig.columns
        .iter()
        .zip(sig.effect.params())
        .enumerate()
        .filter_map(|(k, (c, p))| {
            let c = c.as_ref()?;
            let from = at.and_then(|v| v.get(k).copied()).unwrap_or(sig.reference[k]);
            let (lo, hi) = match reach {
                Reach::Free => (f64::NEG_INFINITY, f64::INFINITY),
                Reach::Bounds => (p.lower, p.upper),
                Reach::Expected => p.expected_range(),
            };
            // A range that holds `from` (an expected range may not hold a stack member's
            // value): the step never forces a move.
            Some((c.as_slice(), (lo - from).min(0.0), (hi - from).max(0.0)))
        })
        .collect()
}

/// The best imitation of `target` by `sig`'s columns (each parameter as far as `reach` lets
/// it): the remainder.
pub(super) fn imitate(target: &[f64], sig: &Signature, reach: Reach) -> Vec<f64> {
    imitate_by(target, &columns(sig, None, reach))
}

/// The best imitation of `target` by `cols` (column, lowest and highest step): the remainder.
pub(super) fn imitate_by(target: &[f64], cols: &[(&[f64], f64, f64)]) -> Vec<f64> {
    let mut rest = target.to_vec();
    let mut beta = vec![0.0; cols.len()];
    // Coordinate descent on a box: converges for a convex least-squares problem.
    for _ in 0..60 {
        let mut moved = 0.0f64;
        for (j, (c, lo, hi)) in cols.iter().enumerate() {
            let cc: f64 = c.iter().map(|x| x * x).sum();
            if cc <= 0.0 {
                continue;
            }
            let step = c.iter().zip(&rest).map(|(a, b)| a * b).sum::<f64>() / cc;
            let new = (beta[j] + step).clamp(*lo, *hi);
            let d = new - beta[j];
            if d != 0.0 {
                for (r, a) in rest.iter_mut().zip(c.iter()) {
                    *r -= d * a;
                }
                beta[j] = new;
                moved = moved.max(d.abs() * cc.sqrt());
            }
        }
        if moved < 1e-12 {
            break;
        }
    }
    rest
}
