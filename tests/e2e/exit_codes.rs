//! Exit codes mean what the help says: one row per command and outcome (0 done, 1 done with
//! problems it reports, 2 error), each checked against the code and against the "Exit status"
//! line of that command's help (a code the help does not list fails the row).

use std::path::Path;

use super::{bin, repo, stderr};

struct Row {
    command: &'static str,
    outcome: &'static str,
    args: Vec<String>,
    env: Option<(&'static str, &'static str)>,
    code: i32,
}

fn row(command: &'static str, outcome: &'static str, code: i32, args: &[&str]) -> Row {
    Row {
        command,
        outcome,
        args: std::iter::once(command)
            .chain(args.iter().copied())
            .map(String::from)
            .collect(),
        env: None,
        code,
    }
}

fn p(rel: &str) -> String {
    repo().join(rel).display().to_string()
}

/// The codes the help of `command` lists after "Exit status:".
fn help_codes(command: &str) -> Vec<i32> {
    let o = bin().args([command, "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&o.stdout).into_owned();
    let line = help
        .split("Exit status:")
        .nth(1)
        .unwrap_or_else(|| panic!("{command} --help has no exit status: {help}"));
    line.split(';')
        .filter_map(|part| part.split_whitespace().next()?.parse().ok())
        .collect()
}

#[test]
fn each_command_and_outcome_gets_the_code_its_help_gives() {
    let cam = p("props/cam6x3/cam6x3.qprop");
    let fake = p("tests/data/bad_inputs/fake_xfoil.sh");
    let tare = |f: &str| p(&format!("tests/data/hidden_effects/torque_tare/{f}"));
    let tunnel = p("tests/data/hidden_effects/no_effect/cam6x3_tunnel.csv");
    let stl = p("props/apcsf_10x4.7/apcsf_10x4.7.stl");
    let polars_args = |j: &str| -> Vec<String> {
        [
            "--geometry",
            &cam,
            "--airfoil",
            "naca4412",
            "--rpm",
            "6000",
            "--j",
            j,
            "--xfoil",
            &fake,
            "--no-cache",
            "--quiet",
            "--out-prop",
            "p.qprop",
        ]
        .map(String::from)
        .to_vec()
    };
    let with = |mut r: Row, env: (&'static str, &'static str)| {
        r.env = Some(env);
        r
    };
    let mut rows = vec![
        row(
            "run",
            "the shipped case without measurements (sweeps, the prop on its motor)",
            0,
            &[&p("props/cam6x3"), "-o", "out"],
        ),
        with(
            row(
                "run",
                "XFOIL crashes at some angles, which the tables interpolate across (a note)",
                0,
                &[
                    &p("tests/data/bad_inputs/case_prop_polars"),
                    "-o",
                    "out",
                    "--xfoil",
                    &fake,
                    "--no-cache",
                    "--quiet",
                ],
            ),
            ("FAKE_MODE", "x_crash_mid"),
        ),
        with(
            row(
                "run",
                "XFOIL crashes in the polars stage of a case whose section model is QPROP's law fitted to them",
                1,
                &[
                    &p("tests/data/bad_inputs/case_prop_polars_qprop"),
                    "-o",
                    "out",
                    "--xfoil",
                    &fake,
                    "--no-cache",
                    "--quiet",
                ],
            ),
            ("FAKE_MODE", "x_crash_mid"),
        ),
        row("run", "no case.toml", 2, &["/tmp", "-o", "out"]),
        row(
            "run",
            "the default case (APC's design file) with NeuralFoil's polars: its notes (standard air, the QPROP fit's fallbacks) are no problem",
            0,
            &["--engine", "neuralfoil", "-o", "out", "--quiet"],
        ),
        row(
            "run",
            "the scanned case (an STL) with NeuralFoil's polars",
            0,
            &[&p("props/apcsf_10x4.7"), "--engine", "neuralfoil", "-o", "out", "--quiet"],
        ),
        row(
            "scan",
            "every station measured",
            0,
            &[&stl, "--stations", "0.3:0.9/4", "-o", "out"],
        ),
        row(
            "scan",
            "a station inside the hub",
            1,
            &[&stl, "--stations", "0.02,0.4,0.6", "-o", "out"],
        ),
        row("scan", "not a scan", 2, &[&cam, "-o", "out"]),
        row(
            "polar",
            "every angle",
            0,
            &[
                "--airfoil",
                "naca4412",
                "--re",
                "1e5",
                "--alpha",
                "-4:8:1",
                "--xfoil",
                &fake,
                "--no-cache",
            ],
        ),
        with(
            row(
                "polar",
                "XFOIL crashes",
                1,
                &[
                    "--airfoil",
                    "naca4412",
                    "--re",
                    "1e5",
                    "--alpha",
                    "-4:8:1",
                    "--xfoil",
                    &fake,
                    "--no-cache",
                ],
            ),
            ("FAKE_MODE", "x_crash_mid"),
        ),
        row(
            "polar",
            "a Reynolds number XFOIL cannot take",
            2,
            &["--airfoil", "naca4412", "--re", "1e300", "--no-cache"],
        ),
        row(
            "predict",
            "every point",
            0,
            &["--prop", &cam, "--rpm", "4000", "--j", "0:0.6:0.1"],
        ),
        row(
            "predict",
            "station solutions that do not converge (blades turned 60 deg back)",
            1,
            &["--prop", &cam, "--rpm", "3000", "--j", "0,0.5", "--dbeta=-60"],
        ),
        row(
            "predict",
            "APC's design file (PE0), its polars by NeuralFoil",
            0,
            &[
                "--prop",
                &p("props/apcsp_10x7/10x7-PERF.PE0"),
                "--rpm",
                "5000",
                "--j",
                "0:0.8:0.1",
                "--engine",
                "neuralfoil",
            ],
        ),
        row(
            "predict",
            "a UIUC geometry table that names no section",
            2,
            &[
                "--prop",
                &p("props/apcsf_10x4.7/apcsf_10x4.7_geom.txt"),
                "--rpm",
                "5000",
                "--engine",
                "neuralfoil",
            ],
        ),
        row(
            "predict",
            "a device as the prop file",
            2,
            &["--prop", "/dev/zero", "--rpm", "4000"],
        ),
        row(
            "compare",
            "a clean tunnel file",
            0,
            &["--prop", &cam, "--measured", &tunnel, "-o", "out"],
        ),
        row(
            "compare",
            "a row with a pressure of 1e200 dropped",
            1,
            &[
                "--prop",
                &tare("cam6x3.qprop"),
                "--measured",
                &p("tests/data/bad_inputs/diag_pressure_1e200.csv"),
                "-o",
                "out",
            ],
        ),
        row(
            "compare",
            "a missing file",
            2,
            &["--prop", &cam, "--measured", "nothing.csv", "-o", "out"],
        ),
        row(
            "diagnose",
            "a clean log",
            0,
            &[
                "--prop",
                &tare("cam6x3.qprop"),
                "--measured",
                &tare("cam6x3_steps.csv"),
                "-o",
                "out",
            ],
        ),
        row(
            "diagnose",
            "a row dropped",
            1,
            &[
                "--prop",
                &tare("cam6x3.qprop"),
                "--measured",
                &p("tests/data/bad_inputs/diag_pressure_1e200.csv"),
                "-o",
                "out",
            ],
        ),
        row(
            "diagnose",
            "an unknown effect",
            2,
            &[
                "--prop",
                &cam,
                "--measured",
                &tunnel,
                "--effects",
                "nosuch",
                "-o",
                "out",
            ],
        ),
        row(
            "validate",
            "no such directory",
            2,
            &[
                "--uiuc",
                "nothing",
                "--pe0",
                "nothing",
                "--airfoils",
                "nothing",
                "-o",
                "out",
            ],
        ),
        row("effects", "the list", 0, &[]),
        row(
            "effects",
            "a user-effect file that is not there",
            2,
            &["--user-effects", "nothing.toml"],
        ),
        row("synth", "measurements written", 0, &["--prop", &cam, "--out", "s.csv"]),
        row(
            "synth",
            "an unknown effect",
            2,
            &["--prop", &cam, "--effect", "nosuch", "--out", "s.csv"],
        ),
        row(
            "export",
            "a JSBSim propeller",
            0,
            &[
                "--to",
                "jsbsim",
                "--prop",
                &cam,
                "--rpm",
                "5000",
                "--j",
                "0:0.5:0.1",
                "-o",
                "sim",
            ],
        ),
        row(
            "export",
            "a J fit of static points",
            2,
            &["--to", "px4-sih", "--prop", &cam, "--rpm", "5000", "-o", "sim"],
        ),
        row(
            "export",
            "measurements' diameter with an exponent and its unit",
            0,
            &["--to", "jsbsim", "--measured", &tunnel, "--diameter", "1.524e-1m", "--ixx", "1e-5", "-o", "sim"],
        ),
        row(
            "export",
            "a diameter without its unit (metres or inches?)",
            2,
            &["--to", "jsbsim", "--measured", &tunnel, "--diameter", "6", "--ixx", "1e-5", "-o", "sim"],
        ),
        row(
            "export",
            "no blade",
            2,
            &["--to", "jsbsim", "--measured", &tunnel, "--diameter", "6in", "--blades", "0", "-o", "sim"],
        ),
        row(
            "export",
            "a moment of inertia of 1e300 kg m^2",
            2,
            &["--to", "jsbsim", "--measured", &tunnel, "--diameter", "6in", "--ixx=1e300", "-o", "sim"],
        ),
        row(
            "predict",
            "sub-zero air given after a space (--temp -10C)",
            0,
            &["--prop", &cam, "--rpm", "4000", "--temp", "-10C", "--pressure", "101325Pa"],
        ),
        row(
            "predict",
            "a negative drag factor reaches its range check",
            2,
            &["--prop", &cam, "--rpm", "4000", "--drag-factor", "-1"],
        ),
        row("prop", "a prop file", 0, &[&cam]),
        row("prop", "not a prop file", 2, &[&stl]),
        row("completions", "bash", 0, &["bash"]),
        row("completions", "an unknown shell", 2, &["nosh"]),
        row("man", "the page", 0, &[]),
        row("man", "an extra argument", 2, &["extra"]),
    ];
    for (j, code, outcome) in [
        ("0.5", 0, "every station fitted"),
        ("0,0.3", 1, "stations without a fit"),
    ] {
        let mut r = row("polars", outcome, code, &[]);
        r.args.extend(polars_args(j));
        rows.push(r);
    }
    rows.push(row(
        "polars",
        "a geometry that is not there",
        2,
        &[
            "--geometry",
            "nothing.qprop",
            "--airfoil",
            "naca4412",
            "--rpm",
            "6000",
            "--out-prop",
            "p.qprop",
        ],
    ));
    // A weights folder with the shipped input distribution and `make` writing its
    // nn-xlarge.npz, as a polars row that asks for NeuralFoil's weights from it (exit 2).
    let shipped = repo().join("crates/neuralfoil/weights");
    let mut weights_dirs = Vec::new(); // removed at the end of the test
    let mut weights_row = |what: &'static str, make: &dyn Fn(&Path)| {
        let guard = tempfile::tempdir().unwrap();
        let dir: &'static Path = Box::leak(guard.path().to_path_buf().into_boxed_path());
        weights_dirs.push(guard);
        std::fs::copy(
            shipped.join("scaled_input_distribution.npz"),
            dir.join("scaled_input_distribution.npz"),
        )
        .unwrap();
        make(&dir.join("nn-xlarge.npz"));
        let mut r = with(
            row("polars", what, 2, &["--engine", "neuralfoil"]),
            ("PROPBET_NEURALFOIL_WEIGHTS", dir.to_str().unwrap()),
        );
        r.args
            .extend(polars_args("0.5").into_iter().filter(|a| a != "--xfoil" && a != &fake));
        rows.push(r);
    };
    // NeuralFoil's weights of another size under this size's name (a renamed file).
    weights_row("NeuralFoil weights renamed to another size", &|f| {
        std::fs::copy(shipped.join("nn-xxsmall.npz"), f).unwrap();
    });
    // A 4 GB file under the weights' name (sparse: nothing is written), refused unread.
    weights_row("a 4 GB file as NeuralFoil's weights", &|f| {
        std::fs::File::create(f).unwrap().set_len(4 << 30).unwrap();
    });
    // validate's 0 and 1 take 25 s with the stand-in XFOIL: campaign::n18 runs it.

    let mut failures = Vec::new();
    let mut seen = std::collections::BTreeSet::new();
    for r in &rows {
        let t = tempfile::tempdir().unwrap();
        let mut cmd = bin();
        cmd.args(&r.args).current_dir(t.path());
        if let Some((k, v)) = r.env {
            cmd.env(k, v);
        }
        let o = cmd.output().unwrap();
        let e = stderr(&o);
        assert!(!e.contains("panicked"), "{} ({}): {e}", r.command, r.outcome);
        if o.status.code() != Some(r.code) {
            failures.push(format!(
                "{} ({}): exit {:?}, want {}: {e}",
                r.command,
                r.outcome,
                o.status.code(),
                r.code
            ));
        }
        if !help_codes(r.command).contains(&r.code) {
            failures.push(format!(
                "{}: its help does not list exit {} ({})",
                r.command, r.code, r.outcome
            ));
        }
        seen.insert((r.command, r.code));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    // Every code a help lists has a row (validate's 0 and 1 are campaign::n18's).
    for command in [
        "run",
        "scan",
        "polar",
        "polars",
        "predict",
        "compare",
        "diagnose",
        "effects",
        "synth",
        "export",
        "prop",
        "completions",
        "man",
    ] {
        for code in help_codes(command) {
            assert!(seen.contains(&(command, code)), "{command}: no row for exit {code}");
        }
    }
}
