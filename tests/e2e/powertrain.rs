//! A case's powertrain: `[motor]` with a driver, `[battery]` and `[esc]` make `propbet run`
//! solve the propeller on its motor, as `propbet predict --motor` does, and put the table in
//! the report; a battery or ESC without what it drives is refused naming the key.

use super::{read_csv, repo, run, stderr};

/// The shipped case of QPROP's example prop on QPROP's example motor and a NiMH pack.
#[test]
fn a_case_with_a_motor_and_battery_gives_predict_motors_table_and_the_reports_section() {
    let t = tempfile::tempdir().unwrap();
    let case = repo().join("props/cam6x3");
    let out = t.path().join("run");
    let o = run(&["run", case.to_str().unwrap(), "-o", out.to_str().unwrap()], t.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let powered = out.join("predict/powered.csv");
    // The same table as the command a user would type for it (the case's battery written as
    // the flag takes it).
    let by_hand = t.path().join("by_hand.csv");
    let prop = case.join("cam6x3.qprop");
    let motor = case.join("s400-6v-dd.motor");
    let o = run(
        &[
            "predict",
            "--prop",
            prop.to_str().unwrap(),
            "--motor",
            motor.to_str().unwrap(),
            "--throttle",
            "0.6,0.8,1",
            "--battery",
            "7S,1500mAh,V=1.2,R=10mOhm,cutoff=1.0",
            "--v",
            "0,4,8,12",
            "--band",
            "-o",
            by_hand.to_str().unwrap(),
        ],
        t.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(
        std::fs::read(&powered).unwrap(),
        std::fs::read(&by_hand).unwrap(),
        "the run's powered table and predict --motor's differ"
    );
    let (h, rows) = read_csv(&powered);
    assert_eq!(rows.len(), 12, "3 throttles x 4 airspeeds");
    for name in ["throttle", "battery_amps", "endurance_min", "ct_lo", "ct_hi", "g_per_w"] {
        assert!(h.iter().any(|c| c == name), "{name} missing: {h:?}");
    }
    // More throttle, more thrust (static rows).
    let thrust: Vec<f64> = rows
        .iter()
        .filter(|r| r[h.iter().position(|c| c == "v_m_s").unwrap()] == "0")
        .map(|r| r[h.iter().position(|c| c == "thrust_n").unwrap()].parse().unwrap())
        .collect();
    assert!(
        thrust.len() == 3 && thrust[0] < thrust[1] && thrust[1] < thrust[2],
        "{thrust:?}"
    );
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.contains("<h2>On its motor</h2>"), "no motor section");
    assert_eq!(html.matches("% throttle</td>").count(), 12, "a row per point");
    assert!(html.contains(
        "predict/powered.csv</code></a>: the propeller on its motor and battery, most thrust: 100 % throttle at 0 m/s"
    ));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["powered"]["solved"], 12);
    assert_eq!(summary["stages"][1]["stage"], "motor");
}

/// What a case's powertrain sections must hold, each refused naming its key, nothing run.
#[test]
fn a_battery_or_esc_without_what_it_drives_is_refused_naming_the_key() {
    let t = tempfile::tempdir().unwrap();
    std::fs::copy(repo().join("props/cam6x3/cam6x3.qprop"), t.path().join("p.qprop")).unwrap();
    std::fs::copy(repo().join("props/motors/s400-6v-dd.motor"), t.path().join("m.motor")).unwrap();
    let head = "name = \"x\"\n[geometry]\nprop = \"p.qprop\"\n[sweep]\nrpm = \"8000\"\nj = \"0\"\n";
    for (body, says) in [
        (
            "[battery]\ncells = 2\n",
            "[battery]: a battery or an ESC needs the motor",
        ),
        (
            "[motor]\nfile = \"m.motor\"\nvolts = 7\n[esc]\nohms = 0.01\n",
            "[esc]: an ESC needs the battery",
        ),
        (
            "[motor]\nfile = \"m.motor\"\nthrottle = 1\n",
            "[motor] throttle: a throttle needs the battery",
        ),
        (
            "[motor]\nfile = \"m.motor\"\nthrottle = 1.5\n[battery]\ncells = 2\n",
            "[motor] throttle: 1.5: a throttle is between 0 and 1",
        ),
        (
            "[motor]\nfile = \"m.motor\"\nvolts = 7\namps = 3\n",
            "[motor]: volts, amps, thrust, throttle: give one of them",
        ),
        (
            "[motor]\nfile = \"m.motor\"\nvolts = 7\n[battery]\ncells = 2\ncutoff_volts = 4\n",
            "the battery is at or below its cutoff",
        ),
        (
            "[motor]\nfile = \"m.motor\"\nvolts = 7\n[battery]\ncells = 2\n[esc]\nohms = -1\n",
            "[esc] ohms: -1: a resistance from 0 to 10 ohm",
        ),
        ("[motor]\nfile = \"m.motor\"\nvolts = \"7,x\"\n", "[motor] volts"),
    ] {
        std::fs::write(t.path().join("case.toml"), format!("{head}{body}")).unwrap();
        let out = t.path().join("out");
        let o = run(&["run", ".", "-o", out.to_str().unwrap()], t.path());
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{body}: {e}");
        assert!(e.contains("case.toml") && e.contains(says), "{body}: {e}");
        assert!(!out.join("predict").exists(), "{body}: a stage ran");
    }
}

/// `predict --motor --out-stations`: each operating point's stations, at the speed the motor
/// and the propeller agree on (their thrust, summed along the blade, the point's).
#[test]
fn a_powered_prediction_writes_the_stations_of_each_operating_point() {
    let t = tempfile::tempdir().unwrap();
    let prop = repo().join("props/cam6x3/cam6x3.qprop");
    let motor = repo().join("props/motors/s400-6v-dd.motor");
    let o = run(
        &[
            "predict",
            "--prop",
            prop.to_str().unwrap(),
            "--motor",
            motor.to_str().unwrap(),
            "--volts",
            "6,7",
            "--v",
            "0,5",
            "-o",
            "p.csv",
            "--out-stations",
            "s.csv",
        ],
        t.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let (h, points) = read_csv(&t.path().join("p.csv"));
    let (sh, stations) = read_csv(&t.path().join("s.csv"));
    let at = |h: &[String], name: &str| h.iter().position(|c| c == name).unwrap();
    assert_eq!(points.len(), 4);
    assert_eq!(stations.len() % points.len(), 0, "the same stations at every point");
    let per = stations.len() / points.len();
    for (i, p) in points.iter().enumerate() {
        let rows = &stations[i * per..(i + 1) * per];
        assert!(rows
            .iter()
            .all(|s| s[at(&sh, "rpm")] == p[at(&h, "rpm")] && s[at(&sh, "v_m_s")] == p[at(&h, "v_m_s")]));
        let num = |s: &Vec<String>, c: &str| s[at(&sh, c)].parse::<f64>().unwrap();
        let thrust: f64 = rows
            .windows(2)
            .map(|w| {
                (num(&w[1], "r_m") - num(&w[0], "r_m")) * (num(&w[0], "dt_dr_n_m") + num(&w[1], "dt_dr_n_m")) / 2.0
            })
            .sum();
        let table: f64 = p[at(&h, "thrust_n")].parse().unwrap();
        // The trapezoid leaves out the hub's and the tip's last pieces: a few per cent less.
        assert!(
            thrust < table && thrust > 0.95 * table,
            "point {i}: {thrust} against {table}"
        );
    }
}

/// A RCbenchmark step log (its columns as the Series 1585 writes them) of `motor` on a
/// propeller of Q = 2e-8 w^2 at 12 V through an ideal ESC: 20 samples at each ESC command,
/// each reading with 1 % noise.
fn generated_log(motor: &propbet_api::motor::Motor) -> String {
    let header = "Time (s),ESC signal (µs),Servo 1 (µs),Servo 2 (µs),Servo 3 (µs),AccX (g),AccY (g),AccZ (g),Torque (N·m),Thrust (N),Voltage (V),Current (A),Motor Electrical Speed (RPM),Motor Optical Speed (RPM),Electrical Power (W),Mechanical Power (W),Motor Efficiency (%),Propeller Mech. Efficiency (N/W),Overall Efficiency (N/W),Vibration (g),App message,";
    let mut state: u64 = 7;
    let mut noise = move || {
        // A sum of four uniforms: near-Gaussian, 1 % standard deviation.
        (0..4)
            .map(|_| {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .sum::<f64>()
            * 0.01
            * 3.0f64.sqrt()
    };
    let mut out = vec![header.to_string()];
    let mut t = 0.0;
    for esc in (1300..=2000).step_by(100) {
        let d = (esc as f64 - 1000.0) / 1000.0;
        // The speed where the motor at d 12 V turns the propeller (bisection).
        let (mut lo, mut hi) = (0.0, motor.free_speed(12.0 * d).unwrap());
        for _ in 0..200 {
            let w = 0.5 * (lo + hi);
            if 2e-8 * w * w < motor.at(w, 12.0 * d).torque {
                lo = w;
            } else {
                hi = w;
            }
        }
        let w = 0.5 * (lo + hi);
        let at = motor.at(w, 12.0 * d);
        for _ in 0..20 {
            t += 0.1;
            let rpm = propbet_api::units::omega_to_rpm(w) * (1.0 + noise());
            out.push(format!(
                "{t},{esc},,,,0,0,-1,{},{},{},{},0,{rpm},,,,,,0,,",
                at.torque * (1.0 + noise()),
                1e-6 * w * w,
                12.0 * (1.0 + noise()),
                d * at.amps * (1.0 + noise()),
            ));
        }
    }
    out.join("\n") + "\n"
}

/// `motor fit --kq`: a type 2 motor whose torque constant is its own, found from a stand log
/// of it within the stated intervals, written as a type 2 file propbet reads back.
#[test]
fn a_type_2_fit_finds_the_torque_constant_of_a_generated_log() {
    let t = tempfile::tempdir().unwrap();
    let truth = propbet_api::motor::Motor::from_params(2, &[0.12, 0.9, 1400.0, 1540.0, 0.0, 0.0, 0.0, 0.0]).unwrap();
    std::fs::write(t.path().join("log.csv"), generated_log(&truth)).unwrap();
    let o = run(
        &["motor", "fit", "--measured", "log.csv", "--kq", "-o", "m.motor"],
        t.path(),
    );
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{e}");
    let text = std::fs::read_to_string(t.path().join("m.motor")).unwrap();
    // The comment line: "R  = x ± y ohm, Io = x ± y A, Kv = x ± y rpm/V (...), Kq = x ± y rpm/V".
    let value = |name: &str| -> (f64, f64) {
        let rest = text
            .split(&format!("{name} = "))
            .nth(1)
            .unwrap_or_else(|| panic!("{name}: {text}"));
        let mut w = rest.split_whitespace();
        let v: f64 = w.next().unwrap().parse().unwrap();
        assert_eq!(w.next(), Some("±"));
        let pm: f64 = w.next().unwrap().trim_end_matches(',').parse().unwrap();
        (v, pm)
    };
    for (name, truth) in [("R ", 0.12), ("Io", 0.9), ("Kv", 1400.0), ("Kq", 1540.0)] {
        let (v, pm) = value(name);
        assert!((v - truth).abs() <= pm, "{name}: {v} ± {pm}, truth {truth}\n{text}");
    }
    // Kq told apart from Kv: its interval narrow, not overlapping Kv's value.
    let (kq, kq_pm) = value("Kq");
    assert!(kq_pm < 0.03 * kq && (kq - 1400.0).abs() > kq_pm, "{kq} ± {kq_pm}");
    // A type 2 motor file: QPROP's eight parameters, read back by propbet.
    let o = run(
        &[
            "predict",
            "--prop",
            super::cam6x3().to_str().unwrap(),
            "--motor",
            "m.motor",
            "--volts",
            "8",
        ],
        t.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(text.lines().any(|l| l.trim_start().starts_with('2')), "{text}");
    // Without the ESC command, refused with the reason.
    let no_esc: String = generated_log(&truth)
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == 0 {
                l.to_string()
            } else {
                let mut c: Vec<&str> = l.split(',').collect();
                c[1] = "";
                c.join(",")
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(t.path().join("no_esc.csv"), no_esc).unwrap();
    let o = run(&["motor", "fit", "--measured", "no_esc.csv", "--kq"], t.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("a fit of Kq needs the ESC command"),
        "{}",
        stderr(&o)
    );
}

/// `compare --motor` on a log the chain itself made (`predict --motor` at throttles on a
/// battery without resistance, through an ideal ESC, written as a RCbenchmark log): the speed
/// at the log's throttle, the current and the motor's efficiency come back as logged.
#[test]
fn compare_with_a_motor_gives_back_the_speed_at_the_throttle_of_a_log_the_chain_made() {
    let t = tempfile::tempdir().unwrap();
    let prop = super::cam6x3();
    let motor = repo().join("props/motors/s400-6v-dd.motor");
    let (prop, motor) = (prop.to_str().unwrap(), motor.to_str().unwrap());
    let o = run(
        &[
            "predict",
            "--prop",
            prop,
            "--motor",
            motor,
            "--battery",
            "2S,R=0",
            "--esc-ohms",
            "0",
            "--throttle",
            "0.5:1:0.1",
            "-o",
            "chain.csv",
        ],
        t.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let (h, rows) = read_csv(&t.path().join("chain.csv"));
    let at = |r: &Vec<String>, c: &str| -> f64 { r[h.iter().position(|x| x == c).unwrap()].parse().unwrap() };
    let mut log = vec![
        "Time (s),ESC signal (µs),Torque (N·m),Thrust (N),Voltage (V),Current (A),Motor Optical Speed (RPM)"
            .to_string(),
    ];
    let mut time = 0.0;
    for r in &rows {
        for _ in 0..20 {
            time += 0.1;
            log.push(format!(
                "{time},{},{},{},{},{},{}",
                1000.0 + 1000.0 * at(r, "throttle"),
                at(r, "torque_nm"),
                at(r, "thrust_n"),
                at(r, "battery_volts"),
                at(r, "battery_amps"),
                at(r, "rpm")
            ));
        }
    }
    std::fs::write(t.path().join("log.csv"), log.join("\n") + "\n").unwrap();
    let o = run(
        &[
            "compare",
            "--prop",
            prop,
            "--measured",
            "log.csv",
            "--motor",
            motor,
            "-o",
            "cmp",
        ],
        t.path(),
    );
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    let (eh, erows) = read_csv(&t.path().join("cmp/electric.csv"));
    assert_eq!(erows.len(), rows.len(), "{eh:?}");
    let col = |r: &Vec<String>, c: &str| -> f64 { r[eh.iter().position(|x| x == c).unwrap()].parse().unwrap() };
    for r in &erows {
        let (rpm, back) = (col(r, "rpm"), col(r, "rpm_at_volts"));
        assert!(
            (back / rpm - 1.0).abs() < 2e-3,
            "{rpm} rpm logged, {back} at the ESC's voltage"
        );
        assert!((col(r, "amps_predicted") / col(r, "amps") - 1.0).abs() < 2e-3);
        assert!((col(r, "eta_motor_predicted") / col(r, "eta_motor") - 1.0).abs() < 2e-3);
    }
    let summary = std::fs::read_to_string(t.path().join("cmp/summary.json")).unwrap();
    let summary: serde_json::Value = serde_json::from_str(&summary).unwrap();
    let rpm_error = summary["electric"]["rpm_at_throttle_median_error"].as_f64().unwrap();
    assert!(rpm_error.abs() < 2e-3, "{rpm_error}");
    let html = std::fs::read_to_string(t.path().join("cmp/report.html")).unwrap();
    assert!(html.contains("speed at the log's throttle"));
}
