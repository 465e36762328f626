//! The uncertainty band end to end: `predict --band`'s columns, the sections' transition that
//! tabulated polars add to it, and the geometry's own accuracy a scan's prop file carries.

use super::{cam6x3, col, read_csv, repo, run, stderr};

/// `--band`: the uncertainty band's six columns after the others, which stay as they are
/// without it; each band holds its value, and the same band in JSON.
#[test]
fn predict_gives_the_uncertainty_band() {
    let dir = tempfile::tempdir().unwrap();
    let prop = cam6x3();
    let sweep = |extra: &[&str], out: &str| {
        let mut args = vec!["predict", "--prop", prop.to_str().unwrap(), "--rpm", "4000,6000"];
        args.extend(["--j", "0:0.4:0.1", "--out", out]);
        args.extend(extra);
        let o = run(&args, dir.path());
        assert!(o.status.success(), "{}", stderr(&o));
    };
    sweep(&[], "plain.csv");
    sweep(&["--band"], "band.csv");
    sweep(&["--band", "--format", "json"], "band.json");
    let (h0, plain) = read_csv(&dir.path().join("plain.csv"));
    let (h, rows) = read_csv(&dir.path().join("band.csv"));
    assert_eq!(h[..h0.len()], h0[..]);
    assert_eq!(h[h0.len()..], ["ct_lo", "ct_hi", "cp_lo", "cp_hi", "eta_lo", "eta_hi"]);
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("band.json")).unwrap()).unwrap();
    for (i, (r, p)) in rows.iter().zip(&plain).enumerate() {
        assert_eq!(r[..h0.len()], p[..]);
        let v = |k: &str| r[col(&h, k)].parse::<f64>().unwrap();
        for q in ["ct", "cp"] {
            let (lo, x, hi) = (v(&format!("{q}_lo")), v(q), v(&format!("{q}_hi")));
            // Blade angle ±0.5°, chord ±6 %, drag ±20 %: a few per cent of CT at least.
            assert!(lo < x && x < hi && (hi - lo) / x > 0.02, "{q} row {i}: {r:?}");
            let json = doc["band"][i][q]["hi"].as_f64().unwrap();
            assert!((json / hi - 1.0).abs() < 1e-6, "{q} row {i}: {json} vs {hi}");
        }
    }
}

/// With tabulated polars the band has a fourth source, the sections' transition (the tables at
/// Ncrit 3 tripped at mid-chord and at Ncrit 7, made from NeuralFoil's difference): the same
/// tables without those widen no band and narrow some.
#[test]
fn tabulated_polars_add_the_sections_transition_to_the_band() {
    let dir = tempfile::tempdir().unwrap();
    let geometry = repo().join("props/apcsf_10x4.7/apcsf_10x4.7_geometry.qprop");
    let polars = [
        "polars",
        "--geometry",
        geometry.to_str().unwrap(),
        "--airfoil",
        "naca4412",
        "--rpm",
        "4000,6000",
        "--j",
        "0,0.3,0.6",
        "--engine",
        "neuralfoil",
        "--out-prop",
        "p.qprop",
        "--out-polars",
        "with.json",
    ];
    let o = run(&polars, dir.path());
    assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
    let mut doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("with.json")).unwrap()).unwrap();
    let stations = doc["stations"].as_array_mut().unwrap();
    assert!(stations.iter().all(|s| s["band"]
        .as_array()
        .is_some_and(|b| b.len() == 2 * s["polars"].as_array().unwrap().len())));
    for s in stations.iter_mut() {
        s.as_object_mut().unwrap().remove("band");
    }
    std::fs::write(dir.path().join("without.json"), serde_json::to_string(&doc).unwrap()).unwrap();
    let width = |tables: &str| {
        let out = format!("{tables}.csv");
        let args = [
            "predict",
            "--prop",
            "p.qprop",
            "--polars",
            tables,
            "--rpm",
            "5000",
            "--j",
            "0:0.5:0.1",
            "--band",
            "--out",
            &out,
        ];
        let o = run(&args, dir.path());
        assert!(o.status.code().is_some_and(|c| c < 2), "{}", stderr(&o));
        let (h, rows) = read_csv(&dir.path().join(&out));
        let v = |r: &Vec<String>, k: &str| r[col(&h, k)].parse::<f64>().unwrap();
        rows.iter().map(|r| v(r, "ct_hi") - v(r, "ct_lo")).collect::<Vec<f64>>()
    };
    let (with, without) = (width("with.json"), width("without.json"));
    assert!(with.iter().zip(&without).all(|(a, b)| a >= b), "{with:?} {without:?}");
    assert!(
        with.iter().zip(&without).any(|(a, b)| a > &(1.05 * b)),
        "{with:?} {without:?}"
    );
}

/// A prop file's own geometry accuracy (the comment line a scan writes) adds to the band's
/// blade angle and chord in root-sum-square: a coarse one widens every band, a fine one leaves
/// it as the stated ranges make it; a line that cannot be read is an error naming it.
#[test]
fn a_prop_files_own_geometry_accuracy_widens_its_band() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(cam6x3()).unwrap();
    let with = |name: &str, line: &str| {
        std::fs::write(dir.path().join(name), format!("{text}\n{line}\n")).unwrap();
    };
    with("plain.qprop", "");
    with(
        "coarse.qprop",
        "# geometry accuracy: blade_angle_deg=2 chord_fraction=0.1",
    );
    with(
        "fine.qprop",
        "# geometry accuracy: blade_angle_deg=0.01 chord_fraction=0.001",
    );
    with(
        "bad.qprop",
        "# geometry accuracy: blade_angle_deg=-2 chord_fraction=0.1",
    );
    let predict = |prop: &str| {
        let out = format!("{prop}.csv");
        let args = [
            "predict",
            "--prop",
            prop,
            "--rpm",
            "6000",
            "--j",
            "0:0.4:0.1",
            "--band",
            "--out",
            &out,
        ];
        let o = run(&args, dir.path());
        (o, dir.path().join(out))
    };
    let width = |prop: &str| {
        let (o, out) = predict(prop);
        assert!(o.status.success(), "{}", stderr(&o));
        let (h, rows) = read_csv(&out);
        let v = |r: &Vec<String>, k: &str| r[col(&h, k)].parse::<f64>().unwrap();
        rows.iter().map(|r| v(r, "ct_hi") - v(r, "ct_lo")).collect::<Vec<f64>>()
    };
    // The largest angle the line may hold makes a band (the pitch offset stays in bounds).
    with(
        "widest.qprop",
        "# geometry accuracy: blade_angle_deg=2.5 chord_fraction=0.13",
    );
    let (plain, coarse, fine) = (width("plain.qprop"), width("coarse.qprop"), width("fine.qprop"));
    assert!(width("widest.qprop").iter().all(|w| w.is_finite() && *w > 0.0));
    for ((p, c), f) in plain.iter().zip(&coarse).zip(&fine) {
        assert!(*c > 1.5 * p, "{plain:?} {coarse:?}");
        assert!((f / p - 1.0).abs() < 0.01, "{plain:?} {fine:?}");
    }
    let (o, out) = predict("bad.qprop");
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let lines = text.lines().count() + 2;
    let expect = format!("bad.qprop: line {lines}: blade_angle_deg = -2 lies outside 0 to 2.5");
    assert!(stderr(&o).contains(&expect), "{expect}: {}", stderr(&o));
    assert!(!out.exists());
}
