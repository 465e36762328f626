//! propbet's motor against the real QPROP 1.22 (built in the tests, `qprop_real::qprop`):
//! every motor file of Drela's runs folder on a prop of his that suits it, over voltages and
//! airspeeds, and the other drivers (RPM, current, thrust) on a type 1 and the type 2 motor;
//! every printed column of QPROP's to its printed digits. And what a bad motor file or an
//! impossible operating point gets.

use std::path::Path;
use std::process::Command;

use propbet_api::qprop::output::{parse_output, Printed, SUMMARY_COLUMNS};

use super::qprop_real::{qprop, qprop_source};
use super::{col, read_csv, run, stderr};

/// QPROP's summary rows for `args` (prop and motor copied into `dir`).
fn qprop_rows(dir: &Path, args: &[&str]) -> Vec<[Printed; 19]> {
    let o = Command::new(qprop()).args(args).current_dir(dir).output().unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    parse_output(&text)
        .unwrap_or_else(|e| panic!("QPROP {args:?}: {e}\n{text}"))
        .summary
}

/// propbet's rows for the same run, as QPROP's 19 columns.
fn propbet_rows(dir: &Path, prop: &str, motor: &str, flags: &[&str]) -> Vec<[f64; 19]> {
    let out = dir.join("powered.csv");
    let mut args = vec![
        "predict",
        "--prop",
        prop,
        "--qprop-compat",
        "--motor",
        motor,
        "-o",
        "powered.csv",
    ];
    args.extend_from_slice(flags);
    let o = run(&args, dir);
    assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
    let (h, rows) = read_csv(&out);
    let num = |r: &Vec<String>, name: &str| -> f64 {
        r[col(&h, name)]
            .parse()
            .unwrap_or_else(|_| panic!("{name}: '{}'", r[col(&h, name)]))
    };
    rows.iter()
        .map(|r| {
            let (v, t) = (num(r, "v_m_s"), num(r, "thrust_n"));
            [
                v,
                num(r, "rpm"),
                0.0,
                t,
                num(r, "torque_nm"),
                num(r, "shaft_power_w"),
                num(r, "volts"),
                num(r, "amps"),
                num(r, "eta_motor"),
                num(r, "eta_prop"),
                num(r, "adv_qprop"),
                num(r, "ct_qprop"),
                num(r, "cp_qprop"),
                num(r, "dv_m_s"),
                num(r, "eta_total"),
                num(r, "electrical_power_w"),
                t * v,
                num(r, "cl_avg"),
                num(r, "cd_avg"),
            ]
        })
        .collect()
}

/// One motor on one prop: QPROP's arguments after the two file names, and propbet's flags for
/// the same points.
struct Case {
    motor: &'static str,
    prop: &'static str,
    qprop: &'static [&'static str],
    propbet: &'static [&'static str],
}

/// A column of QPROP's print that propbet's value does not round to.
struct Mismatch {
    column: &'static str,
    qprop: [Printed; 19],
    propbet: [f64; 19],
    words: String,
}

/// Compares every printed column; returns the mismatches.
fn compare(case: &Case) -> Vec<Mismatch> {
    let work = tempfile::tempdir().unwrap();
    let runs = qprop_source().join("runs");
    for f in [case.motor, case.prop] {
        std::fs::copy(runs.join(f), work.path().join(f)).unwrap();
    }
    std::fs::write(work.path().join("qcon.def"), "1.225\n1.78e-5\n340.0\n").unwrap();
    let mut args = vec![case.prop, case.motor];
    args.extend_from_slice(case.qprop);
    let q = qprop_rows(work.path(), &args);
    let p = propbet_rows(work.path(), case.prop, case.motor, case.propbet);
    assert_eq!(q.len(), p.len(), "{} on {}: row counts", case.motor, case.prop);
    assert!(!q.is_empty());
    let mut wrong = Vec::new();
    for (qr, pr) in q.iter().zip(&p) {
        for (k, (printed, ours)) in qr.iter().zip(pr).enumerate() {
            if !printed.matches(*ours, 1.0) {
                wrong.push(Mismatch {
                    column: SUMMARY_COLUMNS[k],
                    qprop: *qr,
                    propbet: *pr,
                    words: format!(
                        "{} on {} {:?} at V {} rpm {}: {} QPROP {} propbet {ours}",
                        case.motor,
                        case.prop,
                        case.propbet,
                        qr[0].value,
                        qr[1].value,
                        SUMMARY_COLUMNS[k],
                        printed.value
                    ),
                });
            }
        }
    }
    wrong
}

fn words(wrong: &[Mismatch]) -> String {
    wrong.iter().map(|m| m.words.as_str()).collect::<Vec<_>>().join("\n")
}

#[test]
fn every_motor_of_drelas_runs_meets_its_prop_as_qprop_does() {
    // QPROP's argument order: V, RPM, Volt (dBeta, Thrust, Torque, Amps, Pele after it).
    let cases = [
        // QPROP's own example (COMMANDS.txt).
        ("s400-6v-dd", "cam6x3", "6,9,1", "6:9:1"),
        ("s400-7v-dd", "cam6x3", "6,9,1", "6:9:1"),
        ("s300-7v-dd", "cam6x3", "5,8,1", "5:8:1"),
        ("s280-6v-dd", "cam6x3", "4,7,1", "4:7:1"),
        ("s300-7v-5.3", "apc8x6", "6,9,1", "6:9:1"),
        ("s400-6v-4.0", "apc14x10e", "6,9,1", "6:9:1"),
        ("s600-8v-dd", "apc7x4", "6,9,1", "6:9:1"),
        ("s600-10.0", "apc16x10e", "8,11,1", "8:11:1"),
        ("pot30w10v", "cam6x4", "8,11,1", "8:11:1"),
        ("axi2204-54", "apc8x3.8", "7,12,1", "7:12:1"),
        ("axi4130-16", "apc14x10e", "12,18,2", "12:18:2"),
        ("axi4130-20", "apc16x10e", "14,20,2", "14:20:2"),
        ("axi5320-28", "apc18x10e", "18,24,2", "18:24:2"),
    ];
    let mut wrong = Vec::new();
    for (motor, prop, volts_q, volts_p) in cases {
        let qprop = ["0,12/4", "0", volts_q];
        let propbet = ["--volts", volts_p, "--v", "0:12/4"];
        let case = Case {
            motor,
            prop,
            qprop: Box::leak(Box::new(qprop)),
            propbet: Box::leak(Box::new(propbet)),
        };
        wrong.extend(compare(&case));
    }
    assert!(
        wrong.is_empty(),
        "{} columns off QPROP's print:\n{}",
        wrong.len(),
        words(&wrong)
    );
}

/// The current's columns.
const ELECTRIC: [&str; 4] = ["Amps", "effmot", "eff", "Pelec"];

#[test]
fn the_rpm_current_and_thrust_drivers_are_qprops() {
    let mut wrong = Vec::new();
    for motor in ["s400-6v-dd", "s280-6v-dd"] {
        let type_2 = motor == "s280-6v-dd";
        // At a speed: QPROP's VOLTM gives the voltage and current.
        let at_rpm = compare(&Case {
            motor,
            prop: "cam6x3",
            qprop: &["0,10/3", "9000,15000,3000"],
            propbet: &["--rpm", "9000:15000:3000", "--v", "0:10/3"],
        });
        for m in at_rpm {
            // QPROP 1.22's VOLTM returns its first guess of the current, Q Kv + Io0, never
            // updated by its Newton steps: right for type 1, short of type 2's Io1 w + Io2 w^2
            // and Kq. QPROP's print is that guess; propbet's is the model's current.
            let kv = 3800.0 * std::f64::consts::PI * (1.0 / 30.0);
            let guess = m.qprop[4].value * kv + 0.160;
            let print = 0.5 * m.qprop[4].unit * kv + m.qprop[7].unit;
            let defect = type_2 && ELECTRIC.contains(&m.column) && (m.qprop[7].value - guess).abs() <= print;
            if !defect {
                wrong.push(m);
            }
        }
        // QPROP stops its Newton steps at a current or a thrust when the speed has converged;
        // type 2's torque is not linear in the voltage, whose last step is then left out (2e-4
        // of it): the voltage and what follows from it agree to 5e-4.
        let lagging = |m: &Mismatch| {
            let k = SUMMARY_COLUMNS.iter().position(|c| *c == m.column).unwrap();
            let close = (m.propbet[k] / m.qprop[k].value - 1.0).abs() < 5e-4;
            type_2 && (m.column == "Volts" || ELECTRIC.contains(&m.column)) && close
        };
        // At a current: QPROP's Amps driver (the 7th value after the files).
        let at_amps = compare(&Case {
            motor,
            prop: "cam6x3",
            qprop: &["0,10/3", "0", "0", "0", "0", "0", "4,8,2"],
            propbet: &["--amps", "4:8:2", "--v", "0:10/3"],
        });
        wrong.extend(at_amps.into_iter().filter(|m| !lagging(m)));
        // At a thrust: hover (the 5th value; QPROP 1.22 resets the thrust sweep to one point
        // when no torque argument follows it, so a 0 torque is given).
        let at_thrust = compare(&Case {
            motor,
            prop: "cam6x3",
            qprop: &["0", "0", "0", "0", "1.0,2.0,0.5", "0"],
            propbet: &["--thrust", "1:2:0.5"],
        });
        wrong.extend(at_thrust.into_iter().filter(|m| !lagging(m)));
    }
    assert!(
        wrong.is_empty(),
        "{} columns off QPROP's print:\n{}",
        wrong.len(),
        words(&wrong)
    );
}

#[test]
fn a_bad_motor_file_is_refused_by_line_and_value_and_an_impossible_point_is_listed() {
    let dir = tempfile::tempdir().unwrap();
    let prop = super::cam6x3().display().to_string();
    for (text, line, words) in [
        ("Speed-400\n 3\n 0.31\n 0.77\n 2760\n", "line 2", "motor type 3"),
        ("Speed-400\n 1\n -0.31 ! R\n 0.77\n 2760\n", "line 3", "R = -0.31"),
        ("Speed-400\n 1\n 0.31\n 0.77\n 0 ! Kv\n", "line 5", "Kv = 0"),
        ("Speed-400\n 1\n 0.31\n 0.77\n", "line 4", "at least 3"),
        (
            "Speed-400\n 1\n 0.31\n fast\n 2760\n",
            "line 4",
            "'fast' is not a number",
        ),
    ] {
        let motor = dir.path().join("m.motor");
        std::fs::write(&motor, text).unwrap();
        let o = run(
            &[
                "predict",
                "--prop",
                &prop,
                "--motor",
                motor.to_str().unwrap(),
                "--volts",
                "6",
            ],
            dir.path(),
        );
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{e}");
        assert!(
            e.contains("m.motor: ") && e.contains(line) && e.contains(words),
            "{text:?}: {e}"
        );
    }
    // 0.1 V cannot carry the Speed-400's no-load current through its winding; 6 V can. The
    // first point is listed without a solution, the second solved, exit 1.
    let motor = super::repo().join("props/motors/s400-6v-dd.motor");
    let o = run(
        &[
            "predict",
            "--prop",
            &prop,
            "--motor",
            motor.to_str().unwrap(),
            "--volts",
            "0.1,6",
            "-o",
            "p.csv",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("0.1 V cannot carry its no-load current"),
        "{}",
        stderr(&o)
    );
    let (h, rows) = read_csv(&dir.path().join("p.csv"));
    assert_eq!(rows.len(), 2);
    assert!(rows[0][col(&h, "rpm")].is_empty() && rows[0][col(&h, "no_solution")].contains("does not turn"));
    assert_eq!(rows[0][col(&h, "volts")], "0.1");
    let rpm: f64 = rows[1][col(&h, "rpm")].parse().unwrap();
    assert!((11_000.0..11_200.0).contains(&rpm), "{rpm}");
    assert!(rows[1][col(&h, "no_solution")].is_empty());
    // A thrust this propeller cannot give below a tip speed of Mach 1.5.
    let o = run(
        &[
            "predict",
            "--prop",
            &prop,
            "--motor",
            motor.to_str().unwrap(),
            "--thrust",
            "500",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("does not reach 500 N"), "{}", stderr(&o));
}

#[test]
fn on_a_battery_the_throttle_hover_and_endurance_are_consistent() {
    let dir = tempfile::tempdir().unwrap();
    let prop = super::cam6x3().display().to_string();
    let motor = super::repo()
        .join("props/motors/axi2204-54.motor")
        .display()
        .to_string();
    let base = ["predict", "--prop", prop.as_str(), "--motor", motor.as_str()];
    let csv = |flags: &[&str], name: &str| {
        let mut args = base.to_vec();
        args.extend_from_slice(flags);
        args.extend_from_slice(&["-o", name]);
        let o = run(&args, dir.path());
        assert_eq!(o.status.code(), Some(0), "{flags:?}: {}", stderr(&o));
        let (h, rows) = read_csv(&dir.path().join(name));
        move |r: usize, c: &str| -> f64 { rows[r][col(&h, c)].parse().unwrap() }
    };
    // Full throttle on 3S: the motor sees the pack's 11.1 V less the pack's and the ESC's drop.
    let full = csv(&["--battery", "3S,2200mAh", "--throttle", "1"], "full.csv");
    let (amps, volts) = (full(0, "amps"), full(0, "volts"));
    assert!(
        (volts - (11.1 - amps * (3.0 * 0.005 + 0.005))).abs() < 1e-4,
        "{volts} V at {amps} A"
    );
    assert!((full(0, "battery_amps") - amps).abs() < 1e-6);
    // The same motor voltage without the battery gives the same point.
    let same = csv(&["--volts", &format!("{volts}")], "same.csv");
    assert!((same(0, "rpm") / full(0, "rpm") - 1.0).abs() < 1e-5);
    // Hover at half the full-throttle thrust: a throttle below 1, a battery current of the
    // throttle times the motor's, and the endurance of 80 % of 2.2 Ah at that current.
    let half = full(0, "thrust_n") / 2.0;
    let hover = csv(
        &["--battery", "3S,2200mAh", "--thrust", &format!("{half}")],
        "hover.csv",
    );
    let t = hover(0, "throttle");
    assert!(t > 0.3 && t < 1.0, "throttle {t}");
    assert!((hover(0, "battery_amps") - t * hover(0, "amps")).abs() < 1e-5);
    let minutes = 2.2 * 0.8 * 60.0 / hover(0, "battery_amps");
    assert!((hover(0, "endurance_min") / minutes - 1.0).abs() < 1e-5);
    // At that throttle the battery drives the motor back to the same thrust.
    let back = csv(&["--battery", "3S,2200mAh", "--throttle", &format!("{t}")], "back.csv");
    assert!((back(0, "thrust_n") / half - 1.0).abs() < 1e-5);
    // A thrust beyond full throttle is listed, with what it would need; a battery at its
    // cutoff and a throttle above 1 are refused.
    let mut args = base.to_vec();
    args.extend_from_slice(&["--battery", "3S", "--thrust", "30"]);
    let o = run(&args, dir.path());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("% throttle"), "{}", stderr(&o));
    for (flags, words) in [
        (
            &["--battery", "3S,V=3.2", "--throttle", "1"][..],
            "at or below its cutoff",
        ),
        (&["--battery", "3S", "--throttle", "1.5"][..], "--throttle 1.5"),
    ] {
        let mut args = base.to_vec();
        args.extend_from_slice(flags);
        let o = run(&args, dir.path());
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(stderr(&o).contains(words), "{}", stderr(&o));
    }
}

/// `propbet motor fit` on a log: the fitted file, and the held-out median current error the
/// terminal reports [%].
fn fitted(log: &str, extra: &[&str], dir: &Path) -> (String, f64) {
    let log = super::repo().join("../shared/data").join(log).display().to_string();
    let mut args = vec!["motor", "fit", "--measured", log.as_str(), "-o", "fitted.motor"];
    args.extend_from_slice(extra);
    let o = run(&args, dir);
    assert_eq!(o.status.code(), Some(0), "{log}: {}", stderr(&o));
    let e = stderr(&o);
    let held: f64 = e
        .split("predicted: median ")
        .nth(1)
        .and_then(|t| t.split(" %").next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("{e}"));
    (std::fs::read_to_string(dir.join("fitted.motor")).unwrap(), held)
}

#[test]
fn a_motor_fitted_to_real_stand_logs_predicts_their_held_out_currents() {
    let dir = tempfile::tempdir().unwrap();
    // The shared RCbenchmark step logs that carry speed, torque, voltage and current. Kv from
    // the ESC's duty where 3 steps reach half throttle; the maker's where they do not (the
    // PhotoFoil test stops at 1400 µs, the 1585 steps log has 2 above; a number of the right
    // size: the held-out current needs R Kv^2 and Io/Kv only). The Series 1580 logs the ESC's
    // electrical speed: 14 poles.
    let mut medians = Vec::new();
    for (log, extra) in [
        ("thrust_stand/series1585_newton_steps.csv", &["--kv", "2500"][..]),
        ("thrust_stand/series1585_newton_nobom.csv", &[][..]),
        ("photofoil/StepsTestV2_2022-01-18_153833.csv", &["--kv", "1000"][..]),
        (
            "thrust_stand/series1580_gf_steps.csv",
            &["--poles", "14", "--kv", "3000"][..],
        ),
    ] {
        let (text, held) = fitted(log, extra, dir.path());
        assert!(held < 5.0, "{log}: held-out median current error {held} %");
        medians.push(held);
        // The file is a QPROP motor file propbet reads back, its comments say the fit.
        assert!(text.contains("# R  = ") && text.contains("95 % intervals"), "{text}");
        let o = run(
            &[
                "predict",
                "--prop",
                &super::cam6x3().display().to_string(),
                "--motor",
                "fitted.motor",
                "--volts",
                "6",
            ],
            dir.path(),
        );
        assert!(matches!(o.status.code(), Some(0 | 1)), "{log}: {}", stderr(&o));
    }
    eprintln!("held-out median current error per log [%]: {medians:?}");
    // A log without voltage and current, and one whose ESC's duty is not its command's line
    // (its motor's voltage gives a negative R, whatever the speed's scale), are refused with
    // the reason.
    let log = super::repo().join("../shared/data/thrust_stand/series1520_no_torque.csv");
    let o = run(&["motor", "fit", "--measured", log.to_str().unwrap()], dir.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("a motor fit needs at least 4"), "{}", stderr(&o));
    let log = super::repo().join("../shared/data/thrust_stand/series1580_gf_steps.csv");
    let o = run(&["motor", "fit", "--measured", log.to_str().unwrap()], dir.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("the ESC's duty is not (command - 1000 µs) / 1000 µs here; give the maker's Kv"),
        "{}",
        stderr(&o)
    );
    // A log whose two sides disagree (the 1585 without BOM: its speed column a quarter of what
    // its torque constant needs) is fitted for the supply's current and says so.
    let log = super::repo().join("../shared/data/thrust_stand/series1585_newton_nobom.csv");
    let o = run(&["motor", "fit", "--measured", log.to_str().unwrap()], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("from its torque constant") && stderr(&o).contains("they disagree"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn compare_with_a_motor_scores_the_logs_current_and_electrical_power() {
    let dir = tempfile::tempdir().unwrap();
    let log = super::repo().join("props/photofoil_8x4.5/StepsTestV2_2022-01-18_153833.csv");
    let prop = super::repo().join("props/photofoil_8x4.5/QProp_8x4_5.txt");
    let (_, _) = fitted(
        "photofoil/StepsTestV2_2022-01-18_153833.csv",
        &["--kv", "1000"],
        dir.path(),
    );
    let o = run(
        &[
            "compare",
            "--prop",
            prop.to_str().unwrap(),
            "--measured",
            log.to_str().unwrap(),
            "--motor",
            "fitted.motor",
            "-o",
            "cmp",
        ],
        dir.path(),
    );
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(
        out.contains("Supply current on") && out.contains("electrical power"),
        "{out}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("cmp/summary.json")).unwrap()).unwrap();
    let e = &summary["electric"];
    assert_eq!(e["points"], 11, "{e}");
    // The motor fitted to this log gives its current back from the measured torque; from the
    // predicted torque the current is off as the torque is.
    let alone = e["motor_only_current_median_abs_error"].as_f64().unwrap();
    assert!(alone < 0.05, "{e}");
    let current = e["current_median_error"].as_f64().unwrap();
    assert!(
        current.abs() < 0.5 && e["electrical_power_median_error"].as_f64().is_some(),
        "{e}"
    );
    let html = std::fs::read_to_string(dir.path().join("cmp/report.html")).unwrap();
    assert!(html.contains("Electrical: current and power") && html.contains("fig-electric"));
    let (h, rows) = read_csv(&dir.path().join("cmp/electric.csv"));
    assert_eq!(rows.len(), 11);
    assert!(rows
        .iter()
        .all(|r| r[col(&h, "amps_predicted")].parse::<f64>().unwrap() > 0.0));
}

#[test]
fn props_side_by_side_answer_which_prop_for_a_motor() {
    let dir = tempfile::tempdir().unwrap();
    let p = |rel: &str| super::repo().join("props").join(rel).display().to_string();
    let (a, b, c, motor) = (
        p("cam6x3/cam6x3.qprop"),
        p("photofoil_8x4.5/QProp_8x4_5.txt"),
        p("apcsf_10x4.7/apcsf_10x4.7.qprop"),
        p("motors/axi2204-54.motor"),
    );
    let args = [
        "compare-props",
        &a,
        &b,
        &c,
        "--motor",
        &motor,
        "--battery",
        "3S,2200mAh",
        "--hover",
        "2",
        "-o",
        "side",
    ];
    let o = run(&args, dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout).to_string();
    // The three questions: full-throttle thrust, amps at hover, the most grams per watt.
    assert!(
        out.contains("Most grams per watt at hover") && out.contains("Most static thrust at full throttle"),
        "{out}"
    );
    let html = std::fs::read_to_string(dir.path().join("side/report.html")).unwrap();
    assert!(html.contains("Most grams per watt at hover") && html.contains("fig-props"));
    let (h, rows) = read_csv(&dir.path().join("side/props.csv"));
    assert_eq!(rows.len(), 3);
    let g: Vec<f64> = rows
        .iter()
        .map(|r| r[col(&h, "hover_g_per_w")].parse().unwrap())
        .collect();
    assert!(g.windows(2).all(|w| w[0] >= w[1]), "ranked by g/W: {g:?}");
    // Each g/W inside its band, and the answer says whether the first two are told apart.
    for (r, g) in rows.iter().zip(&g) {
        let (lo, hi): (f64, f64) = (
            r[col(&h, "hover_g_per_w_lo")].parse().unwrap(),
            r[col(&h, "hover_g_per_w_hi")].parse().unwrap(),
        );
        assert!(lo < *g && *g < hi, "{}: {lo} {g} {hi}", r[1]);
    }
    // Full throttle's static thrust and current inside their ranges over the band (each end's
    // operating point found again).
    for r in &rows {
        for q in ["full_thrust", "full_battery_amps"] {
            let unit = if q == "full_thrust" { "_n" } else { "" };
            let x = |s: &str| -> f64 { r[col(&h, &format!("{q}{s}{unit}"))].parse().unwrap() };
            let (lo, mid, hi) = (x("_lo"), x(""), x("_hi"));
            assert!(lo < mid && mid < hi && hi < 1.5 * lo, "{} {q}: {lo} {mid} {hi}", r[1]);
        }
    }
    assert!(
        out.contains("not told apart") || out.contains("beyond the predictions' uncertainty bands"),
        "{out}"
    );
    assert!(out.contains(&rows[0][col(&h, "prop")]));
    // Each row is what `predict` says for that prop on that motor and battery.
    for r in &rows {
        let prop = [&a, &b, &c]
            .into_iter()
            .find(|x| x.ends_with(&r[col(&h, "prop")]))
            .unwrap();
        let o = run(
            &[
                "predict",
                "--prop",
                prop,
                "--motor",
                &motor,
                "--battery",
                "3S,2200mAh",
                "--thrust",
                "2",
                "-o",
                "h.csv",
            ],
            dir.path(),
        );
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let (ph, prow) = read_csv(&dir.path().join("h.csv"));
        let amps: f64 = prow[0][col(&ph, "battery_amps")].parse().unwrap();
        let side: f64 = r[col(&h, "hover_battery_amps")].parse().unwrap();
        assert!(
            (amps / side - 1.0).abs() < 1e-6,
            "{}: {amps} A, side by side {side} A",
            r[1]
        );
    }
    // A hover no prop of these can give is listed per prop (exit 1); a hover of 0 is refused.
    let mut high = args;
    high[9] = "40";
    let o = run(&high, dir.path());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("Cannot hover"));
    high[9] = "0";
    let o = run(&high, dir.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--hover 0"), "{}", stderr(&o));
}

/// `predict --motor --band`: at each operating point found, the propeller's band as `predict
/// --band` gives it at that RPM and airspeed; empty where there is no operating point.
#[test]
fn a_powered_prediction_carries_the_propellers_band_at_each_operating_point() {
    let dir = tempfile::tempdir().unwrap();
    let p = |rel: &str| super::repo().join("props").join(rel).display().to_string();
    let (prop, motor) = (p("cam6x3/cam6x3.qprop"), p("motors/axi2204-54.motor"));
    let o = run(
        &[
            "predict", "--prop", &prop, "--motor", &motor, "--thrust", "1,500", "--v", "0,4", "--band", "-o", "m.csv",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o)); // 500 N has no operating point
    let (h, rows) = read_csv(&dir.path().join("m.csv"));
    assert_eq!(rows.len(), 4);
    for r in &rows {
        let cell = |name: &str| r[col(&h, name)].clone();
        if !cell("no_solution").is_empty() {
            assert!(cell("ct_lo").is_empty() && cell("eta_hi").is_empty(), "{r:?}");
            continue;
        }
        let num = |name: &str| cell(name).parse::<f64>().unwrap();
        assert!(num("ct_lo") < num("ct") && num("ct") < num("ct_hi"), "{r:?}");
        assert!(num("cp_lo") < num("cp") && num("cp") < num("cp_hi"), "{r:?}");
        // The same band as predict's at this point.
        let o = run(
            &[
                "predict",
                "--prop",
                &prop,
                "--rpm",
                &cell("rpm"),
                "--v",
                &cell("v_m_s"),
                "--band",
                "-o",
                "p.csv",
            ],
            dir.path(),
        );
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let (hp, rp) = read_csv(&dir.path().join("p.csv"));
        for name in ["ct_lo", "ct_hi", "cp_lo", "cp_hi"] {
            let at: f64 = rp[0][col(&hp, name)].parse().unwrap();
            assert!(
                (at / num(name) - 1.0).abs() < 1e-5,
                "{name}: {at} against {}",
                num(name)
            );
        }
    }
}
