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
