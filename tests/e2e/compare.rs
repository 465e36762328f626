//! `propbet compare` end to end: the photogrammetry study's case, every thrust-stand log, UIUC
//! data, bad input, and the HTML report in a real browser (headless Chromium).

use std::path::{Path, PathBuf};

use super::{cam6x3, repo, run, stderr};

fn photofoil() -> (PathBuf, PathBuf) {
    let d = repo().join("props/photofoil_8x4.5");
    (d.join("QProp_8x4_5.txt"), d.join("StepsTestV2_2022-01-18_153833.csv"))
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Relative errors of thrust and torque at the point nearest `rpm`.
fn errors_at(metrics: &serde_json::Value, rpm: f64) -> (f64, f64) {
    let p = metrics["points"]
        .as_array()
        .unwrap()
        .iter()
        .min_by(|a, b| {
            let d = |p: &serde_json::Value| (p["rpm"].as_f64().unwrap() - rpm).abs();
            d(a).total_cmp(&d(b))
        })
        .unwrap();
    let rel = |q: &str| {
        let m = p["measured"][q].as_f64().unwrap();
        (p["predicted"][q].as_f64().unwrap() - m) / m
    };
    (rel("thrust"), rel("torque"))
}

fn compare(extra: &[&str], measured: &[&Path], prop: &Path, dir: &Path) -> std::process::Output {
    let mut args = vec![
        "compare",
        "--prop",
        prop.to_str().unwrap(),
        "--out",
        "out",
        "--measured",
    ];
    args.extend(measured.iter().map(|p| p.to_str().unwrap()));
    args.extend_from_slice(extra);
    run(&args, dir)
}

#[test]
fn photofoil_study_is_reproduced_then_corrected() {
    // Published (Tang & Chung): thrust about +18 %, torque about -27 % at 12,000 rpm, with R = 4
    // on line 2 read as QPROP does and rho = 1.225.
    let (prop, steps) = photofoil();
    let dir = tempfile::tempdir().unwrap();
    let o = compare(&["--qprop-compat", "--rho", "1.225"], &[&steps], &prop, dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let (t, q) = errors_at(&json(&dir.path().join("out/metrics.json")), 12000.0);
    assert!((0.16..0.20).contains(&t), "thrust error {t}");
    assert!((-0.29..-0.25).contains(&q), "torque error {q}");

    // R read as 4 inches (tip loss on) and the study's own rho = 1.1648.
    let o = compare(&["--rho", "1.1648"], &[&steps], &prop, dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let (t2, q2) = errors_at(&json(&dir.path().join("out/metrics.json")), 12000.0);
    assert!(
        t2 < t - 0.05 && t2 > 0.0,
        "thrust error {t2} after the correction (was {t})"
    );
    assert!(q2 > q && q2 < -0.15, "torque error {q2} (was {q})");
}

#[test]
fn every_thrust_stand_log_loads() {
    let dir = tempfile::tempdir().unwrap();
    let logs = repo().join("tests/data/thrust_stand");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&logs)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "csv"))
        .collect();
    files.sort();
    assert_eq!(files.len(), 8);
    for f in &files {
        let o = compare(&[], &[f], &cam6x3(), dir.path());
        // 0, or 1 when faulty rows were dropped (they are listed); never an error.
        assert!(
            matches!(o.status.code(), Some(0 | 1)),
            "{}: {}",
            f.display(),
            stderr(&o)
        );
        let m = json(&dir.path().join("out/metrics.json"));
        let overall = &m["metrics"]["overall"]["metrics"];
        let points = m["points"].as_array().unwrap();
        assert!(!points.is_empty(), "{}", f.display());
        if overall.get("thrust").is_none() {
            // Series 1780 log: its optical RPM drops out during every step; the points are
            // shown, flagged, and not scored, and the run says so.
            assert!(points.iter().all(|p| !p["flags"].as_array().unwrap().is_empty()));
            assert!(String::from_utf8_lossy(&o.stdout).contains("no point could be scored"));
            continue;
        }
        let no_torque = f.file_name().unwrap().to_string_lossy().contains("no_torque");
        assert_eq!(overall.get("torque").is_none(), no_torque, "{}", f.display());
        // A negative thrust is kept only as a flagged (windmilling) point, never scored.
        for p in points.iter().filter(|p| p["measured"]["ct"].as_f64().unwrap() <= 0.0) {
            let flags = p["flags"].to_string();
            assert!(flags.contains("windmilling"), "{}: {p}", f.display());
        }
        // cam6x3 is not every log's prop: a log of another size is warned about (exit 1).
        if o.status.code() == Some(1) && !stderr(&o).contains("do not overlap the propeller's operating range") {
            assert!(stderr(&o).contains("dropped as faulty"), "{}", stderr(&o));
            let faults = m["files"][0]["dropped"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|d| d["reason"] != "not_spinning")
                .count();
            assert!(faults > 0);
        }
    }
}

#[test]
fn uiuc_static_and_sweeps_give_a_report() {
    let dir = tempfile::tempdir().unwrap();
    let case = repo().join("props/apcsf_10x4.7");
    let uiuc = case.join("uiuc");
    let files: Vec<PathBuf> = [
        "apcsf_10x4.7_static_kt0835.txt",
        "apcsf_10x4.7_kt0836_4014.txt",
        "apcsf_10x4.7_rd0839_6023.txt",
    ]
    .iter()
    .map(|f| uiuc.join(f))
    .collect();
    let refs: Vec<&Path> = files.iter().map(PathBuf::as_path).collect();
    let o = compare(
        &["--atmosphere", "20,101325,40"],
        &refs,
        &case.join("apcsf_10x4.7.qprop"),
        dir.path(),
    );
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    let out = dir.path().join("out");
    for f in [
        "report.html",
        "metrics.json",
        "summary.md",
        "points.csv",
        "plots/coefficients.svg",
        "plots/coefficients.png",
        "plots/static.svg",
        "plots/residuals.png",
    ] {
        assert!(out.join(f).metadata().unwrap().len() > 1000, "{f}");
    }
    let m = json(&out.join("metrics.json"));
    let per_rpm: Vec<&str> = m["metrics"]["per_rpm"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g["name"].as_str().unwrap())
        .collect();
    assert!(
        per_rpm.contains(&"4014 rpm") && per_rpm.contains(&"6023 rpm"),
        "{per_rpm:?}"
    );
    assert!(m["metrics"]["static_points"]["points"].as_u64().unwrap() >= 10);
    assert!(m["metrics"]["forward"]["metrics"]["eta"]["n"].as_u64().unwrap() > 10);
    // 20 °C, 101 325 Pa, 40 %: e_s = 2339 Pa (Buck), p_v = 935.6 Pa,
    // rho = (101325 - 935.6)/(287.058 * 293.15) + 935.6/(461.495 * 293.15) = 1.1999 kg/m^3.
    let rho = m["points"][0]["air"]["fluid"]["rho"].as_f64().unwrap();
    assert!((rho - 1.1999).abs() < 2e-4, "rho {rho}");
    // The headline is validate's window, static and forward flight apart; the points near
    // zero thrust are counted out, not scored.
    let headline: Vec<&str> = m["metrics"]["headline"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g["name"].as_str().unwrap())
        .collect();
    assert_eq!(headline.len(), 2, "{headline:?}");
    assert!(headline[0] == "static" && headline[1].starts_with("forward flight, below 85 %"));
    let windowed = m["metrics"]["headline"][1]["points"].as_u64().unwrap();
    let forward = m["metrics"]["forward"]["points"].as_u64().unwrap();
    let outside = m["metrics"]["outside_window"].as_u64().unwrap();
    assert!(
        outside > 0 && windowed + outside == forward,
        "{windowed} + {outside} != {forward}"
    );
    // summary.json: the same headline, the window and the problems, machine-readable.
    let s = json(&out.join("summary.json"));
    assert_eq!(s["format"], "propbet-compare-summary-1");
    assert!(s["command"].as_str().unwrap().starts_with("propbet compare --prop "));
    assert_eq!(s["outside_window"].as_u64().unwrap(), outside);
    assert_eq!(s["headline"][1]["count"].as_u64().unwrap(), windowed);
    assert_eq!(
        s["headline"][0]["errors"]["thrust"]["mean_error"],
        m["metrics"]["headline"][0]["metrics"]["thrust"]["mean_rel"]
    );
    assert!(s["problems"]["dropped_rows"].is_u64() && s["clean"].is_boolean());
    // With speed: the static test's rise (measured +22.7 % from 2377 to 6528 rpm); no zero-thrust
    // J's shift, the 6023 rpm sweep stopping before zero thrust.
    let trends = m["speed_trends"].as_array().unwrap();
    assert_eq!(trends.len(), 1, "{trends:?}");
    assert!(
        trends[0]
            .as_str()
            .unwrap()
            .starts_with("Static CT grows by +22.7 % from 2377 to 6528 rpm"),
        "{trends:?}"
    );
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.contains("<h2>With speed</h2>"));
    // The headline leads: a table of static and forward-flight errors, with the hover metrics.
    assert!(html.contains("<table class=\"headline\">") && html.contains("not in these numbers"));
    assert!(
        html.contains("<tr><td class=\"text\">static</td><td>16</td>"),
        "no static row"
    );
    assert!(
        html.contains("Hover (16 static points): figure of merit measured"),
        "no hover metrics"
    );
    // The long points table folds, saying how many points are flagged.
    assert!(
        html.contains("<details><summary>") && html.contains(" flagged (the reader"),
        "points table"
    );
    assert!(!html.contains("standard air (ISA"));
    assert!(html.matches("<svg").count() >= 3);
    // The uncertainty band, shaded under each (of two) sweep's curve in CT, CP and efficiency and under
    // the static curve in CT and CP, and said in the caption.
    let shaded = html.matches("<polygon opacity=\"0.15\"").count();
    assert!(shaded >= 2 * 3 + 2, "{shaded} shaded bands");
    assert!(html.contains("shaded: the prediction's uncertainty band (every blade angle ±0.5°"));
    assert!(!html.contains("http://") || html.contains("xmlns=\"http://www.w3.org/2000/svg\""));
    assert!(
        !html.contains("https://") && !html.contains("<script"),
        "self-contained, no script"
    );
}

/// Headless Chromium (package `chromium`, installed by scripts/setup.sh) renders the report:
/// a screenshot with the figures drawn, no console error, no network request.
#[test]
#[ignore = "slow: headless Chromium (scripts/test.sh runs it)"]
fn report_renders_in_headless_chromium() {
    let (prop, steps) = photofoil();
    let dir = tempfile::tempdir().unwrap();
    let o = compare(&[], &[&steps], &prop, dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let report = dir.path().join("out/report.html");
    let shot = dir.path().join("shot.png");
    let profile = dir.path().join("chromium-profile");
    let chromium = ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find(|c| {
            std::process::Command::new(c)
                .arg("--version")
                .output()
                .is_ok_and(|o| o.status.success())
        })
        .expect("chromium is installed (scripts/setup.sh installs it)");
    let out = std::process::Command::new(chromium)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--hide-scrollbars",
            "--enable-logging=stderr",
            "--v=0",
            "--window-size=1400,2400",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("--screenshot={}", shot.display()))
        .arg(format!("file://{}", report.display()))
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "chromium failed: {log}");
    for bad in [
        "Uncaught",
        "ERR_FILE_NOT_FOUND",
        "ERR_NAME_NOT_RESOLVED",
        "Failed to load resource",
        ":CONSOLE",
    ] {
        assert!(!log.contains(bad), "browser reported '{bad}': {log}");
    }
    let bytes = std::fs::read(&shot).expect("screenshot written");
    let dec = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut r = dec.read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size().unwrap()];
    let info = r.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (1400, 2400));
    // The page is not blank: headings, tables and the drawn figures put ink on a few percent
    // of the pixels, and the palette's blue (0, 114, 178) of the plotted series is there.
    let px = info.line_size / info.width as usize;
    let pixels: Vec<&[u8]> = buf[..info.buffer_size()].chunks(px).collect();
    let ink = pixels.iter().filter(|p| p[0] < 128 && p[1] < 128 && p[2] < 128).count();
    let blue = pixels
        .iter()
        .filter(|p| p[0] < 40 && (90..140).contains(&p[1]) && (150..210).contains(&p[2]))
        .count();
    assert!(ink > pixels.len() / 100, "only {ink} dark pixels");
    assert!(blue > 200, "only {blue} series-blue pixels");
}

fn bad_log(dir: &Path, name: &str, text: &str) -> (i32, String, PathBuf) {
    let f = dir.join(name);
    std::fs::write(&f, text).unwrap();
    let o = compare(&[], &[&f], &cam6x3(), dir);
    (o.status.code().unwrap(), stderr(&o), f)
}

const HEAD: &str =
    "Time (s),ESC signal (µs),Torque (N·m),Thrust (N),Motor Electrical Speed (RPM),Motor Optical Speed (RPM),\n";

#[test]
fn bad_measured_files_get_clear_messages() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // File-level problems: exit 2, the file and the problem named, nothing written.
    let (code, err, _) = bad_log(
        d,
        "nothrust.csv",
        "Time (s),ESC signal (µs),Torque (N·m),Motor Optical Speed (RPM)\n0,1500,0.01,5000\n",
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("nothrust.csv") && err.contains("no thrust column"),
        "{err}"
    );
    let (code, err, _) = bad_log(
        d,
        "stone.csv",
        "Time (s),ESC signal (µs),Thrust (stone),Motor Optical Speed (RPM)\n0,1500,1,5000\n",
    );
    assert_eq!(code, 2);
    assert!(
        err.contains("stone.csv") && err.contains("unknown unit 'stone'") && err.contains("gf"),
        "{err}"
    );
    let (code, err, _) = bad_log(d, "idle.csv", &format!("{HEAD}0,1000,0,0,0,0,\n1,1000,0,0,0,0,\n"));
    assert_eq!(code, 2);
    assert!(err.contains("idle.csv") && err.contains("zero in every row"), "{err}");
    assert!(!d.join("out/report.html").exists(), "no report from a failed run");
    let (code, err, _) = bad_log(d, "generic.csv", "speed,pull\n5000,1\n");
    assert_eq!(code, 2);
    assert!(err.contains("no rpm column") && err.contains("column map"), "{err}");

    // Row-level problems: the run goes on, exit 1, each dropped row counted and listed.
    let mut log = String::from(HEAD);
    let mut t = 0.0;
    for (k, esc) in [1400, 1600, 1800].iter().enumerate() {
        for i in 0..12 {
            let rpm = 6000.0 + 2000.0 * k as f64 + (i % 3) as f64;
            log.push_str(&format!("{t:.2},{esc},-0.01,{:.4},{rpm},0,\n", 0.5 + k as f64 * 0.3));
            t += 0.1;
        }
    }
    let mut lines: Vec<String> = log.lines().map(String::from).collect();
    lines[3] = lines[3].replace("6002,0", "0,0"); // an RPM dropout: thrust steady, filled
    lines[5] = lines[5].replace(",0.5000,", ",NaN,"); // not a number
    lines[15] = lines[15].replace(",0.8000,", ",-0.8000,"); // negative thrust
    let prev_t = lines[20].split(',').next().unwrap().to_string();
    let rest = lines[21].split_once(',').unwrap().1.to_string();
    lines[21] = format!("{prev_t},{rest}"); // duplicate time
    let (code, err, _) = bad_log(d, "rows.csv", &(lines.join("\n") + "\n"));
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("dropped as faulty"), "{err}");
    let m = json(&d.join("out/metrics.json"));
    let dropped: Vec<(u64, String)> = m["files"][0]["dropped"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| (x["line"].as_u64().unwrap(), x["reason"].as_str().unwrap().to_string()))
        .collect();
    assert_eq!(
        dropped,
        vec![
            (6, "not_a_number".to_string()),
            (16, "negative_thrust".to_string()),
            (22, "duplicate_time".to_string()),
        ]
    );
    let html = std::fs::read_to_string(d.join("out/report.html")).unwrap();
    assert!(html.contains("3 dropped rows"), "dropped rows listed");
    assert!(html.contains("RPM sensor dropouts: 1 rows"), "the filled row is said");
    for text in [
        "not a number",
        "Thrust (N) = 'NaN'",
        "negative thrust",
        "duplicate time",
    ] {
        assert!(html.contains(text), "report lists '{text}'");
    }
    assert_eq!(m["files"][0]["points"].as_array().unwrap().len(), 3);
}

#[test]
fn bad_flags_and_missing_files() {
    let dir = tempfile::tempdir().unwrap();
    let (prop, steps) = photofoil();
    for (args, msg) in [
        (vec!["--atmosphere", "20,101325"], "temperature, pressure and humidity"),
        (vec!["--atmosphere", "20,1013,40"], "outside 10,000..200,000 Pa"),
        (vec!["--poles", "7"], "even number of poles"),
        (vec!["--rho", "-1"], "--rho -1: not a plausible value for air"),
        (
            vec!["--drag-factor=0"],
            "--drag-factor 0: the sections' drag multiplier, a positive number",
        ),
        (
            vec!["--drag-factor", "inf"],
            "--drag-factor inf: the sections' drag multiplier, a positive number",
        ),
        (
            vec!["--rpm-source", "optical"],
            "'Motor Optical Speed (RPM)' is zero in every row",
        ),
    ] {
        let o = compare(&args, &[&steps], &prop, dir.path());
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(stderr(&o).contains(msg), "{args:?}: {}", stderr(&o));
    }
    let o = compare(&[], &[&dir.path().join("nope.csv")], &prop, dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("nope.csv: cannot read"));
}

/// APC's own prediction (`--per3`) is drawn beside propbet's and scored on the same points, the
/// same window and the same measure; a file that is not a PER3 file stops the
/// command before anything is written.
#[test]
fn apc_prediction_is_drawn_and_scored_beside_propbets() {
    let dir = tempfile::tempdir().unwrap();
    let case = repo().join("props/apcsf_10x4.7");
    let files = [
        case.join("uiuc/apcsf_10x4.7_static_kt0835.txt"),
        case.join("uiuc/apcsf_10x4.7_kt0836_4014.txt"),
    ];
    let refs: Vec<&Path> = files.iter().map(PathBuf::as_path).collect();
    let per3 = case.join("PER3_10x47SF.dat");
    let o = compare(
        &["--per3", per3.to_str().unwrap()],
        &refs,
        &case.join("apcsf_10x4.7.qprop"),
        dir.path(),
    );
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    // The terminal gives APC's errors under propbet's, per group.
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        stdout
            .matches("  APC's prediction (PER3_10x47SF.dat): thrust mean error")
            .count(),
        2,
        "{stdout}"
    );
    let out = dir.path().join("out");
    let s = json(&out.join("summary.json"));
    assert!(s["command"].as_str().unwrap().contains("--per3 "));
    let name = s["reference"]["name"].as_str().unwrap();
    assert_eq!(name, "APC's prediction (PER3_10x47SF.dat)");
    // The same groups and counts as propbet's headline; APC's static thrust is its own.
    for g in 0..2 {
        assert_eq!(s["reference"]["headline"][g]["points"], s["headline"][g]["points"]);
        assert_eq!(s["reference"]["headline"][g]["count"], s["headline"][g]["count"]);
    }
    let apc = s["reference"]["headline"][0]["errors"]["thrust"]["mean_error"]
        .as_f64()
        .unwrap();
    let own = s["headline"][0]["errors"]["thrust"]["mean_error"].as_f64().unwrap();
    assert!(apc.is_finite() && (apc - own).abs() > 1e-3, "{apc} {own}");
    // APC's static CT at 4000 rpm, read by hand from the PER3 file's 4000 rpm block (J = 0:
    // Ct 0.1348), against the UIUC static point nearest 4000 rpm (4029 rpm, CT 0.1158): APC is
    // 16 % high there; the scored mean over the 16 static points is of that size.
    assert!(apc > 0.05 && apc < 0.25, "APC static thrust error {apc}");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.contains("dashed: APC's prediction (PER3_10x47SF.dat)"));
    assert!(html.contains("<th>thrust, APC's prediction</th>"));
    // Not a PER3 file: exit 2, the file named, nothing written.
    let bad = dir.path().join("bad.dat");
    std::fs::write(&bad, "this is not APC's table\n").unwrap();
    let o = run(
        &[
            "compare",
            "--prop",
            case.join("apcsf_10x4.7.qprop").to_str().unwrap(),
            "--measured",
            files[0].to_str().unwrap(),
            "--per3",
            bad.to_str().unwrap(),
            "--out",
            "out2",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("bad.dat") && stderr(&o).contains("not an APC PER3 file"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.path().join("out2").exists());
}

/// A QPROP output (`--qprop-output`) is drawn and scored beside propbet's prediction: QPROP's
/// own 8000 rpm sweep of the CAM 6x3 (tests/reference/qprop) against data made by propbet's
/// QPROP-compatible model scores as propbet does, to QPROP's printed digits and the
/// interpolation between its 1 m/s rows.
#[test]
fn a_qprop_output_is_drawn_and_scored_beside_propbets() {
    let dir = tempfile::tempdir().unwrap();
    let prop = cam6x3();
    let o = run(
        &[
            "synth",
            "--prop",
            prop.to_str().unwrap(),
            "--qprop-compat",
            "--noise",
            "1%",
            "--rpm",
            "8000",
            "--j",
            "0:0.4:0.04",
            "--seed",
            "3",
            "--out",
            "data.csv",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let qprop = repo().join("tests/reference/qprop/cam6x3_Vsweep_rpm8000.out");
    let data = dir.path().join("data.csv");
    let o = compare(
        &["--qprop-compat", "--qprop-output", qprop.to_str().unwrap()],
        &[data.as_path()],
        &prop,
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let s = json(&dir.path().join("out/summary.json"));
    assert_eq!(s["reference"]["name"], "QPROP's prediction (cam6x3_Vsweep_rpm8000.out)");
    for g in 0..2 {
        for q in ["thrust", "torque"] {
            let own = s["headline"][g]["errors"][q]["mean_error"].as_f64().unwrap();
            let theirs = s["reference"]["headline"][g]["errors"][q]["mean_error"]
                .as_f64()
                .unwrap();
            assert!((own - theirs).abs() < 0.004, "{g} {q}: propbet {own}, QPROP {theirs}");
            assert_eq!(
                s["reference"]["headline"][g]["errors"][q]["n"],
                s["headline"][g]["errors"][q]["n"]
            );
        }
    }
    // Not a QPROP output, or both references at once: exit 2.
    let bad = dir.path().join("bad.out");
    std::fs::write(&bad, "no header here\n").unwrap();
    for extra in [
        vec!["--qprop-output", bad.to_str().unwrap()],
        vec![
            "--qprop-output",
            qprop.to_str().unwrap(),
            "--per3",
            qprop.to_str().unwrap(),
        ],
    ] {
        let o = compare(&extra, &[data.as_path()], &prop, dir.path());
        assert_eq!(o.status.code(), Some(2), "{extra:?}");
    }
    let o = compare(
        &["--qprop-output", bad.to_str().unwrap()],
        &[data.as_path()],
        &prop,
        dir.path(),
    );
    assert!(
        stderr(&o).contains("bad.out") && stderr(&o).contains("QPROP"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn measurements_of_another_propeller_are_warned_about_first_with_exit_1() {
    // A 6-inch folder's prediction against the Series 1780 log of a far larger prop (about
    // 9 N at 3,470 rpm): measured thrust a median 47 times the prediction.
    let dir = tempfile::tempdir().unwrap();
    let log = repo().join("tests/data/thrust_stand/series1780_log.csv");
    let o = compare(&[], &[&log], &cam6x3(), dir.path());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains(
            "warning: the measurements do not overlap the propeller's operating range: measured thrust is a median"
        ),
        "{e}"
    );
    let html = std::fs::read_to_string(dir.path().join("out/report.html")).unwrap();
    let warn = html.find("do not overlap the propeller's operating range").unwrap();
    assert!(
        warn < html.find("<table").unwrap(),
        "the warning comes before the numbers"
    );
    let md = std::fs::read_to_string(dir.path().join("out/summary.md")).unwrap();
    assert!(md.contains("> the measurements do not overlap"), "{md}");
    // The right prop passes: the PhotoFoil study's log against its own prop file.
    let (prop, steps) = photofoil();
    let o = compare(&["--rho", "1.1648"], &[&steps], &prop, dir.path());
    assert!(!stderr(&o).contains("do not overlap"), "{}", stderr(&o));
}
