//! Unit tests of `discover.rs`.

use super::*;

fn partition(folds: &[Vec<usize>], n: usize) {
    let mut all: Vec<usize> = folds.iter().flatten().copied().collect();
    all.sort_unstable();
    assert_eq!(all, (0..n).collect::<Vec<_>>(), "every point in exactly one fold");
    assert!(folds.iter().all(|f| !f.is_empty()));
}

#[test]
fn folds_partition_the_points() {
    let groups: Vec<i64> = (0..23).map(|i| i % 4).collect();
    let f = folds_of(&groups, 5, 7);
    assert_eq!(f.kfold.len(), 5);
    partition(&f.kfold, 23);
    let sizes: Vec<usize> = f.kfold.iter().map(Vec::len).collect();
    assert!(sizes.iter().all(|&s| s == 4 || s == 5), "{sizes:?}");
    let loro = f.loro.expect("four RPM groups");
    assert_eq!(loro.len(), 4);
    partition(&loro, 23);
    assert!(loro.iter().all(|g| g.iter().all(|&i| groups[i] == groups[g[0]])));
    // The same seed gives the same folds; two groups give no leave-one-RPM-out.
    assert_eq!(folds_of(&groups, 5, 7).kfold, f.kfold);
    assert!(folds_of(&[0, 0, 1, 1], 2, 1).loro.is_none());
    // More folds than points: one point each.
    partition(&folds_of(&[0, 1, 2], 10, 1).kfold, 3);
}

fn outcome(sse: f64, rows: usize, params: usize) -> FitOutcome {
    FitOutcome {
        stack: Stack::baseline(),
        p: vec![0.0; params],
        residuals: vec![0.0; rows],
        jacobian: DMatrix::zeros(rows, params),
        sse,
        sd: vec![0.0; params],
        evaluations: 1,
        at_bound: vec![false; params],
        stop: crate::fit::Stop::Converged,
    }
}

#[test]
fn a_rung_takes_the_best_effect_inside_its_bounds() {
    // The best score ends on a bound (the 9x4.7 SF's chord-scale alone at 0.85, held out
    // 5.8 %, against elastic-twist's 7.6 %): the rung takes the best inside.
    // (Scores lower is better, here the held-out errors themselves.)
    assert_eq!(rung_choice(&[(5.8, false), (8.9, true), (7.6, true)]), Some(2));
    assert_eq!(rung_choice(&[(7.6, true), (9.0, true)]), Some(0));
    // Every option on a bound: the best of them.
    assert_eq!(rung_choice(&[(4.0, false), (3.0, false)]), Some(1));
    assert_eq!(rung_choice(&[]), None);
}

#[test]
fn the_f_test_matches_the_table() {
    // F(1, 20) = 4.351 is the 5 % critical value (NIST/SEMATECH e-Handbook, table 1.3.6.7.3):
    // reduced SSE = full SSE (1 + 4.351/20) with 21 rows and one parameter.
    let full = outcome(1.0, 21, 1);
    let (f, p) = f_test(1.0 + 4.351 / 20.0, &full, 1);
    assert!((f - 4.351).abs() < 1e-9, "{f}");
    assert!((p - 0.05).abs() < 1e-3, "{p}");
    // F(2, 30) = 3.316 at 5 %.
    let full = outcome(2.0, 32, 2);
    let (_, p) = f_test(2.0 * (1.0 + 2.0 * 3.316 / 30.0), &full, 2);
    assert!((p - 0.05).abs() < 1e-3, "{p}");
    // No improvement: p = 1; a perfect fit of imperfect data: p = 0.
    assert_eq!(f_test(1.0, &outcome(1.0, 21, 1), 1).1, 1.0);
    assert_eq!(f_test(1.0, &outcome(0.0, 21, 1), 1).1, 0.0);
}
