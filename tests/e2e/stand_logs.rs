//! Every kind of real thrust-stand log `compare` must take, each written here byte by byte:
//! sparse rows, a spreadsheet's Latin-1 CR-only re-save, trimmed and `;` exports, a polar run
//! that windmills, idle rows, a batch with a bad file, a log that cannot be a propeller's, and
//! Tyto's Flight Stand and database tables.

use std::path::Path;

use super::{read_csv, repo, run, stderr};

/// The shipped 10x4.7 Slow Flyer: the loads below are of its size.
fn prop() -> String {
    repo()
        .join("props/apcsf_10x4.7/apcsf_10x4.7.qprop")
        .display()
        .to_string()
}

/// A propeller of that size: thrust [N] and torque [N m] at `rpm`.
fn loads(rpm: f64) -> (f64, f64) {
    (1.46e-7 * rpm * rpm, 2.5e-9 * rpm * rpm)
}

/// RCbenchmark's full header (Series 1580, thrust in gf).
const HEADER: &str = "Time (s),ESC signal (µs),Servo 1 (µs),Servo 2 (µs),Servo 3 (µs),AccX (g),AccY (g),AccZ (g),\
Torque (N·m),Thrust (gf),Voltage (V),Current (A),Motor Electrical Speed (RPM),Motor Optical Speed (RPM),\
Electrical Power (W),Mechanical Power (W),Motor Efficiency (%),Propeller Mech. Efficiency (gf/W),\
Overall Efficiency (gf/W),Vibration (g),App message,";

/// A step test as the app writes it: `steps` RPMs held `per` rows each (a 0 rpm step first),
/// thrust logged negative and torque positive; `loads_every`: the load cells written on one row
/// in that many (the others empty, as a sparse log), `esc`: the ESC column written or empty.
fn step_log(steps: &[f64], per: usize, loads_every: usize, esc: bool) -> (String, usize) {
    let mut rows = vec![HEADER.to_string()];
    let mut spinning = 0;
    let mut t = 0.0;
    for (k, &rpm) in std::iter::once(&0.0).chain(steps).enumerate() {
        for i in 0..per {
            t += 0.025;
            let r = if rpm > 0.0 {
                rpm * (1.0 + 0.002 * ((7 * i) as f64).sin())
            } else {
                0.0
            };
            spinning += usize::from(r > 0.0);
            let (thrust, torque) = loads(r);
            let logged = i % loads_every == 0;
            let cell = |v: String| if logged { v } else { String::new() };
            let esc = if esc {
                format!("{}", 1000 + 100 * k)
            } else {
                String::new()
            };
            rows.push(format!(
                "{t:.3},{esc},,,,,,,{},{},12.1,3.2,{r:.0},0,,,,,,,,",
                cell(format!("{torque:.6}")),
                cell(format!("{:.4}", -thrust / 9.80665e-3)),
            ));
        }
    }
    (rows.join("\n") + "\n", spinning)
}

fn compare(files: &[&Path], dir: &Path) -> std::process::Output {
    let p = prop();
    let mut args = vec!["compare", "--prop", p.as_str(), "--out", "out", "--measured"];
    args.extend(files.iter().map(|f| f.to_str().unwrap()));
    run(&args, dir)
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap()).unwrap()
}

/// points.csv's rows as maps of column to cell.
fn points(dir: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let (h, rows) = read_csv(&dir.join("out/points.csv"));
    rows.into_iter().map(|r| h.iter().cloned().zip(r).collect()).collect()
}

fn num(row: &std::collections::HashMap<String, String>, c: &str) -> f64 {
    row[c].parse().unwrap_or_else(|_| panic!("{c} = {:?}", row[c]))
}

/// Class 1: thrust and torque on one row in ten, RPM on every row, the ESC column empty
/// throughout: every spinning row is used, each point's loads the mean of the readings in it.
#[test]
fn sparse_rows_take_each_sensors_latest_reading() {
    let dir = tempfile::tempdir().unwrap();
    // Without an ESC column the rows are binned by RPM (200 rpm bins here): one bin per step.
    let (text, spinning) = step_log(&[3000.0, 4400.0, 6000.0, 7600.0], 120, 10, false);
    let f = dir.path().join("sparse.csv");
    std::fs::write(&f, text).unwrap();
    let o = compare(&[&f], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let pts = points(dir.path());
    assert_eq!(pts.len(), 4, "{pts:?}");
    let used: f64 = pts.iter().map(|p| num(p, "samples_rpm")).sum();
    assert!(
        used >= 0.95 * spinning as f64,
        "{used} of {spinning} spinning rows used"
    );
    for p in &pts {
        assert_eq!(num(p, "samples_thrust"), 12.0, "one reading in ten of 120 rows");
        let (t, _) = loads(num(p, "rpm"));
        assert!((num(p, "thrust_n") / t - 1.0).abs() < 0.01, "{p:?}");
    }
    let s = summary(dir.path());
    assert_eq!(s["clean"], true, "{s}");
}

/// Class 2: a spreadsheet's re-save: no BOM, `µ` as the byte 0xB5, CR-only line ends, no
/// trailing comma; read as the UTF-8 file is, with the same line numbers.
#[test]
fn a_latin1_cr_only_resave_reads_with_true_line_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let (text, _) = step_log(&[3000.0, 5000.0, 7000.0], 60, 1, true);
    let utf8 = dir.path().join("utf8.csv");
    std::fs::write(&utf8, &text).unwrap();
    let resaved: Vec<u8> = text
        .lines()
        .map(|l| l.trim_end_matches(','))
        .collect::<Vec<_>>()
        .join("\r")
        .chars()
        .map(|c| u8::try_from(u32::from(c)).expect("Latin-1"))
        .collect();
    assert_eq!(resaved[21], 0xB5, "the byte of the issue");
    let latin = dir.path().join("resaved.csv");
    std::fs::write(&latin, resaved).unwrap();
    let o = compare(&[&utf8], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let a = points(dir.path());
    let o = compare(&[&latin], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let b = points(dir.path());
    let key = |p: &std::collections::HashMap<String, String>| {
        (p["line_first"].clone(), p["line_last"].clone(), p["thrust_n"].clone())
    };
    assert_eq!(
        a.iter().map(key).collect::<Vec<_>>(),
        b.iter().map(key).collect::<Vec<_>>()
    );
    assert_eq!(a[0]["line_first"], "62", "the header and 60 rows at 0 rpm before it");
    let md = std::fs::read_to_string(dir.path().join("out/summary.md")).unwrap();
    assert!(md.contains("not UTF-8 (byte 21 is 0xB5): read as Windows-1252"), "{md}");
}

/// Class 3: a header without Time and the optical column reads; the same as `;` with
/// decimal commas and CRLF gives the same points.
#[test]
fn trimmed_and_semicolon_exports_read_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let mut comma = String::from("ESC signal (µs),Torque (N·m),Thrust (gf),Motor Electrical Speed (RPM)\n");
    for (k, rpm) in [3000.0, 4500.0, 6000.0, 7500.0].iter().enumerate() {
        for i in 0..30 {
            let r = rpm * (1.0 + 0.002 * ((3 * i) as f64).sin());
            let (t, q) = loads(r);
            comma.push_str(&format!("{},{q:.6},{:.4},{r:.0}\n", 1100 + 100 * k, t / 9.80665e-3));
        }
    }
    let semi = comma.replace(',', ";").replace('.', ",").replace('\n', "\r\n");
    let (a, b) = (dir.path().join("trimmed.csv"), dir.path().join("semi.csv"));
    std::fs::write(&a, &comma).unwrap();
    std::fs::write(&b, &semi).unwrap();
    let o = compare(&[&a], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let pa = points(dir.path());
    let o = compare(&[&b], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let pb = points(dir.path());
    assert_eq!(pa.len(), 4);
    for (x, y) in pa.iter().zip(&pb) {
        assert_eq!(
            (&x["rpm"], &x["thrust_n"], &x["line_first"]),
            (&y["rpm"], &y["thrust_n"], &y["line_first"])
        );
    }
}

/// Class 4: a stand that logs pull positive, a polar run whose low-RPM rows windmill (negative
/// thrust): nothing flipped, the pull rows kept positive, the windmilling rows kept negative and
/// flagged, not scored, not faults.
#[test]
fn signs_follow_physics_and_windmilling_stays_negative() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::from("Time (s),ESC signal (µs),Torque (N·m),Thrust (N),Motor Optical Speed (RPM)\n");
    let mut t = 0.0;
    // 40 windmilling rows at 1,000-1,800 rpm, then 3 pulling steps: most rows negative.
    for (esc, rpm, thrust) in [(1050, 1000.0, -0.6), (1100, 1400.0, -0.5), (1150, 1800.0, -0.4)]
        .into_iter()
        .chain([(1600, 5000.0, loads(5000.0).0), (1700, 5600.0, loads(5600.0).0)])
    {
        for i in 0..20 {
            t += 0.05;
            let r = rpm * (1.0 + 0.001 * ((5 * i) as f64).sin());
            text.push_str(&format!("{t:.2},{esc},{:.6},{thrust:.4},{r:.0}\n", loads(r).1));
        }
    }
    let f = dir.path().join("polar.csv");
    std::fs::write(&f, text).unwrap();
    let o = compare(&[&f], dir.path());
    assert_ne!(o.status.code(), Some(2), "{}", stderr(&o));
    let pts = points(dir.path());
    assert_eq!(pts.len(), 5, "{pts:?}");
    for p in &pts {
        let (rpm, thrust) = (num(p, "rpm"), num(p, "thrust_n"));
        if rpm > 4000.0 {
            assert!(thrust > 3.0 && p["scored"] == "1", "the pull kept: {p:?}");
        } else {
            assert!(
                thrust < 0.0 && p["scored"] == "0",
                "windmilling kept negative, not scored: {p:?}"
            );
        }
    }
    let md = std::fs::read_to_string(dir.path().join("out/summary.md")).unwrap();
    assert!(!md.contains("thrust is logged negative"), "nothing flipped: {md}");
    assert!(md.contains("windmilling"), "{md}");
    assert_eq!(summary(dir.path())["problems"]["dropped_rows"], 0);
}

/// Class 5: idle rows (1-2 rpm at -0.01 gf) and a repeated t = 0 row are idle, not faults: exit
/// 0, clean.
#[test]
fn idle_rows_are_not_faults() {
    let dir = tempfile::tempdir().unwrap();
    let (text, _) = step_log(&[4000.0, 6000.0, 8000.0], 40, 1, true);
    // The spinning rows only, the first of them twice (a repeated first time stamp).
    let mut lines: Vec<String> = text.lines().take(1).map(str::to_string).collect();
    lines.extend(text.lines().skip(41).map(str::to_string));
    lines.insert(1, lines[1].clone());
    for l in lines.iter_mut().skip(3).take(5) {
        let mut c: Vec<String> = l.split(',').map(str::to_string).collect();
        c[12] = "2".into();
        c[9] = "-0.01".into();
        *l = c.join(",");
    }
    let f = dir.path().join("idle.csv");
    std::fs::write(&f, lines.join("\n") + "\n").unwrap();
    let o = compare(&[&f], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = summary(dir.path());
    assert_eq!(
        (&s["clean"], &s["problems"]["dropped_rows"]),
        (&true.into(), &0.into()),
        "{s}"
    );
    let md = std::fs::read_to_string(dir.path().join("out/summary.md")).unwrap();
    assert!(md.contains("idle"), "{md}");
}

/// Class 6 and 7: one bad file in a batch is refused and named, the others read and reported;
/// exit 1, and summary.json carries the refusal and `clean: false`.
#[test]
fn a_batch_goes_on_past_a_bad_file() {
    let dir = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    for (k, steps) in [[3000.0, 5000.0, 7000.0], [3500.0, 5500.0, 7500.0]].iter().enumerate() {
        let f = dir.path().join(format!("good{k}.csv"));
        std::fs::write(&f, step_log(steps, 30, 1, true).0).unwrap();
        files.push(f);
    }
    let (text, _) = step_log(&[3000.0], 30, 1, true);
    let zero: Vec<String> = text
        .lines()
        .map(|l| {
            let mut c: Vec<&str> = l.split(',').collect();
            if !l.starts_with("Time") {
                c[12] = "0";
            }
            c.join(",")
        })
        .collect();
    let bad = dir.path().join("zero_rpm.csv");
    std::fs::write(&bad, zero.join("\n")).unwrap();
    files.insert(1, bad);
    let refs: Vec<&Path> = files.iter().map(|p| p.as_path()).collect();
    let o = compare(&refs, dir.path());
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("zero_rpm.csv: not read:") && err.contains("good1.csv: 120 rows"),
        "{err}"
    );
    let s = summary(dir.path());
    assert_eq!(s["clean"], false);
    assert!(s["warnings"][0].as_str().unwrap().contains("zero_rpm.csv"), "{s}");
    assert_eq!(points(dir.path()).len(), 6);
    let html = std::fs::read_to_string(dir.path().join("out/report.html")).unwrap();
    assert!(html.contains("<b>refused</b>"), "the batch table names it");
    // The batch table, in the page and in Markdown: the files read first with their counts,
    // the refused one after them with why.
    let row = |f: &str| {
        html.lines()
            .find(|l| l.starts_with(&format!("<tr><td><code>{f}")))
            .unwrap_or("")
    };
    assert!(
        row(&files[0].display().to_string())
            .ends_with("<td>RcBenchmark</td><td>120</td><td>3</td><td>0 / 30</td><td>read</td></tr>"),
        "{}",
        row(&files[0].display().to_string())
    );
    let md = std::fs::read_to_string(dir.path().join("out/summary.md")).unwrap();
    let bad_row = format!("| `{}` | | | 0 | | refused: ", files[1].display());
    assert!(md.contains(&bad_row), "{md}");
    assert!(md.find("good1.csv` | RcBenchmark | 120 | 3 |").unwrap() < md.find(&bad_row).unwrap());
}

/// Class 7 and 8: a log whose thrust does not rise with RPM is read, warned about with its
/// lines, exit 1; summary.json carries the warning and is not clean.
#[test]
fn a_log_that_cannot_be_a_propeller_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::from("Time (s),ESC signal (µs),Thrust (N),Motor Optical Speed (RPM)\n");
    for (k, rpm) in [467.0, 1200.0, 2000.0, 3000.0, 4044.0].iter().enumerate() {
        for i in 0..10 {
            let t = 0.12 + 0.03 * k as f64;
            text.push_str(&format!(
                "{:.1},{},{t:.3},{rpm}\n",
                (10 * k + i) as f64 * 0.1,
                1100 + 100 * k
            ));
        }
    }
    let f = dir.path().join("flat.csv");
    std::fs::write(&f, text).unwrap();
    let o = compare(&[&f], dir.path());
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("thrust does not rise with RPM") && err.contains("lines 2-11"),
        "{err}"
    );
    let s = summary(dir.path());
    assert_eq!(s["clean"], false);
    assert!(
        s["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|w| w.as_str().unwrap().contains("does not rise")),
        "{s}"
    );
}

/// Class 8 of the work: Tyto's Flight Stand (two powertrains, each its own series) and database
/// tables read by name, the loads in kgf converted, the stand's negative thrust oriented.
#[test]
fn flight_stand_and_tyto_database_files_read() {
    let dir = tempfile::tempdir().unwrap();
    let data = repo().join("tests/data/thrust_stand");
    let fs = data.join("flight_stand_two_powertrains.csv");
    let db = data.join("tyto_database.csv");
    let o = compare(&[&fs, &db], dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let pts = points(dir.path());
    let of = |s: &str| pts.iter().filter(|p| p["file"].ends_with(s)).count();
    assert_eq!(
        (of("[Powertrain 1]"), of("[Powertrain 2]"), of("tyto_database.csv")),
        (8, 8, 10)
    );
    for p in &pts {
        let (t, _) = loads(num(p, "rpm"));
        assert!((num(p, "thrust_n") / t - 1.0).abs() < 0.01, "{p:?}");
    }
    let sparse = pts.iter().find(|p| p["file"].ends_with("[Powertrain 2]")).unwrap();
    assert!(
        num(sparse, "samples_thrust") * 3.0 < num(sparse, "samples_rpm"),
        "{sparse:?}"
    );
}

#[test]
fn a_logs_zero_at_rest_is_taken_off_before_the_motor_is_fitted() {
    // The Series 1780 script log's current sensor reads -1.24 A with the propeller at rest:
    // taken as the motor's, every Kv gives a negative no-load current. Its zero taken off, the
    // maker's-Kv fit holds a motor (a Kv of the right size for its 4,500 rpm at 30 V).
    let dir = tempfile::tempdir().unwrap();
    let log = super::repo().join("../shared/data/thrust_stand/series1780_script_columns.csv");
    for kv in ["150", "250", "400"] {
        let o = run(
            &[
                "motor",
                "fit",
                "--measured",
                log.to_str().unwrap(),
                "--kv",
                kv,
                "-o",
                "m.motor",
            ],
            dir.path(),
        );
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(0), "Kv {kv}: {e}");
        assert!(e.contains("at rest (") && e.contains("the current -1.236 A"), "{e}");
        let io: f64 = e
            .split("Io = ")
            .nth(1)
            .and_then(|t| t.split(' ').next())
            .and_then(|t| t.parse().ok())
            .unwrap_or_else(|| panic!("{e}"));
        assert!((0.1..=5.0).contains(&io), "Kv {kv}: Io = {io} A");
    }
}
