//! The inputs that broke propbet (`tests/data/bad_inputs`, from `../shared/examples/bad_inputs`),
//! each run with the command the shared README gives: a clear message and exit code, no panic,
//! no hang, no inf or NaN in an output.

use super::*;

fn bad(name: &str) -> String {
    repo().join("tests/data/bad_inputs").join(name).display().to_string()
}

fn apc_prop() -> String {
    repo()
        .join("props/apcsf_10x4.7/apcsf_10x4.7.qprop")
        .display()
        .to_string()
}

/// Every number of every CSV and JSON file under `dir` is finite.
fn outputs_finite(dir: &Path) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            outputs_finite(&p);
        } else if matches!(p.extension().and_then(|x| x.to_str()), Some("csv" | "json")) {
            let text = std::fs::read_to_string(&p).unwrap();
            for bad in ["inf", "NaN", "nan"] {
                let hit = text
                    .split(|c: char| !(c.is_alphanumeric() || ".-_/".contains(c)))
                    .any(|w| w == bad || w == "-inf");
                assert!(!hit, "{}: holds {bad}", p.display());
            }
        }
    }
}

#[test]
fn tabulated_polars_out_of_order_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    // The shared file is of the first polars format: refused as such, naming the file.
    let shared = bad("polars_alpha_reversed.json");
    let o = run(
        &["predict", "--prop", &apc_prop(), "--polars", &shared, "--rpm", "5000"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("polars_alpha_reversed.json") && e.contains("written by another version of propbet"),
        "{e}"
    );
    // The same content in today's format: the descending angles are named.
    let mut v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&shared).unwrap()).unwrap();
    v["format"] = "propbet-blade-polars-2".into();
    v["rpm"] = serde_json::json!([5000.0, 5000.0]);
    v["v"] = serde_json::json!([0.0, 0.0]);
    for st in v["stations"].as_array_mut().unwrap() {
        let (re, a) = (st["re"].clone(), st["alpha_deg"].clone());
        st["re_range"] = serde_json::json!([re, re]);
        st["alpha_range_deg"] = serde_json::json!([a, a]);
    }
    let file = dir.path().join("polars_alpha_reversed.json").display().to_string();
    std::fs::write(&file, serde_json::to_string(&v).unwrap()).unwrap();
    let o = run(
        &[
            "predict",
            "--prop",
            &apc_prop(),
            "--polars",
            &file,
            "--rpm",
            "5000",
            "--v",
            "0,5",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("polars_alpha_reversed.json") && e.contains("angles not ascending") && e.contains("station"),
        "{e}"
    );
}

#[test]
fn absurd_measured_values_are_dropped_and_listed() {
    let dir = tempfile::tempdir().unwrap();
    // Static CT of +-1e308: the rows are dropped, the others compared; exit 1 (faults reported).
    let o = run(
        &[
            "compare",
            "--prop",
            &apc_prop(),
            "--measured",
            &bad("uiuc_static_inf_hang.txt"),
            "--out",
            "static",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("beyond any small propeller's values"),
        "{}",
        stderr(&o)
    );
    outputs_finite(&dir.path().join("static"));
    // A J sweep with CT and CP of 1e308: the diagnosis runs on the rest; exit 1 as compare's, and
    // its page lists the dropped rows with their lines.
    let o = run(
        &[
            "diagnose",
            "--prop",
            &apc_prop(),
            "--measured",
            &bad("uiuc_sweep_1e308_kt0000_4014.txt"),
            "--out",
            "sweep",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("2 beyond any small propeller's values"),
        "{}",
        stderr(&o)
    );
    let page = std::fs::read_to_string(dir.path().join("sweep/report.html")).unwrap();
    assert!(
        page.contains("2 dropped rows") && page.contains("<h2>Measured files</h2>"),
        "{page}"
    );
    outputs_finite(&dir.path().join("sweep"));
    // A thrust of 1e308 N in every row of a thrust-stand log: nothing is left, and that is said.
    let o = run(
        &[
            "compare",
            "--prop",
            cam6x3().to_str().unwrap(),
            "--measured",
            &bad("stand_thrust_1e308.csv"),
            "--out",
            "stand",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("stand_thrust_1e308.csv") && e.contains("63 beyond any small propeller's values (first at line 2)"),
        "{e}"
    );
    assert!(!dir.path().join("stand/points.csv").exists());
}

#[test]
fn a_duplicated_column_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        &[
            "compare",
            "--prop",
            cam6x3().to_str().unwrap(),
            "--measured",
            &bad("stand_duplicated_header.csv"),
            "--out",
            "out",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("stand_duplicated_header.csv") && e.contains("'Thrust (N)' appears twice"),
        "{e}"
    );
    assert!(!dir.path().join("out/report.html").exists());
}

#[test]
fn a_huge_grid_is_refused_before_it_is_allocated() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(&["run", &bad("run_huge_grid"), "-o", "out"], dir.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("at most 1000000 in one sweep"), "{}", stderr(&o));
    let o = run(
        &[
            "predict",
            "--prop",
            cam6x3().to_str().unwrap(),
            "--rpm",
            "1000:20000/100000",
            "--j",
            "0:1/100000",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("10000000000 operating points"), "{}", stderr(&o));
}

#[test]
fn tip_radius_in_metres_with_stations_in_cm_is_read_as_qprop_reads_it() {
    // QPROP 1.22 gives this file exactly the numbers of cam6x3 (T = 0.6596 N at 5 m/s, 8000 rpm:
    // ../shared/reference/qprop/cam6x3_*), and so does propbet, with and without --qprop-compat.
    let dir = tempfile::tempdir().unwrap();
    let thrust = |prop: &str, extra: &[&str]| -> (f64, String) {
        let mut args = vec!["predict", "--prop", prop, "--rpm", "8000", "--v", "5", "--out", "p.csv"];
        args.extend_from_slice(extra);
        let o = run(&args, dir.path());
        assert!(o.status.success(), "{}", stderr(&o));
        let (h, r) = read_csv(&dir.path().join("p.csv"));
        (r[0][col(&h, "thrust_n")].parse().unwrap(), stderr(&o))
    };
    let file = bad("prop_R_metres_stations_cm.qprop");
    for extra in [&[][..], &["--qprop-compat"][..]] {
        let (t, e) = thrust(&file, extra);
        let (t_ref, _) = thrust(cam6x3().to_str().unwrap(), extra);
        assert_eq!(t, t_ref);
        assert!((t - 0.6596).abs() < 5e-5, "{t}");
        assert!(
            e.contains("line 4: R = 0.0762 would lie inside the blade") && !e.contains("line 0"),
            "{e}"
        );
    }
}

#[test]
fn a_cloud_with_corrupt_coordinates_is_refused_not_searched_for_ever() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(
        &["scan", &bad("cloud_hang.ply"), "--stations", "0.3:0.9/5", "-o", "out"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("cloud_hang.ply") && e.contains("not a propeller"), "{e}");
    assert!(!dir.path().join("out/geometry.csv").exists());
}

#[test]
fn absurd_operating_points_and_cases_that_would_overwrite_their_inputs_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let cam = cam6x3();
    let o = run(
        &[
            "predict",
            "--prop",
            cam.to_str().unwrap(),
            "--rpm",
            "8000",
            "--v",
            "1e300",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("beyond any small propeller's operating range"),
        "{}",
        stderr(&o)
    );
    let o = run(
        &["predict", "--prop", cam.to_str().unwrap(), "--rpm", "1e20"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    // A case whose measurements lie in its own output directory.
    let case = dir.path().join("case");
    std::fs::create_dir_all(case.clone()).unwrap();
    std::fs::create_dir_all(dir.path().join("out")).unwrap();
    std::fs::copy(&cam, case.join("cam6x3.qprop")).unwrap();
    std::fs::write(dir.path().join("out/m.csv"), "rpm,thrust_N\n8000,1.0\n").unwrap();
    std::fs::write(
        case.join("case.toml"),
        "name = \"x\"\n[geometry]\nprop = \"cam6x3.qprop\"\n[sweep]\nrpm = \"8000\"\nj = \"0:0.4:0.2\"\n\
         [measured]\nfiles = [\"../out/m.csv\"]\n",
    )
    .unwrap();
    let o = run(&["run", "case", "-o", "out"], dir.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("inside the output directory"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(dir.path().join("out/m.csv")).unwrap(),
        "rpm,thrust_N\n8000,1.0\n"
    );
}

#[test]
fn a_closed_standard_error_or_output_is_not_a_panic() {
    // `propbet ... 2>&1 >/dev/null | head -1`: the reader of the pipe has gone when propbet
    // writes its warnings (this prop file has two); the messages are lost, the run is not.
    for (out, err) in [(false, true), (true, false)] {
        let pipe = |on: bool| {
            if on {
                std::process::Stdio::piped()
            } else {
                std::process::Stdio::null()
            }
        };
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_propbet"))
            .args([
                "prop",
                repo().join("props/photofoil_8x4.5/QProp_8x4_5.txt").to_str().unwrap(),
            ])
            .stdout(pipe(out))
            .stderr(pipe(err))
            .spawn()
            .unwrap();
        drop(child.stdout.take());
        drop(child.stderr.take());
        let status = child.wait().unwrap();
        assert_ne!(
            status.code(),
            Some(101),
            "panicked with stdout closed {out}, stderr closed {err}"
        );
    }
}

#[test]
fn a_file_that_is_not_an_input_is_quoted_in_a_short_clean_excerpt() {
    // A case (or a flag) may name any file; its errors quote at most a short
    // excerpt, with no control characters, never the whole line or file.
    let dir = tempfile::tempdir().unwrap();
    let line = format!("\x1b[2J\x07SECRET-{}\n", "x".repeat(400));
    std::fs::write(dir.path().join("other.txt"), line.repeat(20)).unwrap();
    let cam = cam6x3();
    for args in [
        vec!["polar", "--airfoil", "other.txt", "--re", "5e4"],
        vec!["scan", "other.txt", "-o", "s"],
        vec![
            "compare",
            "--prop",
            cam.to_str().unwrap(),
            "--measured",
            "other.txt",
            "-o",
            "c",
        ],
        vec!["predict", "--prop", "other.txt", "--rpm", "5000"],
    ] {
        let o = run(&args, dir.path());
        let err = stderr(&o);
        assert!(matches!(o.status.code(), Some(1 | 2)), "{args:?}: {err}");
        assert!(err.contains("other.txt"), "{args:?}: the file is named: {err}");
        assert!(!err.contains('\x1b') && !err.contains('\x07'), "{args:?}: {err:?}");
        assert!(
            !err.contains(&"x".repeat(100)),
            "{args:?}: the line is echoed whole: {err}"
        );
    }
}

#[test]
fn commands_refuse_an_output_over_an_input_before_they_write_anything() {
    // The refusal comes first; the output directory stays as it was.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::copy(cam6x3(), out.join("prop.qprop")).unwrap();
    let steps = repo().join("tests/data/hidden_effects/torque_tare/cam6x3_steps.csv");
    std::fs::copy(&steps, out.join("points.csv")).unwrap();
    let before = |d: &Path| {
        let mut v: Vec<_> = walk(d);
        v.sort();
        v
    };
    let listing = before(&out);
    for args in [
        vec![
            "compare",
            "--prop",
            "out/prop.qprop",
            "--measured",
            "out/points.csv",
            "-o",
            "out",
        ],
        vec![
            "diagnose",
            "--prop",
            "out/prop.qprop",
            "--measured",
            "out/points.csv",
            "--out",
            "out",
        ],
        vec!["synth", "--prop", "out/prop.qprop", "--format", "uiuc", "-o", "out"],
        vec!["synth", "--prop", "out/prop.qprop", "-o", "out/prop.qprop"],
        vec![
            "polars",
            "--geometry",
            "out/prop.qprop",
            "--airfoil",
            "naca4412",
            "--rpm",
            "5000",
            "--out-prop",
            "out/prop.qprop",
        ],
        vec![
            "polar",
            "--airfoil",
            "out/points.csv",
            "--re",
            "5e4",
            "-o",
            "out/points.csv",
        ],
    ] {
        let o = run(&args, dir.path());
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("inside the output directory") || err.contains("refusing to overwrite an input"),
            "{args:?}: {err}"
        );
        assert_eq!(before(&out), listing, "{args:?} wrote into the output directory");
    }
    assert_eq!(
        std::fs::read(out.join("points.csv")).unwrap(),
        std::fs::read(&steps).unwrap()
    );
}

/// Every file under `d` with its size.
fn walk(d: &Path) -> Vec<(PathBuf, u64)> {
    let mut v = Vec::new();
    for e in std::fs::read_dir(d).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            v.push((p.clone(), 0));
            v.extend(walk(&p));
        } else {
            let n = std::fs::metadata(&p).unwrap().len();
            v.push((p, n));
        }
    }
    v
}

#[test]
fn a_copied_case_whose_paths_do_not_resolve_fails_before_anything_runs() {
    // A case that names a file beside its folder (../airfoils); a copy elsewhere must fail at
    // once, naming the file, and leave no output folder.
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("copy");
    std::fs::create_dir_all(case.join("uiuc")).unwrap();
    let src = repo().join("props/apcsf_10x4.7");
    for e in std::fs::read_dir(&src).unwrap() {
        let p = e.unwrap().path();
        if p.is_file() {
            std::fs::copy(&p, case.join(p.file_name().unwrap())).unwrap();
        }
    }
    for e in std::fs::read_dir(src.join("uiuc")).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, case.join("uiuc").join(p.file_name().unwrap())).unwrap();
    }
    let toml = std::fs::read_to_string(case.join("case.toml")).unwrap();
    let toml = toml.replace("airfoil = \"e63\"", "airfoil = \"../airfoils/e63.dat\"");
    std::fs::write(case.join("case.toml"), toml).unwrap();
    let o = run(&["run", "copy", "-o", "out", "--quiet"], dir.path());
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("airfoils/e63.dat") && err.contains("not exist") && err.contains("nothing was run"),
        "{err}"
    );
    assert!(
        !dir.path().join("out").exists(),
        "no output folder from a case that cannot run"
    );
}
