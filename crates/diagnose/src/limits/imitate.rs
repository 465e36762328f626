//! How well one candidate's signature (with others beside it) reproduces a change of the
//! residual rows: bounded least squares by coordinate descent.

use super::Signature;

/// `sig`'s columns with how far each parameter may move: from `at` (its current values; its
/// reference where None) to its bounds, or without bounds (`bounded` false, for the table of
/// ties).
pub(super) fn columns<'a>(sig: &'a Signature, at: Option<&[f64]>, bounded: bool) -> Vec<(&'a [f64], f64, f64)> {
    sig.columns
        .iter()
        .zip(sig.effect.params())
        .enumerate()
        .filter_map(|(k, (c, p))| {
            let c = c.as_ref()?;
            let from = at.and_then(|v| v.get(k).copied()).unwrap_or(sig.reference[k]);
            let (lo, hi) = if bounded {
                (p.lower - from, p.upper - from)
            } else {
                (f64::NEG_INFINITY, f64::INFINITY)
            };
            Some((c.as_slice(), lo, hi))
        })
        .collect()
}

/// The best imitation of `target` by `sig`'s columns (each parameter kept within its bounds
/// when `bounded`): the remainder.
pub(super) fn imitate(target: &[f64], sig: &Signature, bounded: bool) -> Vec<f64> {
    imitate_by(target, &columns(sig, None, bounded))
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
