//! `propbet export`: the flight-simulator files checked by their consumers and by an
//! independent computation from the prediction's own CSV. JSBSim (the Python package the setup
//! script installs into `.venv`) flies the exported propeller; the Gazebo and PX4 SIH values
//! are recomputed here from `propbet predict`'s table; data that cannot support an export are
//! refused, nothing written.

use std::path::{Path, PathBuf};
use std::process::Command;

use super::{cam6x3, col, read_csv, repo, run, stderr};

const SWEEP: [&str; 4] = ["--rpm", "4000,5000,6000", "--j", "0:0.6:0.05"];

fn export(dir: &Path, to: &str) -> std::process::Output {
    let prop = cam6x3();
    let mut args = vec!["export", "--to", to, "--prop", prop.to_str().unwrap()];
    args.extend(SWEEP);
    args.extend(["-o", "sim"]);
    let o = run(&args, dir);
    assert!(o.status.success(), "{}", stderr(&o));
    o
}

/// The (median, worst) thrust and torque differences a file's header states, in percent.
fn stated_fit(text: &str) -> [f64; 4] {
    let line = text
        .lines()
        .find(|l| l.contains("This file against those points"))
        .expect("a fit line");
    let nums: Vec<f64> = line
        .split(['(', ')', ',', ';', ' '])
        .zip(line.split(['(', ')', ',', ';', ' ']).skip(1))
        .filter(|(_, unit)| *unit == "%")
        .map(|(n, _)| n.parse().unwrap())
        .collect();
    [nums[0], nums[1], nums[2], nums[3]]
}

/// The prediction's table: (rpm, J, thrust, torque, ct, cp) per row.
fn predicted(dir: &Path) -> Vec<[f64; 6]> {
    let prop = cam6x3();
    let mut args = vec!["predict", "--prop", prop.to_str().unwrap()];
    args.extend(SWEEP);
    args.extend(["-o", "sweep.csv"]);
    let o = run(&args, dir);
    assert!(o.status.success(), "{}", stderr(&o));
    let (h, rows) = read_csv(&dir.join("sweep.csv"));
    let c = ["rpm", "j", "thrust_n", "torque_nm", "ct", "cp"].map(|n| col(&h, n));
    rows.iter().map(|r| c.map(|k| r[k].parse().unwrap())).collect()
}

fn value(text: &str, open: &str, close: &str) -> f64 {
    let a = text.find(open).unwrap_or_else(|| panic!("no {open}")) + open.len();
    let b = a + text[a..].find(close).unwrap();
    text[a..b].trim().parse().unwrap()
}

#[test]
fn gazebo_constants_are_the_prediction_static_thrust_and_torque() {
    let dir = tempfile::tempdir().unwrap();
    export(dir.path(), "gazebo");
    let sdf = std::fs::read_to_string(dir.path().join("sim/gazebo_motor_model.sdf")).unwrap();
    let kf = value(&sdf, "<motorConstant>", "</motorConstant>");
    let km = value(&sdf, "<momentConstant>", "</momentConstant>");
    // Recomputed from the CSV: T/omega^2 and Q/T at each static row, and the worst difference
    // the constants make, which the header states.
    let rows: Vec<[f64; 6]> = predicted(dir.path()).into_iter().filter(|r| r[1] == 0.0).collect();
    assert_eq!(rows.len(), 3);
    let (mut worst_t, mut worst_q) = (0.0f64, 0.0f64);
    for r in &rows {
        let w2 = (r[0] * std::f64::consts::TAU / 60.0).powi(2);
        worst_t = worst_t.max((kf * w2 / r[2] - 1.0).abs());
        worst_q = worst_q.max((km * kf * w2 / r[3] - 1.0).abs());
        let (kf_row, km_row) = (r[2] / w2, r[3] / r[2]);
        assert!(
            (kf / kf_row - 1.0).abs() < 0.01,
            "motorConstant {kf} against {kf_row} at {} rpm",
            r[0]
        );
        assert!(
            (km / km_row - 1.0).abs() < 0.08,
            "momentConstant {km} against {km_row} at {} rpm",
            r[0]
        );
    }
    let fit = stated_fit(&sdf);
    assert!((fit[1] - 100.0 * worst_t).abs() < 0.06, "{fit:?} vs {worst_t}");
    assert!((fit[3] - 100.0 * worst_q).abs() < 0.06, "{fit:?} vs {worst_q}");
    assert!(sdf.contains("<maxRotVelocity>628.3</maxRotVelocity>"), "{sdf}");
}

#[test]
fn px4_sih_parameters_reproduce_the_prediction_as_stated() {
    let dir = tempfile::tempdir().unwrap();
    export(dir.path(), "px4-sih");
    let text = std::fs::read_to_string(dir.path().join("sim/px4_sih.params")).unwrap();
    let param = |name: &str| -> f64 {
        let l = text
            .lines()
            .find(|l| l.starts_with(&format!("param set-default {name} ")))
            .unwrap_or_else(|| panic!("no {name} in\n{text}"));
        l.rsplit(' ').next().unwrap().parse().unwrap()
    };
    assert!((param("SIH_F_DIA_INCH") - 6.0).abs() < 1e-6);
    assert_eq!(param("SIH_F_RPM_MAX"), 6000.0);
    assert!(param("SIH_F_CT2") <= 0.0 && param("SIH_F_CP2") <= 0.0 && param("SIH_F_CT0") > 0.0);
    // PX4's Thruster: CT(J) = max(CT0 + CT1 J + CT2 J^2, 0), torque = CP/(2 pi) rho n^2 D^5.
    let ct = |j: f64| (param("SIH_F_CT0") + param("SIH_F_CT1") * j + param("SIH_F_CT2") * j * j).max(0.0);
    let cp = |j: f64| (param("SIH_F_CP0") + param("SIH_F_CP1") * j + param("SIH_F_CP2") * j * j).max(0.0);
    let rows = predicted(dir.path());
    let ct_max = rows.iter().map(|r| r[4]).fold(0.0, f64::max);
    let (rho, d): (f64, f64) = (1.225, 6.0 * 0.0254);
    let mut errs_t = Vec::new();
    let mut errs_q = Vec::new();
    for r in rows.iter().filter(|r| r[4] >= 0.25 * ct_max) {
        let n = r[0] / 60.0;
        let t = ct(r[1]) * rho * n * n * d.powi(4);
        let q = cp(r[1]) / std::f64::consts::TAU * rho * n * n * d.powi(5);
        errs_t.push((t / r[2] - 1.0).abs());
        errs_q.push((q / r[3] - 1.0).abs());
    }
    let worst = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    let fit = stated_fit(&text);
    assert_eq!(errs_t.len(), 27);
    assert!(
        (fit[1] - 100.0 * worst(&errs_t)).abs() < 0.06,
        "{fit:?} vs {}",
        worst(&errs_t)
    );
    assert!(
        (fit[3] - 100.0 * worst(&errs_q)).abs() < 0.06,
        "{fit:?} vs {}",
        worst(&errs_q)
    );
    // The quadratic carries the prediction within a few percent (SIH has no RPM dependence).
    assert!(fit[1] < 3.0 && fit[3] < 10.0, "{fit:?}");
}

fn python() -> PathBuf {
    let p = repo().join(".venv/bin/python");
    assert!(
        p.exists(),
        "{}: no Python environment; scripts/setup.sh makes it (JSBSim from the Python registry)",
        p.display()
    );
    p
}

/// propbet's thrust and power at (rpm, V) in air of density rho, for the model `model` (prop
/// file and its flags).
fn propbet_point(dir: &Path, model: &[String], rpm: f64, v: f64, rho: f64) -> (f64, f64) {
    let mut args: Vec<String> = vec!["predict".into()];
    args.extend(model.iter().cloned());
    for (k, x) in [("--rpm", rpm), ("--v", v), ("--rho", rho)] {
        args.extend([k.to_string(), format!("{x}")]);
    }
    args.extend(["--format".into(), "json".into()]);
    let argv: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = run(&argv, dir);
    assert!(o.status.success(), "{}", stderr(&o));
    let doc: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let p = &doc["points"][0];
    (p["thrust"].as_f64().unwrap(), p["power"].as_f64().unwrap())
}

/// Exports `model` at `rpms` x J 0..0.6 for JSBSim and flies it at three (RPM, J) points:
/// propbet's shaft power there is what the test gives JSBSim's engine; JSBSim finds its own
/// steady RPM and thrust, which must be propbet's at that RPM within the fit the export
/// reported (plus 0.5 % for linear interpolation between table rows and JSBSim's integration).
fn jsbsim_flies(model: &[String], rpms: &str, d: f64, targets: [(f64, f64); 3]) {
    let dir = tempfile::tempdir().unwrap();
    let mut args: Vec<String> = vec!["export".into(), "--to".into(), "jsbsim".into()];
    args.extend(model.iter().cloned());
    args.extend(["--rpm", rpms, "--j", "0:0.6:0.025", "-o", "sim"].map(String::from));
    let argv: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = run(&argv, dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let file = std::fs::read_dir(dir.path().join("sim"))
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    let text = std::fs::read_to_string(&file).unwrap();
    let fit = stated_fit(&text);
    let rho0 = 1.1904; // JSBSim's standard atmosphere at 1000 ft, where the bench flies.
    let targets: Vec<(f64, f64)> = targets.iter().map(|&(rpm, j)| (rpm, j * rpm / 60.0 * d)).collect();
    let cases: Vec<[f64; 2]> = targets
        .iter()
        .map(|&(rpm, v)| [propbet_point(dir.path(), model, rpm, v, rho0).1, v])
        .collect();
    let o = Command::new(python())
        .arg(repo().join("tests/e2e/jsbsim_run.py"))
        .arg(dir.path().join("jsbsim"))
        .arg(&file)
        .arg(serde_json::to_string(&cases).unwrap())
        .output()
        .unwrap();
    assert!(o.status.success(), "JSBSim: {}", String::from_utf8_lossy(&o.stderr));
    let last = o.stdout.rsplit(|b| *b == b'\n').find(|l| !l.is_empty()).unwrap();
    let runs: Vec<serde_json::Value> = serde_json::from_slice(last).unwrap();
    for (run, (rpm0, _)) in runs.iter().zip(targets) {
        let g = |k: &str| run[k].as_f64().unwrap();
        assert!(run["steady"].as_bool().unwrap(), "{run}");
        assert!(
            (g("rpm") / rpm0 - 1.0).abs() < 0.03,
            "JSBSim settles at {} rpm for {rpm0}: {run}",
            g("rpm")
        );
        let (t, p) = propbet_point(dir.path(), model, g("rpm"), g("v_m_s"), g("rho"));
        let (dt, dp) = ((g("thrust_n") / t - 1.0).abs(), (g("power_w") / p - 1.0).abs());
        eprintln!(
            "{}: JSBSim at {:.0} rpm, {:.2} m/s: thrust {:+.2} %, power {:+.2} % of propbet's (fit {fit:?})",
            file.display(),
            g("rpm"),
            g("v_m_s"),
            100.0 * (g("thrust_n") / t - 1.0),
            100.0 * (g("power_w") / p - 1.0)
        );
        assert!(
            100.0 * dt <= fit[1] + 0.5,
            "thrust {} against propbet's {t}: fit {fit:?}",
            g("thrust_n")
        );
        assert!(
            100.0 * dp <= fit[3] + 0.5,
            "power {} against propbet's {p}: fit {fit:?}",
            g("power_w")
        );
    }
}

#[test]
fn jsbsim_flies_the_exported_propeller_as_propbet_predicts_it() {
    // A prop file's QPROP law: its drag's Reynolds exponent makes CP change with RPM, which the
    // export carries in CP_MACH.
    let cam = vec!["--prop".to_string(), cam6x3().display().to_string()];
    jsbsim_flies(
        &cam,
        "4000,5000,6000",
        0.1524,
        [(4500.0, 0.0), (5000.0, 0.2), (5800.0, 0.35)],
    );
    // The APC 10x4.7 with its shipped XFOIL tables (the default model: tables, Snel's
    // rotational augmentation, drag factor 1.25).
    let apc = repo().join("props/apcsf_10x4.7");
    let apc = vec![
        "--prop".to_string(),
        apc.join("apcsf_10x4.7.qprop").display().to_string(),
        "--polars".to_string(),
        apc.join("apcsf_10x4.7.polars.json").display().to_string(),
    ];
    jsbsim_flies(
        &apc,
        "4000,5000,6000",
        0.254,
        [(4300.0, 0.0), (5000.0, 0.25), (5700.0, 0.4)],
    );
}

#[test]
fn exports_the_data_cannot_support_are_refused_with_what_is_missing() {
    let dir = tempfile::tempdir().unwrap();
    let prop = cam6x3();
    let p = prop.to_str().unwrap();
    // Static-only: the J fits and the map are refused, and nothing is written.
    for (to, says) in [
        ("px4-sih", "only static points (J = 0)"),
        ("jsbsim", "only static points (J = 0)"),
        ("gazebo,map", "only static points (J = 0)"),
    ] {
        let o = run(
            &["export", "--to", to, "--prop", p, "--rpm", "4000,6000", "-o", "out"],
            dir.path(),
        );
        assert_eq!(o.status.code(), Some(2), "{to}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "{to}: {}", stderr(&o));
        assert!(!dir.path().join("out").exists(), "{to}: something written");
    }
    // One RPM is no map.
    let o = run(
        &[
            "export",
            "--to",
            "map",
            "--prop",
            p,
            "--rpm",
            "5000",
            "--j",
            "0:0.5:0.1",
            "-o",
            "out",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("2 or more RPMs") && stderr(&o).contains("5000 rpm"),
        "{}",
        stderr(&o)
    );
    // No static point for Gazebo.
    let o = run(
        &[
            "export",
            "--to",
            "gazebo",
            "--prop",
            p,
            "--rpm",
            "5000",
            "--j",
            "0.2:0.5:0.1",
            "-o",
            "out",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("zero airspeed"), "{}", stderr(&o));
    // A static thrust-stand log: Gazebo's constants, no CT(J).
    let log = repo().join("tests/data/thrust_stand/series1585_newton_steps.csv");
    let l = log.to_str().unwrap();
    let from_log = |to: &str| {
        run(
            &["export", "--to", to, "--measured", l, "--diameter", "10in", "-o", "out"],
            dir.path(),
        )
    };
    let o = from_log("px4-sih");
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("only static points (J = 0)"), "{}", stderr(&o));
    let o = from_log("gazebo");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.path().join("out/gazebo_motor_model.sdf").exists());
    // Measurements without a diameter, JSBSim without an inertia.
    let o = run(&["export", "--to", "gazebo", "--measured", l, "-o", "out2"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--diameter"), "{}", stderr(&o));
}

#[test]
fn wind_tunnel_measurements_are_smoothed_into_every_export() {
    let dir = tempfile::tempdir().unwrap();
    let data = repo().join("tests/data/hidden_effects/no_effect");
    let (csv, prop) = (data.join("cam6x3_tunnel.csv"), data.join("cam6x3.qprop"));
    let o = run(
        &[
            "export",
            "--to",
            "all",
            "--measured",
            csv.to_str().unwrap(),
            "--prop",
            prop.to_str().unwrap(),
            "-o",
            "sim",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let map: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("sim/map.json")).unwrap()).unwrap();
    let rpms: Vec<f64> = map["curves"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["rpm"].as_f64().unwrap())
        .collect();
    assert_eq!(rpms.len(), 3, "{rpms:?}");
    assert!(map["note"]
        .as_str()
        .unwrap()
        .contains("least-squares polynomial of degree 3"));
    // The smoothing's residual is the noise of the synthetic measurements (about 1 %), stated.
    let worst = map["fit"]["thrust"]["largest"].as_f64().unwrap();
    assert!(worst > 0.001 && worst < 0.03, "{worst}");
    let xml = std::fs::read_to_string(dir.path().join("sim/Graupner_CAM_6x3_folder.xml")).unwrap();
    assert!(xml.contains("CT_MACH") && xml.contains("smoothed"), "{xml}");
}
