//! Unit tests of `metrics.rs`.

use super::*;
use crate::Quantities;
use approx::assert_relative_eq;

#[test]
fn the_figure_of_merit_is_one_for_an_actuator_disc_and_compared_at_static_points() {
    // An actuator disc's power P = T^1.5 / sqrt(2 rho A): FM 1 from its coefficients.
    let (rho, d, n, t) = (1.2, 0.25, 100.0, 5.0);
    let area = std::f64::consts::PI * d * d / 4.0;
    let p = t * f64::sqrt(t) / (2.0 * rho * area).sqrt();
    let (ct, cp) = (t / (rho * n * n * d.powi(4)), p / (rho * n.powi(3) * d.powi(5)));
    assert_relative_eq!(figure_of_merit(ct, cp), 1.0, epsilon = 1e-12);
    // Thrust 10 % high at the same power: FM 1.1^1.5 - 1 = 15.4 % high; forward points and
    // points without power are left out.
    let with = |v: f64, ct: [f64; 2], cp: [Option<f64>; 2]| {
        let mut x = pt("s", 5000.0, 0.0, 1.0, 1.0);
        x.v = v;
        x.measured.ct = Some(ct[0]);
        x.predicted.ct = Some(ct[1]);
        x.measured.cp = cp[0];
        x.predicted.cp = cp[1];
        x
    };
    let pts = [
        with(0.0, [0.10, 0.11], [Some(0.04), Some(0.04)]),
        with(0.0, [0.10, 0.11], [Some(0.04), None]),
        with(5.0, [0.05, 0.10], [Some(0.03), Some(0.03)]),
    ];
    assert_relative_eq!(
        static_figure_of_merit_error(&pts),
        1.1f64.powf(1.5) - 1.0,
        epsilon = 1e-12
    );
    assert!(static_figure_of_merit_error(&pts[2..]).is_nan(), "no static point: NaN");
}

fn pt(label: &str, rpm: f64, j: f64, meas: f64, pred: f64) -> ComparedPoint {
    let q = |t: f64| Quantities {
        thrust: Some(t),
        ..Default::default()
    };
    ComparedPoint {
        label: label.into(),
        lines: (1, 1),
        rpm,
        j,
        measured: q(meas),
        predicted: q(pred),
        ..Default::default()
    }
}

#[test]
fn window_errors_stop_below_85_percent_of_the_zero_thrust_j() {
    // Measured CT crosses zero at J = 0.5: J 0.45 (>= 0.425) is left out.
    let mk = |j: f64, ct: f64, ctp: f64, cp: f64, cpp: f64| {
        let mut p = pt("x", 5000.0, j, 1.0, 1.0);
        p.measured.ct = Some(ct);
        p.predicted.ct = Some(ctp);
        p.measured.cp = Some(cp);
        p.predicted.cp = Some(cpp);
        p
    };
    let pts = vec![
        mk(0.2, 0.08, 0.08, 0.04, 0.044),
        mk(0.0, 0.1, 0.11, 0.05, 0.05),
        mk(0.45, 0.01, 0.02, 0.02, 0.02),
        mk(0.55, -0.01, 0.0, 0.01, 0.01),
    ];
    let (ct, cp) = window_errors(&pts, VALIDATION_J_WINDOW);
    // In the points' order.
    assert_eq!(ct.len(), 2);
    assert!(ct[0].abs() < 1e-12 && (ct[1] - 0.1).abs() < 1e-12, "{ct:?}");
    assert!((cp[0] - 0.1).abs() < 1e-12, "{cp:?}");
    assert_eq!(in_window(&pts, VALIDATION_J_WINDOW), vec![true, true, false, false]);
    // A wider window takes J = 0.45 in.
    assert_eq!(in_window(&pts, 0.95), vec![true, true, true, false]);
}

#[test]
fn regime_errors_are_signed_and_split_at_half_the_prop_s_zero_thrust_j() {
    let mk = |file: usize, j: f64, ct: [f64; 2], cp: [f64; 2]| {
        let mut p = pt("x", 5000.0, j, 1.0, 1.0);
        p.file = file;
        p.measured.ct = Some(ct[0]);
        p.predicted.ct = Some(ct[1]);
        p.measured.cp = Some(cp[0]);
        p.predicted.cp = Some(cp[1]);
        p
    };
    // File 0: static, thrust 10 % high, power 5 % low. File 1: a low-J sweep that never
    // reaches zero thrust (no zero-thrust J of its own). File 2: crosses zero at J = 0.6.
    let pts = vec![
        mk(0, 0.0, [0.10, 0.11], [0.05, 0.0475]),
        mk(0, 0.0, [0.10, 0.11], [0.05, 0.0475]),
        mk(1, 0.1, [0.09, 0.0855], [0.05, 0.05]),
        mk(1, 0.25, [0.08, 0.076], [0.05, 0.05]),
        mk(2, 0.35, [0.05, 0.06], [0.04, 0.044]),
        mk(2, 0.55, [0.01, 0.02], [0.02, 0.02]),
        mk(2, 0.65, [-0.01, 0.0], [0.01, 0.01]),
    ];
    let [st, low, high] = regime_errors(&pts, VALIDATION_J_WINDOW);
    assert_eq!((st.points, low.points, high.points), (2, 2, 1));
    assert!((st.ct - 0.1).abs() < 1e-12 && (st.cp + 0.05).abs() < 1e-12, "{st:?}");
    // File 1's points are below half of the prop's zero-thrust J (0.6, file 2's).
    assert!((low.ct + 0.05).abs() < 1e-12 && low.cp.abs() < 1e-12, "{low:?}");
    // J = 0.35 is above 0.3; J = 0.55 is outside the window (0.85 x 0.6 = 0.51).
    assert!(
        (high.ct - 0.2).abs() < 1e-12 && (high.cp - 0.1).abs() < 1e-12,
        "{high:?}"
    );
    // Without a zero-thrust J every forward point is in the first regime; no static: NaN.
    let [st, low, high] = regime_errors(&pts[2..4], VALIDATION_J_WINDOW);
    assert_eq!((st.points, low.points, high.points), (0, 2, 0));
    assert!(st.ct.is_nan() && high.cp.is_nan());
}

#[test]
fn the_static_rise_is_from_the_lowest_to_the_highest_static_rpm() {
    let mk = |rpm: f64, j: f64, ct: [f64; 2]| {
        let mut p = pt("x", rpm, j, 1.0, 1.0);
        p.measured.ct = Some(ct[0]);
        p.predicted.ct = Some(ct[1]);
        p
    };
    // Out of order, with a forward point (not static) at a higher RPM and a point without
    // a prediction.
    let mut none = mk(7000.0, 0.0, [0.13, 0.1]);
    none.predicted.ct = None;
    let pts = vec![
        mk(6000.0, 0.0, [0.12, 0.105]),
        mk(2400.0, 0.0, [0.10, 0.1]),
        mk(4000.0, 0.0, [0.11, 0.102]),
        mk(8000.0, 0.3, [0.05, 0.06]),
        none,
    ];
    let r = static_rise(&pts).unwrap();
    assert_eq!((r.rpm_lo, r.rpm_hi), (2400.0, 6000.0));
    assert!(
        (r.measured - 0.2).abs() < 1e-12 && (r.predicted - 0.05).abs() < 1e-12,
        "{r:?}"
    );
    // Less than 1.3x in RPM, or one point: none.
    assert!(static_rise(&[mk(2400.0, 0.0, [0.1, 0.1]), mk(3000.0, 0.0, [0.1, 0.1])]).is_none());
    assert!(static_rise(&pts[..1]).is_none());
}

#[test]
fn the_zero_thrust_shift_follows_the_sweeps_crossings() {
    // Three J sweeps (files by label) whose measured CT crosses zero at 0.65, 0.64, 0.62
    // and whose predicted CT at 0.60, 0.61, 0.62 (CT = k (J0 - J) through J = 0.5 and 0.7),
    // and a static file at a higher RPM.
    let mut pts = Vec::new();
    for (f, (rpm, jm, jp)) in [(4000.0, 0.65, 0.60), (5000.0, 0.64, 0.61), (6800.0, 0.62, 0.62)]
        .into_iter()
        .enumerate()
    {
        for j in [0.5, 0.7] {
            let mut p = pt("x", rpm, j, 1.0, 1.0);
            p.file = f;
            p.measured.ct = Some(0.3 * (jm - j));
            p.predicted.ct = Some(0.3 * (jp - j));
            pts.push(p);
        }
    }
    let mut st = pt("s", 9000.0, 0.0, 1.0, 1.0);
    st.file = 3;
    st.measured.ct = Some(0.1);
    st.predicted.ct = Some(-0.1);
    pts.push(st);
    let z = zero_thrust_shift(&pts).unwrap();
    assert_eq!((z.rpm_lo, z.sweeps), (4000.0, 3));
    assert_eq!(z.rpm_hi, 6800.0);
    // Falling measured, rising predicted: the fitted lines' ends, near the sweeps' own.
    let q = z.predicted.unwrap();
    assert!(
        z.measured_change() < -0.03 && z.predicted_change().unwrap() > 0.02,
        "{z:?}"
    );
    assert!(
        (z.measured.0 - 0.652).abs() < 0.005 && (q.1 - 0.621).abs() < 0.005,
        "{z:?}"
    );
    // One sweep, or sweeps within 1.2x in RPM: none.
    assert!(zero_thrust_shift(&pts[..2]).is_none());
    let mut near: Vec<ComparedPoint> = pts[..4].to_vec();
    near[2].rpm = 4400.0;
    near[3].rpm = 4400.0;
    assert!(zero_thrust_shift(&near).is_none());
    // A sweep whose prediction never reaches zero thrust is left out of the predicted line
    // (the other two still span 1.7x); with two such sweeps there is no predicted line,
    // and the measured one stays.
    let mut short = pts.clone();
    short[3].predicted.ct = Some(0.01);
    let z = zero_thrust_shift(&short).unwrap();
    assert_eq!(z.sweeps, 3);
    assert!(
        z.predicted
            .is_some_and(|q| (q.0 - 0.60).abs() < 1e-9 && (q.1 - 0.62).abs() < 1e-9),
        "{z:?}"
    );
    short[5].predicted.ct = Some(0.01);
    let z = zero_thrust_shift(&short).unwrap();
    assert!(z.predicted.is_none() && z.measured_change() < -0.03, "{z:?}");
}

#[test]
fn sweeps_of_one_nominal_speed_share_a_group() {
    let mut a = pt("a", 4997.0, 0.3, 1.0, 1.0);
    a.nominal_rpm = Some(4997.0);
    let mut b = pt("b", 5018.0, 0.3, 1.0, 1.0);
    b.nominal_rpm = Some(5018.0);
    let c = pt("c", 6023.0, 0.0, 1.0, 1.0);
    assert_eq!(sweep_group(&a), (5000, "5000 rpm".to_string()));
    assert_eq!(sweep_group(&a), sweep_group(&b));
    assert_eq!(sweep_group(&c).0, 6000);
}

#[test]
fn bias_rmse_and_relative_errors() {
    let pts = vec![
        pt("a", 4100.0, 0.0, 1.0, 1.1),
        pt("b", 4900.0, 0.0, 2.0, 1.8),
        pt("c", 5500.0, 0.3, 4.0, 4.0),
    ];
    let m = metrics(&pts);
    let t = &m.overall.metrics["thrust"];
    assert_eq!(t.n, 3);
    assert_relative_eq!(t.bias, (0.1 - 0.2) / 3.0, epsilon = 1e-12);
    assert_relative_eq!(t.rmse, ((0.01 + 0.04) / 3.0f64).sqrt(), epsilon = 1e-12);
    assert_relative_eq!(t.mean_rel, (0.1 - 0.1 + 0.0) / 3.0, epsilon = 1e-12);
    assert_relative_eq!(t.mean_abs_rel, 0.2 / 3.0, epsilon = 1e-12);
    assert_relative_eq!(t.max_rel.abs(), 0.1, epsilon = 1e-12);
    assert_eq!(m.per_rpm.len(), 2);
    assert_eq!(m.per_rpm[0].name, "static, 4000-5000 rpm band");
    assert_eq!(m.per_rpm[0].points, 2);
    assert_eq!(m.per_j[0].name, "static (J = 0)");
    assert_eq!(m.per_j[1].name, "J 0.2-0.4");
    assert_eq!(m.static_points.unwrap().points, 2);
    assert!(!m.overall.metrics.contains_key("torque"));
}

#[test]
fn flagged_points_are_not_scored() {
    let mut bad = pt("bad", 5000.0, 0.0, 1.0, 3.0);
    bad.flags.push("unsteady".into());
    let m = metrics(&[pt("a", 5000.0, 0.0, 1.0, 1.0), bad]);
    assert_eq!(m.unscored, 1);
    assert_eq!(m.overall.metrics["thrust"].rmse, 0.0);
}

#[test]
fn halves_hold_whole_sweeps_alternately_by_rpm_and_share_the_static_points() {
    let read = |name: &str, text: &str| {
        let opts = propbet_measure::ReadOptions {
            name: Some(name.to_string()),
            ..Default::default()
        };
        propbet_measure::read(text, &opts).unwrap()
    };
    let sweep = "J CT CP eta\n0.2 0.10 0.05 0.40\n0.4 0.08 0.05 0.64\n";
    let statics = "RPM CT CP\n3000 0.10 0.05\n4000 0.11 0.05\n5000 0.12 0.05\n6000 0.12 0.05\n7000 0.13 0.06\n";
    let names = [
        "p_kt1_6000",
        "p_static_kt0",
        "p_kt2_4000",
        "p_kt3_5000",
        "p_kt4_5010",
        "p_kt5_6019",
        "p_kt6_7013",
        "p_kt7_7018",
    ];
    let files: Vec<PathBuf> = names.iter().map(|n| PathBuf::from(format!("uiuc/{n}.txt"))).collect();
    let sets: Vec<MeasuredSet> = names
        .iter()
        .map(|n| read(&format!("{n}.txt"), if n.contains("static") { statics } else { sweep }))
        .collect();
    let [a, b] = halves(&files, &sets);
    // Each set as the RPMs of its points, rounded.
    let rpms = |h: &[MeasuredSet]| -> Vec<Vec<i64>> {
        h.iter()
            .map(|s| s.points.iter().map(|p| p.rpm().round() as i64).collect())
            .collect()
    };
    // The static test's rows alternately (first, third and fifth to the first half), then the
    // sweeps by RPM, each sweep's runs together: 4000 and 6000 (two runs) to the first half,
    // 5000 (two runs) and 7000 (two runs) to the second.
    let sweep_at = |r: i64| vec![r, r];
    assert_eq!(
        rpms(&a),
        vec![vec![3000, 5000, 7000], sweep_at(4000), sweep_at(6000), sweep_at(6019)]
    );
    assert_eq!(
        rpms(&b),
        vec![
            vec![4000, 6000],
            sweep_at(5000),
            sweep_at(5010),
            sweep_at(7013),
            sweep_at(7018)
        ]
    );
    assert_eq!((a[0].rows, b[0].rows), (3, 2));
    // No point in both halves, none lost.
    let count = |h: &[MeasuredSet]| h.iter().map(|s| s.points.len()).sum::<usize>();
    assert_eq!(
        count(&a) + count(&b),
        sets.iter().map(|s| s.points.len()).sum::<usize>()
    );
}

#[test]
fn the_twist_gap_is_the_mean_over_r_r_0_6_to_0_9() {
    // Design twist 20 deg everywhere; measured 18 at 0.6, 17 at 0.75, 19 at 0.9 (mean gap 2),
    // and stations outside the span that would change it.
    let stations = [(0.3, 0.0), (0.6, 18.0), (0.75, 17.0), (0.9, 19.0), (0.95, 40.0)];
    assert!((twist_gap(&stations, |_| 20.0) - 2.0).abs() < 1e-12);
    assert!(twist_gap(&stations[..1], |_| 20.0).is_nan());
}
