//! Unit tests of `reduce.rs`.

use super::*;

fn sample(line: usize, t: f64, esc: f64, rpm: f64, thrust: f64) -> Sample {
    Sample {
        line,
        time: Some(t),
        esc: Some(esc),
        omega: propbet_units::rpm_to_omega(rpm),
        omega_other: None,
        thrust,
        torque: Some(-thrust * 0.01),
        airspeed: 0.0,
        temperature: None,
        pressure: None,
        humidity: None,
        volts: None,
        amps: None,
        fresh: crate::table::Fresh::ALL,
    }
}

/// A synthetic step test: each step rises over 3 samples, then holds with noise.
fn step_log() -> Vec<Sample> {
    let mut v = Vec::new();
    let mut line = 2;
    let mut t = 0.0;
    for (k, esc) in [1000.0, 1200.0, 1400.0, 1600.0].into_iter().enumerate() {
        let target = 3000.0 * k as f64;
        for i in 0..20 {
            let rise = if i < 3 { (i as f64 + 1.0) / 4.0 } else { 1.0 };
            let noise = if i % 2 == 0 { 10.0 } else { -10.0 };
            let rpm = if k == 0 { 0.0 } else { target * rise + noise };
            v.push(sample(line, t, esc, rpm, rpm * rpm * 1e-7));
            line += 1;
            t += 0.1;
        }
    }
    v
}

#[test]
fn steps_drop_transient_and_keep_scatter() {
    let mut dropped = Vec::new();
    let mut notes = Vec::new();
    let (red, pts) = reduce_log(step_log(), false, &mut dropped, &mut notes, &ReduceOptions::default());
    assert_eq!(red, Reduction::Steps);
    assert_eq!(pts.len(), 3);
    assert_eq!(dropped.len(), 20, "idle rows dropped");
    assert!(dropped.iter().all(|d| d.reason == DropReason::NotSpinning));
    for (k, p) in pts.iter().enumerate() {
        let target = 3000.0 * (k + 1) as f64;
        assert!((p.rpm() - target).abs() < 3.0, "{} vs {target}", p.rpm());
        assert_eq!(p.transient, 3);
        assert_eq!(p.omega.n, 17);
        let sd = propbet_units::omega_to_rpm(p.omega.sd.unwrap());
        assert!((sd - 10.0).abs() < 1.0, "sd {sd}");
        assert!(p.flags.is_empty());
    }
    assert!(notes.iter().any(|n| n.contains("torque is logged negative")));
    let Loads::Forces { torque: Some(q), .. } = pts[0].loads else {
        panic!()
    };
    assert!(q.mean > 0.0);
}

#[test]
fn rpm_dropouts_are_filled_from_the_other_sensor_or_the_steady_step_and_said() {
    // The electrical sensor reads 7/2 of the optical (the app's pole pairs left at 2 on a
    // 14-pole motor); the optical reads 0 on every fifth row.
    let mut log = step_log();
    for (i, s) in log.iter_mut().enumerate() {
        s.omega_other = Some(s.omega * 3.5);
        if i % 5 == 4 {
            s.omega = 0.0;
        }
    }
    let (mut dropped, mut notes) = (Vec::new(), Vec::new());
    let (_, pts) = reduce_log(log, false, &mut dropped, &mut notes, &ReduceOptions::default());
    assert_eq!(pts.len(), 3);
    assert_eq!(dropped.len(), 20, "only the idle step: {dropped:?}");
    assert!(pts.iter().all(|p| p.omega.n >= 16 && p.flags.is_empty()), "{pts:?}");
    assert!(
        notes
            .iter()
            .any(|n| n.contains("take the other RPM sensor's reading times 0.2857")),
        "{notes:?}"
    );
    // One sensor: zero and low readings while thrust holds take the step's steady RPM; a
    // zero where the thrust is not the step's is dropped as a dropout, not "not spinning".
    let mut log = step_log();
    for i in [25, 30, 35] {
        log[i].omega = 0.0;
    }
    log[45].omega *= 0.5;
    log[50].omega = 0.0;
    log[50].thrust *= 0.5;
    let (mut dropped, mut notes) = (Vec::new(), Vec::new());
    let (_, pts) = reduce_log(log, false, &mut dropped, &mut notes, &ReduceOptions::default());
    assert!(pts.iter().all(|p| p.flags.is_empty()), "{pts:?}");
    assert_eq!(pts[0].omega.n, 17, "the step of rows 20-39 keeps its dropouts");
    assert!(
        notes.iter().any(|n| n.starts_with("RPM sensor dropouts: 4 rows")),
        "{notes:?}"
    );
    let lost: Vec<(usize, DropReason)> = dropped
        .iter()
        .filter(|d| d.reason != DropReason::NotSpinning)
        .map(|d| (d.line, d.reason))
        .collect();
    assert_eq!(lost, vec![(52, DropReason::RpmDropout)]);
}

#[test]
fn faulty_rows_are_listed() {
    let mut log = step_log();
    log[30].time = log[29].time; // duplicate time
    log[50].time = Some(400.0); // stray row
    log[65].thrust = -5.0; // negative thrust where the step's other rows pull
    log[70].omega = -100.0;
    let mut dropped = Vec::new();
    let (_, pts) = reduce_log(log, false, &mut dropped, &mut Vec::new(), &ReduceOptions::default());
    assert_eq!(pts.len(), 3);
    let reasons: Vec<(usize, DropReason)> = dropped
        .iter()
        .filter(|d| d.reason.is_fault())
        .map(|d| (d.line, d.reason))
        .collect();
    assert_eq!(
        reasons,
        vec![
            (32, DropReason::DuplicateTime),
            (52, DropReason::TimeOutOfOrder),
            (72, DropReason::NegativeRpm),
            (67, DropReason::NegativeThrust),
        ]
    );
}

/// Negative thrust where no row at the same RPM and airspeed pulls is windmilling: kept as
/// data, its point flagged; where the rows beside it pull, a fault; at the load cell's zero,
/// idle.
#[test]
fn negative_thrust_is_windmilling_a_fault_or_idle_by_its_neighbours() {
    let mut rows: Vec<Sample> = (5..9).map(|i| sample(i, i as f64, 1500.0, 5000.0, 2.0)).collect();
    rows.push(sample(3, 1.0, 1500.0, 5000.0, -0.3));
    rows[4].airspeed = 12.0;
    rows.push(sample(4, 2.0, 1500.0, 5000.0, -0.2));
    rows.push(sample(9, 9.0, 1500.0, 5000.0, -0.01));
    let mut dropped = Vec::new();
    let out = orient(rows, &mut dropped, &mut Vec::new());
    assert_eq!(out.len(), 5);
    assert!(
        out.iter().any(|s| s.line == 3 && s.thrust == -0.3),
        "kept, never flipped"
    );
    let reasons: Vec<(usize, DropReason, bool)> = dropped
        .iter()
        .map(|d| (d.line, d.reason, d.reason.is_fault()))
        .collect();
    assert_eq!(
        reasons,
        vec![(4, DropReason::NegativeThrust, true), (9, DropReason::Idle, false)]
    );
}

/// The pull direction is the highest-RPM rows', not the majority's: a polar run logged pull
/// positive whose many low-RPM rows windmill keeps every sign as logged.
#[test]
fn the_sign_follows_the_highest_rpm_rows_not_the_majority() {
    let mut rows: Vec<Sample> = (0..30)
        .map(|i| sample(i + 2, i as f64, 1100.0, 1000.0 + 20.0 * i as f64, -10.0))
        .collect();
    rows.extend((0..10).map(|i| sample(i + 40, 40.0 + i as f64, 1900.0, 5000.0, 42.0)));
    let mut notes = Vec::new();
    let mut dropped = Vec::new();
    let out = orient(rows, &mut dropped, &mut notes);
    assert!(dropped.is_empty(), "{dropped:?}");
    assert_eq!(out.len(), 40);
    assert!(out.iter().filter(|s| s.omega > 400.0).all(|s| s.thrust == 42.0));
    assert!(out.iter().filter(|s| s.omega < 400.0).all(|s| s.thrust == -10.0));
    assert!(
        !notes.iter().any(|n| n.contains("thrust is logged negative")),
        "{notes:?}"
    );
    // Logged the other way round, both signs flip together.
    let flipped: Vec<Sample> = out
        .iter()
        .map(|s| Sample {
            thrust: -s.thrust,
            ..*s
        })
        .collect();
    let again = orient(flipped, &mut Vec::new(), &mut notes);
    assert_eq!(
        again.iter().map(|s| s.thrust).collect::<Vec<_>>(),
        out.iter().map(|s| s.thrust).collect::<Vec<_>>()
    );
    assert!(
        notes.iter().any(|n| n.contains("thrust is logged negative")),
        "{notes:?}"
    );
}

/// Rows far below the log's top RPM, and a repeated first time stamp, are idle, not faults.
#[test]
fn idle_rows_and_a_repeated_first_stamp_are_not_faults() {
    let mut log = step_log().split_off(20);
    log[5].omega = propbet_units::rpm_to_omega(2.0);
    log[5].thrust = -0.0001;
    log.insert(0, log[0]);
    let mut dropped = Vec::new();
    reduce_log(log, false, &mut dropped, &mut Vec::new(), &ReduceOptions::default());
    assert!(dropped.iter().all(|d| !d.reason.is_fault()), "{dropped:?}");
    assert!(dropped
        .iter()
        .any(|d| d.reason == DropReason::Idle && d.detail.contains("first time stamp")));
}

#[test]
fn ramps_are_binned() {
    let log: Vec<Sample> = (0..600)
        .map(|i| sample(i + 2, i as f64 * 0.05, 1000.0 + i as f64, 2000.0 + 10.0 * i as f64, 1.0))
        .collect();
    let mut notes = Vec::new();
    let (red, pts) = reduce_log(log, false, &mut Vec::new(), &mut notes, &ReduceOptions::default());
    assert_eq!(red, Reduction::Ramp);
    // 6000 rpm span / 30 = 200 rpm bins.
    assert!(notes.iter().any(|n| n.contains("200 rpm bins")), "{notes:?}");
    assert!(pts.len() >= 29 && pts.len() <= 31, "{}", pts.len());
    assert!(pts.windows(2).all(|w| w[1].rpm() > w[0].rpm()));
}

#[test]
fn nice_widths() {
    assert_eq!(nice(47.0), 50.0);
    assert_eq!(nice(180.0), 200.0);
    assert_eq!(nice(210.0), 250.0);
    assert_eq!(nice(50.0), 50.0);
}
