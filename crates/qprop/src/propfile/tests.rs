//! Unit tests of `propfile.rs`.

use super::write::join;
use super::*;
use proptest::prelude::*;

const CAM: &str = include_str!("../../../../props/cam6x3/cam6x3.qprop");

fn err(text: &str) -> String {
    parse_prop(text).unwrap_err().to_string()
}

#[test]
fn full_precision_rows_are_rounded_to_fit_qprops_line() {
    let (mut f, _) = parse_prop(CAM).unwrap();
    let c = QpropCoefficients::from_array([
        -0.022252612361,
        3.3356735801,
        -0.40740000001,
        0.88450000003,
        0.12677403261,
        0.99681726581,
        0.99681726582,
        0.56160000001,
        17668.506671,
        -0.22529375781,
    ]);
    for i in 0..f.rows.len() {
        f.rows[i].r += 1.0 / 3.0;
        f.set_station_coeffs(i, &c);
    }
    let text = write_prop(&f);
    assert!(text.lines().all(|l| l.len() <= QPROP_LINE_MAX - 2), "{text}");
    let (g, _) = parse_prop(&text).unwrap();
    for i in 0..f.rows.len() {
        for (a, b) in g.coeffs_at(i).to_array().iter().zip(c.to_array()) {
            assert!((a / b - 1.0).abs() < 1e-3, "{a} vs {b}");
        }
        assert!((g.rows[i].r / f.rows[i].r - 1.0).abs() < 1e-4);
    }
}

#[test]
fn a_tip_radius_off_by_rounding_is_the_last_station_and_a_shorter_one_is_refused() {
    // What validate wrote for APC's 12x10E: 12 in / 2 as metres, and the last station.
    let text = |rad: &str| {
        format!(
            "apce 12x10\n 2 {rad}\n\n 0.5 5.8\n -0.3 1.2\n 0.028 0.05 0.05 0.5\n 70000 -0.7\n\n \
                 1 1 1\n 0 0 0\n\n 0.05 0.02 20\n 0.1524 0.01 10\n"
        )
    };
    let (f, _) = parse_prop(&text("0.15239999999999998")).unwrap();
    assert_eq!(f.tip_radius(RadiusReading::Documented), 0.1524);
    let e = err(&text("0.1523"));
    assert!(
        e.contains("tip radius R = 0.1523") && e.contains("less than the last radius 0.1524"),
        "{e}"
    );
}

#[test]
fn reads_cam6x3() {
    let (f, w) = parse_prop(CAM).unwrap();
    assert_eq!(f.name, "Graupner CAM 6x3 folder");
    assert_eq!(f.blades, 2.0);
    assert_eq!(f.radius, None);
    assert_eq!(f.global, [0.5, 5.8, -0.3, 1.2, 0.028, 0.05, 0.05, 0.5, 70000.0, -0.7]);
    assert_eq!(f.scale, [0.0254, 0.0254, 1.0]);
    assert_eq!(f.rows.len(), 7);
    assert_eq!(
        f.rows[5],
        PropRow {
            r: 2.875,
            chord: 0.30,
            beta: 4.6,
            coeffs: vec![]
        }
    );
    assert!(w.is_empty(), "{w:?}");
    let b = f.to_blade(RadiusReading::Documented);
    assert!((b.tip_radius - 3.0 * 0.0254).abs() < 1e-15);
}

#[test]
fn format_features() {
    // Comments with # and !, commas, tabs, D exponents, a BOM, CRLF, per-station columns
    // filled from the left.
    let text = "\u{feff}! comment\r\nmy prop ! trailing\r\n# c\n 3, 0.1 ! R\n0.4 6.0\n-0.2,1.1\n0.02 0.04 0.05 0.3\n5D4 -0.5\n1 1 1\n0\t0 0\n0.01 0.02 30 0.6\n0.05 0.015 12 0.7 5.5\n0.1 0.01 8\n";
    let (f, w) = parse_prop(text).unwrap();
    assert_eq!(f.name, "my prop");
    assert_eq!(f.blades, 3.0);
    assert_eq!(f.radius, Some(0.1));
    assert_eq!(f.global[8], 50000.0);
    let k0 = f.coeffs_at(0);
    assert_eq!((k0.cl0, k0.cl_a), (0.6, 6.0));
    let k1 = f.coeffs_at(1);
    assert_eq!((k1.cl0, k1.cl_a, k1.cl_min), (0.7, 5.5, -0.2));
    assert_eq!(f.coeffs_at(2).cl0, 0.4);
    assert!(w.is_empty(), "{w:?}");
}

#[test]
fn bad_input_is_named() {
    assert_eq!(err(""), "line 1: file ends before the name line");
    assert_eq!(
        err("name\n2\n0.5 5.8\n"),
        "line 4: file ends before the CLmin CLmax line"
    );
    let base = "n\n2\n0.5 5.8\n-0.3 1.2\n0.03 0.05 0.05 0.5\n70000 -0.7\n1 1 1\n0 0 0\n";
    assert_eq!(
        err(&format!("{base}0.01 0.01 10\n0.01 0.01 9\n"))
            .split(':')
            .next()
            .unwrap(),
        "line 10"
    );
    assert!(err(&format!("{base}0.02 0.01 10\n0.01 0.01 9\n")).contains("does not increase"));
    assert!(err(&format!("{base}0.01 -0.01 10\n0.02 0.01 9\n")).contains("chords must not be negative"));
    assert!(err(&format!("{base}0.01 0.01 NaN\n0.02 0.01 9\n")).contains("'NaN' is not a finite number"));
    assert!(err(&format!("{base}0.01 0.01 1O\n0.02 0.01 9\n")).contains("line 9: '1O' is not a number"));
    assert!(err(&format!("{base}0.01 0.01\n")).contains("line 9: expected 3 numbers"));
    assert!(err(&format!("{base}0.01 0.01 10\n")).contains("at least two radial rows"));
    assert!(err("n\n2\n0.5 5.8\n-0.3 1.2\n0.03 0.05\n").contains("line 5: expected 4 numbers"));
    assert!(err("n\n0\n").contains("blade count must be positive"));
}

#[test]
fn warns_where_qprop_differs() {
    let (f, w) = parse_prop(&CAM.replace(" 2           ! Nblades", " 2 3 ! Nblades R")).unwrap();
    assert_eq!(f.tip_radius(RadiusReading::Qprop122), 3.0);
    assert!((f.tip_radius(RadiusReading::Documented) - 0.0762).abs() < 1e-15);
    assert!(w.iter().any(|w| w.message.contains("unscaled")), "{w:?}");
}

#[test]
fn writes_what_it_reads() {
    let (f, _) = parse_prop(CAM).unwrap();
    let (g, _) = parse_prop(&write_prop(&f)).unwrap();
    assert_eq!(f, g);
    // A scan's accuracy travels as a comment line QPROP skips, and reads back exactly.
    let scanned = PropFile {
        accuracy: Some(GeometryAccuracy {
            blade_angle_deg: 0.1 + 0.2,
            chord: 0.0204,
        }),
        ..f.clone()
    };
    let text = write_prop(&scanned);
    let (back, w) = parse_prop(&text).unwrap();
    assert_eq!(back, scanned);
    assert!(w.is_empty(), "{w:?}");
    let skipped: String = text
        .lines()
        .filter(|l| !l.starts_with(ACCURACY_PREFIX))
        .collect::<Vec<_>>()
        .join("\n");
    assert_eq!(parse_prop(&skipped).unwrap().0, f);
    // A name with a newline (a case's name, --name) stays one line.
    let h = PropFile {
        name: "two\nlines\r\tname".into(),
        ..f
    };
    let (k, _) = parse_prop(&write_prop(&h)).unwrap();
    assert_eq!(k.name, "two lines  name");
    // A name longer than QPROP reads is cut to its line, on a character boundary, and
    // the file reads back without the long-line warning.
    let long = PropFile {
        name: "é".repeat(100),
        ..k
    };
    let text = write_prop(&long);
    assert!(text.lines().all(|l| l.len() <= QPROP_LINE_MAX), "{text}");
    let (back, w) = parse_prop(&text).unwrap();
    assert!(
        back.name.ends_with("...") && back.name.starts_with("éé"),
        "{}",
        back.name
    );
    assert!(w.iter().all(|w| !w.message.contains("characters long")), "{w:?}");
}

fn finite() -> impl Strategy<Value = f64> {
    prop_oneof![-1e6..1e6f64, -1.0..1.0f64, Just(0.1 + 0.2), 1e-30..1e-20f64]
}

proptest! {
    #[test]
    fn round_trip_any_numbers(
        blades in 1u8..8, r0 in 0.001..0.05f64, steps in proptest::collection::vec(0.001..0.02f64, 2..30),
        g in proptest::array::uniform10(finite()), extra in proptest::collection::vec(finite(), 0..11),
        radius in proptest::option::of(1.0..2.0f64),
    ) {
        let mut global = g;
        global[1] = global[1].abs() + 0.1; // CL_a > 0
        global[8] = global[8].abs() + 1.0; // REref > 0
        let mut r = r0;
        let mut rows = Vec::new();
        for (i, s) in steps.iter().enumerate() {
            r += s;
            let mut coeffs: Vec<f64> = if i % 3 == 0 { extra.clone() } else { vec![] };
            if coeffs.len() > 1 { coeffs[1] = coeffs[1].abs() + 0.1; }
            if coeffs.len() > 8 { coeffs[8] = coeffs[8].abs() + 1.0; }
            rows.push(PropRow { r, chord: 0.01 + s, beta: 40.0 * s, coeffs });
        }
        let f = PropFile { name: "p".into(), blades: blades as f64, radius, radius_in_metres: false, radius_line: 0, global, accuracy: None,
            scale: [1.0, 1.0, 1.0], offset: [0.0; 3], rows, row_lines: vec![] };
        let text = write_prop(&f);
        let (g1, _) = parse_prop(&text).unwrap();
        let (g2, _) = parse_prop(&write_prop(&g1)).unwrap();
        prop_assert_eq!(&g1, &g2);
        // Rows short enough for QPROP are written exactly.
        let fits = f.rows.iter().all(|r| {
            let mut v = vec![r.r, r.chord, r.beta];
            v.extend(&r.coeffs);
            join(&v).len() < QPROP_LINE_MAX - 2
        });
        if fits { prop_assert_eq!(&f, &g1); }
    }
}

/// A file of another kind is named as such, its contents never quoted.
#[test]
fn a_file_of_another_kind_is_not_echoed() {
    let e = parse_prop("root:x:0:0:root:/root:/bin/bash\nsecret:x:1:1\n")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("line 2: not a QPROP prop file") && !e.contains("secret"),
        "{e}"
    );
}
