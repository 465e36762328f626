//! The second reliability campaign's defects (N1-N40 of `../shared/examples/bad_inputs`,
//! reproducers copied to `tests/data/bad_inputs`): each runs with the command the shared
//! README gives and gets what it says propbet must: a clear message naming the file, line or
//! value and exit 2, or exit 1 with the row or point dropped and listed; never a panic, hang,
//! abort, or inf / NaN in an output; nothing overwritten.

use super::*;

fn bad(name: &str) -> String {
    repo().join("tests/data/bad_inputs").join(name).display().to_string()
}

fn path(rel: &str) -> String {
    repo().join(rel).display().to_string()
}

/// Every number of every CSV and JSON file under `dir` is finite.
fn outputs_finite(dir: &Path) {
    if !dir.exists() {
        return;
    }
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            outputs_finite(&p);
        } else if matches!(p.extension().and_then(|x| x.to_str()), Some("csv" | "json" | "md")) {
            let text = std::fs::read_to_string(&p).unwrap();
            for w in text.split(|c: char| !(c.is_alphanumeric() || ".-_".contains(c))) {
                assert!(
                    !matches!(w, "inf" | "-inf" | "NaN" | "nan" | "-nan"),
                    "{}: holds {w}",
                    p.display()
                );
            }
        }
    }
}

/// One row of the campaign's table: the item, the command (`OUT` is replaced by a fresh
/// output folder), the exit code and what stderr must say.
struct Case {
    id: &'static str,
    args: Vec<String>,
    code: i32,
    says: &'static str,
}

fn case(id: &'static str, args: &[&str], code: i32, says: &'static str) -> Case {
    Case {
        id,
        args: args.iter().map(|s| s.to_string()).collect(),
        code,
        says,
    }
}

#[test]
fn each_item_gets_a_clear_message_and_its_exit_code() {
    let h = |f: &str| path(&format!("tests/data/hidden_effects/torque_tare/{f}"));
    let (hq, apc, cam) = (
        h("cam6x3.qprop"),
        path("props/apcsf_10x4.7/apcsf_10x4.7.qprop"),
        path("props/cam6x3/cam6x3.qprop"),
    );
    let cases = vec![
        // N1: a logged pressure of 1e200 is dropped with its value, no panic.
        case(
            "N1",
            &[
                "--threads",
                "1",
                "diagnose",
                "--prop",
                &hq,
                "--measured",
                &bad("diag_pressure_1e200.csv"),
                "-o",
                "OUT",
            ],
            1,
            "1 beyond any small propeller's values (first at line 5)",
        ),
        // N5: a tiny positive RPM.
        case(
            "N5",
            &["predict", "--prop", &cam, "--rpm", "1e-300", "--j", "0,0.3"],
            2,
            "--rpm: 1e-300 is below 1 rpm",
        ),
        case(
            "N5 (run)",
            &["run", &bad("case_sweep_tiny_rpm"), "-o", "OUT"],
            2,
            "4e-297 is below 1 rpm",
        ),
        case(
            "N5 (UIUC)",
            &[
                "compare",
                "--prop",
                &apc,
                "--measured",
                &bad("uiuc_tiny_rpm_static_kt0000.txt"),
                "-o",
                "OUT",
            ],
            1,
            "1 beyond any small propeller's values",
        ),
        // N6 and N30: densities no air has.
        case(
            "N6",
            &[
                "compare",
                "--prop",
                &hq,
                "--measured",
                &h("cam6x3_steps.csv"),
                "--rho",
                "1e-310",
                "-o",
                "OUT",
            ],
            2,
            "--rho 1e-310: not a plausible value for air (0.01-20 kg/m^3)",
        ),
        case(
            "N30",
            &["predict", "--prop", &cam, "--rpm", "4000", "--rho", "1e300"],
            2,
            "--rho 1e300: not a plausible",
        ),
        case(
            "N30 (effect)",
            &[
                "predict",
                "--prop",
                &cam,
                "--rpm",
                "4000",
                "--effect",
                "pitch-offset:deg=1e308",
            ],
            2,
            "pitch-offset:deg = 1e308 is outside its bounds [-3, 3]",
        ),
        // N7: logged air state.
        case(
            "N7 (0 Pa)",
            &[
                "compare",
                "--prop",
                &hq,
                "--measured",
                &bad("stand_pressure_zero.csv"),
                "-o",
                "OUT",
            ],
            2,
            "line 2: air pressure 0 Pa is outside 10000-200000 Pa",
        ),
        case(
            "N7 (hPa)",
            &[
                "compare",
                "--prop",
                &hq,
                "--measured",
                &bad("stand_pressure_in_hpa.csv"),
                "-o",
                "OUT",
            ],
            2,
            "air pressure 1013 Pa is outside 10000-200000 Pa (hPa or kPa logged as Pa?)",
        ),
        case(
            "N7 (-300 C)",
            &[
                "compare",
                "--prop",
                &hq,
                "--measured",
                &bad("stand_temp_minus300C.csv"),
                "-o",
                "OUT",
            ],
            2,
            "air temperature -300 °C is outside",
        ),
        // N8: a sweep of zeros.
        case(
            "N8",
            &[
                "compare",
                "--prop",
                &apc,
                "--measured",
                &bad("uiuc_zero_ct_kt0000_4014.txt"),
                "-o",
                "OUT",
            ],
            2,
            "every one of its 6 points is 0",
        ),
        // N2: one file given twice.
        case(
            "N2",
            &[
                "compare",
                "--prop",
                &hq,
                "--measured",
                &h("cam6x3_steps.csv"),
                &h("cam6x3_steps.csv"),
                "-o",
                "OUT",
            ],
            2,
            "given twice among the measured files",
        ),
        // N15: a short row.
        case(
            "N15",
            &[
                "compare",
                "--prop",
                &hq,
                "--measured",
                &bad("stand_short_row.csv"),
                "-o",
                "OUT",
            ],
            1,
            "1 empty cell (first at line 6)",
        ),
        // N16: one column for three quantities.
        case(
            "N16",
            &[
                "compare",
                "--prop",
                &cam,
                "--measured",
                &bad("colmap_gen.csv"),
                "--columns",
                &bad("colmap_same_column.toml"),
                "-o",
                "OUT",
            ],
            2,
            "rpm, thrust, torque all name column 'Motor speed'",
        ),
        // N17: a load column without its unit.
        case(
            "N17",
            &[
                "compare",
                "--prop",
                &cam,
                "--measured",
                &bad("stand_thrust_no_unit.csv"),
                "-o",
                "OUT",
            ],
            2,
            "column 'Thrust' has no unit",
        ),
        // N12: two stations 0.001 in apart make the spline swing (chord 6 times the largest).
        case(
            "N12",
            &[
                "predict",
                "--prop",
                &bad("prop_close_stations.qprop"),
                "--rpm",
                "8000",
                "--v",
                "5",
            ],
            2,
            "prop_close_stations.qprop: the spline through the stations swings to a chord [m] of",
        ),
        case(
            "N12 (closer)",
            &["prop", &bad("prop_closer_stations.qprop")],
            2,
            "remove one of them or space the stations out",
        ),
        // N9: a PER3 table with a CT of 1e308: those rows left out and said (a warning: the
        // comparison runs, exit 0).
        case(
            "N9",
            &[
                "compare",
                "--prop",
                &apc,
                "--measured",
                &path("props/apcsf_10x4.7/uiuc/apcsf_10x4.7_kt0836_4014.txt"),
                &path("props/apcsf_10x4.7/uiuc/apcsf_10x4.7_static_kt0835.txt"),
                "--per3",
                &bad("per3_ct_1e308.dat"),
                "-o",
                "OUT",
            ],
            0,
            "rows of its tables left out (not finite, or beyond any propeller's CT, CP or J), first line 24",
        ),
        // N3: thousands of threads.
        case(
            "N3",
            &["--threads", "4000", "predict", "--prop", &cam, "--rpm", "4000"],
            2,
            "--threads 4000: from 1 to 256",
        ),
        // N11: a reference table whose chord is 0 at a measured station.
        case(
            "N11",
            &[
                "scan",
                &path("props/apcsf_10x4.7/apcsf_10x4.7.stl"),
                "--stations",
                "0.3:0.9/5",
                "--reference",
                &bad("geom_zero_chord.txt"),
                "-o",
                "OUT",
            ],
            0,
            "(the table's chord is 0 at r/R 0.75: no chord error there)",
        ),
        // N25: a parameter's scale of 0.
        case(
            "N25",
            &[
                "diagnose",
                "--prop",
                &hq,
                "--measured",
                &h("cam6x3_steps.csv"),
                "--user-effects",
                &bad("fx_param_scale_zero.toml"),
                "--effects",
                "fx",
                "-o",
                "OUT",
            ],
            2,
            "fx_param_scale_zero.toml: effect `fx`: parameter `c`: scale 0 must be positive",
        ),
        // N30: huge numbers are written short.
        case(
            "N30 (re)",
            &["polar", "--airfoil", "naca4412", "--re", "1e300", "--no-cache"],
            2,
            "NACA 4412 at Re 1e300: invalid XFOIL request: Reynolds number 1e300 must be in (0, 1e9)",
        ),
        case(
            "N30 (thickness)",
            &[
                "polar",
                "--airfoil",
                "naca4412",
                "--re",
                "1e5",
                "--thickness",
                "1e308",
                "--no-cache",
            ],
            2,
            "--thickness 1e308: target thickness 1e308 must be in (0, 0.5)",
        ),
        // N4: a device or a directory is not read.
        case(
            "N4 (device)",
            &["predict", "--prop", "/dev/zero", "--rpm", "4000"],
            2,
            "/dev/zero: is a pipe, socket or device, not a file propbet can read",
        ),
        case(
            "N4 (directory)",
            &["scan", "/tmp", "-o", "OUT"],
            2,
            "/tmp: is a directory, not a file propbet can read",
        ),
    ];
    // N13: user-effect hooks that move the point beyond any test, or give a NaN chord.
    let mut cases = cases;
    for (id, file, says) in [
        (
            "N13 (V)",
            "fx_v_times_1e300.toml",
            "the effects fx move the operating point to an airspeed of 6e300 m/s",
        ),
        ("N13 (rpm)", "fx_rpm_times_1e6.toml", "to 3000000000 rpm"),
        ("N13 (rho)", "fx_rho_negative.toml", "an air density of -0.075 kg/m^3"),
        ("N13 (chord)", "fx_chord_sqrt_inboard.toml", "a chord of NaN m"),
    ] {
        let fx = bad(file);
        let args = [
            "predict",
            "--prop",
            &cam,
            "--rpm",
            "3000",
            "--v",
            "0,6",
            "--user-effects",
            &fx,
            "--effect",
            "fx",
        ];
        cases.push(case(id, &args, 2, says));
    }
    let mut failures = Vec::new();
    for c in &cases {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let args: Vec<String> = c
            .args
            .iter()
            .map(|a| {
                if a == "OUT" {
                    out.display().to_string()
                } else {
                    a.clone()
                }
            })
            .collect();
        let argv: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = run(&argv, dir.path());
        let e = stderr(&o);
        let said = format!("{e}{}", String::from_utf8_lossy(&o.stdout));
        if o.status.code() != Some(c.code) || !said.contains(c.says) {
            failures.push(format!(
                "{}: exit {:?} (want {}), stderr: {e}",
                c.id,
                o.status.code(),
                c.code
            ));
        }
        assert!(!e.contains("panicked"), "{}: {e}", c.id);
        outputs_finite(&out);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn n38_a_symlink_in_the_output_folder_is_refused_and_nothing_is_overwritten() {
    let t = tempfile::tempdir().unwrap();
    let (case_dir, out) = (t.path().join("case"), t.path().join("out"));
    std::fs::create_dir_all(&case_dir).unwrap();
    std::fs::create_dir_all(&out).unwrap();
    let h = repo().join("tests/data/hidden_effects/torque_tare");
    std::fs::copy(h.join("cam6x3.qprop"), case_dir.join("cam6x3.qprop")).unwrap();
    std::fs::copy(h.join("cam6x3_steps.csv"), case_dir.join("sweep.csv")).unwrap();
    std::fs::write(
        case_dir.join("case.toml"),
        "name = \"c\"\n[geometry]\nprop = \"cam6x3.qprop\"\n[sweep]\nrpm = \"4000,8000\"\nj = \"0:0.6:0.1\"\n\
         [measured]\nfiles = [\"sweep.csv\"]\n",
    )
    .unwrap();
    std::os::unix::fs::symlink(&case_dir, out.join("predict")).unwrap();
    let before = std::fs::read(case_dir.join("sweep.csv")).unwrap();
    let o = run(
        &[
            "run",
            case_dir.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--quiet",
            "--no-cache",
        ],
        t.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("a symbolic link (to"), "{}", stderr(&o));
    assert_eq!(std::fs::read(case_dir.join("sweep.csv")).unwrap(), before);
    // The same for compare's plots folder.
    let (elsewhere, out2) = (t.path().join("elsewhere"), t.path().join("out2"));
    std::fs::create_dir_all(&elsewhere).unwrap();
    std::fs::create_dir_all(&out2).unwrap();
    std::fs::write(elsewhere.join("static.svg"), "precious").unwrap();
    std::os::unix::fs::symlink(&elsewhere, out2.join("plots")).unwrap();
    let o = run(
        &[
            "compare",
            "--prop",
            h.join("cam6x3.qprop").to_str().unwrap(),
            "--measured",
            h.join("cam6x3_steps.csv").to_str().unwrap(),
            "-o",
            out2.to_str().unwrap(),
        ],
        t.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(elsewhere.join("static.svg")).unwrap(),
        "precious"
    );
}

#[test]
fn n39_n40_names_cannot_drive_the_terminal_or_become_html() {
    let t = tempfile::tempdir().unwrap();
    let o = run(&["prop", &bad("prop_title_ansi.qprop")], t.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("name: Cam ?]0;PWNED"));
    let o = run(&["run", &bad("case_name_ansi"), "-o", "ansi", "--quiet"], t.path());
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    for (what, bytes) in [("stdout", &o.stdout), ("stderr", &o.stderr)] {
        assert!(
            !bytes.contains(&0x1b),
            "{what} holds an escape: {}",
            String::from_utf8_lossy(bytes)
        );
    }
    // A measured file's name with a tag in it: the summary quotes it, as text.
    let h = repo().join("tests/data/hidden_effects/torque_tare");
    let log = t.path().join("<img src=x onerror=alert(1)>.csv");
    std::fs::copy(h.join("cam6x3_steps.csv"), &log).unwrap();
    let o = run(
        &[
            "compare",
            "--prop",
            h.join("cam6x3.qprop").to_str().unwrap(),
            "--measured",
            log.to_str().unwrap(),
            "-o",
            "md",
        ],
        t.path(),
    );
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    let md = std::fs::read_to_string(t.path().join("md/summary.md")).unwrap();
    assert!(md.contains("&lt;img src=x") && !md.contains("<img"), "{md}");
}

#[test]
fn n36_a_cache_that_cannot_store_a_polar_warns_and_the_polar_is_used() {
    // The stand-in XFOIL (no fault) fills a cache; each entry then becomes a directory, so
    // that the cache can neither read nor store it (as a read-only or full cache would fail).
    let t = tempfile::tempdir().unwrap();
    let xfoil = bad("fake_xfoil.sh");
    let args = [
        "polar",
        "--airfoil",
        "naca4412",
        "--re",
        "1e5",
        "--alpha",
        "-4:8:1",
        "--xfoil",
        &xfoil,
        "--cache",
        "C",
    ];
    let first = run(&args, t.path());
    assert_eq!(first.status.code(), Some(0), "{}", stderr(&first));
    let mut entries = 0;
    for shard in std::fs::read_dir(t.path().join("C")).unwrap() {
        for e in std::fs::read_dir(shard.unwrap().path()).unwrap() {
            let p = e.unwrap().path();
            std::fs::remove_file(&p).unwrap();
            std::fs::create_dir(&p).unwrap();
            entries += 1;
        }
    }
    assert!(entries > 0);
    let second = run(&args, t.path());
    assert_eq!(second.status.code(), Some(0), "{}", stderr(&second));
    assert!(
        stderr(&second).contains("the cache could not store the polars XFOIL computed; they were used"),
        "{}",
        stderr(&second)
    );
    assert_eq!(second.stdout, first.stdout, "the same polar, computed again");
}

/// Processes whose command line holds `needle` (from /proc).
fn processes_with(needle: &str) -> usize {
    std::fs::read_dir("/proc")
        .unwrap()
        .filter_map(|e| std::fs::read(e.ok()?.path().join("cmdline")).ok())
        .filter(|c| String::from_utf8_lossy(c).replace('\0', " ").contains(needle))
        .count()
}

#[test]
fn n33_n34_n35_xfoil_and_its_children_and_folders_go_with_propbet() {
    let t = tempfile::tempdir().unwrap();
    let tmp = t.path().join("tmp");
    std::fs::create_dir(&tmp).unwrap();
    let xfoil = bad("fake_xfoil.sh");
    let polar = |mode: &str| {
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_propbet"));
        c.args([
            "polar",
            "--airfoil",
            "naca4412",
            "--re",
            "1e5",
            "--alpha",
            "-4:8:1",
            "--no-cache",
        ])
        .args(["--xfoil", &xfoil])
        .env("FAKE_MODE", mode)
        .env("TMPDIR", &tmp)
        .current_dir(t.path())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null());
        c
    };
    // N35: an XFOIL that exits normally leaves a background child (`sleep 307`): it goes too.
    let status = polar("x_bg_child").status().unwrap();
    assert!(status.code().is_some());
    std::thread::sleep(std::time::Duration::from_millis(300));
    assert_eq!(processes_with("sleep 307"), 0, "a child of XFOIL outlived it");
    // N34: SIGTERM to propbet while XFOIL hangs (`sleep 100007` at its 4th angle).
    let mut child = polar("x_hang_mid").spawn().unwrap();
    let start = std::time::Instant::now();
    while processes_with("sleep 100007") == 0 && start.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    assert!(processes_with("sleep 100007") > 0, "the hang did not start");
    rustix::process::kill_process(
        rustix::process::Pid::from_raw(child.id() as i32).unwrap(),
        rustix::process::Signal::TERM,
    )
    .unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(128 + 15));
    std::thread::sleep(std::time::Duration::from_millis(300));
    assert_eq!(
        processes_with("sleep 100007"),
        0,
        "XFOIL outlived an interrupted propbet"
    );
    // N33: nothing left in TMPDIR.
    let left: Vec<_> = std::fs::read_dir(&tmp)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "left in TMPDIR: {left:?}");
}

#[test]
fn n23_a_relative_xfoil_path_is_the_callers() {
    let t = tempfile::tempdir().unwrap();
    std::fs::copy(bad("fake_xfoil.sh"), t.path().join("fake.sh")).unwrap();
    let o = run(
        &[
            "polar",
            "--airfoil",
            "naca4412",
            "--re",
            "1e5",
            "--alpha",
            "-4:8:1",
            "--xfoil",
            "./fake.sh",
            "--no-cache",
        ],
        t.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).lines().count() > 5);
}

#[test]
fn n19_a_first_row_out_of_time_order_is_described_without_nan() {
    let t = tempfile::tempdir().unwrap();
    let h = repo().join("tests/data/hidden_effects/torque_tare");
    let text = std::fs::read_to_string(h.join("cam6x3_steps.csv")).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let rest = lines[1].split_once(',').unwrap().1.to_string();
    lines[1] = format!("77.12,{rest}");
    std::fs::write(t.path().join("log.csv"), lines.join("\n") + "\n").unwrap();
    let o = run(
        &[
            "compare",
            "--prop",
            h.join("cam6x3.qprop").to_str().unwrap(),
            "--measured",
            "log.csv",
            "-o",
            "out",
        ],
        t.path(),
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let m = std::fs::read_to_string(t.path().join("out/metrics.json")).unwrap();
    assert!(m.contains("t = 77.12 s, first row, before the next row's"), "{m}");
    assert!(!m.contains("NaN"));
}

#[test]
fn n18_validate_writes_no_nan_on_clean_inputs() {
    // The stand-in XFOIL gives each section a flat polar: some columns have no value (no
    // point in a J range, a prop of another maker with no held-out ladder); they are empty.
    let t = tempfile::tempdir().unwrap();
    let o = run(
        &[
            "validate",
            "--uiuc",
            &path("tests/data/validate/uiuc"),
            "--pe0",
            &path("tests/data/validate/pe0"),
            "--airfoils",
            &path("props/airfoils"),
            "--out",
            "v",
            "--xfoil",
            &bad("fake_xfoil.sh"),
            "--no-cache",
            "--quiet",
        ],
        t.path(),
    );
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    assert!(t.path().join("v/validation.csv").exists());
    outputs_finite(&t.path().join("v"));
}

#[test]
fn n31_toml_errors_name_their_place_without_echoing_the_line() {
    let t = tempfile::tempdir().unwrap();
    let case = t.path().join("deep");
    std::fs::create_dir(&case).unwrap();
    let deep = format!("name = \"x\"\nbad = {}1{}\n", "{a=".repeat(5000), "}".repeat(5000));
    std::fs::write(case.join("case.toml"), deep).unwrap();
    let o = run(&["run", "deep", "-o", "out"], t.path());
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(
        e.contains("case.toml: line 2, column") && e.len() < 300,
        "{} bytes: {e}",
        e.len()
    );
}

#[test]
fn n29_a_ply_without_z_or_with_x_twice_is_named() {
    let t = tempfile::tempdir().unwrap();
    for (props, says) in [
        (
            "property float x\nproperty float y\n",
            "names its 'z' coordinate 0 times",
        ),
        (
            "property float x\nproperty float x\nproperty float z\n",
            "names its 'x' coordinate 2 times",
        ),
    ] {
        let cols = props.lines().count();
        let rows: String = (0..3)
            .map(|k| format!("{}\n", vec![k.to_string(); cols].join(" ")))
            .collect();
        let ply = format!("ply\nformat ascii 1.0\nelement vertex 3\n{props}end_header\n{rows}");
        std::fs::write(t.path().join("c.ply"), ply).unwrap();
        let o = run(&["scan", "c.ply", "-o", "out"], t.path());
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(
            stderr(&o).contains("c.ply") && stderr(&o).contains(says),
            "{}",
            stderr(&o)
        );
    }
}

#[test]
fn n4_a_fifo_is_refused_without_blocking() {
    let t = tempfile::tempdir().unwrap();
    let fifo = t.path().join("log.csv");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let o = run_or_hang(
        &[
            "compare",
            "--prop",
            &path("props/cam6x3/cam6x3.qprop"),
            "--measured",
            &fifo.display().to_string(),
            "-o",
            "out",
        ],
        t.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("log.csv: is a pipe, socket or device"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn n14_a_flattened_stl_is_refused() {
    // The shipped binary STL with every z set to 0 (as make_flat_stl.py does).
    let mut b = std::fs::read(repo().join("props/apcsf_10x4.7/apcsf_10x4.7.stl")).unwrap();
    let n = u32::from_le_bytes(b[80..84].try_into().unwrap()) as usize;
    for i in 0..n {
        for k in 0..3 {
            let o = 84 + 50 * i + 12 + 12 * k + 8;
            b[o..o + 4].copy_from_slice(&0f32.to_le_bytes());
        }
    }
    let t = tempfile::tempdir().unwrap();
    std::fs::write(t.path().join("flat.stl"), b).unwrap();
    let o = run(&["scan", "flat.stl", "--stations", "0.3:0.9/5", "-o", "out"], t.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("flat.stl: not a propeller: the surface is flat"),
        "{}",
        stderr(&o)
    );
    assert!(!t.path().join("out/prop.qprop").exists());
}

#[test]
fn n22_a_case_prop_file_with_polars_runs() {
    let t = tempfile::tempdir().unwrap();
    let o = run(
        &[
            "run",
            &bad("case_prop_polars"),
            "-o",
            "out",
            "--xfoil",
            &bad("fake_xfoil.sh"),
            "--no-cache",
        ],
        t.path(),
    );
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    assert!(t.path().join("out/report.html").exists());
    assert!(t.path().join("out/polars/prop.qprop").exists());
}

#[test]
fn n24_a_half_written_polar_row_keeps_the_rows_before_it() {
    let t = tempfile::tempdir().unwrap();
    let o = bin()
        .args([
            "polar",
            "--airfoil",
            "naca4412",
            "--re",
            "1e5",
            "--alpha",
            "-4:8:1",
            "--xfoil",
            &bad("fake_xfoil.sh"),
            "--no-cache",
        ])
        .env("FAKE_MODE", "x_half_polar")
        .current_dir(t.path())
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let rows = String::from_utf8_lossy(&o.stdout)
        .lines()
        .filter(|l| l.starts_with("100000,"))
        .count();
    // 13 angles asked; the fake crashes half-way through its 5th row and the restart goes on.
    assert!(rows >= 8, "{rows} rows: {}", String::from_utf8_lossy(&o.stdout));
    assert!(!stderr(&o).contains("unreadable"), "{}", stderr(&o));
}

#[test]
fn n26_scan_args_that_the_case_sets_elsewhere_are_refused() {
    let t = tempfile::tempdir().unwrap();
    let stl = path("props/apcsf_10x4.7/apcsf_10x4.7.stl");
    for (args, says) in [
        (
            r#"["--reference", "/etc/passwd"]"#,
            "--reference is set by `reference` in [geometry]",
        ),
        (r#"["--name", "x"]"#, "--name is set by the case's `name`"),
    ] {
        let case = t.path().join("case");
        std::fs::create_dir_all(&case).unwrap();
        std::fs::write(
            case.join("case.toml"),
            format!(
                "name = \"c\"\n[geometry]\nscan = \"{stl}\"\nscan_args = {args}\n[sweep]\nrpm = \"4000\"\nj = \"0\"\n"
            ),
        )
        .unwrap();
        let o = run(&["run", "case", "-o", "out"], t.path());
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(stderr(&o).contains(says), "{}", stderr(&o));
        assert!(!t.path().join("out").exists());
    }
}

#[test]
fn n37_a_folder_another_propbet_writes_is_refused() {
    let t = tempfile::tempdir().unwrap();
    let out = t.path().join("out");
    std::fs::create_dir(&out).unwrap();
    // The lock a running propbet holds on its output folder.
    let held = std::fs::File::open(&out).unwrap();
    held.try_lock().unwrap();
    let h = |f: &str| path(&format!("tests/data/hidden_effects/torque_tare/{f}"));
    let compare = [
        "compare",
        "--prop",
        &h("cam6x3.qprop"),
        "--measured",
        &h("cam6x3_steps.csv"),
        "-o",
        "out",
    ];
    let o = run(&compare, t.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("out: another propbet is writing this folder"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 0, "nothing written");
    let case = path("props/cam6x3");
    let o = run(&["run", &case, "-o", "out"], t.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(!out.join(INCOMPLETE_TXT).exists());
    drop(held);
    let o = run(&compare, t.path());
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    assert!(out.join("report.html").exists());
}

const INCOMPLETE_TXT: &str = "INCOMPLETE.txt";

#[test]
fn a_scan_that_fails_half_way_leaves_its_folder_marked_incomplete() {
    // A write that fails after the first outputs (a directory where scan.json goes) stands in
    // for a disk that fills up: the folder keeps INCOMPLETE.txt naming the command.
    let t = tempfile::tempdir().unwrap();
    let out = t.path().join("out");
    std::fs::create_dir_all(out.join("scan.json")).unwrap();
    let stl = path("props/apcsf_10x4.7/apcsf_10x4.7.stl");
    let o = run(&["scan", &stl, "--stations", "0.3:0.9/4", "-o", "out"], t.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        out.join("prop.qprop").exists(),
        "the outputs before the failure are written"
    );
    let marker = std::fs::read_to_string(out.join(INCOMPLETE_TXT)).unwrap();
    assert!(
        marker.contains("`propbet scan ") && marker.contains("has not finished"),
        "{marker}"
    );
    // Done again into a clean folder: no marker.
    std::fs::remove_dir_all(&out).unwrap();
    let o = run(&["scan", &stl, "--stations", "0.3:0.9/4", "-o", "out"], t.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(!out.join(INCOMPLETE_TXT).exists());
}

#[test]
fn airfoil_is_required_with_sections_airfoil_only() {
    let t = tempfile::tempdir().unwrap();
    let case = t.path().join("case");
    std::fs::create_dir_all(&case).unwrap();
    std::fs::write(
        case.join("case.toml"),
        format!(
            "name = \"c\"\n[geometry]\nprop = \"{}\"\n[polars]\nsections = \"airfoil\"\n[sweep]\nrpm = \"4000\"\nj = \"0\"\n",
            path("props/cam6x3/cam6x3.qprop")
        ),
    )
    .unwrap();
    let o = run(&["run", "case", "-o", "out"], t.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("[polars] sections = \"airfoil\" needs `airfoil`"),
        "{}",
        stderr(&o)
    );
    // `polars` without --airfoil needs the scanned sections.
    let o = run(
        &[
            "polars",
            "--geometry",
            &path("props/cam6x3/cam6x3.qprop"),
            "--rpm",
            "4000",
            "--out-prop",
            "p.qprop",
        ],
        t.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--airfoil"), "{}", stderr(&o));
}
