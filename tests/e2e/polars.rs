//! `propbet polar` and `propbet polars` with the real XFOIL (and fake ones for faults).

use std::os::unix::fs::PermissionsExt;
use std::path::Path;

use super::{cam6x3, col, read_csv, repo, run, run_or_hang, stderr};

#[test]
#[ignore = "slow: real XFOIL (scripts/test.sh runs it)"]
fn polar_of_naca4412_csv_fit_and_plot() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        &[
            "polar",
            "--airfoil",
            "naca4412",
            "--re",
            "1e5",
            "--alpha",
            "-4:12:0.5",
            "--no-cache",
            "--quiet",
            "--out",
            "p.csv",
            "--plot",
            "p.svg",
            "--fit-out",
            "fit.json",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let (h, rows) = read_csv(&dir.path().join("p.csv"));
    let (a, cl, cd) = (col(&h, "alpha_deg"), col(&h, "cl"), col(&h, "cd"));
    let r4 = rows.iter().find(|r| r[a] == "4").expect("a point at 4 deg");
    let (cl4, cd4): (f64, f64) = (r4[cl].parse().unwrap(), r4[cd].parse().unwrap());
    // Acceptance values (Debian's XFOIL 6.99).
    assert!(
        (cl4 - 0.888).abs() <= 0.01 && (cd4 - 0.0197).abs() <= 0.001,
        "cl {cl4} cd {cd4}"
    );
    let svg = std::fs::read_to_string(dir.path().join("p.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("drag polar"));
    let fits: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.path().join("fit.json")).unwrap()).unwrap();
    let cla = fits[0]["coeffs"]["cl_a"].as_f64().unwrap();
    assert!(cla > 4.5 && cla < 7.5, "CL_a = {cla}");
    assert!(stderr(&o).contains("linear range"), "{}", stderr(&o));
}

#[test]
fn polar_bad_input_gets_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("bad.dat"), "MY FOIL\n1.0 0.0\n0.5 zero.one\n").unwrap();
    let o = run(
        &["polar", "--airfoil", "bad.dat", "--re", "1e5", "--no-cache"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("bad.dat, line 3"), "{}", stderr(&o));

    let o = run(
        &["polar", "--airfoil", "naca2412", "--re", "0", "--no-cache"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("must be positive"), "{}", stderr(&o));

    let o = run(&["polar", "--airfoil", "missing.dat", "--re", "1e5"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("missing.dat"), "{}", stderr(&o));

    let o = run(
        &[
            "polar",
            "--airfoil",
            "naca2412",
            "--re",
            "1e5",
            "--xfoil",
            "/nonexistent/xfoil",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("apt-get install xfoil"), "{}", stderr(&o));

    // Output over the input is refused.
    let foil = repo().join("props/airfoils/clarky.dat");
    let copy = dir.path().join("clarky.dat");
    std::fs::copy(&foil, &copy).unwrap();
    let o = run(
        &[
            "polar",
            "--airfoil",
            "clarky.dat",
            "--re",
            "1e5",
            "--no-cache",
            "--out",
            "clarky.dat",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(std::fs::read(&copy).unwrap(), std::fs::read(&foil).unwrap());
}

/// An `xfoil` in `dir` that dies of SIGFPE at once, as Debian's does without a display.
pub(super) fn crashing_xfoil(dir: &std::path::Path) -> std::path::PathBuf {
    let fake = dir.join("xfoil");
    std::fs::write(
        &fake,
        "#!/bin/sh\necho ' Polar accumulation enabled'\necho 'Program received signal SIGFPE'\nkill -FPE $$\n",
    )
    .unwrap();
    std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    fake
}

#[test]
fn an_xfoil_that_always_crashes_is_an_error_not_a_hang() {
    let dir = tempfile::tempdir().unwrap();
    let fake = crashing_xfoil(dir.path());
    let o = run_or_hang(
        &[
            "polar",
            "--airfoil",
            "naca2412",
            "--re",
            "1e5",
            "--alpha",
            "0:3:1",
            "--no-cache",
            "--quiet",
            "--xfoil",
            fake.to_str().unwrap(),
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("SIGFPE"), "{}", stderr(&o));
}

#[test]
fn a_blade_whose_xfoil_never_converges_names_each_station_and_its_fallback() {
    let dir = tempfile::tempdir().unwrap();
    let fake = crashing_xfoil(dir.path());
    let o = run(
        &[
            "polars",
            "--geometry",
            cam6x3().to_str().unwrap(),
            "--airfoil",
            "naca4412",
            "--rpm",
            "8000",
            "--alpha",
            "0:2:1",
            "--no-cache",
            "--quiet",
            "--xfoil",
            fake.to_str().unwrap(),
            "--out-prop",
            "fit.qprop",
        ],
        dir.path(),
    );
    // The terminal wraps its sentences: read them as one line each.
    let e = stderr(&o).split_whitespace().collect::<Vec<_>>().join(" ");
    assert_eq!(o.status.code(), Some(1), "{e}");
    // Every station says where (r, Re range, angles), what failed and the fallback.
    assert!(
        e.contains("station 1 (r = ") && e.contains(", Re ") && e.contains("alpha "),
        "{e}"
    );
    assert!(
        e.contains("fallback: the tables use the neighbouring stations' polars"),
        "{e}"
    );
    assert!(e.contains("keeps the coefficients of"), "{e}");
    // The prop file is still written, with the geometry's own coefficients.
    assert!(dir.path().join("fit.qprop").is_file());
}

#[test]
#[ignore = "slow: real XFOIL (scripts/test.sh runs it)"]
fn polars_of_a_blade_make_a_prop_file_and_a_tabulated_model() {
    let dir = tempfile::tempdir().unwrap();
    let cam = cam6x3();
    // The same blade twice: once computed, once from the cache.
    let polars = |extra: &[&str]| {
        let mut args = vec![
            "polars",
            "--geometry",
            cam.to_str().unwrap(),
            "--airfoil",
            "naca4412",
            "--rpm",
            "6000,10000",
            "--j",
            "0,0.3",
            "--alpha",
            "-6:12:1",
            "--quiet",
            "--cache",
            "cache",
        ];
        args.extend_from_slice(extra);
        let o = run(&args, dir.path());
        assert!(
            o.status.code() == Some(0) || o.status.code() == Some(1),
            "{}",
            stderr(&o)
        );
        stderr(&o)
    };
    // What the run said (a rung without a polar is reported there, with XFOIL's reason).
    let said = polars(&["--out-prop", "fit.qprop", "--out-polars", "fit.json"]);
    let text = prop_file_and_polars_on_the_ladder(dir.path(), &said);
    section_models_predict(dir.path());
    // The second run comes from the cache, byte for byte (its time is measured in
    // benchsuite/polars_blade.sh, not here).
    polars(&["--out-prop", "fit2.qprop"]);
    assert_eq!(std::fs::read(dir.path().join("fit2.qprop")).unwrap(), text.as_bytes());
}

/// `polars`' prop file (every row its ten coefficients, QPROP's line length) and its polars
/// file (each station's polars on the Reynolds ladder, covering the Re it sees); the prop file.
fn prop_file_and_polars_on_the_ladder(dir: &Path, said: &str) -> String {
    let text = std::fs::read_to_string(dir.join("fit.qprop")).unwrap();
    // Every row carries its own ten coefficients and fits QPROP's 128-character line.
    let rows: Vec<&str> = text
        .lines()
        .filter(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            w.len() == 13 && w.iter().all(|x| x.parse::<f64>().is_ok())
        })
        .collect();
    assert_eq!(rows.len(), 7, "{text}");
    assert!(text.lines().all(|l| l.len() <= 126));
    // Each station's polars cover the Re it sees from 6000 to 10000 rpm, on the ladder.
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("fit.json")).unwrap()).unwrap();
    assert_eq!(json["rpm"], serde_json::json!([6000.0, 10000.0]));
    for st in json["stations"].as_array().unwrap() {
        let range: Vec<f64> = st["re_range"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert!(range[1] > 1.5 * range[0], "{range:?}");
        let res: Vec<f64> = st["polars"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p["re"].as_f64().unwrap())
            .collect();
        assert!(res.len() >= 3, "{res:?}\n{said}");
        let ladder = |re: f64| (5.0 * re.log10() - (5.0 * re.log10()).round()).abs() < 1e-6;
        assert!(res.iter().all(|&re| ladder(re)), "{res:?}");
        assert!(
            res[0] <= range[0] && res[res.len() - 1] >= range[1],
            "{res:?} vs {range:?}"
        );
    }
    text
}

/// Both section models predict from `polars`' outputs; the tabulated one close to the fitted one
/// at the design point; rotational augmentation as asked, and refused when unknown.
fn section_models_predict(dir: &Path) {
    let thrust = |extra: &[&str]| -> f64 {
        let mut args = vec![
            "predict",
            "--prop",
            "fit.qprop",
            "--rpm",
            "8000",
            "--v",
            "0",
            "--out",
            "p.csv",
        ];
        args.extend_from_slice(extra);
        let o = run(&args, dir);
        assert!(o.status.success(), "{}", stderr(&o));
        let (h, r) = read_csv(&dir.join("p.csv"));
        r[0][col(&h, "thrust_n")].parse().unwrap()
    };
    let fitted = thrust(&[]);
    let tabulated = thrust(&["--polars", "fit.json"]);
    assert!(fitted > 0.2 && tabulated > 0.2, "{fitted} {tabulated}");
    assert!(
        (tabulated / fitted - 1.0).abs() < 0.15,
        "fitted {fitted} N, tabulated {tabulated} N"
    );
    // Rotational augmentation (Snel) is the tabulated model's default: it only adds lift
    // where a section lifts less than its attached-flow line, which the inner sections at
    // static thrust do; QPROP's law has none unless asked.
    let off = thrust(&["--polars", "fit.json", "--rotation", "off"]);
    assert_eq!(thrust(&["--polars", "fit.json", "--rotation", "snel"]), tabulated);
    assert!(tabulated > off, "snel {tabulated} N, off {off} N");
    assert!(thrust(&["--rotation", "snel"]) >= fitted);
    let o = run(
        &[
            "predict",
            "--prop",
            "fit.qprop",
            "--rpm",
            "8000",
            "--rotation",
            "du-selig",
        ],
        dir,
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--rotation `du-selig`: expected off or snel"),
        "{}",
        stderr(&o)
    );
}

/// Hidden in synthetic data (1 % noise) at Ncrit 8 with the tables of `fit.json`, the
/// transition effect is found first, with its value.
fn transition_hidden_at_ncrit_8_is_found(dir: &Path) {
    let o = run(
        &[
            "synth",
            "--prop",
            "fit.qprop",
            "--polars",
            "fit.json",
            "--effect",
            "transition:ncrit=8",
            "--rpm",
            "4000:10000/4",
            "--j",
            "0:0.4/9",
            "--noise",
            "1%",
            "--seed",
            "5",
            "--out",
            "hidden.csv",
        ],
        dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = run(
        &[
            "diagnose",
            "--prop",
            "fit.qprop",
            "--polars",
            "fit.json",
            "--measured",
            "hidden.csv",
            "--max-steps",
            "1",
            "--out",
            "d",
        ],
        dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let d: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("d/diagnosis.json")).unwrap()).unwrap();
    let ranking = &d["diagnosis"]["ranking"];
    assert_eq!(ranking[0]["id"], "transition", "{ranking}");
    let ncrit = d["final_params"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["effect"] == "transition")
        .and_then(|p| p["value"].as_f64())
        .unwrap_or_else(|| panic!("{}", d["final_params"]));
    assert!((ncrit - 8.0).abs() < 0.7, "fitted Ncrit {ncrit}");
}

/// Processes whose command line contains all of `words`.
fn processes_with(words: &[&str]) -> Vec<u32> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir("/proc").unwrap().flatten() {
        let Ok(pid) = entry.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let Ok(cmd) = std::fs::read(entry.path().join("cmdline")) else {
            continue;
        };
        let cmd = String::from_utf8_lossy(&cmd).replace('\0', " ");
        if words.iter().all(|w| cmd.contains(w)) {
            found.push(pid);
        }
    }
    found
}

#[test]
#[ignore = "slow: real XFOIL (scripts/test.sh runs it)"]
fn killing_propbet_stops_its_private_x_server() {
    let dir = tempfile::tempdir().unwrap();
    let mut child = super::bin()
        .args([
            "polars",
            "--geometry",
            cam6x3().to_str().unwrap(),
            "--airfoil",
            "naca4412",
            "--rpm",
            "8000",
            "--no-cache",
            "--quiet",
            "--out-prop",
            "k.qprop",
        ])
        .current_dir(dir.path())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let pid = child.id().to_string();
    let start = std::time::Instant::now();
    let watcher = loop {
        let w = processes_with(&["propbet-xvfb", &pid]);
        if !w.is_empty() {
            break w;
        }
        assert!(
            start.elapsed().as_secs() < 120,
            "no private Xvfb appeared in two minutes"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    child.kill().unwrap();
    child.wait().unwrap();
    let start = std::time::Instant::now();
    while watcher
        .iter()
        .any(|p| std::path::Path::new(&format!("/proc/{p}")).exists())
    {
        assert!(
            start.elapsed().as_secs() < 120,
            "the Xvfb watcher outlived propbet by two minutes"
        );
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
}

#[test]
fn a_polar_with_an_xfoil_fault_exits_1() {
    // A fake XFOIL that speaks the dialogue and dies of SIGFPE at 2 deg: the other angles come
    // back, the fault is said, and the exit code is 1 (not 0).
    let dir = tempfile::tempdir().unwrap();
    let fake = xfoil_runner::fake::write_fake_xfoil(
        dir.path(),
        r#"[ "$arg" = "2.000000" ] && { echo 'Program received signal SIGFPE'; kill -FPE $$; }"#,
    )
    .unwrap();
    let o = run(
        &[
            "polar",
            "--airfoil",
            "naca2412",
            "--re",
            "1e5",
            "--alpha",
            "0:4:1",
            "--no-cache",
            "--quiet",
            "--xfoil",
            fake.to_str().unwrap(),
            "--out",
            "p.csv",
        ],
        dir.path(),
    );
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("SIGFPE") || e.contains("crash"), "{e}");
    let text = std::fs::read_to_string(dir.path().join("p.csv")).unwrap();
    assert!(text.lines().count() >= 4, "the converged angles are written: {text}");
}

/// `--trip X/C` forces transition on both surfaces (XFOIL's XTR): on the thin, cambered E63 at
/// Re 63,000 and Ncrit 5 the free upper surface stays laminar and separates near the trailing
/// edge at small angles (cl 0.03 at -2 deg, Debian's XFOIL 6.99), the tripped one keeps its lift
/// (cl 0.34): docs/studies/transition-trip.md. A trip outside (0, 1] is refused.
#[test]
#[ignore = "slow: real XFOIL (scripts/test.sh runs it)"]
fn a_trip_forces_transition_and_keeps_the_lift_at_small_angles() {
    let dir = tempfile::tempdir().unwrap();
    let e63 = repo().join("props/airfoils/e63.dat");
    let cl_at = |extra: &[&str], out: &str| -> f64 {
        let mut args = vec![
            "polar",
            "--airfoil",
            e63.to_str().unwrap(),
            "--re",
            "63000",
            "--ncrit",
            "5",
            "--alpha",
            "-2:0:1",
            "--panels",
            "120",
            "--no-cache",
            "--quiet",
            "--out",
            out,
        ];
        args.extend_from_slice(extra);
        let o = run(&args, dir.path());
        assert!(o.status.success(), "{}", stderr(&o));
        let (h, rows) = read_csv(&dir.path().join(out));
        let r = rows
            .iter()
            .find(|r| r[col(&h, "alpha_deg")] == "-2")
            .expect("a point at -2 deg");
        r[col(&h, "cl")].parse().unwrap()
    };
    let free = cl_at(&[], "free.csv");
    let tripped = cl_at(&["--trip", "0.05"], "trip.csv");
    assert!(free < 0.15 && tripped > free + 0.2, "free {free}, tripped {tripped}");
    let o = run(
        &["polar", "--airfoil", "naca4412", "--re", "1e5", "--trip", "1.5"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--trip 1.5: `free`, or the chord fraction"),
        "{}",
        stderr(&o)
    );
}

/// `--ncrit-effect`: the same rungs at other Ncrit values, the `transition` effect built from
/// them, hidden in synthetic data and found by `diagnose` with its Ncrit; bounds and bad values.
#[test]
#[ignore = "slow: real XFOIL (scripts/test.sh runs it)"]
fn ncrit_tables_make_a_transition_effect_that_diagnose_finds() {
    let dir = tempfile::tempdir().unwrap();
    let cam = cam6x3();
    // `propbet polars` of the CAM 6x3 with NACA 4412 sections and `extra`.
    let polars = |extra: &[&str]| {
        let mut args = vec!["polars", "--geometry", cam.to_str().unwrap(), "--airfoil", "naca4412"];
        args.extend_from_slice(extra);
        run(&args, dir.path())
    };
    let o = polars(&[
        "--rpm",
        "4000,10000",
        "--j",
        "0,0.4",
        "--alpha",
        "-6:12:1",
        "--ncrit-effect",
        "9,2",
        "--quiet",
        "--cache",
        "cache",
        "--out-prop",
        "fit.qprop",
        "--out-polars",
        "fit.json",
    ]);
    assert!(
        o.status.code() == Some(0) || o.status.code() == Some(1),
        "{}",
        stderr(&o)
    );
    // Every station has its own Ncrit's rungs and the same rungs at 2 and 9.
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("fit.json")).unwrap()).unwrap();
    for st in json["stations"].as_array().unwrap() {
        let res = |key: &str, ncrit: f64| -> Vec<f64> {
            st[key]
                .as_array()
                .map(|a| {
                    a.iter()
                        .filter(|p| p["ncrit"].as_f64() == Some(ncrit))
                        .map(|p| p["re"].as_f64().unwrap())
                        .collect()
                })
                .unwrap_or_default()
        };
        let own = res("polars", 5.0);
        assert!(own.len() >= 2, "{}", stderr(&o));
        for n in [2.0, 9.0] {
            let other = res("other_ncrit", n);
            assert!(
                other.len() + 1 >= own.len() && other.iter().all(|re| own.contains(re)),
                "Ncrit {n}: {other:?} against {own:?}\n{}",
                stderr(&o)
            );
        }
    }
    transition_hidden_at_ncrit_8_is_found(dir.path());
    // Beyond the computed tables: refused, naming the bounds; without them: not an effect.
    let predict = |extra: &[&str]| {
        let mut args = vec!["predict", "--prop", "fit.qprop", "--rpm", "6000", "--v", "0"];
        args.extend_from_slice(extra);
        run(&args, dir.path())
    };
    let o = predict(&["--polars", "fit.json", "--effect", "transition:ncrit=12"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("transition:ncrit = 12 is outside its bounds [2, 9]"),
        "{}",
        stderr(&o)
    );
    let o = predict(&["--effect", "transition:ncrit=3"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("unknown effect `transition`"), "{}", stderr(&o));
    // `propbet effects` says where it comes from.
    let o = run(&["effects"], dir.path());
    let listed = String::from_utf8_lossy(&o.stdout);
    assert!(
        listed.contains("transition (section)") && listed.contains("--ncrit-effect"),
        "{listed}"
    );
    // An Ncrit the polars already have, or none XFOIL takes.
    for (bad, says) in [("5", "the polars' own Ncrit"), ("30", "from 0.1 to 20")] {
        let o = polars(&["--rpm", "6000", "--ncrit-effect", bad, "--out-prop", "x.qprop"]);
        assert_eq!(o.status.code(), Some(2), "{bad}");
        assert!(stderr(&o).contains(says), "{bad}: {}", stderr(&o));
        assert!(!dir.path().join("x.qprop").exists());
    }
}
