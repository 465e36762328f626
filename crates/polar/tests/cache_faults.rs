//! The polar cache and XFOIL's faults, with a fake `xfoil` (`xfoil_runner::fake`): a polar whose XFOIL hung is not cached, since a hang may be
//! the machine's load rather than XFOIL's answer; a polar without one is; `auto` where XFOIL
//! gives no polar.

use std::path::{Path, PathBuf};
use std::time::Duration;

use propbet_polar::{PolarCache, PolarEngine, PolarJob, Source};
use xfoil_runner::{DisplayChoice, Xfoil, XfoilConfig};

/// A fake XFOIL that runs `behaviour` (bash) at each `ALFA $arg` before saving the point.
fn fake(dir: &Path, behaviour: &str) -> PathBuf {
    xfoil_runner::fake::write_fake_xfoil(dir, behaviour).unwrap()
}

fn engine(exe: PathBuf, cache: &Path) -> PolarEngine {
    let mut c = XfoilConfig::new(exe);
    c.display = DisplayChoice::Headless;
    c.stall_timeout = Duration::from_millis(400);
    c.startup_timeout = Duration::from_secs(1);
    c.point_timeout = Duration::from_millis(200);
    PolarEngine::new(Xfoil::new(c).unwrap(), Some(PolarCache::open(cache).unwrap()))
}

fn job() -> PolarJob {
    let foil = propbet_polar::naca4_from_name("naca2412").unwrap().unwrap();
    PolarJob::new(foil, 1e5, 0.0, 9.0, (-2..=4).map(f64::from).collect())
}

#[test]
fn a_polar_whose_xfoil_hung_is_not_cached_a_clean_one_is() {
    let dir = tempfile::tempdir().unwrap();
    let hangs = engine(
        fake(dir.path(), r#"[ "$arg" = "3.000000" ] && while :; do :; done"#),
        &dir.path().join("cache"),
    );
    let (first, s1) = hangs.compute(&job()).unwrap();
    assert_eq!(s1, Source::Xfoil);
    assert!(!first.faults.is_empty(), "the hang is reported");
    assert_eq!(
        hangs.compute(&job()).unwrap().1,
        Source::Xfoil,
        "computed again, not replayed"
    );

    let clean_dir = tempfile::tempdir().unwrap();
    let clean = engine(fake(clean_dir.path(), ""), &clean_dir.path().join("cache"));
    assert_eq!(clean.compute(&job()).unwrap().1, Source::Xfoil);
    assert_eq!(clean.compute(&job()).unwrap().1, Source::Cache);
}

#[test]
fn polars_not_started_within_the_commands_budget_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let e = engine(fake(dir.path(), ""), &dir.path().join("cache")).with_budget(0.001);
    std::thread::sleep(Duration::from_millis(10));
    let err = e.compute(&job()).unwrap_err().to_string();
    assert!(err.contains("Re 100000") && err.contains("XFOIL time budget"), "{err}");
}

#[test]
fn auto_answers_with_neuralfoil_where_xfoil_gave_nothing_and_with_xfoils_error_where_neither_can() {
    let dir = tempfile::tempdir().unwrap();
    let net = propbet_neuralfoil::Network::shipped(propbet_neuralfoil::DEFAULT_SIZE).unwrap();
    let e = engine(fake(dir.path(), ""), &dir.path().join("cache"))
        .with_neuralfoil(net)
        .with_budget(0.001);
    std::thread::sleep(Duration::from_millis(10));
    let (p, source) = e.compute(&job()).unwrap();
    assert_eq!(source, Source::NeuralFoil);
    assert_eq!(p.neuralfoil.len(), p.points.len());
    // A trailing edge 4 % of the chord thick: XFOIL takes it, NeuralFoil does not, and the
    // budget's error stands.
    let mut blunt = job();
    let n = blunt.airfoil.points.len();
    for (i, q) in blunt.airfoil.points.iter_mut().enumerate() {
        q[1] += if i < n / 2 { 0.02 } else { -0.02 } * q[0];
    }
    let err = e.compute(&blunt).unwrap_err().to_string();
    assert!(err.contains("XFOIL time budget"), "{err}");
}
