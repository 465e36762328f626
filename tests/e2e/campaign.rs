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
        // The terminal wraps long sentences: read them with their line breaks as spaces.
        let said = format!("{e}{}", String::from_utf8_lossy(&o.stdout));
        let said = said.split_whitespace().collect::<Vec<_>>().join(" ");
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

mod single;
