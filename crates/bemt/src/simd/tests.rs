//! The vector path against the scalar reference, batches against single points, warm starts
//! against cold ones.

use super::*;
use crate::aero::QpropCoefficients;
use crate::rotor::{Discretization, QpropBlade};

/// QPROP's example prop (cam6x3), with per-station coefficient variation so that lanes
/// differ in every constant.
fn rotor() -> Rotor {
    let r: Vec<f64> = [0.75, 1.0, 1.5, 2.0, 2.5, 2.875, 3.0]
        .iter()
        .map(|x| x * 0.0254)
        .collect();
    let chord = [0.66, 0.69, 0.63, 0.55, 0.44, 0.30, 0.19]
        .iter()
        .map(|x| x * 0.0254)
        .collect();
    let beta = [27.5f64, 22.0, 15.2, 10.2, 6.5, 4.6, 4.2]
        .iter()
        .map(|x| x.to_radians())
        .collect();
    let coeffs = (0..7)
        .map(|i| {
            let f = i as f64 / 6.0;
            QpropCoefficients::from_array([
                0.4 + 0.2 * f,
                5.8,
                -0.3,
                1.1 + 0.2 * f,
                0.028,
                0.05,
                0.04,
                0.5,
                7e4,
                -0.7,
            ])
        })
        .collect();
    QpropBlade {
        blades: 2.0,
        tip_radius: 0.0762,
        r,
        chord,
        beta,
        coeffs,
    }
    .to_rotor(Discretization::default())
    .unwrap()
}

/// `a`'s thrust and torque within `tol` of `b`'s, relative to `b`'s thrust plus torque over
/// the tip radius; the same stations unconverged.
fn assert_loads_agree(a: &PointResult, b: &PointResult, rotor: &Rotor, tol: f64, what: &str) {
    assert_eq!(a.not_converged, b.not_converged, "{what}");
    let scale = b.thrust.abs() + b.torque.abs() / rotor.tip_radius + 1e-12;
    assert!(
        (a.thrust - b.thrust).abs() < tol * scale,
        "{what}: thrust {} vs {}",
        a.thrust,
        b.thrust
    );
    assert!(
        (a.torque - b.torque).abs() < tol * scale * rotor.tip_radius,
        "{what}: torque {} vs {}",
        a.torque,
        b.torque
    );
}

#[test]
fn vector_and_scalar_paths_agree() {
    let rotor = rotor();
    let prepared = Prepared::new(&rotor).unwrap();
    // 25 stations: three full groups of 8, the last station on the scalar path.
    assert_eq!(prepared.groups.len(), 3);
    assert_eq!(prepared.scalar, vec![24]);
    let fluid = Fluid::default();
    let mut worst: f64 = 0.0;
    for rpm in [1500.0, 6000.0, 14000.0, 30000.0, 60000.0] {
        for v in [-8.0, 0.0, 3.0, 11.0, 25.0, 45.0] {
            for dbeta in [-6.0f64, 0.0, 9.0] {
                let opts = SolverOptions {
                    dbeta: dbeta.to_radians(),
                    keep_stations: true,
                    ..Default::default()
                };
                let op = OperatingPoint::from_rpm(v, rpm);
                let a = solve_point_prepared(&rotor, Some(&prepared), &fluid, op, &opts);
                let b = solve_point_prepared(&rotor, None, &fluid, op, &opts);
                assert_eq!(a.not_converged, b.not_converged, "rpm {rpm} v {v} dbeta {dbeta}");
                for (x, y) in [(a.thrust, b.thrust), (a.torque, b.torque), (a.cl_avg, b.cl_avg)] {
                    let scale = b.thrust.abs() + b.torque.abs() / rotor.tip_radius + 1e-12;
                    worst = worst.max((x - y).abs() / scale);
                }
                for (s, t) in a.stations.iter().zip(&b.stations) {
                    assert_eq!(s.stalled, t.stalled);
                    assert!(
                        (s.alpha - t.alpha).abs() < 1e-9,
                        "rpm {rpm} v {v}: {} vs {}",
                        s.alpha,
                        t.alpha
                    );
                }
            }
        }
    }
    assert!(worst < 1e-9, "worst relative difference {worst}");
}

#[test]
fn a_warm_start_finds_the_cold_roots_in_fewer_iterations() {
    use crate::{solve_point_scalar, solve_point_scalar_psi, Convergence, Psi};
    let rotor = rotor();
    let fluid = Fluid::default();
    let iterations = |p: &PointResult| -> u32 {
        p.stations
            .iter()
            .map(|s| match s.convergence {
                Convergence::Newton { iterations } => iterations,
                _ => 0,
            })
            .sum()
    };
    let (mut cold_iterations, mut warm_iterations) = (0, 0);
    for rpm in [1500.0, 6000.0, 14000.0, 30000.0] {
        for v in [0.0, 3.0, 11.0, 25.0] {
            let base = SolverOptions {
                keep_stations: true,
                ..Default::default()
            };
            let mut psi = Vec::new();
            let op = OperatingPoint::from_rpm(v, rpm);
            let recorded = solve_point_scalar_psi(&rotor, &fluid, op, &base, Psi::Record(&mut psi));
            assert_eq!(psi.len(), rotor.stations.len());
            assert!(psi.iter().all(|p| p.is_finite()), "{psi:?}");
            // Recording changes nothing; no start given is the cold start.
            let cold = solve_point_scalar(&rotor, &fluid, op, &base);
            assert_eq!(recorded.thrust.to_bits(), cold.thrust.to_bits());
            let none = solve_point_scalar_psi(&rotor, &fluid, op, &base, Psi::From(&[]));
            assert_eq!(none.torque.to_bits(), cold.torque.to_bits());
            // A model a little apart (a forward difference of the pitch): the same root, to
            // the Newton tolerance (1e-6 rad in psi: cold and warm stop at other iterates).
            let near = SolverOptions {
                dbeta: 0.01f64.to_radians(),
                ..base
            };
            let cold = solve_point_scalar(&rotor, &fluid, op, &near);
            let warm = solve_point_scalar_psi(&rotor, &fluid, op, &near, Psi::From(&psi));
            assert_loads_agree(&warm, &cold, &rotor, 1e-6, &format!("{rpm} rpm, {v} m/s"));
            cold_iterations += iterations(&cold);
            warm_iterations += iterations(&warm);
        }
    }
    assert!(
        (warm_iterations as f64) < 0.8 * cold_iterations as f64,
        "{warm_iterations} warm Newton iterations against {cold_iterations} cold"
    );
}

#[test]
fn batches_of_points_match_single_points() {
    let rotor = rotor();
    let prepared = Prepared::new(&rotor).unwrap();
    let fluid = Fluid::default();
    for dbeta in [-6.0f64, 0.0, 9.0] {
        let opts = SolverOptions {
            dbeta: dbeta.to_radians(),
            ..Default::default()
        };
        // Mixed speeds and rotation rates in one batch, and a short batch.
        let ops: Vec<OperatingPoint> = (0..11)
            .map(|k| OperatingPoint::from_rpm(-8.0 + 5.3 * k as f64, 1500.0 + 5300.0 * (k % 4) as f64))
            .collect();
        for batch in ops.chunks(8) {
            let many = solve_batch(&rotor, &prepared, &fluid, batch, &opts);
            for (op, a) in batch.iter().zip(&many) {
                let b = solve_point_prepared(&rotor, None, &fluid, *op, &opts);
                assert_loads_agree(a, &b, &rotor, 1e-9, &format!("{op:?}"));
                assert!((a.cd_avg - b.cd_avg).abs() < 1e-9 * b.cd_avg.abs().max(1e-3), "{op:?}");
            }
        }
    }
}
