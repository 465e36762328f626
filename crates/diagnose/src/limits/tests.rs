//! The rules of what the data can tell, on made-up signatures and residuals.

use super::*;
use std::sync::Arc;

use propbet_effects::{Effect, Hook, Param};

/// A stand-in effect: only its id and parameters matter to the judge.
#[derive(Debug)]
struct Named(&'static str, Vec<Param>);

impl Effect for Named {
    fn id(&self) -> &str {
        self.0
    }
    fn params(&self) -> &[Param] {
        &self.1
    }
    fn hooks(&self) -> &[Hook] {
        &[Hook::Loads]
    }
    fn explanation(&self) -> &str {
        ""
    }
}

fn named(id: &'static str) -> Arc<dyn Effect> {
    Arc::new(Named(id, vec![Param::new("x", "-", 0.0, (-1.0, 1.0), 0.01, "")]))
}

/// Thrust-only points: 4 RPMs x 8 J, one file per RPM.
fn data() -> Data {
    let mut obs = Vec::new();
    for (f, rpm) in [3000.0, 4000.0, 5000.0, 6000.0].into_iter().enumerate() {
        for k in 0..8 {
            obs.push(crate::tests::obs(f, rpm, 0.1 * f64::from(k), 1.0));
        }
    }
    Data {
        obs,
        thrust_floor: 0.05,
        torque_floor: 1e-12,
    }
}

/// White residuals of RMS `sd` (alternating signs: no correlation between neighbours).
fn noise(n: usize, sd: f64) -> Vec<f64> {
    (0..n).map(|i| if i % 2 == 0 { sd } else { -sd }).collect()
}

/// The data, the judge of white residuals of 1 % on them, and J about its mean over the rows.
fn white() -> (Data, Judge, Vec<f64>) {
    let d = data();
    let judge = Judge::new(&d, &noise(d.obs.len(), 0.01), None, None);
    let j = d.obs.iter().map(|o| o.j - 0.35).collect();
    (d, judge, j)
}

fn sig(id: &'static str, col: Vec<f64>) -> Signature {
    Signature {
        effect: named(id),
        reference: vec![0.0],
        columns: vec![Some(col)],
    }
}

#[test]
fn a_change_below_the_detection_limit_is_never_named() {
    let d = data();
    let n = d.obs.len();
    let judge = Judge::new(&d, &noise(n, 0.01), None, None);
    // 3 standard errors of 1 % over 32 uncorrelated rows: 0.53 %.
    let t = judge.noise().shape_threshold[0];
    assert!((t - 3.0 * 0.01 / (n as f64).sqrt()).abs() < 1e-12, "{t}");
    let j: Vec<f64> = d.obs.iter().map(|o| o.j - 0.35).collect();
    let weak: Vec<f64> = j.iter().map(|x| 0.5 * t * x / rms(&j)).collect();
    let strong: Vec<f64> = j.iter().map(|x| 3.0 * t * x / rms(&j)).collect();
    assert_eq!(judge.answer(&weak, "a", &[], &[], false).0, AnswerKind::BelowLimit);
    assert_eq!(judge.answer(&strong, "a", &[], &[], false).0, AnswerKind::Found);
    // Its detection limit: the size whose change is just detectable.
    let sep = separability(&judge, &[sig("a", j.iter().map(|x| x / rms(&j)).collect())]);
    assert!((sep.limits[0].limit.unwrap() - t).abs() < 1e-9, "{:?}", sep.limits[0]);
}

#[test]
fn a_separable_pair_is_answered_alone_and_an_inseparable_one_as_a_group() {
    let (d, judge, j) = white();
    let change: Vec<f64> = j.iter().map(|x| 0.05 * x).collect();
    // B moves the rows as the change does (2x per unit): it reproduces it inside its bounds.
    let alike = sig("b", j.iter().map(|x| 2.0 * x).collect());
    // C moves them with the square of J around its mean: orthogonal to the change.
    let q: Vec<f64> = j.iter().map(|x| x * x - 0.0525).collect();
    let other = sig("c", q);
    assert_eq!(
        judge.answer(&change, "a", std::slice::from_ref(&other), &[], false).0,
        AnswerKind::Found
    );
    assert_eq!(
        judge
            .answer(&change, "a", &[alike.clone(), other.clone()], &[], false)
            .0,
        AnswerKind::Group
    );
    assert_eq!(judge.group(&change, "a", &[alike.clone(), other], &[]), ["a", "b"]);
    // B and C together make it, where neither alone does: with C in the stack (free to move as
    // a refit would), B is a rival; without, not.
    let half = sig(
        "b2",
        j.iter()
            .zip(&d.obs)
            .map(|(x, o)| x + 5.0 * (o.j - 0.35).powi(2))
            .collect(),
    );
    let bend = sig("c2", d.obs.iter().map(|o| -(o.j - 0.35).powi(2)).collect());
    let pair = [half, bend];
    assert_eq!(judge.group(&change, "a", &pair[..1], &[]), ["a"]);
    // Neither alone, both together without the stack: a pair rival.
    assert_eq!(judge.group(&change, "a", &pair, &[]), ["a", "b2 + c2"]);
    assert_eq!(judge.group(&change, "a", &pair, &[("c2", &[0.0])]), ["a", "b2"]);
    // B needs x = 0.025 for it; bounded to 0.01 it cannot follow: told apart.
    let bounded = Signature {
        effect: Arc::new(Named("b", vec![Param::new("x", "-", 0.0, (0.0, 0.01), 0.001, "")])),
        ..alike
    };
    assert_eq!(judge.answer(&change, "a", &[bounded], &[], false).0, AnswerKind::Found);
}

#[test]
fn the_model_error_holds_a_level_and_trends_with_rpm_and_j_not_a_bend() {
    let d = data();
    let n = d.obs.len();
    let usual = ModelError {
        thrust: 0.07,
        torque: 0.07,
        props: 10,
        kind: "APC Sport",
    };
    let with = Judge::new(&d, &noise(n, 0.01), None, Some(usual));
    let without = Judge::new(&d, &noise(n, 0.01), None, None);
    // A 4 % level (a density error, a chord scale): seen against the scatter alone, within
    // the 7 % the model usually misses.
    let level = vec![0.04; n];
    assert!(without.strength(&level) > 1.0);
    assert_eq!(
        with.answer(&level, "density", &[], &[], false).0,
        AnswerKind::BelowLimit
    );
    // A trend with RPM of the same size: the same.
    let trend: Vec<f64> = d.obs.iter().map(|o| 0.1 * (o.rpm() / 4500.0).ln()).collect();
    assert!(rms(&trend) < 0.07 && without.strength(&trend) > 1.0);
    assert_eq!(
        with.answer(&trend, "re-lift", &[], &[], false).0,
        AnswerKind::BelowLimit
    );
    // A trend with J (the model's usual error has one: a pitch-like error) likewise.
    let j_trend: Vec<f64> = d.obs.iter().map(|o| 0.1 * (o.j - 0.35)).collect();
    assert!(rms(&j_trend) < 0.07 && without.strength(&j_trend) > 1.0);
    assert_eq!(
        with.answer(&j_trend, "pitch-offset", &[], &[], false).0,
        AnswerKind::BelowLimit
    );
    // A change that bends with J (a tare growing towards zero thrust) is none of these: judged
    // on the scatter.
    let bend: Vec<f64> = d.obs.iter().map(|o| 0.2 * ((o.j - 0.35).powi(2) - 0.0525)).collect();
    assert!(rms(&bend) < 0.07 && with.strength(&bend) > 1.0);
}

#[test]
fn correlated_residuals_count_as_fewer_rows() {
    let d = data();
    let n = d.obs.len();
    // A smooth error along each sweep: neighbours alike.
    let smooth: Vec<f64> = d.obs.iter().map(|o| 0.01 * (3.0 * o.j).sin()).collect();
    let white = noise(n, rms(&smooth));
    let a = Judge::new(&d, &smooth, None, None);
    let b = Judge::new(&d, &white, None, None);
    assert!(a.noise().neighbour_correlation[0] > 0.5, "{:?}", a.noise());
    assert_eq!(b.noise().neighbour_correlation[0], 0.0);
    assert!(a.noise().shape_threshold[0] > 2.0 * b.noise().shape_threshold[0]);
}

#[test]
fn a_torque_tare_and_more_drag_are_told_apart_by_a_run_at_lower_rpm() {
    let ids = vec!["torque-tare".to_string(), "drag-scale".to_string()];
    let how = tell_apart(&data(), &ids);
    assert!(how.contains("static run down to 1500 rpm"), "{how}");
}

#[test]
fn a_rival_stands_in_only_in_the_direction_its_bounds_allow() {
    let (_, judge, j) = white();
    // A's change as the verdict measures it: the rows without A minus the rows with it. A made
    // the rows lower by 0.05 j.
    let removed: Vec<f64> = j.iter().map(|x| 0.05 * x).collect();
    // A one-sided parameter (a tare: 0 or more) whose unit raises the rows by j cannot lower
    // them; one whose unit lowers them can.
    let one_sided = |id: &'static str, sign: f64| Signature {
        effect: Arc::new(Named(id, vec![Param::new("k", "-", 0.0, (0.0, 1.0), 0.01, "")])),
        reference: vec![0.0],
        columns: vec![Some(j.iter().map(|x| sign * x).collect())],
    };
    assert_eq!(judge.group(&removed, "a", &[one_sided("up", 1.0)], &[]), ["a"]);
    assert_eq!(
        judge.group(&removed, "a", &[one_sided("down", -1.0)], &[]),
        ["a", "down"]
    );
}

#[test]
fn a_calibration_factor_names_the_candidates_that_make_its_change_inside_their_expected_ranges() {
    let (_, judge, j) = white();
    let change: Vec<f64> = j.iter().map(|x| 0.05 * x).collect();
    // B makes the change at x = -0.025 (its column 2 J, the rows to make -0.05 J).
    let within = |lo: f64| Signature {
        effect: Arc::new(Named(
            "b",
            vec![Param::new("x", "-", 0.0, (-1.0, 1.0), 0.01, "").expecting(lo, 0.1)],
        )),
        ..sig("b", j.iter().map(|x| 2.0 * x).collect())
    };
    // Expected down to -0.1: a physical stand-in, said beside the calibration factor.
    let (kind, group) = judge.answer(&change, "a", &[within(-0.1)], &[], true);
    assert_eq!(
        (kind, group.as_slice()),
        (AnswerKind::Calibration, &["a".to_string(), "b".into()][..])
    );
    // Expected down to -0.01 only: it makes the change only beyond its expected range, as a
    // calibration factor itself; none is said (a plain group would hold it, inside its bounds).
    let (kind, group) = judge.answer(&change, "a", &[within(-0.01)], &[], true);
    assert_eq!((kind, group.len()), (AnswerKind::Calibration, 0));
    assert_eq!(judge.group(&change, "a", &[within(-0.01)], &[]), ["a", "b"]);
}
