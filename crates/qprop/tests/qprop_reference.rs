//! Reproduces every RPM-driven QPROP 1.22 run in `tests/reference/qprop` (copied from
//! `../shared/reference/qprop`, see its PROVENANCE.md) to the precision QPROP prints, for the
//! summary rows and the radial block, with the solver in QPROP-compatibility mode.

use std::path::PathBuf;

use propbet_bemt::{solve_point, solve_points, Discretization, Fluid, OperatingPoint, PointResult, SolverOptions};
use propbet_qprop::output::{QpropOutput, RADIAL_COLUMNS, SUMMARY_COLUMNS};
use propbet_qprop::{parse_output, parse_prop, qprop_sequence, Printed, RadiusReading};

fn reference_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/reference/qprop")
}

/// (command from COMMANDS.txt, output file). The motor-driven voltage sweep
/// (`qprop cam6x3 s400-6v-dd 0,12/7 0 6,9,1`) is not RPM-driven and not reproduced here.
const RUNS: &[(&str, &str)] = &[
    ("qprop cam6x3 null 0 12000", "cam6x3_point_V0_rpm12000.out"),
    ("qprop cam6x3 null 8 14000", "cam6x3_point_V8_rpm14000.out"),
    ("qprop cam6x3 null 0,16/17 8000", "cam6x3_Vsweep_rpm8000.out"),
    ("qprop cam6x3 null 0,30/31 16000", "cam6x3_Vsweep_rpm16000.out"),
    ("qprop cam6x3 null 0 2000,24000/23", "cam6x3_rpmsweep_V0.out"),
    ("qprop cam6x3 null 5 12000 0 -4,4,2", "cam6x3_dbeta_sweep.out"),
    ("qprop apc8x6 null 10 6000", "apc8x6_point_V10_rpm6000.out"),
    ("qprop apc8x6 null 0,25/26 6000", "apc8x6_Vsweep_rpm6000.out"),
    (
        "qprop photofoil_8x4.5_noR null 0 9000",
        "photofoil_8x4.5_noR_point_V0_rpm9000.out",
    ),
    (
        "qprop photofoil_8x4.5_noR null 0 3000,12000/10",
        "photofoil_8x4.5_noR_rpmsweep_V0.out",
    ),
    (
        "qprop photofoil_8x4.5 null 0 3000,12000/10",
        "photofoil_8x4.5_asgiven_rpmsweep_V0.out",
    ),
];

/// Summary columns that depend only on the propeller (the others are QPROP's motor model).
const PROP_COLUMNS: [usize; 14] = [0, 1, 2, 3, 4, 5, 9, 10, 11, 12, 13, 16, 17, 18];

struct Mismatches(Vec<String>);

impl Mismatches {
    /// Half a unit of the last printed digit, plus 2e-6 relative: QPROP stops its Newton
    /// iteration at |d psi| < 1e-6, so its own numbers carry noise of that order, which shows
    /// in the printed digits only where a quantity is ill-conditioned (effprop = TV/(Q Omega) at
    /// the windmill point of apc8x6 at 20 m/s, where Q = -3.1e-4 N m is a near-cancellation).
    fn check(&mut self, what: &str, printed: Printed, ours: f64) {
        if (ours - printed.value).abs() > 0.5 * printed.unit + 2e-6 * printed.value.abs() {
            self.0
                .push(format!("{what}: QPROP printed {} , propbet {ours:.6e}", printed.value));
        }
    }
}

/// A single point's stations against QPROP's radial table; the numbers compared.
fn check_stations(out_file: &str, out: &QpropOutput, p: &PointResult, v: f64, bad: &mut Mismatches) -> usize {
    let mut compared = 0;
    assert_eq!(out.radial.len(), p.stations.len(), "{out_file}");
    for (i, (s, printed)) in p.stations.iter().zip(&out.radial).enumerate() {
        let (effi, effp) = if s.wa != 0.0 && s.wt != 0.0 {
            (
                (v / (p.omega * s.r) * (s.wt / s.wa)).clamp(-99.0, 99.0),
                ((s.cl - s.cd * s.wa / s.wt) / (s.cl + s.cd * s.wt / s.wa)).clamp(-99.0, 99.0),
            )
        } else {
            (0.0, 0.0)
        };
        let ours: [f64; 12] = [
            s.r,
            s.chord,
            s.beta * 180.0 / propbet_bemt::solve::QPROP_PI,
            s.cl,
            s.cd,
            (s.re + 0.5).floor(),
            s.mach,
            effi,
            effp,
            s.wa,
            s.vt.atan2(s.wa).to_degrees(),
            s.lambda_w,
        ];
        for k in 0..12 {
            let what = format!("{out_file} station {} {}", i + 1, RADIAL_COLUMNS[k]);
            bad.check(&what, printed[k], ours[k]);
            compared += 1;
        }
    }
    compared
}

#[test]
fn reproduces_every_rpm_driven_qprop_run() {
    let dir = reference_dir();
    let mut bad = Mismatches(Vec::new());
    let mut compared = 0usize;
    let commands = std::fs::read_to_string(dir.join("COMMANDS.txt")).unwrap();
    for (cmd, out_file) in RUNS {
        assert!(
            commands.lines().any(|l| l.trim() == *cmd),
            "{cmd} is not in COMMANDS.txt"
        );
        let args: Vec<&str> = cmd.split_whitespace().collect();
        let (prop, _) = parse_prop(&std::fs::read_to_string(dir.join(args[1])).unwrap()).unwrap();
        let out = parse_output(&std::fs::read_to_string(dir.join(out_file)).unwrap()).unwrap();
        let fluid = Fluid {
            rho: out.rho,
            mu: out.mu,
            a: out.a,
        };
        let rotor = prop
            .to_blade(RadiusReading::Qprop122)
            .to_rotor(Discretization {
                stations: 25,
                qprop_reref_quirk: true,
            })
            .unwrap();
        let speeds = qprop_sequence(args[3]).unwrap();
        let rpms = qprop_sequence(args[4]).unwrap();
        let dbetas = args.get(6).map_or(vec![0.0], |a| qprop_sequence(a).unwrap());
        // QPROP nests dBeta > RPM > V. Sweeps go through `solve_points` (the production path,
        // vectorised over points), single points through `solve_point` (with stations).
        let mut rows = out.summary.iter();
        let single = speeds.len() * rpms.len() * dbetas.len() == 1;
        for &db in &dbetas {
            let opts = SolverOptions {
                dbeta: db * propbet_bemt::solve::QPROP_PI / 180.0,
                keep_stations: single,
                ..SolverOptions::default()
            };
            let grid: Vec<(f64, f64)> = rpms.iter().flat_map(|&r| speeds.iter().map(move |&v| (r, v))).collect();
            let ops: Vec<OperatingPoint> = grid.iter().map(|&(r, v)| OperatingPoint::from_rpm(v, r)).collect();
            let solved = if single {
                vec![solve_point(&rotor, &fluid, ops[0], &opts)]
            } else {
                solve_points(&rotor, &fluid, &ops, &opts)
            };
            for (&(rpm, v), p) in grid.iter().zip(solved) {
                {
                    let row = rows
                        .next()
                        .unwrap_or_else(|| panic!("{out_file}: fewer rows than points"));
                    let effprop = if p.power != 0.0 { p.thrust * v / p.power } else { 0.0 };
                    let ours: [f64; 19] = [
                        v,
                        p.rpm,
                        db,
                        p.thrust,
                        p.torque,
                        p.power,
                        0.0,
                        0.0,
                        0.0,
                        effprop,
                        p.adv_qprop.unwrap(),
                        p.ct_qprop.unwrap(),
                        p.cp_qprop.unwrap(),
                        p.dv,
                        0.0,
                        0.0,
                        p.thrust * v,
                        p.cl_avg,
                        p.cd_avg,
                    ];
                    for &k in &PROP_COLUMNS {
                        let what = format!("{out_file} V={v} rpm={rpm} dbeta={db} {}", SUMMARY_COLUMNS[k]);
                        bad.check(&what, row[k], ours[k]);
                        compared += 1;
                    }
                    assert_eq!(p.not_converged, 0, "{out_file} V={v} rpm={rpm}");
                    if single {
                        compared += check_stations(out_file, &out, &p, v, &mut bad);
                    }
                }
            }
        }
        assert!(rows.next().is_none(), "{out_file}: more rows than points");
    }
    assert!(compared > 2500, "compared only {compared} numbers");
    assert!(
        bad.0.is_empty(),
        "{} of {compared} numbers differ:\n{}",
        bad.0.len(),
        bad.0.join("\n")
    );
}
