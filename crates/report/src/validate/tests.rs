//! Unit tests of `validate.rs`.

use super::*;
use propbet_compare::metrics::{RegimeError, Regimes, StaticRise, ZeroThrustShift};
use propbet_diagnose::signature::RpmTrend;
use propbet_validate::{BeforeAfter, Per3Score, Spread};

fn row(p: &str, x: f64, apc: bool) -> Row {
    Row {
        prop: p.into(),
        points: 10,
        implausible: 0,
        beyond_polars: (0, 250),
        band: [None, None],
        ct: BeforeAfter {
            before: Spread {
                median: x,
                p90: 2.0 * x,
            },
            after: Spread {
                median: x / 2.0,
                p90: x,
            },
        },
        cp: BeforeAfter {
            before: Spread { median: x, p90: x },
            after: Spread { median: x, p90: x },
        },
        per3: apc.then_some(Per3Score {
            points: 9,
            ct: Spread { median: 0.08, p90: 0.2 },
            cp: Spread { median: 0.06, p90: 0.1 },
        }),
        ladder: "none".into(),
        held_out_ladders: ["none".into(), "none".into()],
        twist_gap: -1.24,
        uiuc_geometry: true,
        assumed_section: None,
        left_out: Vec::new(),
        static_fm: 0.131,
        regimes: Regimes {
            static_points: RegimeError {
                points: 4,
                ct: 0.076,
                cp: -0.03,
            },
            low_j: RegimeError {
                points: 0,
                ct: f64::NAN,
                cp: f64::NAN,
            },
            high_j: RegimeError {
                points: 6,
                ct: -x,
                cp: 0.0,
            },
        },
        static_rise: (x > 0.15).then_some(StaticRise {
            rpm_lo: 2377.0,
            rpm_hi: 6528.0,
            measured: 0.227,
            predicted: 0.094,
        }),
        forward_rpm_trend: (x > 0.15).then_some(RpmTrend {
            change: -0.123,
            lo: 4005.0,
            hi: 6707.0,
        }),
        zero_thrust_shift: (x > 0.15).then_some(ZeroThrustShift {
            rpm_lo: 4008.0,
            rpm_hi: 6819.0,
            sweeps: 4,
            measured: (0.651, 0.615),
            predicted: Some((0.612, 0.631)),
        }),
        repeatability: Some(0.004),
    }
}

#[test]
fn an_outlier_always_says_why() {
    assert_eq!(outlier_reason(&row("apce_a", 0.1, false)), None);
    // Nothing stands out in its data but its errors: the largest of them is the reason.
    let r = row("apce_b", 0.3, false);
    assert_eq!(
        outlier_reason(&r).unwrap(),
        "largest error CT -30 % (forward, J0/2 to 0.85 J0)"
    );
    let mut r = row("apcsf_c", 0.2, false);
    r.twist_gap = -3.8;
    r.repeatability = Some(0.031);
    r.static_fm = 0.24;
    assert_eq!(
        outlier_reason(&r).unwrap(),
        "UIUC's measured twist is +3.8° from APC's design (r/R 0.6-0.9); its repeated points disagree by 3.1 %; \
         static figure of merit +24 %; largest error CT -20 % (forward, J0/2 to 0.85 J0)"
    );
    r.uiuc_geometry = false;
    assert!(outlier_reason(&r)
        .unwrap()
        .starts_with("APC's design blade: no UIUC geometry"));
}

#[test]
fn tables_have_a_row_per_prop_family_medians_and_the_median_over_props() {
    let rows = [
        row("apce_a", 0.1, false),
        row("apce_b", 0.3, false),
        row("apcsf_c", 0.2, false),
    ];
    let skipped = [("apcc_7.4x8.25".to_string(), "no PE0 file".to_string())];
    let md = markdown(&rows, &skipped, "tables");
    assert!(md.contains("| apce_a | E | 10 | 10.0 % | 20.0 % |"), "{md}");
    assert!(md.contains("| 10.0 % | +13.1 % | -1.2° | none | none / none |"), "{md}");
    assert!(md.contains("| **E (median of 2)** |  | 20 | 20.0 % |"), "{md}");
    assert!(!md.contains("SF (median"), "a family of one has no median row: {md}");
    assert!(
        md.contains("| **all (median over props)** |  | 30 | 20.0 % | 40.0 % |"),
        "{md}"
    );
    assert!(
        md.contains("| apcc_7.4x8.25 | apcc | 0 | – |") && md.contains("not validated: no PE0 file"),
        "{md}"
    );
    assert!(!md.contains("APC CT"), "no PER3, no APC columns");
    // Where the error is: signed, a row per validated prop, "–" for a regime without points.
    assert!(
        md.contains(
            "| apce_b | +7.6 / -3.0 % (4) | – | -30.0 / +0.0 % (6) | +22.7 / +9.4 % (2377-6528 rpm) | -12.3 % (4005-6707 rpm) \
             | 0.651 → 0.615 (-5.5 %) / 0.612 → 0.631 (+3.1 %) (4008-6819 rpm) |"
        ),
        "{md}"
    );
    // No static test spanning 1.3x: "–".
    assert!(
        md.contains("| apce_a | +7.6 / -3.0 % (4) | – | -10.0 / +0.0 % (6) | – | – | – |"),
        "{md}"
    );
    // The answer first: the medians over the three props (no PER3, no band: not said).
    assert!(
        md.starts_with(
            "**Over the 3 props predicted with their maker's sections, the median error is 20.0 % in CT and 20.0 % in CP; after the held-out calibration 10.0 % and"
        ),
        "{md}"
    );
    assert!(
        !md.contains("APC's own code on the same points") && !md.contains("band holds"),
        "{md}"
    );
    // One prop: said in the singular.
    let one = headline(&rows[..1]).unwrap();
    assert!(
        one.starts_with("For the one prop predicted with its maker's sections, the median error is"),
        "{one}"
    );
    let page = html(&rows, &skipped, "tables");
    assert!(
        page.contains("<h1>Validation on measured propellers</h1>\n<p><b>Over the 3 props"),
        "{page}"
    );
    // 7 rows in the first table, 1 + 3 in the second.
    assert_eq!(page.matches("<tr>").count() + page.matches("<tr class").count(), 11);
    assert!(page.contains("<h2>Where the error is</h2>"), "{page}");
}

#[test]
fn a_model_that_never_reaches_zero_thrust_has_no_predicted_zero_thrust_j() {
    let mut a = row("apce_a", 0.3, false);
    if let Some(z) = a.zero_thrust_shift.as_mut() {
        z.predicted = None;
    }
    let md = markdown(&[a], &[], "tables");
    assert!(
        md.contains("| 0.651 → 0.615 (-5.5 %) / the model's beyond the measured J (4008-6819 rpm) |"),
        "{md}"
    );
}

#[test]
fn a_blade_without_uiuc_geometry_and_files_left_out_are_said() {
    let mut a = row("apce_a", 0.1, false);
    a.uiuc_geometry = false;
    a.twist_gap = f64::NAN;
    a.left_out = vec![
        ("apce_a_kt1.txt".into(), "a UIUC J sweep needs its RPM".into()),
        ("x.txt".into(), "d/x.txt: line 3: not a number".into()),
    ];
    let rows = [a, row("apce_b", 0.3, false)];
    let md = markdown(&rows, &[], "tables");
    assert!(
        md.contains("| +13.1 % | no UIUC geometry file: APC's design blade used | none |"),
        "{md}"
    );
    assert!(
        md.contains(&format!(
            "{LEFT_OUT_INTRO}\n\n- apce_a: apce_a_kt1.txt: a UIUC J sweep needs its RPM\n- apce_a: d/x.txt: line 3: not a number\n"
        )),
        "{md}"
    );
    let page = html(&rows, &[], "tables");
    assert!(
        page.contains("<li>apce_a: apce_a_kt1.txt: a UIUC J sweep needs its RPM</li>"),
        "{page}"
    );
    // Every file read: no list.
    assert!(!markdown(&rows[1..], &[], "tables").contains(LEFT_OUT_INTRO));
}

#[test]
fn assumed_sections_have_their_own_median() {
    let mut g = row("gwsdd_9x5", 0.5, false);
    g.assumed_section = Some("sd7037 t/c 0.092 (another maker)".into());
    let mut d = row("da4002_9x6.75", 0.7, false);
    d.assumed_section = g.assumed_section.clone();
    let rows = [row("apce_a", 0.1, false), row("apce_b", 0.3, false), g, d];
    let md = markdown(&rows, &[], "tables");
    assert!(
        md.contains("sections assumed: sd7037 t/c 0.092 (another maker)"),
        "{md}"
    );
    assert!(md.contains("Props without APC's sections"), "{md}");
    // The median over props is the APC props' (10 and 30 %: 20 %, their mean), the assumed
    // ones' (50 and 70 %: 60 %) apart.
    assert!(md.contains("| **all (median over props)** |  | 20 | 20.0 % |"), "{md}");
    assert!(
        md.contains("| **sections assumed (median of 2)** |  | 20 | 60.0 % |"),
        "{md}"
    );
    assert!(!markdown(&rows[..2], &[], "tables").contains("Props without APC's sections"));
    // On the page the note wraps as text; the numbers beside it stay on their line.
    let page = html(&rows, &[], "tables");
    assert!(page.contains("<td class=\"text\">sections assumed: sd7037"), "{page}");
    assert!(page.contains("<td style=\"white-space:nowrap\">-1.2°</td>"), "{page}");
}

#[test]
fn apc_columns_when_per3_is_given() {
    let rows = [row("apce_a", 0.1, true), row("apcsf_c", 0.2, false)];
    let md = markdown(&rows, &[], "tables");
    assert!(md.contains("| APC CT median | APC CT p90 |"), "{md}");
    assert!(
        md.contains("| apce_a | E | 10 | 10.0 % | 20.0 % | 10.0 % | 10.0 % | 8.0 % | 20.0 % | 6.0 % | 10.0 % |"),
        "{md}"
    );
    assert!(
        md.contains("| apcsf_c | SF | 10 | 20.0 % | 40.0 % | 20.0 % | 20.0 % | – | – | – | – |"),
        "{md}"
    );
    // The median over props of APC's columns uses the props that have them (10 and 20 %:
    // 15 %).
    assert!(
        md.contains("| **all (median over props)** |  | 20 | 15.0 % | 30.0 % | 15.0 % | 15.0 % | 8.0 % | 20.0 % | 6.0 % | 10.0 % |"),
        "{md}"
    );
}
