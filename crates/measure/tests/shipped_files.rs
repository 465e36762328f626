//! Every measured file the project ships (copies of ../shared, see their PROVENANCE.md) loads,
//! with the points and drops its content implies. Expected values were read from the files
//! themselves (python csv, see each comment).

use std::path::PathBuf;

use propbet_measure::{read, DropReason, Format, Loads, ReadOptions, Reduction, RpmSource, Speed};

/// The shipped copy of a ../shared file.
fn shared(rel: &str) -> PathBuf {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let file = rel.rsplit('/').next().unwrap();
    let copy = if rel.starts_with("data/thrust_stand/") {
        root.join("tests/data/thrust_stand").join(file)
    } else if rel.starts_with("data/photofoil/") {
        root.join("props/photofoil_8x4.5").join(file)
    } else if rel.starts_with("data/uiuc/apcsf_10x4.7") {
        root.join("props/apcsf_10x4.7/uiuc").join(file)
    } else if let Some(r) = rel.strip_prefix("examples/hidden_effects/") {
        root.join("tests/data/hidden_effects").join(r)
    } else {
        panic!("{rel}: not shipped")
    };
    assert!(copy.exists(), "{}", copy.display());
    copy
}

fn load(rel: &str, opts: ReadOptions) -> propbet_measure::MeasuredSet {
    let path = shared(rel);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let opts = ReadOptions {
        name: Some(path.file_name().unwrap().to_string_lossy().into_owned()),
        ..opts
    };
    read(&text, &opts).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

fn thrust_n(p: &propbet_measure::MeasuredPoint) -> f64 {
    match p.loads {
        Loads::Forces { thrust, .. } => thrust.mean,
        Loads::Coefficients { .. } => panic!("forces expected"),
    }
}

#[test]
fn photofoil_step_summary() {
    let set = load(
        "data/photofoil/StepsTestV2_2022-01-18_153833.csv",
        ReadOptions::default(),
    );
    assert_eq!(set.format, Format::RcBenchmark);
    assert_eq!(set.reduction, Reduction::AveragedSteps);
    // 12 rows; the first (ESC 1000) does not spin.
    assert_eq!(set.points.len(), 11);
    assert_eq!(set.dropped.len(), 1);
    assert_eq!(set.dropped[0].reason, DropReason::NotSpinning);
    assert_eq!(set.rpm_source, Some(RpmSource::Electrical));
    // Row at ESC 1425: 12003 rpm, 893.5315 gf, torque -0.165572 N m (flipped to positive).
    let p = set.points.iter().find(|p| (p.rpm() - 12003.0).abs() < 0.5).unwrap();
    assert!((thrust_n(p) - 0.8935315286100613 * 9.80665).abs() < 1e-9);
    let Loads::Forces { torque: Some(q), .. } = p.loads else {
        panic!()
    };
    assert!((q.mean - 0.16557216788216017).abs() < 1e-12);
    assert!(set.notes.iter().any(|n| n.contains("torque is logged negative")));
}

#[test]
fn series_1520_has_no_torque() {
    let set = load("data/thrust_stand/series1520_no_torque.csv", ReadOptions::default());
    assert!(!set.has_torque);
    assert_eq!(set.points.len(), 11);
    assert!(set
        .points
        .iter()
        .all(|p| matches!(p.loads, Loads::Forces { torque: None, .. })));
    // Electrical speed, first row 3421 rpm, 15.1717 gf.
    assert!((set.points[0].rpm() - 3421.0).abs() < 1e-9);
    assert!((thrust_n(&set.points[0]) - 0.015171654199725802 * 9.80665).abs() < 1e-12);
}

#[test]
fn series_1580_in_grams() {
    let set = load("data/thrust_stand/series1580_gf_steps.csv", ReadOptions::default());
    assert_eq!(set.points.len(), 21);
    assert_eq!(set.faults(), 0);
    assert!((set.points[20].rpm() - 25594.0).abs() < 1e-9);
    assert!((thrust_n(&set.points[20]) - 0.04853719777074354 * 9.80665).abs() < 1e-12);
}

#[test]
fn series_1585_steps_in_newtons() {
    for f in ["series1585_newton_steps.csv", "series1585_newton_nobom.csv"] {
        let set = load(&format!("data/thrust_stand/{f}"), ReadOptions::default());
        assert_eq!(set.reduction, Reduction::Steps, "{f}");
        assert!(set.points.len() >= 10, "{f}: {} points", set.points.len());
        // Steps of ~15 samples at 1150..1600 µs: every point averages several samples and keeps
        // their scatter.
        for p in &set.points {
            assert!(p.omega.n >= 3 && p.omega.sd.is_some(), "{f} {}", p.label);
            assert!(thrust_n(p) > 0.0);
        }
        // Thrust rises with RPM across the distinct ESC steps.
        let mut by_rpm: Vec<(f64, f64)> = set.points.iter().map(|p| (p.rpm(), thrust_n(p))).collect();
        by_rpm.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert!(by_rpm.last().unwrap().1 > 5.0 * by_rpm[0].1, "{f}: {by_rpm:?}");
    }
}

#[test]
fn series_1780_logs() {
    let set = load("data/thrust_stand/series1780_log.csv", ReadOptions::default());
    assert_eq!(set.rpm_source, Some(RpmSource::Optical));
    // Line 3 is a stray row (t = 400 s between 0.08 s and 1.5 s, with 10 values more than the
    // header names).
    let stray = set.dropped.iter().find(|d| d.line == 3).unwrap();
    assert_eq!(stray.reason, DropReason::TimeOutOfOrder);
    assert!(set.notes.iter().any(|n| n.contains("more values than the header")));
    assert!(set
        .notes
        .iter()
        .any(|n| n.contains("4N76 Temp") && n.contains("not air temperature")));
    // The optical sensor reads 0 for 2,222 rows of the long 1560 µs step (about 9 N, 17 A) and
    // misses pulses in most others (readings of 1 to 3,494 rpm while thrust and torque hold):
    // those rows take the step's steady reading, about 3,470 rpm (351 of its readings lie
    // between 3,400 and 3,500). The spinning rows are those drawing more than 1 A (python
    // csv: 3,662); at least 90 % of them are in a scored point.
    let text = std::fs::read_to_string(shared("data/thrust_stand/series1780_log.csv")).unwrap();
    let mut rows = csv::ReaderBuilder::new().flexible(true).from_reader(text.as_bytes());
    let current = rows.headers().unwrap().iter().position(|h| h == "Current (A)").unwrap();
    let spinning = rows
        .records()
        .filter(|r| r.as_ref().unwrap()[current].parse::<f64>().unwrap() > 1.0)
        .count();
    assert_eq!(spinning, 3662);
    let kept: usize = set
        .points
        .iter()
        .filter(|p| p.flags.is_empty())
        .map(|p| p.omega.n)
        .sum();
    assert!(
        kept as f64 >= 0.9 * spinning as f64,
        "{kept} of {spinning} spinning rows kept"
    );
    let step = set.points.iter().find(|p| p.label == "ESC 1560 µs").unwrap();
    assert!((step.rpm() - 3470.0).abs() < 15.0 && step.flags.is_empty(), "{step:?}");
    let filled = set.notes.iter().find(|n| n.starts_with("RPM sensor dropouts")).unwrap();
    assert!(filled.contains("ESC 1560 µs"), "{filled}");
    // Not a dropout: the 3,407 rows after the run, at ESC 1000 µs, 0.04 A, where the optical
    // sensor reads 0 (and 1 seven times).
    let stopped = set
        .dropped
        .iter()
        .filter(|d| d.reason == DropReason::NotSpinning)
        .count();
    assert_eq!(stopped, 3407);

    // A closed-loop (PID) run: the command holds for a few samples at a time; those holds are
    // the steady points, the ramps between them are not used.
    let set = load(
        "data/thrust_stand/series1780_script_columns.csv",
        ReadOptions::default(),
    );
    assert_eq!(set.reduction, Reduction::Steps);
    let steady = set.points.iter().filter(|p| p.flags.is_empty()).count();
    assert!(steady >= 30, "{steady} steady points");
}

#[test]
fn rpm_source_choices() {
    let e = read(
        &std::fs::read_to_string(shared("data/thrust_stand/series1780_log.csv")).unwrap(),
        &ReadOptions {
            rpm_source: Some(RpmSource::Electrical),
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("no 'Motor Electrical Speed' column"), "{e}");
    let set = load(
        "data/photofoil/StepsTestV2_2022-01-18_153833.csv",
        ReadOptions {
            poles: Some(14),
            ..Default::default()
        },
    );
    assert!((set.points.last().unwrap().rpm() - 12436.0 * 2.0 / 14.0).abs() < 1e-9);
}

#[test]
fn uiuc_files() {
    let set = load("data/uiuc/apcsf_10x4.7_static_kt0835.txt", ReadOptions::default());
    assert_eq!(set.format, Format::UiucStatic);
    assert!((set.points[0].rpm() - 2377.0).abs() < 1e-9);
    let set = load("data/uiuc/apcsf_10x4.7_kt0836_4014.txt", ReadOptions::default());
    assert_eq!(set.format, Format::UiucSweep);
    assert!((set.points[0].rpm() - 4014.0).abs() < 1e-9);
    assert!(matches!(set.points[0].speed, Speed::AdvanceRatio(j) if (j - 0.142).abs() < 1e-12));
    assert!(matches!(set.points[0].loads, Loads::Coefficients { ct, cp } if ct == 0.0994 && cp == 0.0451));
}

#[test]
fn hidden_effect_files() {
    let set = load(
        "examples/hidden_effects/torque_tare/cam6x3_steps.csv",
        ReadOptions::default(),
    );
    assert_eq!(set.format, Format::RcBenchmark);
    assert!(set.points.len() >= 3);
    let set = load(
        "examples/hidden_effects/pitch_offset/apc8x6_tunnel.csv",
        ReadOptions::default(),
    );
    assert_eq!(set.format, Format::Generic);
    assert_eq!(set.reduction, Reduction::Rows);
}
