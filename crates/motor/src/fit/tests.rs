//! The fit on generated step logs: the constants back, within their intervals; both sides of
//! the motor; a step the ESC never reaches.
use super::*;

#[test]
fn t_quantiles_are_students() {
    // Tables: t(0.975; 5) = 2.571, t(0.975; 30) = 2.042, infinity 1.960.
    assert!((t975(5) - 2.571).abs() < 0.03, "{}", t975(5));
    assert!((t975(30) - 2.042).abs() < 0.005);
    assert!((t975(100_000) - 1.960).abs() < 0.001);
}

/// `m` at `volts` on a propeller of Q = c w^2: its speed and its torque and current there.
fn on_quadratic_prop(m: &Motor, volts: f64, c: f64) -> (f64, crate::model::MotorPoint) {
    let (mut lo, mut hi) = (0.0, m.free_speed(volts).unwrap());
    for _ in 0..200 {
        let w = 0.5 * (lo + hi);
        if c * w * w < m.at(w, volts).torque {
            lo = w;
        } else {
            hi = w;
        }
    }
    let w = 0.5 * (lo + hi);
    (w, m.at(w, volts))
}

/// A generated step log of `m` on a propeller Q = c w^2 (a 7 A load at full throttle) at 12 V through an ideal ESC,
/// five samples per step, each reading with `noise` relative Gaussian noise.
fn generated(m: &Motor, noise: f64, seed: u64) -> Vec<FitPoint> {
    let mut state = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
    let mut uniform = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    let mut gauss = move || (-2.0 * uniform().ln()).sqrt() * (2.0 * std::f64::consts::PI * uniform()).cos();
    let vb = 12.0;
    let mut out = Vec::new();
    for k in 3..=10 {
        let d = k as f64 / 10.0;
        let (w, at) = on_quadratic_prop(m, d * vb, 2e-8);
        for _ in 0..5 {
            out.push(FitPoint {
                omega: w * (1.0 + noise * gauss()),
                torque: at.torque * (1.0 + noise * gauss()),
                volts: vb * (1.0 + noise * gauss()),
                amps: d * at.amps * (1.0 + noise * gauss()),
                esc: Some(1000.0 + 1000.0 * d),
            });
        }
    }
    out
}

#[test]
fn generated_logs_with_one_percent_noise_give_their_constants_within_the_intervals() {
    let m = Motor::dc1(0.12, 0.9, 1400.0).unwrap();
    let truth = [0.12, 0.9, 1400.0];
    let mut inside = [0usize; 3];
    let runs = 40;
    for seed in 0..runs {
        let f = fit_motor(&generated(&m, 0.01, seed), None, FitKind::Type1).unwrap();
        for (k, e) in [f.r, f.io, f.kv_rpm].iter().enumerate() {
            if (e.value - truth[k]).abs() <= e.plus_minus {
                inside[k] += 1;
            }
            // The intervals say something: under a third of the value.
            assert!(e.plus_minus < 0.34 * truth[k], "seed {seed}: {k} {e:?}");
        }
    }
    // 95 % intervals: at least 34 of 40 (a binomial 95 % of 40 falls below 34 with
    // probability 1.6 %).
    eprintln!("intervals holding R, Io, Kv: {inside:?} of {runs}");
    for (k, n) in inside.iter().enumerate() {
        assert!(*n >= 34, "parameter {k}: {n} of {runs} intervals hold the truth");
    }
}

#[test]
fn a_type_2_fit_finds_a_torque_constant_of_its_own_within_its_interval() {
    // Kq 10 % above Kv: the supply pays 10 % more than the shaft power's share.
    let m = Motor::from_params(2, &[0.12, 0.9, 1400.0, 1540.0, 0.0, 0.0, 0.0, 0.0]).unwrap();
    let truth = [0.12, 0.9, 1400.0, 1540.0];
    let mut inside = [0usize; 4];
    let mut inside_given = 0;
    let runs = 40;
    for seed in 0..runs {
        let f = fit_motor(&generated(&m, 0.01, seed), None, FitKind::Type2).unwrap();
        let kq = f.kq_rpm.expect("type 2 fits Kq");
        for (k, e) in [f.r, f.io, f.kv_rpm, kq].iter().enumerate() {
            if (e.value - truth[k]).abs() <= e.plus_minus {
                inside[k] += 1;
            }
        }
        // Kq and Io are told apart well; R and Kv trade against each other on a
        // propeller's load (the current and the speed rise together): wide, but holding.
        assert!(
            kq.plus_minus < 0.03 * truth[3] && f.io.plus_minus < 0.15 * truth[1],
            "seed {seed}: {kq:?} {:?}",
            f.io
        );
        assert_eq!(f.motor.kind, crate::MotorKind::Dc2);
        // With the maker's Kv, R is found as well as type 1 finds it.
        let given = fit_motor(&generated(&m, 0.01, seed), Some(1400.0), FitKind::Type2).unwrap();
        if (given.r.value - truth[0]).abs() <= given.r.plus_minus {
            inside_given += 1;
        }
        assert!(given.r.plus_minus < 0.34 * truth[0], "seed {seed}: {:?}", given.r);
    }
    assert!(inside_given >= 34, "R with Kv given: {inside_given} of {runs}");
    eprintln!("intervals holding R, Io, Kv, Kq: {inside:?} of {runs}");
    for (k, n) in inside.iter().enumerate() {
        assert!(*n >= 34, "parameter {k}: {n} of {runs} intervals hold the truth");
    }
    // A type 1 fit of the same logs cannot hold both: it puts the extra power in R and Io.
    let one = fit_motor(&generated(&m, 0.0, 1), None, FitKind::Type1).unwrap();
    assert!(one.rms_current > 1e-4, "{}", one.rms_current);
    let two = fit_motor(&generated(&m, 0.0, 1), None, FitKind::Type2).unwrap();
    assert!(two.rms_current < 1e-9, "{}", two.rms_current);
    assert!((two.kq_rpm.unwrap().value / 1540.0 - 1.0).abs() < 1e-6);
}

#[test]
fn a_noiseless_log_gives_its_motor_back() {
    let m = Motor::dc1(0.12, 0.9, 1400.0).unwrap();
    let vb = 12.0;
    let points: Vec<FitPoint> = (5..=10)
        .map(|k| {
            let d = k as f64 / 10.0;
            let (w, at) = on_quadratic_prop(&m, d * vb, 2e-9);
            FitPoint {
                omega: w,
                torque: at.torque,
                volts: vb,
                amps: d * at.amps,
                esc: Some(1000.0 + 1000.0 * d),
            }
        })
        .collect();
    let f = fit_motor(&points, None, FitKind::Type1).unwrap();
    assert!((f.r.value / 0.12 - 1.0).abs() < 1e-6, "{:?}", f.r);
    assert!((f.io.value / 0.9 - 1.0).abs() < 1e-6, "{:?}", f.io);
    assert!((f.kv_rpm.value / 1400.0 - 1.0).abs() < 1e-6, "{:?}", f.kv_rpm);
    assert!(f.rms_current < 1e-9);
    let given = fit_motor(&points, Some(1400.0), FitKind::Type1).unwrap();
    assert!((given.r.value / 0.12 - 1.0).abs() < 1e-6);
    assert!(matches!(
        fit_motor(&points[..3], None, FitKind::Type1),
        Err(FitError::TooFew(3))
    ));
    let no_esc: Vec<FitPoint> = points.iter().map(|p| FitPoint { esc: None, ..*p }).collect();
    assert_eq!(fit_motor(&no_esc, None, FitKind::Type1), Err(FitError::NoKv));
}

/// A step log as [`generated`] makes, its ESC commands up to 1950 µs where the ESC gives at
/// most `top` duty (its command never reached), the torque read `torque_scale` times.
fn saturated(m: &Motor, top: f64, torque_scale: f64) -> Vec<FitPoint> {
    let vb = 16.0;
    (5..=10)
        .map(|k| {
            let command = (1000.0 + 100.0 * k as f64).min(1950.0);
            let d = ((command - 1000.0) / 1000.0).min(top);
            let (w, at) = on_quadratic_prop(m, d * vb, 2e-8);
            FitPoint {
                omega: w,
                torque: at.torque * torque_scale,
                volts: vb,
                amps: d * at.amps,
                esc: Some(command),
            }
        })
        .collect()
}

#[test]
fn both_sides_agree_on_a_motor_and_a_step_the_esc_never_reaches_is_left_out() {
    let m = Motor::dc1(0.12, 0.9, 1400.0).unwrap();
    // The sides agree on a generated log with 1 % noise, within their intervals.
    let s = sides::both_sides(&generated(&m, 0.01, 3)).unwrap().unwrap();
    let apart = (s.torque_kv_rpm.value - s.kv_rpm.value).abs();
    assert!(apart < s.kv_rpm.plus_minus + s.torque_kv_rpm.plus_minus, "{s:?}");
    assert!(s.disagreement().abs() < sides::DISAGREE, "{s:?}");
    // The ESC stops at 92 % duty: the 1950 µs step is off the others' line and left out.
    let log = saturated(&m, 0.92, 1.0);
    let s = sides::both_sides(&log).unwrap().unwrap();
    assert_eq!(s.left_out, [1950.0], "{s:?}");
    assert!((s.kv_rpm.value / 1400.0 - 1.0).abs() < 1e-6, "{s:?}");
    let f = fit_motor(&log, None, FitKind::Type1).unwrap();
    assert!(
        (f.kv_rpm.value / 1400.0 - 1.0).abs() < 1e-6 && (f.io.value / 0.9 - 1.0).abs() < 1e-6,
        "{f:?}"
    );
}

#[test]
fn a_torque_read_high_leaves_io_and_says_the_sides_disagree() {
    let m = Motor::dc1(0.12, 0.9, 1400.0).unwrap();
    // A torque cell reading 5 % high: the torque side keeps its intercept, and its slope
    // says 5 %.
    let log = saturated(&m, 1.0, 1.05);
    let s = sides::both_sides(&log).unwrap().unwrap();
    assert!((s.disagreement() + 1.0 - 1.0 / 1.05).abs() < 1e-6, "{s:?}");
    assert!((s.io.value / 0.9 - 1.0).abs() < 1e-6, "{s:?}");
    let f = fit_motor(&log, None, FitKind::Type1).unwrap();
    assert!((f.io.value / 0.9 - 1.0).abs() < 1e-6, "{f:?}");
    // A duty map that is not the ESC's (its commands read 300 µs high) is refused by name.
    let off: Vec<FitPoint> = log
        .iter()
        .map(|p| FitPoint {
            esc: p.esc.map(|u| u + 300.0),
            ..*p
        })
        .collect();
    assert!(matches!(
        fit_motor(&off, None, FitKind::Type1),
        Err(FitError::DutyMap(_))
    ));
}
