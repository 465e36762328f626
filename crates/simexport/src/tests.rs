//! Unit tests of `simexport.rs`.

use super::*;

fn synthetic(measured: bool) -> Source {
    // CT = 0.11 - 0.05 J - 0.1 J^2, CP = 0.045 - 0.02 J - 0.03 J^2, times (rpm/5000)^0.1.
    let mut points = Vec::new();
    for rpm in [4000.0, 5000.0, 6000.0] {
        for k in 0..=24 {
            let j = 0.025 * k as f64;
            let f: f64 = (rpm / 5000.0f64).powf(0.1);
            points.push(Point {
                rpm,
                j,
                ct: (0.11 - 0.05 * j - 0.1 * j * j) * f,
                cp: (0.045 - 0.02 * j - 0.03 * j * j) * f,
            });
        }
    }
    Source {
        points,
        diameter: 0.254,
        blades: 2.0,
        ixx: Some((2e-5, "given".into())),
        origin: "a test".into(),
        name: "test prop".into(),
        measured,
    }
}

#[test]
fn sih_gets_a_quadratic_back_to_within_the_rpm_spread() {
    let e = px4_sih(&synthetic(false)).unwrap();
    let text = &e.files[0].1;
    assert!(text.contains("param set-default SIH_F_CT0 0.1"), "{text}");
    // The RPM factor (0.98 to 1.02) is all SIH cannot carry.
    assert!(
        e.fit.thrust.largest < 0.025 && e.fit.thrust.largest > 0.005,
        "{:?}",
        e.fit
    );
}

#[test]
fn jsbsim_reproduces_rpm_dependence_through_the_mach_tables() {
    let e = jsbsim(&synthetic(false)).unwrap();
    // Exact at J = 0; beyond, JSBSim reads the factor at the helical tip Mach number,
    // a little above the static one the factor was placed at.
    assert!(e.fit.thrust.median < 1e-3 && e.fit.thrust.largest < 3e-3, "{:?}", e.fit);
    assert!(e.fit.torque.largest < 3e-3, "{:?}", e.fit);
    assert!(e.files[0].1.contains("CT_MACH"));
    assert_eq!(e.files[0].0, "test_prop.xml");
    assert_eq!(
        file_stem("APC 10x4.7 Slow Flyer (E63, 4.25\")"),
        "APC_10x4.7_Slow_Flyer"
    );
    assert_eq!(file_stem("//"), "propeller");
}

#[test]
fn gazebo_constants_are_those_of_the_static_coefficients() {
    let src = synthetic(false);
    let e = gazebo(&src, Some((5000.0, 5000.0))).unwrap();
    // At 5000 rpm, CT 0.11: kf = CT rho D^4/(2 pi)^2.
    let kf = 0.11 * 1.225 * 0.254f64.powi(4) / std::f64::consts::TAU.powi(2);
    assert!(e.values.contains(&format!("motorConstant {kf:.4e}")), "{}", e.values);
    assert!(e.fit.thrust.largest < 1e-12);
}

#[test]
fn static_only_data_are_refused_for_curves_and_one_rpm_for_a_map() {
    let mut src = synthetic(true);
    src.points.retain(|p| p.j == 0.0);
    for t in [Target::Px4Sih, Target::Jsbsim, Target::Map] {
        let e = export(t, &src).unwrap_err().to_string();
        assert!(e.contains("static points (J = 0)"), "{t:?}: {e}");
    }
    assert!(export(Target::Gazebo, &src).is_ok());
    let mut one = synthetic(true);
    one.points.retain(|p| p.rpm == 5000.0);
    let e = export(Target::Map, &one).unwrap_err().to_string();
    assert!(e.contains("2 or more RPMs") && e.contains("5000 rpm"), "{e}");
    let mut moving = synthetic(false);
    moving.points.retain(|p| p.j > 0.1);
    assert!(export(Target::Gazebo, &moving)
        .unwrap_err()
        .to_string()
        .contains("zero airspeed"));
}

#[test]
fn measured_curves_are_smoothed_and_their_residual_reported() {
    let mut src = synthetic(true);
    for (k, p) in src.points.iter_mut().enumerate() {
        p.ct *= 1.0 + 0.01 * if k % 2 == 0 { 1.0 } else { -1.0 };
    }
    let e = map(&src).unwrap();
    assert!(
        e.fit.thrust.median > 0.005 && e.fit.thrust.largest < 0.03,
        "{:?}",
        e.fit
    );
    assert!(e.files[0].1.contains("Smoothing: each RPM"));
}

#[test]
fn a_rectangular_blade_has_the_textbook_inertia() {
    // B rho 0.685 t c^2 R^3 / 3 for a constant chord from 0 to R.
    let r: Vec<f64> = (0..=100).map(|k| 0.1 * k as f64 / 100.0).collect();
    let c = vec![0.02; r.len()];
    let i = blade_ixx(2.0, &r, &c, 0.1, 1200.0);
    let exact = 2.0 * 1200.0 * 0.685 * 0.1 * 0.02f64.powi(2) * 0.1f64.powi(3) / 3.0;
    assert!((i / exact - 1.0).abs() < 1e-3, "{i} {exact}");
}

/// A control character in a path (the origin names the files) cannot start a live line of any
/// export: every header line stays a comment.
#[test]
fn a_newline_in_a_path_never_reaches_a_line_of_its_own() {
    let mut src = synthetic(false);
    src.origin = "prop /tmp/x\nparam set-default SIH_F_CT0 99\r\n1,2,3".into();
    for e in [px4_sih(&src).unwrap(), map(&src).unwrap(), gazebo(&src, None).unwrap()] {
        for (name, text) in &e.files {
            assert!(
                !text.contains("SIH_F_CT0 99\n")
                    && !text.lines().any(|l| l.starts_with("param set-default SIH_F_CT0 99")),
                "{name}: {text}"
            );
            assert!(!text.lines().any(|l| l == "1,2,3"), "{name}");
        }
    }
}

/// A prediction at RPMs closer than 3 % apart: every RPM its own curve, every row labelled with
/// the RPM its CT came from (none thinned, none moved to a neighbour's label).
#[test]
fn a_prediction_map_keeps_every_rpm_under_its_own_label() {
    let mut src = synthetic(false);
    src.points = (0..40)
        .flat_map(|k| {
            let rpm = 1000.0 + 5.0 * k as f64;
            (0..4).map(move |i| Point {
                rpm,
                j: 0.1 * i as f64,
                ct: rpm * 1e-5 + 0.01 * i as f64,
                cp: 0.04,
            })
        })
        .collect();
    let e = map(&src).unwrap();
    let csv = &e.files[0].1;
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("rpm"))
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 160, "every point");
    for r in &rows {
        let (rpm, j, v, ct) = (r[0], r[1], r[2], r[3]);
        assert!((ct - (rpm * 1e-5 + 0.1 * j)).abs() < 1e-6, "{r:?}: CT from its own RPM");
        assert!((v - j * rpm / 60.0 * src.diameter).abs() < 1e-3, "{r:?}");
    }
}

/// A static-only log refused for PX4 SIH is told what measurements would do, never `--j` (which
/// `--measured` does not take).
#[test]
fn the_advice_for_static_measurements_fits_measurements() {
    let mut src = synthetic(true);
    src.points.retain(|p| p.j == 0.0);
    let e = px4_sih(&src).unwrap_err().to_string();
    assert!(
        e.contains("only static points") && e.contains("wind-tunnel files"),
        "{e}"
    );
    assert!(!e.contains("give a J sweep"), "{e}");
}
