//! The campaign's items that need more than a command and its expected message: symlinks
//! and folders in use, names that could drive a terminal, caches that cannot store, XFOIL's
//! children and folders going with propbet, FIFOs, half-written files.

use super::*;

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
    // The list of flags is refused whole (removed in 0.2.0), naming the keys to write instead.
    let says = "[geometry] scan_args: removed in 0.2.0; write each flag of `propbet scan` as a key";
    for args in [r#"["--reference", "/etc/passwd"]"#, r#"["--name", "x"]"#] {
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
