//! The runner's fault handling, with fake `xfoil` scripts that crash, hang, babble or write
//! garbage at chosen angles. They speak just enough of XFOIL's dialogue: `PACC` + file name,
//! `ALFA a` (a point saved to the polar file), `QUIT`.

use std::os::unix::fs::PermissionsExt;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use xfoil_runner::{DisplayChoice, FaultKind, SweepRequest, Xfoil, XfoilConfig, XfoilError};

/// A fake XFOIL whose reaction to `ALFA $arg` is `behaviour` ([`xfoil_runner::fake`]).
fn fake(behaviour: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = xfoil_runner::fake::write_fake_xfoil(dir.path(), behaviour).unwrap();
    (dir, path)
}

fn runner(exe: PathBuf) -> Xfoil {
    let mut c = XfoilConfig::new(exe);
    c.display = DisplayChoice::Headless;
    c.stall_timeout = Duration::from_millis(500);
    c.startup_timeout = Duration::from_secs(1);
    c.point_timeout = Duration::from_millis(200);
    Xfoil::new(c).unwrap()
}

fn request() -> SweepRequest {
    let coords: Vec<[f64; 2]> = (0..40)
        .map(|i| {
            let t = std::f64::consts::TAU * f64::from(i) / 40.0;
            [0.5 + 0.5 * t.cos(), 0.06 * t.sin()]
        })
        .collect();
    SweepRequest::new(coords, 1e5, 0.0, (-3..=6).map(f64::from).collect())
}

fn alphas(out: &xfoil_runner::SweepOutcome) -> Vec<f64> {
    out.points.iter().map(|p| p.alpha_deg).collect()
}

#[test]
fn a_clean_fake_converges_everything_in_one_run() {
    let (_d, exe) = fake("");
    let out = runner(exe).sweep(&request()).unwrap();
    assert_eq!(alphas(&out), (-3..=6).map(f64::from).collect::<Vec<_>>());
    assert_eq!(out.runs, 1, "up and back, then down and back, in the same process");
    assert!(out.hysteresis.is_empty());
    assert!(out.faults.is_empty() && out.unconverged_deg.is_empty());
}

/// An XFOIL executable held open for writing when it is started (as a just-written wrapper is
/// by a process another thread forked a moment before, until that process execs) is started
/// once it is free: the busy executable (ETXTBSY) is tried again, not a fault.
#[test]
fn an_executable_busy_for_a_moment_is_started_once_free() {
    let (_d, exe) = fake("");
    let held = std::fs::OpenOptions::new().append(true).open(&exe).unwrap();
    let release = std::thread::spawn(move || {
        std::thread::sleep(Duration::from_millis(60));
        drop(held);
    });
    let out = runner(exe).sweep(&request()).unwrap();
    release.join().unwrap();
    assert_eq!(alphas(&out), (-3..=6).map(f64::from).collect::<Vec<_>>());
    assert!(out.faults.is_empty(), "{:?}", out.faults);
}

/// A section that stalls at 5 deg on the way up and reattaches only at 2 deg on the way down.
const STALL_LOOP: &str = r#"a=${arg%%.*}; [ $init = 1 ] && st=0
if [ $a -ge 5 ]; then st=1; elif [ $a -le 2 ]; then st=0; fi
[ "$st" = 1 ] && { cl=0.3; cd=0.2; }"#;

#[test]
fn a_hysteresis_loop_is_seen_from_both_sides_and_the_attached_branch_kept() {
    let (_d, exe) = fake(STALL_LOOP);
    let out = runner(exe).sweep(&request()).unwrap();
    assert_eq!(alphas(&out), (-3..=6).map(f64::from).collect::<Vec<_>>());
    let at: Vec<f64> = out.hysteresis.iter().map(|b| b.kept.alpha_deg).collect();
    assert_eq!(
        at,
        vec![3.0, 4.0],
        "stalled on the return only there: {:?}",
        out.hysteresis
    );
    for b in &out.hysteresis {
        assert!((b.kept.cl - (0.4 + 0.1 * b.kept.alpha_deg)).abs() < 1e-9, "{b:?}");
        assert_eq!((b.other.cl, b.other.cd), (0.3, 0.2));
        let p = out.points.iter().find(|p| p.alpha_deg == b.kept.alpha_deg).unwrap();
        assert_eq!(*p, b.kept);
    }
    assert_eq!(out.runs, 1);
}

#[test]
fn sweeps_that_end_or_start_at_zero_have_nothing_to_return_over_there() {
    let (_d, exe) = fake(STALL_LOOP);
    let x = runner(exe);
    for range in [(-3..=0), (0..=6), (0..=0), (-1..=1)] {
        let mut r = request();
        r.section.alphas_deg = range.clone().map(f64::from).collect();
        let out = x.sweep(&r).unwrap();
        assert_eq!(alphas(&out), r.section.alphas_deg, "{range:?}");
        assert!(out.unconverged_deg.is_empty(), "{range:?}");
    }
}

#[test]
fn an_angle_missed_on_the_way_out_is_filled_by_the_return() {
    // 4 deg does not converge coming from below, does from above.
    let (_d, exe) =
        fake(r#"if [ "$arg" = "4.000000" ] && [ "${prev%%.*}" -lt 4 ]; then prev=$arg; continue; fi; prev=$arg"#);
    let out = runner(exe).sweep(&request()).unwrap();
    assert_eq!(alphas(&out), (-3..=6).map(f64::from).collect::<Vec<_>>());
    assert!(out.unconverged_deg.is_empty() && out.hysteresis.is_empty());
    assert_eq!(out.runs, 1, "no retry pass: the return converged it");
}

#[test]
fn a_crash_is_restarted_beyond_the_failed_angle() {
    let (_d, exe) = fake(r#"[ "$arg" = "3.000000" ] && kill -FPE $$"#);
    let out = runner(exe).sweep(&request()).unwrap();
    assert_eq!(alphas(&out), vec![-3.0, -2.0, -1.0, 0.0, 1.0, 2.0, 4.0, 5.0, 6.0]);
    assert_eq!(out.unconverged_deg, vec![3.0]);
    // Crashed by continuation, and again from a fresh boundary layer in the retry pass.
    assert_eq!(out.faults.len(), 2);
    assert_eq!(out.faults[0].alpha_deg, 3.0);
    assert_eq!(out.faults[1].alpha_deg, 3.0);
    match &out.faults[0].kind {
        FaultKind::Crash { status } => assert!(status.contains("SIGFPE") || status.contains('8'), "{status}"),
        k => panic!("expected a crash, got {k:?}"),
    }
    assert!(
        out.faults[0].output_tail.contains("a =  3.000000"),
        "{}",
        out.faults[0].output_tail
    );
    assert_eq!(
        out.runs, 3,
        "sweep, restart after the crash (its return not through 3), retry pass"
    );
}

#[test]
fn a_hang_is_killed_and_the_sweep_goes_on() {
    // An endless loop that prints nothing, as an untrapped XFOIL does on NaN.
    let (_d, exe) = fake(r#"[ "$arg" = "-2.000000" ] && while :; do :; done"#);
    let t = Instant::now();
    let out = runner(exe).sweep(&request()).unwrap();
    assert!(t.elapsed() < Duration::from_secs(5), "took {:?}", t.elapsed());
    assert_eq!(alphas(&out), vec![-3.0, -1.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    assert!(matches!(out.faults[0].kind, FaultKind::Hang { .. }), "{:?}", out.faults);
    assert_eq!(out.faults[0].alpha_deg, -2.0);
}

#[test]
fn endless_chatter_is_stopped_by_the_run_budget() {
    let (_d, exe) = fake(r#"[ "$arg" = "5.000000" ] && while :; do echo " XFOIL   c>"; sleep 0.01; done"#);
    let t = Instant::now();
    let out = runner(exe).sweep(&request()).unwrap();
    assert!(t.elapsed() < Duration::from_secs(8), "took {:?}", t.elapsed());
    assert_eq!(out.faults.len(), 2, "once by continuation, once in the retry pass");
    assert!(matches!(out.faults[0].kind, FaultKind::Hang { .. }));
    assert_eq!(out.unconverged_deg, vec![5.0]);
}

#[test]
fn angles_lost_by_continuation_are_retried_from_a_fresh_boundary_layer() {
    // Angles 1..3 "do not converge" by continuation (nothing saved), but do after INIT.
    let (_d, exe) = fake(r#"case "$arg" in 1.000000|2.000000|3.000000) [ $init = 0 ] && continue ;; esac"#);
    let out = runner(exe).sweep(&request()).unwrap();
    assert_eq!(alphas(&out), (-3..=6).map(f64::from).collect::<Vec<_>>());
    assert!(out.unconverged_deg.is_empty() && out.faults.is_empty());
    assert_eq!(out.runs, 2, "sweep (its returns lose them too), retry pass");
}

#[test]
fn spurious_low_drag_points_are_rejected() {
    // cd = 0.001 at Re 1e5 is below laminar flat-plate friction: not a real solution.
    let (_d, exe) = fake(
        r#"[ "$arg" = "4.000000" ] && { printf '%8.3f %8.4f %9.5f %9.5f %8.4f %8.4f %8.4f\n' 4 1.2 0.001 0.001 -0.1 0.5 1.0 >> "$polar"; continue; }"#,
    );
    let out = runner(exe).sweep(&request()).unwrap();
    assert!(!alphas(&out).contains(&4.0));
    assert_eq!(out.unconverged_deg, vec![4.0]);
}

#[test]
fn crashing_everywhere_is_an_error_with_the_output() {
    let (_d, exe) = fake(r#"echo "Program received signal SIGFPE"; kill -FPE $$"#);
    let e = runner(exe).sweep(&request()).unwrap_err();
    let text = e.to_string();
    assert!(matches!(e, XfoilError::NoPoints { .. }), "{text}");
    assert!(text.contains("Program received signal SIGFPE"), "{text}");
}

#[test]
fn crashing_before_the_first_angle_is_a_startup_error() {
    let dir = tempfile::tempdir().unwrap();
    let exe = dir.path().join("xfoil");
    std::fs::write(&exe, "#!/bin/bash\necho ' Paneling airfoil'\nkill -FPE $$\n").unwrap();
    std::fs::set_permissions(&exe, std::fs::Permissions::from_mode(0o755)).unwrap();
    let e = runner(exe).sweep(&request()).unwrap_err();
    assert!(matches!(e, XfoilError::Startup { .. }), "{e}");
    assert!(e.to_string().contains("Paneling airfoil"), "{e}");
}

/// What Debian's XFOIL prints when its X display refuses the connection (seen at random
/// rungs of validate runs), then exits 1.
const REFUSE: &str = r#"echo " XFOIL   c>   Cannot open display...aborting"; exit 1"#;

#[test]
fn a_display_that_refuses_once_costs_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let flag = dir.path().join("refused");
    let (_d, exe) = fake(&format!(
        r#"[ -e "{}" ] || {{ touch "{}"; {REFUSE}; }}"#,
        flag.display(),
        flag.display()
    ));
    let out = runner(exe).sweep(&request()).unwrap();
    assert!(flag.exists(), "the fake refused its first run");
    assert_eq!(alphas(&out), (-3..=6).map(f64::from).collect::<Vec<_>>());
    assert!(
        out.faults.is_empty() && out.unconverged_deg.is_empty(),
        "{:?}",
        out.faults
    );
}

#[test]
fn a_display_that_always_refuses_is_an_error_naming_it() {
    let (_d, exe) = fake(REFUSE);
    let e = runner(exe).sweep(&request()).unwrap_err();
    assert!(matches!(e, XfoilError::Display(_)), "{e}");
    let text = e.to_string();
    assert!(text.contains("could not open the X display"), "{text}");
    assert!(
        text.contains(&format!("{} attempts", xfoil_runner::DISPLAY_ATTEMPTS)),
        "{text}"
    );
    assert!(text.contains("Cannot open display"), "XFOIL's own words: {text}");
}

#[test]
fn garbage_in_the_polar_file_is_an_error() {
    let (_d, exe) = fake(r#"[ "$arg" = "2.000000" ] && echo "  2.000  NaN-ish garbage" >> "$polar""#);
    let e = runner(exe).sweep(&request()).unwrap_err();
    assert!(matches!(e, XfoilError::Garbage { .. }), "{e}");
    assert!(e.to_string().contains("garbage"), "{e}");
}

#[test]
fn bad_requests_are_refused_before_any_process() {
    let (_d, exe) = fake("");
    let x = runner(exe);
    let mut r = request();
    r.reynolds = 0.0;
    assert!(x.sweep(&r).unwrap_err().to_string().contains("Reynolds number 0"));
    let mut r = request();
    r.reynolds = -5e4;
    assert!(matches!(x.sweep(&r), Err(XfoilError::BadRequest(_))));
    let mut r = request();
    r.coordinates[7][1] = f64::NAN;
    assert!(x.sweep(&r).unwrap_err().to_string().contains("point 8"));
    let mut r = request();
    r.section.alphas_deg = vec![2.0, 1.0];
    assert!(x.sweep(&r).unwrap_err().to_string().contains("ascending"));
}

#[test]
fn a_missing_xfoil_says_how_to_install_it() {
    let e = Xfoil::new(XfoilConfig::new(PathBuf::from("/nonexistent/xfoil"))).unwrap_err();
    assert!(e.to_string().contains("apt-get install xfoil"), "{e}");
}

#[test]
fn a_hung_wrappers_children_are_killed_with_it() {
    // At -2 deg the fake starts a child of its own (as a wrapper script would start the real
    // XFOIL), records its pid, and hangs: the runner must end both.
    let pids = tempfile::tempdir().unwrap();
    let pid_file = pids.path().join("child.pid");
    let behaviour = format!(
        r#"[ "$arg" = "-2.000000" ] && {{ sleep 60 & echo $! > {}; while :; do :; done; }}"#,
        pid_file.display()
    );
    let (_d, exe) = fake(&behaviour);
    let out = runner(exe).sweep(&request()).unwrap();
    assert!(matches!(out.faults[0].kind, FaultKind::Hang { .. }), "{:?}", out.faults);
    let pid = std::fs::read_to_string(&pid_file).unwrap().trim().to_string();
    // The child is gone (or a zombie reaped by init): no live process with that pid.
    let t = Instant::now();
    let alive = || {
        std::fs::read_to_string(format!("/proc/{pid}/stat"))
            .map(|s| s.split_whitespace().nth(2).is_none_or(|state| state != "Z"))
            .unwrap_or(false)
    };
    while alive() {
        assert!(
            t.elapsed() < Duration::from_secs(2),
            "the wrapper's child {pid} outlived the kill"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[test]
fn absurd_values_are_not_converged_points() {
    // At 2 deg the fake saves cl 1e30, at 3 deg a negative drag.
    let (_d, exe) = fake(
        r#"if [ "$arg" = "2.000000" ] && [ $acc = 1 ]; then printf '%8.3f %8.4f %9.5f %9.5f %8.4f %8.4f %8.4f\n' 2 1e30 0.02 0.005 -0.1 0.5 1.0 >> "$polar"; continue; fi
      if [ "$arg" = "3.000000" ] && [ $acc = 1 ]; then printf '%8.3f %8.4f %9.5f %9.5f %8.4f %8.4f %8.4f\n' 3 0.7 -0.02 0.005 -0.1 0.5 1.0 >> "$polar"; continue; fi"#,
    );
    let out = runner(exe).sweep(&request()).unwrap();
    assert!(
        !alphas(&out).contains(&2.0) && !alphas(&out).contains(&3.0),
        "{:?}",
        alphas(&out)
    );
    assert!(out.unconverged_deg.contains(&2.0) && out.unconverged_deg.contains(&3.0));
}

#[test]
fn a_sweep_gives_up_when_its_budget_runs_out() {
    // Endless chatter at every angle from 1 deg: each run is stopped by its own budget, and the
    // sweep by its total one instead of restarting for minutes.
    let (_d, exe) =
        fake(r#"if [ "${arg%%.*}" -ge 1 ] 2>/dev/null; then while :; do echo " XFOIL   c>"; sleep 0.01; done; fi"#);
    let mut c = XfoilConfig::new(exe);
    c.display = DisplayChoice::Headless;
    c.stall_timeout = Duration::from_millis(500);
    c.startup_timeout = Duration::from_secs(1);
    c.point_timeout = Duration::from_millis(300);
    c.sweep_budget = Duration::from_millis(1500);
    let t = Instant::now();
    let out = Xfoil::new(c).unwrap().sweep(&request()).unwrap();
    assert!(t.elapsed() < Duration::from_secs(4), "took {:?}", t.elapsed());
    assert!(
        out.faults
            .iter()
            .any(|f| matches!(f.kind, FaultKind::OverBudget { .. })),
        "{:?}",
        out.faults
    );
    assert!(out.unconverged_deg.contains(&6.0), "{:?}", out.unconverged_deg);
    // What converged before the budget ran out is kept.
    assert!(alphas(&out).contains(&0.0), "{:?}", alphas(&out));
}
