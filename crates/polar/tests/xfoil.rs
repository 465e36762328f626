//! Polars from the real XFOIL 6.99 (installed by scripts/setup.sh): the acceptance values, the
//! QPROP reduction against XFOIL's own points, the low-Re sections APC uses, and the cache.

use std::path::Path;

use propbet_bemt::{DragInput, QpropAirfoil, SectionAero};
use propbet_polar::{fit_qprop, naca4_from_name, Airfoil, AlphaWeights, PolarCache, PolarEngine, PolarJob, Source};
use xfoil_runner::{find_xfoil, Xfoil, XfoilConfig};

fn engine(cache: Option<&Path>) -> PolarEngine {
    let exe =
        find_xfoil(None, std::env::var_os("PATH").as_deref()).expect("XFOIL must be installed (scripts/setup.sh)");
    PolarEngine::new(
        Xfoil::new(XfoilConfig::new(exe)).unwrap(),
        cache.map(|d| PolarCache::open(d).unwrap()),
    )
}

fn shipped(name: &str) -> Airfoil {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../props/airfoils")
        .join(name);
    Airfoil::parse(&std::fs::read_to_string(&path).unwrap(), name)
        .unwrap()
        .0
}

fn grid(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let n = ((hi - lo) / step).round() as usize;
    (0..=n).map(|i| lo + step * i as f64).collect()
}

#[test]
#[ignore = "slow: real XFOIL (scripts/test.sh runs it)"]
fn naca4412_at_re_1e5_matches_debian_xfoil() {
    let e = engine(None);
    let job = PolarJob::new(
        naca4_from_name("naca4412").unwrap().unwrap(),
        1e5,
        0.0,
        9.0,
        grid(-4.0, 12.0, 0.5),
    );
    let (p, src) = e.compute(&job).unwrap();
    assert_eq!(src, Source::Xfoil);
    let p4 = p.at_alpha(4.0).unwrap();
    // Acceptance values, from Debian's XFOIL 6.99 on its own `NACA 4412`.
    assert!((p4.cl - 0.888).abs() <= 0.01, "cl(4) = {}", p4.cl);
    assert!((p4.cd - 0.0197).abs() <= 0.001, "cd(4) = {}", p4.cd);
    assert!(
        p.points.len() >= 30,
        "{} points, failed {:?}",
        p.points.len(),
        p.unconverged_deg
    );
}

#[test]
#[ignore = "slow: real XFOIL (scripts/test.sh runs it)"]
fn qprop_fit_reproduces_xfoil_over_the_linear_range() {
    let e = engine(None);
    let foil = naca4_from_name("naca4412").unwrap().unwrap();
    let jobs: Vec<PolarJob> = [7e4, 1e5, 1.4e5]
        .iter()
        .map(|&re| PolarJob::new(foil.clone(), re, 0.0, 9.0, grid(-6.0, 14.0, 1.0)))
        .collect();
    let polars: Vec<_> = e
        .compute_all(&jobs, &propbet_polar::compute::no_progress)
        .into_iter()
        .map(|r| r.unwrap().0)
        .collect();
    let fit = fit_qprop(&polars, 1e5, &AlphaWeights::Uniform, -0.5).unwrap();
    // Drag falls with Re; at Re 7e4-1.4e5 laminar bubbles make it steeper than laminar
    // friction's -0.5 (XFOIL gives about -1 for this section here).
    assert!(
        fit.re_exp_fitted && fit.coeffs.re_exp < -0.2 && fit.coeffs.re_exp > -1.5,
        "{:?}",
        fit.coeffs
    );
    assert!(
        fit.linear_range_deg[1] - fit.linear_range_deg[0] >= 6.0,
        "{:?}",
        fit.linear_range_deg
    );
    // Check the law itself, through the solver's section model, against XFOIL's points.
    let model = QpropAirfoil::new(fit.coeffs);
    let centre = &polars[1];
    let mut checked = 0;
    for p in centre
        .points
        .iter()
        .filter(|p| p.alpha_deg >= fit.linear_range_deg[0] && p.alpha_deg <= fit.linear_range_deg[1])
    {
        let a = p.alpha_deg.to_radians();
        let l = model.lift(a, 1e5, 0.0);
        let cd = model.drag(&DragInput {
            alpha: a,
            cl: l.cl,
            stalled: l.stalled,
            re: 1e5,
            mach: 0.0,
        });
        assert!(
            (l.cl - p.cl).abs() <= 0.03,
            "cl at {} deg: {} vs XFOIL {}",
            p.alpha_deg,
            l.cl,
            p.cl
        );
        assert!(
            (cd / p.cd - 1.0).abs() <= 0.10,
            "cd at {} deg: {} vs XFOIL {}",
            p.alpha_deg,
            cd,
            p.cd
        );
        checked += 1;
    }
    assert!(checked >= 7, "only {checked} points in the linear range");
}

#[test]
#[ignore = "slow: real XFOIL (scripts/test.sh runs it)"]
fn apc_sections_give_polars_at_low_re() {
    let e = engine(None);
    let e63 = shipped("e63.dat");
    let (t, _) = {
        let mut n = e63.clone();
        n.normalise();
        n.max_thickness()
    };
    assert!((t - 0.0425).abs() < 0.001);
    let clarky = shipped("clarky.dat");
    let mut jobs = Vec::new();
    for foil in [&e63, &clarky] {
        for re in [3e4, 6e4, 1e5, 1.5e5] {
            jobs.push(PolarJob::new(foil.clone(), re, 0.0, 9.0, grid(-6.0, 12.0, 1.0)));
        }
    }
    for (job, r) in jobs
        .iter()
        .zip(e.compute_all(&jobs, &propbet_polar::compute::no_progress))
    {
        let (p, _) = r.unwrap_or_else(|e| panic!("{} at Re {}: {e}", job.airfoil.name, job.re));
        assert!(
            p.points.len() >= 6,
            "{} at Re {}: {} points, failed {:?}",
            job.airfoil.name,
            job.re,
            p.points.len(),
            p.unconverged_deg
        );
        // Cambered sections lift well at moderate incidence; drag positive and sane.
        let best = p
            .points
            .iter()
            .filter(|q| (2.0..=8.0).contains(&q.alpha_deg))
            .map(|q| q.cl)
            .fold(f64::MIN, f64::max);
        assert!(
            best > 0.5,
            "{} at Re {}: best cl at 2..8 deg = {best}",
            job.airfoil.name,
            job.re
        );
        assert!(p.points.iter().all(|q| q.cd > 0.003 && q.cd < 0.5));
    }
}

#[test]
#[ignore = "slow: real XFOIL (scripts/test.sh runs it)"]
fn the_cache_returns_the_same_polar_and_heals_corruption() {
    let dir = tempfile::tempdir().unwrap();
    let e = engine(Some(dir.path()));
    let job = PolarJob::new(shipped("clarky.dat"), 8e4, 0.05, 9.0, grid(-2.0, 6.0, 1.0));
    let (first, s1) = e.compute(&job).unwrap();
    assert_eq!(s1, Source::Xfoil);
    let t = std::time::Instant::now();
    let (again, s2) = e.compute(&job).unwrap();
    assert_eq!(s2, Source::Cache);
    assert_eq!(first, again);
    assert!(t.elapsed().as_millis() < 500);
    // A different Ncrit is a different polar.
    let mut other = job.clone();
    other.section.ncrit = 5.0;
    assert_eq!(e.compute(&other).unwrap().1, Source::Xfoil);
    // Corrupt every entry: detected, recomputed, replaced.
    for sub in std::fs::read_dir(dir.path()).unwrap() {
        for f in std::fs::read_dir(sub.unwrap().path()).unwrap() {
            let f = f.unwrap().path();
            let mut bytes = std::fs::read(&f).unwrap();
            bytes.truncate(bytes.len() / 2);
            std::fs::write(&f, bytes).unwrap();
        }
    }
    let (healed, s3) = e.compute(&job).unwrap();
    assert_eq!(s3, Source::RecomputedCorrupt);
    assert_eq!(healed, first);
    assert_eq!(e.compute(&job).unwrap().1, Source::Cache);
}
