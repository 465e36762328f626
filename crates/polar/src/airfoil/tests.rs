//! Unit tests of `airfoil.rs`.

#[test]
fn thin_airfoil_cl0_of_naca_mean_lines() {
    // NACA 2412: alpha_L0 = -2.077 deg by thin-airfoil theory (Anderson, Fundamentals of
    // Aerodynamics, example 4.6), CL0 = 2 pi x 0.03625 rad.
    let cl0 = super::naca4_cl0(0.02, 0.4);
    assert!(
        (cl0 - 2.0 * std::f64::consts::PI * 2.077f64.to_radians()).abs() < 2e-3,
        "{cl0}"
    );
    assert_eq!(super::naca4_cl0(0.0, 0.0), 0.0);
    assert!(super::naca4_cl0(0.04, 0.4) > cl0);
}

use super::*;

const E63: &str = include_str!("../../../../props/airfoils/e63.dat");
const CLARKY: &str = include_str!("../../../../props/airfoils/clarky.dat");

#[test]
fn e63_is_closed_at_the_trailing_edge() {
    let (a, repairs) = Airfoil::parse(E63, "e63.dat").unwrap();
    assert_eq!(a.name, "E63  (4.25%)");
    assert_eq!(a.points.first(), a.points.last());
    assert!(
        repairs.iter().any(|r| r.0.contains("closed the trailing edge")),
        "{repairs:?}"
    );
    let (t, _) = a.max_thickness();
    assert!((t - 0.0425).abs() < 0.001, "t/c = {t}");
}

#[test]
fn flat_bottoms_are_found_and_kept_when_scaled_as_a_whole() {
    let mut clarky = Airfoil::parse(CLARKY, "clarky.dat").unwrap().0;
    clarky.normalise();
    assert!(clarky.has_flat_bottom());
    let mut e63 = Airfoil::parse(E63, "e63.dat").unwrap().0;
    e63.normalise();
    assert!(!e63.has_flat_bottom(), "E63's lower surface is concave");
    let naca = naca4_from_name("naca4412").unwrap().unwrap();
    assert!(!naca.has_flat_bottom());
    let thick = clarky.scale_whole(0.20).unwrap();
    assert!((thick.max_thickness().0 - 0.20).abs() < 1e-9);
    assert!(thick.has_flat_bottom(), "scaled as a whole, the bottom stays flat");
    // About the camber line the bottom bulges.
    assert!(!clarky.scale_thickness(0.20).unwrap().has_flat_bottom());
    assert!(clarky.scale_whole(0.0).is_err() && clarky.scale_whole(f64::NAN).is_err());
}

/// The largest camber (mid-line height) of a normalised contour.
fn max_camber(a: &Airfoil) -> f64 {
    let (upper, lower) = a.surfaces();
    upper
        .iter()
        .filter(|q| q[0] > 0.01 && q[0] < 0.99)
        .map(|q| 0.5 * (q[1] + interp_surface(&lower, q[0])))
        .fold(f64::MIN, f64::max)
}

#[test]
fn apc_scaling_thins_as_a_whole_and_thickens_about_the_camber_line() {
    let naca = naca4_from_name("naca4412").unwrap().unwrap();
    assert!((max_camber(&naca) - 0.04).abs() < 0.002, "{}", max_camber(&naca));
    // Thinned (APC12 at an electric prop's t/c 0.10): camber falls with the thickness.
    let thin = naca.scale_as_apc(0.10).unwrap();
    assert!((thin.max_thickness().0 - 0.10).abs() < 1e-9);
    let want = 0.04 * 0.10 / naca.max_thickness().0;
    assert!(
        (max_camber(&thin) - want).abs() < 0.002,
        "{} vs {want}",
        max_camber(&thin)
    );
    // Thickened (E63 at a root's 0.20): its own camber kept, not scaled 4.7 times.
    let mut e63 = Airfoil::parse(E63, "e63.dat").unwrap().0;
    e63.normalise();
    let thick = e63.scale_as_apc(0.20).unwrap();
    assert!((thick.max_thickness().0 - 0.20).abs() < 0.002);
    assert!(
        (max_camber(&thick) - max_camber(&e63)).abs() < 0.003,
        "{} vs {}",
        max_camber(&thick),
        max_camber(&e63)
    );
    // Flat-bottomed (Clark-Y) thickened: as a whole, the bottom stays flat.
    let mut clarky = Airfoil::parse(CLARKY, "clarky.dat").unwrap().0;
    clarky.normalise();
    assert!(clarky.scale_as_apc(0.20).unwrap().has_flat_bottom());
    assert!(naca.scale_as_apc(0.0).is_err() && e63.scale_as_apc(0.7).is_err());
}

#[test]
fn lednicer_reads_like_selig() {
    let (selig, _) = Airfoil::parse(CLARKY, "clarky.dat").unwrap();
    let (upper, lower) = selig.surfaces();
    let mut led = format!("CLARK Y\n{}. {}.\n\n", upper.len(), lower.len());
    for q in upper.iter().chain([[f64::NAN; 2]].iter()).chain(lower.iter()) {
        if q[0].is_nan() {
            led.push('\n');
        } else {
            led.push_str(&format!("{} {}\n", q[0], q[1]));
        }
    }
    let (a, repairs) = Airfoil::parse(&led, "clarky-lednicer.dat").unwrap();
    assert!(repairs.iter().any(|r| r.0.contains("Lednicer")));
    assert_eq!(a.points, selig.points);
    let bad = led.replacen(&format!("{}.", upper.len()), &format!("{}.", upper.len() + 3), 1);
    let e = Airfoil::parse(&bad, "x.dat").unwrap_err().to_string();
    assert!(e.contains("announces"), "{e}");
    // Counts that overflow when added (found by fuzzing: a panic in release builds).
    let huge = "E63\n3.00000  99999999999999999999\n0.99719  -0\n0.98938  0.0\n";
    assert!(Airfoil::parse(huge, "h.dat")
        .unwrap_err()
        .to_string()
        .contains("announces"));
}

#[test]
fn garbage_names_the_line() {
    let e = Airfoil::parse("NACA 0012\n1.0 0.0\n0.5 banana\n", "bad.dat")
        .unwrap_err()
        .to_string();
    assert!(e.contains("bad.dat, line 3"), "{e}");
    let e = Airfoil::parse("1 0\n0.5 0.1\n0 0\n", "short.dat")
        .unwrap_err()
        .to_string();
    assert!(e.contains("at least 10"), "{e}");
    let e = Airfoil::parse("x\n1 0\n0.5 NaN\n", "nan.dat").unwrap_err().to_string();
    assert!(e.contains("line 3"), "{e}");
}

#[test]
fn an_upper_surface_alone_is_an_open_contour() {
    let (a, _) = Airfoil::parse(CLARKY, "clarky.dat").unwrap();
    let le = a.leading_edge_index();
    let half: String = a.points[..=le].iter().map(|q| format!("{} {}\n", q[0], q[1])).collect();
    let e = Airfoil::parse(&format!("half\n{half}"), "half.dat")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("open contour") || e.contains("no area") || e.contains("leading edge"),
        "{e}"
    );
}

#[test]
fn a_figure_eight_is_self_intersecting() {
    let mut text = String::from("eight\n");
    for i in 0..40 {
        let t = std::f64::consts::TAU * f64::from(i) / 40.0;
        text.push_str(&format!(
            "{} {}\n",
            0.5 + 0.5 * t.cos(),
            0.1 * (2.0 * t).sin() + 0.03 * t.sin()
        ));
    }
    let e = Airfoil::parse(&text, "eight.dat").unwrap_err().to_string();
    assert!(e.contains("crosses itself"), "{e}");
}

#[test]
fn clockwise_files_are_reversed() {
    let (a, _) = Airfoil::parse(CLARKY, "clarky.dat").unwrap();
    let mut rev = String::from("rev\n");
    for q in a.points.iter().rev() {
        rev.push_str(&format!("{} {}\n", q[0], q[1]));
    }
    let (b, repairs) = Airfoil::parse(&rev, "rev.dat").unwrap();
    assert!(repairs.iter().any(|r| r.0.contains("reversed")));
    assert_eq!(a.points, b.points);
}

#[test]
fn naca_4412_has_its_digits() {
    let a = naca4_from_name("naca4412").unwrap().unwrap();
    let (t, xt) = a.max_thickness();
    assert!((t - 0.12).abs() < 0.002, "t = {t}");
    assert!((xt - 0.3).abs() < 0.05, "x(t) = {xt}");
    // Camber 4 % at 40 %.
    let (u, l) = a.surfaces();
    let c = (interp_surface(&u, 0.4) + interp_surface(&l, 0.4)) / 2.0;
    assert!((c - 0.04).abs() < 0.002, "camber = {c}");
    a.check("naca4412").unwrap();
    assert!(naca4_from_name("naca44x2").is_none());
    assert!(naca4_from_name("clarky").is_none());
}

#[test]
fn thickness_scaling_keeps_x_and_the_leading_edge() {
    let (mut a, _) = Airfoil::parse(E63, "e63.dat").unwrap();
    a.normalise();
    let b = a.scale_thickness(0.06).unwrap();
    let (t, _) = b.max_thickness();
    assert!((t - 0.06).abs() < 1e-3, "t = {t}");
    let le = a.leading_edge_index();
    assert_eq!(a.points[le], b.points[le]);
    for (p, q) in a.points.iter().zip(&b.points) {
        assert_eq!(p[0], q[0]);
    }
    // No panel shrinks to nothing.
    assert!(b.points.windows(2).all(|w| dist(w[0], w[1]) > 1e-6));
    b.check("scaled").unwrap();
}

#[test]
fn repanel_keeps_the_shape() {
    let (mut a, _) = Airfoil::parse(CLARKY, "clarky.dat").unwrap();
    a.normalise();
    let b = a.repanel(161).unwrap();
    assert_eq!(b.points.len(), 161);
    b.check("repaneled").unwrap();
    let (ta, _) = a.max_thickness();
    let (tb, _) = b.max_thickness();
    assert!((ta - tb).abs() < 1e-3, "{ta} vs {tb}");
    assert_eq!(b.points[80], a.points[a.leading_edge_index()]);
}

#[test]
fn blend_halfway_is_between() {
    let (mut e63, _) = Airfoil::parse(E63, "e63.dat").unwrap();
    e63.normalise();
    let mut naca = naca4_from_name("naca4412").unwrap().unwrap();
    naca.normalise();
    let mid = e63.blend(&naca, 0.5, 61).unwrap();
    let (t, _) = mid.max_thickness();
    assert!(t > 0.05 && t < 0.11, "t = {t}");
    mid.check("blend").unwrap();
    let same = e63.blend(&naca, 0.0, 61).unwrap();
    let (t0, _) = same.max_thickness();
    assert!((t0 - 0.0425).abs() < 0.002);
}

#[test]
fn normalise_undoes_rotation_and_scale() {
    let mut a = naca4_from_name("naca2412").unwrap().unwrap();
    let orig = a.points.clone();
    let (s, c) = 0.3f64.sin_cos();
    for q in &mut a.points {
        *q = [3.0 + 0.2 * (c * q[0] - s * q[1]), -1.0 + 0.2 * (s * q[0] + c * q[1])];
    }
    let (chord, angle) = a.normalise();
    assert!(
        (chord - 0.2).abs() < 1e-9 && (angle - 0.3).abs() < 1e-9,
        "{chord} {angle}"
    );
    for (p, q) in a.points.iter().zip(&orig) {
        assert!(dist(*p, *q) < 1e-9);
    }
}

#[test]
fn selig_round_trip() {
    let (a, _) = Airfoil::parse(CLARKY, "clarky.dat").unwrap();
    let (b, _) = Airfoil::parse(&a.to_selig(), "again").unwrap();
    assert_eq!(a.name, b.name);
    for (p, q) in a.points.iter().zip(&b.points) {
        assert!(dist(*p, *q) < 1e-7);
    }
}
