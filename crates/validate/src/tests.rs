//! Unit tests of `validate.rs`.

use super::blade::{apc_airfoil, assumed_pe0};
use super::held_out::{carried, lowest};
use super::*;
use propbet_compare::ComparedPoint;

#[test]
fn the_forward_rpm_trend_is_the_j_sweeps_in_the_window() {
    use propbet_compare::Quantities;
    // (file, rpm, J, measured CT, CT error)
    let mk = |file: usize, rpm: f64, j: f64, ct: f64, e: f64| ComparedPoint {
        file,
        rpm,
        j,
        measured: Quantities {
            ct: Some(ct),
            ..Default::default()
        },
        predicted: Quantities {
            ct: Some(ct * (1.0 + e)),
            ..Default::default()
        },
        ..Default::default()
    };
    // Two sweeps whose CT error falls by 0.1 per e-fold of RPM at every J, each with a
    // point past 85 % of its zero-thrust J (J0 = 0.5) whose error is huge, and a static
    // test with a trend of its own: only the sweeps' points in the window count.
    let mut pts = Vec::new();
    for (file, rpm) in [(1, 3000.0f64), (2, 6000.0)] {
        let e = -0.1 * (rpm / 3000.0).ln();
        for j in [0.1, 0.2, 0.3] {
            pts.push(mk(file, rpm, j, 0.1 * (1.0 - 2.0 * j), e));
        }
        pts.push(mk(file, rpm, 0.45, 0.01, 5.0 * rpm / 3000.0));
        pts.push(mk(file, rpm, 0.55, -0.01, 0.0));
    }
    for rpm in [2000.0, 4000.0, 6000.0] {
        pts.push(mk(0, rpm, 0.0, 0.1, 0.3 * (rpm / 2000.0).ln()));
    }
    let t = forward_rpm_trend(&pts, VALIDATION_J_WINDOW).unwrap();
    assert!((t.change + 0.1 * 2f64.ln()).abs() < 1e-9, "{t:?}");
    assert_eq!((t.lo.round(), t.hi.round()), (3000.0, 6000.0));
    // One sweep: no trend.
    assert!(forward_rpm_trend(&pts[..5], VALIDATION_J_WINDOW).is_none());
}

/// A temporary directory with an empty file of each name.
fn dir_of(names: &[&str]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for f in names {
        std::fs::write(dir.path().join(f), "").unwrap();
    }
    dir
}

#[test]
fn every_uiuc_file_names_its_prop() {
    assert_eq!(
        uiuc_name("apcsf_10x4.7_static_kt0835.txt").as_deref(),
        Some("apcsf_10x4.7")
    );
    assert_eq!(uiuc_name("apcff_4.2x4_0617rd_6043.txt").as_deref(), Some("apcff_4.2x4"));
    assert_eq!(uiuc_name("apce_10x5_geom.txt").as_deref(), Some("apce_10x5"));
    for not in [
        "README.txt",
        "apce_10x5.txt",
        "apce_tenx5_geom.txt",
        "apce_10x5_geom.dat",
        "_10x5_a.txt",
    ] {
        assert_eq!(uiuc_name(not), None, "{not}");
    }
    // A prop with J sweeps and no geometry file is a prop of the directory, once.
    let dir = dir_of(&[
        "apce_10x5_kt0821_5000.txt",
        "apce_10x5_static_pg0819.txt",
        "apcsf_9x4.7_geom.txt",
        "notes.txt",
    ]);
    assert_eq!(uiuc_props(dir.path()).unwrap(), ["apce_10x5", "apcsf_9x4.7"]);
}

#[test]
fn pe0_blade_at_uiucs_stations() {
    let inch = 0.0254;
    let pe0 = propbet_qprop::apc::Pe0 {
        thickness: vec![(1.0 * inch, 0.1), (5.0 * inch, 0.1)],
        chord: vec![(1.0 * inch, 1.0 * inch), (5.0 * inch, 0.5 * inch)],
        twist: vec![(1.0 * inch, 30.0), (5.0 * inch, 10.0)],
        airfoils: [(1.0 * inch, "E63".into()), (2.0 * inch, "E63".into())],
    };
    // R = 5 in: APC's first station at r/R 0.2, so 0.15 is the one held inboard of it.
    let t = pe0_table(&pe0, 5.0 * inch);
    assert_eq!(t.len(), 18);
    assert!((t[0].r_r - 0.15).abs() < 1e-12 && (t[17].r_r - 1.0).abs() < 1e-12);
    assert!((t[0].c_r - 0.2).abs() < 1e-12 && (t[0].beta.to_degrees() - 30.0).abs() < 1e-9);
    // r/R 0.6 = 3 in: halfway, chord 0.75 in, twist 20 deg.
    assert!((t[9].c_r - 0.15).abs() < 1e-12 && (t[9].beta.to_degrees() - 20.0).abs() < 1e-9);
    // R = 3 in: the first station at r/R 1/3, the table from 0.3.
    let t = pe0_table(&pe0, 3.0 * inch);
    assert!((t[0].r_r - 0.3).abs() < 1e-12, "{:?}", t[0]);
}

#[test]
fn apc_files_are_found_as_they_are_often_saved() {
    let dir = dir_of(&[
        "10x4.7SF-PERF.PE0",
        "per3_10x47sf.dat",
        "11x7E-PERF.PE0",
        "11X7E-PERF.PE0",
    ]);
    let found = |n: &str| find_apc_file(dir.path(), n).map(|p| p.file_name().unwrap().to_string_lossy().into_owned());
    assert_eq!(found("10x47SF-PERF.PE0").as_deref(), Some("10x4.7SF-PERF.PE0"));
    assert_eq!(found("PER3_10x47SF.dat").as_deref(), Some("per3_10x47sf.dat"));
    // The exact name first where several match.
    assert_eq!(found("11x7E-PERF.PE0").as_deref(), Some("11x7E-PERF.PE0"));
    assert_eq!(found("10x6-PERF.PE0"), None);
    assert_eq!(find_apc_file(&dir.path().join("missing"), "10x6-PERF.PE0"), None);
}

#[test]
fn apc_airfoil_names_find_their_sections() {
    let foils = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../props/airfoils");
    let name = |n: &str| apc_airfoil(n, &foils).map(|a| a.name);
    // APC12 and NACA names are generated (the same section), the others read from files.
    let apc12 = apc_airfoil("APC12", &foils).unwrap();
    let naca = apc_airfoil("NACA 4412", &foils).unwrap();
    assert_eq!(apc12.points, naca.points);
    for n in ["E63", "CLARK-Y", "Clark Y", "SD7037", "e387"] {
        assert!(name(n).is_ok(), "{n}: {:?}", name(n));
    }
    let e = name("APC-X9").unwrap_err().to_string();
    assert!(e.contains("airfoil \"APC-X9\"") && e.contains("apcx9.dat"), "{e}");
}

#[test]
fn generic_sections_parse() {
    let assumed = |t: &str| match Sections::parse_generic(t).unwrap() {
        Some(Sections::Assumed { airfoil, thickness, .. }) => Some((airfoil, thickness)),
        _ => None,
    };
    assert_eq!(assumed("sd7037"), Some(("sd7037".into(), None)));
    assert_eq!(assumed(" naca4412:0.08 "), Some(("naca4412".into(), Some(0.08))));
    assert!(Sections::parse_generic("none").unwrap().is_none());
    for bad in ["clarky:0.9", "clarky:x", ":0.1", ""] {
        let e = Sections::parse_generic(bad).unwrap_err().to_string();
        assert!(e.contains("--generic-section"), "{bad}: {e}");
    }
}

#[test]
fn an_assumed_section_rides_on_uiucs_blade() {
    let rows = [
        propbet_measure::uiuc::GeometryRow {
            r_r: 0.2,
            c_r: 0.1,
            beta: 0.5,
        },
        propbet_measure::uiuc::GeometryRow {
            r_r: 1.0,
            c_r: 0.05,
            beta: 0.2,
        },
    ];
    let p = assumed_pe0(&rows, 0.1, "sd7037", 0.092);
    assert_eq!(p.thickness_at(0.05), 0.092);
    assert!((p.chord_at(0.1) - 0.005).abs() < 1e-15 && (p.twist_at(0.02) - 0.5f64.to_degrees()).abs() < 1e-12);
    assert_eq!(p.airfoils[0].1, "sd7037");
    assert_eq!(
        p.blend_at(0.05),
        1.0,
        "one airfoil: the blend is all the second, the same"
    );
}

/// A held-out half carries the rung its own points score lowest: the baseline when no rung
/// beats it, the shorter ladder of equals, never a rung without a score.
#[test]
fn a_held_out_half_carries_the_rung_it_scores_lowest() {
    assert_eq!(lowest(&[0.10, 0.07, 0.08]), 1);
    assert_eq!(lowest(&[0.10, 0.12, 0.11]), 0);
    assert_eq!(lowest(&[0.10, 0.08, 0.06]), 2);
    assert_eq!(lowest(&[0.10, 0.10]), 0, "equal: the shorter ladder");
    assert_eq!(lowest(&[0.10, f64::NAN, 0.09]), 2);
    assert_eq!(lowest(&[f64::NAN, 0.12]), 1);
    assert_eq!(lowest(&[0.10]), 0, "the baseline alone");
}

/// A rung that raises the ladder's leave-one-RPM-out error above the baseline's is not
/// carried, however well it scores on its own points; without that error, the score decides.
#[test]
fn a_rung_that_raises_the_leave_one_rpm_out_error_is_not_carried() {
    let scores = [0.10, 0.07, 0.06];
    assert_eq!(carried(&scores, &[Some(0.2), Some(0.18), Some(0.19)]), 2);
    assert_eq!(carried(&scores, &[Some(0.2), Some(0.18), Some(0.21)]), 1);
    assert_eq!(carried(&scores, &[Some(0.2), Some(0.22), Some(0.21)]), 0);
    assert_eq!(carried(&scores, &[None, None, None]), 2, "one RPM: no such error");
    assert_eq!(carried(&scores, &[Some(0.2), None, Some(0.25)]), 1);
    assert_eq!(carried(&scores, &[]), 2);
}
