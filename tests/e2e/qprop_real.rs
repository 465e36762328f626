//! The real QPROP 1.22, built from Drela's source (`../shared/reference/qprop/src`, gfortran
//! from the setup script) into a temporary folder, beside propbet: solver parity on Drela's own
//! example props, and the QPROP file a run exports (`predict/qprop_export.qprop`) run through
//! the real program against propbet's prediction and against the fidelity the run reports.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use super::{col, read_csv, repo, run, stderr};

pub(super) fn qprop_source() -> PathBuf {
    repo().join("../shared/reference/qprop")
}

/// QPROP 1.22 built once per test binary (BUILD.md's one gfortran line) in a temporary folder
/// that lives as long as the process.
pub(super) fn qprop() -> &'static Path {
    static EXE: OnceLock<PathBuf> = OnceLock::new();
    EXE.get_or_init(|| {
        let dir = Box::leak(Box::new(tempfile::tempdir().unwrap()));
        let src = qprop_source().join("src");
        let files = [
            "qprop.f", "bnsolv.f", "cdfun.f", "gvcalc.f", "io.f", "motor.f", "spline.f", "tqcalc.f", "tpdes.f",
            "qcget.f",
        ];
        let o = Command::new("gfortran")
            .args(["-O2", "-fdefault-real-8", "-std=legacy", "-o"])
            .arg(dir.path().join("qprop"))
            .args(files.iter().map(|f| src.join(f)))
            .current_dir(dir.path())
            .output()
            .expect("gfortran (scripts/setup.sh installs it)");
        assert!(o.status.success(), "gfortran: {}", String::from_utf8_lossy(&o.stderr));
        dir.path().join("qprop")
    })
}

/// QPROP's thrust and torque for `prop` at one (V, rpm), in air (rho, mu, a).
fn qprop_point(prop: &Path, v: f64, rpm: f64, air: (f64, f64, f64)) -> (f64, f64) {
    let work = tempfile::tempdir().unwrap();
    std::fs::copy(prop, work.path().join("prop")).unwrap();
    std::fs::write(
        work.path().join("qcon.def"),
        format!("{}\n{}\n{}\n", air.0, air.1, air.2),
    )
    .unwrap();
    let o = Command::new(qprop())
        .args(["prop", "null", &format!("{v}"), &format!("{rpm}")])
        .current_dir(work.path())
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    // The result is the first line of numbers after the column header (a comment line in a
    // single-point run; QPROP's "GVCALC: Not converged" lines may come between).
    let row: Vec<f64> = text
        .lines()
        .skip_while(|l| !l.contains("V(m/s)"))
        .skip(1)
        .filter(|l| !l.contains("GVCALC"))
        .map(|l| -> Vec<f64> {
            l.trim_start_matches([' ', '#'])
                .split_whitespace()
                .filter_map(|w| w.parse().ok())
                .collect()
        })
        .find(|v: &Vec<f64>| v.len() >= 5)
        .unwrap_or_else(|| panic!("no QPROP result for {} at V {v} rpm {rpm}: {text}", prop.display()));
    (row[3], row[4])
}

/// QPROP prints 4 significant digits: a relative difference below this is agreement.
const PRINTED: f64 = 1.5e-3;

/// propbet's thrust and torque for `prop` read as QPROP 1.22 reads it, at one (V, rpm) in
/// standard air (QPROP's defaults), `dir` the working folder.
fn propbet_qprop_compat_point(prop: &str, v: f64, rpm: f64, dir: &Path) -> (f64, f64) {
    let out = dir.join(format!("p_{v}_{rpm}.csv"));
    let o = run(
        &[
            "predict",
            "--prop",
            prop,
            "--qprop-compat",
            "--rpm",
            &format!("{rpm}"),
            "--v",
            &format!("{v}"),
            "--out",
            out.to_str().unwrap(),
        ],
        dir,
    );
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    let (h, rows) = read_csv(&out);
    (
        rows[0][col(&h, "thrust_n")].parse().unwrap(),
        rows[0][col(&h, "torque_nm")].parse().unwrap(),
    )
}

#[test]
fn propbet_reads_and_solves_drelas_example_props_as_qprop_does() {
    let runs = qprop_source().join("runs");
    let t = tempfile::tempdir().unwrap();
    let mut worst: f64 = 0.0;
    for (prop, points) in [
        ("cam6x3", [(0.0, 8000.0), (8.0, 14000.0), (15.0, 20000.0)]),
        ("apc8x6", [(0.0, 6000.0), (10.0, 6000.0), (20.0, 9000.0)]),
        ("apc14x10e", [(0.0, 4000.0), (12.0, 6000.0), (20.0, 7000.0)]),
        ("cam6x7", [(0.0, 8000.0), (10.0, 12000.0), (20.0, 14000.0)]),
    ] {
        for (v, rpm) in points {
            let (tq, qq) = qprop_point(&runs.join(prop), v, rpm, (1.225, 1.78e-5, 340.0));
            let p = runs.join(prop).display().to_string();
            let (tp, qp) = propbet_qprop_compat_point(&p, v, rpm, t.path());
            let (dt, dq) = (
                (tp - tq).abs() / tq.abs().max(1e-3),
                (qp - qq).abs() / qq.abs().max(1e-5),
            );
            worst = worst.max(dt).max(dq);
            assert!(
                dt < PRINTED && dq < PRINTED,
                "{prop} V {v} rpm {rpm}: QPROP {tq} N {qq} N m, propbet {tp} N {qp} N m"
            );
        }
    }
    eprintln!(
        "Drela's example props: propbet --qprop-compat within {:.3} % of QPROP 1.22",
        100.0 * worst
    );
}

/// Runs a shipped case and checks its exported QPROP file with the real program at every point
/// of the sweep where the run's own fidelity check looks (the scored window): real QPROP agrees with propbet's QPROP-exact reading of the file (so the report's
/// fidelity numbers are QPROP's), and with the prediction within `within` (median, worst).
fn exported_file_through_real_qprop(case: &str, extra: &[&str], within: Option<(f64, f64)>) {
    exported_case_through_real_qprop(&repo().join("props").join(case), extra, within);
}

/// [`exported_file_through_real_qprop`] for the case in `dir`.
fn exported_case_through_real_qprop(dir: &Path, extra: &[&str], within: Option<(f64, f64)>) {
    let case = dir.file_name().unwrap().to_string_lossy().to_string();
    let t = tempfile::tempdir().unwrap();
    let mut args = vec![
        "run".to_string(),
        dir.display().to_string(),
        "-o".into(),
        "out".into(),
        "--quiet".into(),
    ];
    args.extend(extra.iter().map(|s| s.to_string()));
    let argv: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = run(&argv, t.path());
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    let out = t.path().join("out");
    let file = out.join("predict/qprop_export.qprop");
    // A scanned blade's own accuracy travels in the export, on a comment line QPROP skips.
    let text = std::fs::read_to_string(&file).unwrap();
    assert_eq!(
        text.contains("# geometry accuracy:"),
        out.join("scan/prop.qprop").exists(),
        "{text}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let fid = &summary["qprop_export"]["fidelity"];
    let reported = |k: &str, i: usize| fid[k][["median", "largest"][i]].as_f64().unwrap();
    let (h, rows) = read_csv(&out.join("predict/sweep.csv"));
    let get = |r: &Vec<String>, c: &str| -> f64 { r[col(&h, c)].parse().unwrap() };
    let rho = get(&rows[0], "rho_kg_m3");
    // The scored window, as compare draws it: below 85 % of each RPM's zero-thrust J (the
    // prediction's, linear between the last positive and first non-positive CT).
    let j0 = |rpm: f64| -> f64 {
        let mut c: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| get(r, "rpm") == rpm)
            .map(|r| (get(r, "j"), get(r, "ct")))
            .collect();
        c.sort_by(|a, b| a.0.total_cmp(&b.0));
        c.windows(2)
            .find(|w| w[0].1 > 0.0 && w[1].1 <= 0.0)
            .map_or(f64::INFINITY, |w| {
                w[0].0 + w[0].1 / (w[0].1 - w[1].1) * (w[1].0 - w[0].0)
            })
    };
    let (mut dt, mut dq) = (Vec::new(), Vec::new());
    for r in rows
        .iter()
        .filter(|r| get(r, "thrust_n") > 0.0 && get(r, "torque_nm") > 0.0 && get(r, "j") < 0.85 * j0(get(r, "rpm")))
    {
        let (tq, qq) = qprop_point(&file, get(r, "v_m_s"), get(r, "rpm"), (rho, 1.78e-5, 340.0));
        dt.push((tq / get(r, "thrust_n") - 1.0).abs());
        dq.push((qq / get(r, "torque_nm") - 1.0).abs());
    }
    let stat = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        let n = v.len();
        let median = if n % 2 == 1 {
            v[n / 2]
        } else {
            0.5 * (v[n / 2 - 1] + v[n / 2])
        };
        [median, v[n - 1]]
    };
    let (st, sq) = (stat(&mut dt), stat(&mut dq));
    eprintln!(
        "{case}: real QPROP 1.22 on the exported file: thrust {:.2} % median, {:.2} % worst; torque {:.2} %, {:.2} % over {} points (the run reported {:.2} / {:.2} and {:.2} / {:.2})",
        100.0 * st[0], 100.0 * st[1], 100.0 * sq[0], 100.0 * sq[1], dt.len(),
        100.0 * reported("thrust", 0), 100.0 * reported("thrust", 1), 100.0 * reported("torque", 0), 100.0 * reported("torque", 1)
    );
    assert_eq!(dt.len() as u64, fid["points"].as_u64().unwrap());
    for (k, s) in [("thrust", st), ("torque", sq)] {
        for (i, real) in s.iter().enumerate() {
            assert!(
                (real - reported(k, i)).abs() < PRINTED,
                "{case} {k}: real QPROP {real} vs reported {}",
                reported(k, i)
            );
        }
    }
    if let Some((median, worst)) = within {
        assert!(
            st[0] <= median && sq[0] <= median && st[1] <= worst && sq[1] <= worst,
            "{case}: {st:?} {sq:?}"
        );
    }
}

#[test]
fn the_photofoil_export_through_real_qprop_is_the_prediction() {
    // A QPROP-law prop file without tables: the export keeps its coefficients (REref moved
    // exactly), so QPROP gives the prediction to its printed digits.
    exported_file_through_real_qprop("photofoil_8x4.5", &[], Some((PRINTED, PRINTED)));
}

/// Every UIUC geometry table of the shared data, as a case's blade (its stations end at
/// r/R = 1.00, whose radius the export once read back a rounding beyond the tip), exports to a
/// QPROP file the real QPROP 1.22 reads and solves as propbet reports.
#[test]
fn every_uiuc_geometry_exports_to_a_file_real_qprop_reads() {
    let uiuc = repo().join("../shared/data/uiuc");
    let mut tables: Vec<PathBuf> = std::fs::read_dir(&uiuc)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.to_string_lossy().ends_with("_geom.txt"))
        .collect();
    tables.sort();
    assert!(tables.len() >= 13, "{tables:?}");
    let t = tempfile::tempdir().unwrap();
    for table in &tables {
        let name = table.file_name().unwrap().to_string_lossy().replace("_geom.txt", "");
        let dir = t.path().join(&name);
        std::fs::create_dir(&dir).unwrap();
        std::fs::copy(table, dir.join("geom.txt")).unwrap();
        // The table's diameter is in UIUC's file name: the copy keeps it.
        std::fs::rename(dir.join("geom.txt"), dir.join(table.file_name().unwrap())).unwrap();
        std::fs::write(
            dir.join("case.toml"),
            format!(
                "name = \"{name}\"\n[geometry]\nprop = \"{}\"\n[polars]\nairfoil = \"e63\"\n[sweep]\nrpm = \"5000\"\nj = \"0.3:0.9:0.1\"\n",
                table.file_name().unwrap().to_string_lossy()
            ),
        )
        .unwrap();
        exported_case_through_real_qprop(&dir, &["--engine", "neuralfoil"], None);
    }
}

#[test]
#[ignore = "slow: the default case with real XFOIL (run by scripts/test.sh)"]
fn the_default_case_export_through_real_qprop_gives_the_reported_fidelity() {
    let cache = tempfile::tempdir().unwrap();
    exported_file_through_real_qprop("apcsf_10x4.7", &["--cache", cache.path().to_str().unwrap()], None);
}
