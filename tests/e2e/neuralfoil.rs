//! The NeuralFoil engine from the command line: polars without XFOIL, `auto` with an XFOIL
//! that crashes, the engine and confidence of every point, weights that cannot be used.

use std::path::Path;

use super::polars::crashing_xfoil;
use super::{bin, repo, run_or_hang, stderr};

/// `--engine neuralfoil` needs no XFOIL (the one given crashes and is never started) and makes
/// every station's polars, each point listed as NeuralFoil's with its confidence; `--engine
/// auto` with that crashing XFOIL takes every polar from NeuralFoil instead of failing.
#[test]
fn the_neuralfoil_engine_needs_no_xfoil_and_auto_falls_back_to_it() {
    let dir = tempfile::tempdir().unwrap();
    let fake = crashing_xfoil(dir.path());
    for engine in ["neuralfoil", "auto"] {
        let out = dir.path().join(engine);
        std::fs::create_dir_all(&out).unwrap();
        let mut args = blade_polars(engine, &out);
        args.extend(["--no-cache", "--xfoil", fake.to_str().unwrap()].map(String::from));
        let o = run_or_hang(&args.iter().map(String::as_str).collect::<Vec<_>>(), dir.path());
        assert!(matches!(o.status.code(), Some(0 | 1)), "{engine}: {}", stderr(&o));
        let j: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("polars.json")).unwrap()).unwrap();
        let stations = j["stations"].as_array().unwrap();
        assert_eq!(stations.len(), 25, "{engine}");
        for s in stations {
            for p in s["polars"].as_array().unwrap() {
                let n = p["points"].as_array().unwrap().len();
                assert!(n >= 20, "{engine}: {n} points");
                assert_eq!(
                    p["neuralfoil"].as_array().unwrap().len(),
                    n,
                    "{engine}: every point NeuralFoil's"
                );
            }
        }
        assert!(std::fs::read_to_string(out.join("fit.qprop")).unwrap().lines().count() > 25);
    }
    // Weights from a folder of the user's: a corrupt or missing file is named, exit 2.
    let weights = dir.path().join("weights");
    std::fs::create_dir_all(&weights).unwrap();
    std::fs::write(weights.join("nn-xlarge.npz"), b"PK\x03\x04 not a zip").unwrap();
    let stats = "scaled_input_distribution.npz";
    std::fs::copy(
        repo().join("crates/neuralfoil/weights").join(stats),
        weights.join(stats),
    )
    .unwrap();
    let polar = [
        "polar",
        "--airfoil",
        "naca4412",
        "--re",
        "1e5",
        "--engine",
        "neuralfoil",
        "--quiet",
    ];
    for (what, size) in [("not NeuralFoil's weights", "xlarge"), ("cannot read", "large")] {
        let o = bin()
            .args(polar)
            .args(["--neuralfoil-size", size])
            .env("PROPBET_NEURALFOIL_WEIGHTS", &weights)
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let named = weights.join(if size == "xlarge" {
            "nn-xlarge.npz"
        } else {
            "nn-large.npz"
        });
        assert!(
            stderr(&o).contains(&format!("{}: {what}", named.display())),
            "{}",
            stderr(&o)
        );
    }
    // One section's polar table says which engine made each point, and how sure NeuralFoil is.
    let o = run_or_hang(&polar, dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let csv = String::from_utf8(o.stdout).unwrap();
    let mut lines = csv.lines();
    assert!(lines.next().unwrap().ends_with(",engine,confidence"), "{csv}");
    let rows: Vec<&str> = lines.collect();
    assert!(rows.len() > 20, "{csv}");
    for row in rows {
        let cols: Vec<&str> = row.split(',').collect();
        assert_eq!(cols[10], "neuralfoil", "{row}");
        let c: f64 = cols[11].parse().unwrap();
        assert!((0.0..=1.0).contains(&c), "{row}");
    }
}

/// `auto` on a machine without XFOIL (none given, none on PATH) makes NeuralFoil's polars and
/// says so; an XFOIL given that is not there stays an error.
#[test]
fn auto_without_xfoil_is_neuralfoil_and_a_missing_given_xfoil_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let args = blade_polars("auto", dir.path());
    let o = bin()
        .args(&args)
        .env("PATH", dir.path())
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    let polars = dir.path().join("polars.json");
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&polars).unwrap()).unwrap();
    for s in j["stations"].as_array().unwrap() {
        for p in s["polars"].as_array().unwrap() {
            assert_eq!(
                p["neuralfoil"].as_array().unwrap().len(),
                p["points"].as_array().unwrap().len()
            );
        }
    }
    let o = bin()
        .args(&args)
        .args(["--xfoil", "/nonexistent/xfoil"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("/nonexistent/xfoil"), "{}", stderr(&o));
}

/// `propbet polars` of the 25-station benchmark blade (NACA 4412, 6000 rpm static) with
/// `engine`, writing `fit.qprop` and `polars.json` into `out`.
fn blade_polars(engine: &str, out: &Path) -> Vec<String> {
    let blade = repo().join("benchsuite/blade25.qprop");
    let path = |f: &str| out.join(f).to_str().unwrap().to_string();
    let mut v: Vec<String> = ["polars", "--geometry", blade.to_str().unwrap(), "--airfoil", "naca4412"]
        .map(String::from)
        .to_vec();
    v.extend(["--rpm", "6000", "--engine", engine, "--quiet"].map(String::from));
    v.extend([
        "--out-prop".to_string(),
        path("fit.qprop"),
        "--out-polars".into(),
        path("polars.json"),
    ]);
    v
}
