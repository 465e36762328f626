//! propbet's evaluation of NeuralFoil's networks against the `neuralfoil` package itself
//! (installed into `.venv` by `scripts/setup.sh`): the package fits each shipped airfoil's
//! Kulfan parameters and evaluates its network over angles, Reynolds numbers, Ncrit and forced
//! transition; propbet evaluates the same network at the same parameters. Within CL 0.005,
//! ln CD 0.01 and confidence 0.01 on every case (the bounds), for two network sizes.

use std::path::{Path, PathBuf};
use std::process::Command;

use propbet_neuralfoil::{Condition, Kulfan, Network};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The package's answers (see `tests/reference.py`).
fn reference(size: &str) -> Vec<serde_json::Value> {
    let repo = repo();
    let airfoils: Vec<String> = std::fs::read_dir(repo.join("props/airfoils"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "dat"))
        .map(|p| p.display().to_string())
        .collect();
    assert!(airfoils.len() >= 5, "{airfoils:?}");
    let out = Command::new(repo.join(".venv/bin/python"))
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference.py"))
        .arg(size)
        .args(&airfoils)
        .output()
        .expect("the project's .venv (scripts/setup.sh installs neuralfoil there)");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

fn numbers(v: &serde_json::Value) -> [f64; 8] {
    let a: Vec<f64> = v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    a.try_into().unwrap()
}

fn parity(size: &str) {
    let net = Network::shipped(size).unwrap();
    let cases = reference(size);
    assert!(cases.len() >= 500, "{} cases", cases.len());
    let (mut dcl, mut dlncd, mut dconf) = (0.0f64, 0.0f64, 0.0f64);
    for c in &cases {
        let f = |k: &str| c[k].as_f64().unwrap();
        let k = &c["kulfan"];
        let kulfan = Kulfan {
            upper: numbers(&k["upper"]),
            lower: numbers(&k["lower"]),
            leading_edge: k["leading_edge"].as_f64().unwrap(),
            te_thickness: k["te_thickness"].as_f64().unwrap(),
        };
        let a = net.evaluate(
            &kulfan,
            &Condition {
                alpha_deg: f("alpha"),
                re: f("re"),
                ncrit: f("ncrit"),
                xtr_upper: f("xtr"),
                xtr_lower: f("xtr"),
            },
        );
        dcl = dcl.max((a.cl - f("cl")).abs());
        dlncd = dlncd.max((a.cd.ln() - f("cd").ln()).abs());
        dconf = dconf.max((a.confidence - f("confidence")).abs());
        assert!((a.cm - f("cm")).abs() < 0.005, "{c}: cm {}", a.cm);
    }
    eprintln!(
        "{size}: {} cases, largest differences CL {dcl:.2e}, ln CD {dlncd:.2e}, confidence {dconf:.2e}",
        cases.len()
    );
    assert!(
        dcl < 0.005 && dlncd < 0.01 && dconf < 0.01,
        "CL {dcl}, ln CD {dlncd}, confidence {dconf}"
    );
}

#[test]
fn the_default_network_gives_the_packages_coefficients() {
    parity(propbet_neuralfoil::DEFAULT_SIZE);
}

#[test]
fn the_smallest_network_too() {
    parity("xxsmall");
}

/// The coordinates of a Selig `.dat` file.
fn coordinates(path: &str) -> Vec<[f64; 2]> {
    propbet_neuralfoil::cst::selig_points(&std::fs::read_to_string(path).unwrap())
}

/// propbet's Kulfan fit gives the package's parameters on every shipped airfoil, and so its
/// coefficients; the fit's shape error is small against the section's thickness.
#[test]
fn the_kulfan_fit_is_the_packages() {
    let net = Network::shipped(propbet_neuralfoil::DEFAULT_SIZE).unwrap();
    let cases = reference(propbet_neuralfoil::DEFAULT_SIZE);
    let mut seen = std::collections::BTreeMap::new();
    for c in &cases {
        seen.entry(c["airfoil"].as_str().unwrap().to_string()).or_insert(c);
    }
    for (path, c) in seen {
        let fit = propbet_neuralfoil::cst::fit(&coordinates(&path)).unwrap();
        let k = &c["kulfan"];
        let theirs: Vec<f64> = numbers(&k["upper"])
            .into_iter()
            .chain(numbers(&k["lower"]))
            .chain([k["leading_edge"].as_f64().unwrap(), k["te_thickness"].as_f64().unwrap()])
            .collect();
        let ours: Vec<f64> = fit
            .kulfan
            .upper
            .into_iter()
            .chain(fit.kulfan.lower)
            .chain([fit.kulfan.leading_edge, fit.kulfan.te_thickness])
            .collect();
        let worst = ours.iter().zip(&theirs).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        eprintln!(
            "{path}: parameters within {worst:.1e} of the package's; shape error RMS {:.2e}, largest {:.2e} chord",
            fit.rms, fit.max
        );
        assert!(worst < 1e-9, "{path}: {ours:?} against {theirs:?}");
        assert!(fit.max < 0.01, "{path}: shape error {}", fit.max);
        let a = net.evaluate(
            &fit.kulfan,
            &Condition {
                alpha_deg: c["alpha"].as_f64().unwrap(),
                re: c["re"].as_f64().unwrap(),
                ncrit: c["ncrit"].as_f64().unwrap(),
                xtr_upper: c["xtr"].as_f64().unwrap(),
                xtr_lower: c["xtr"].as_f64().unwrap(),
            },
        );
        assert!((a.cl - c["cl"].as_f64().unwrap()).abs() < 0.005, "{path}");
    }
}
