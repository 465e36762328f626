//! Unit tests of `signature.rs`.

use super::*;
use crate::Observation;

/// The findings of a signature, by kind.
fn shows(s: &Signature) -> Vec<&Shows> {
    s.parts.iter().map(|p| &p.shows).collect()
}

fn groups_confounded(s: &Signature) -> Option<(bool, Option<f64>)> {
    s.parts.iter().find_map(|p| match p.shows {
        Shows::RpmGroups { confounded, power, .. } => Some((confounded, power)),
        _ => None,
    })
}

fn rpm_trend(s: &Signature) -> Option<(f64, Regime, bool)> {
    s.parts.iter().find_map(|p| match p.shows {
        Shows::WithRpm {
            trend, regime, faster, ..
        } => Some((trend.change, regime, faster)),
        _ => None,
    })
}

/// Thrust-only data: (rpm group's RPM, J) per point.
fn data(points: &[(f64, f64)]) -> Data {
    let obs = points
        .iter()
        .enumerate()
        .map(|(index, &(rpm, j))| Observation {
            index,
            file: 0,
            label: format!("line {index}"),
            omega: propbet_units::rpm_to_omega(rpm),
            v: 0.0,
            j,
            fluid: propbet_bemt::Fluid::QPROP_DEFAULT,
            thrust: 1.0,
            torque: None,
            rpm_group: rpm as i64,
            rpm_name: format!("{rpm} rpm"),
            mach_tip: 0.1,
        })
        .collect();
    Data {
        obs,
        thrust_floor: 0.05,
        torque_floor: 0.0,
    }
}

#[test]
fn rpm_groups_at_other_j_are_not_called_an_rpm_trend() {
    // A low-J sweep at 3000 rpm and a high-J one at 6000 rpm, the error a function of J
    // alone: no J bin holds both speeds, and the groups' errors differ through J only.
    let pts: Vec<(f64, f64)> = (0..6)
        .map(|k| (3000.0, 0.05 * k as f64))
        .chain((0..6).map(|k| (6000.0, 0.42 + 0.05 * k as f64)))
        .collect();
    let e: Vec<f64> = pts.iter().map(|p| -p.1).collect();
    let s = &signatures(&data(&pts), &e, &[])[0];
    assert_eq!(groups_confounded(s), Some((true, None)), "{s:?}");
    // Both speeds at the same J: the trend at fixed J says it, once.
    let pts: Vec<(f64, f64)> = [3000.0, 6000.0]
        .into_iter()
        .flat_map(|r| (0..6).map(move |k| (r, 0.05 * k as f64)))
        .collect();
    let e: Vec<f64> = pts.iter().map(|p| -0.2 * (p.0 / 3000.0 - 1.0)).collect();
    let s = &signatures(&data(&pts), &e, &[])[0];
    let (change, _, _) = rpm_trend(s).unwrap();
    assert!((change + 0.2).abs() < 5e-4, "{s:?}");
    assert_ne!(groups_confounded(s).map(|g| g.0), Some(true), "{s:?}");
    // The high-J sweep reaching further at 6000 rpm, the error growing with J: the trend at
    // fixed J is measured on the J both speeds share, the groups are not compared.
    let mut pts = pts;
    pts.extend((1..5).map(|k| (6000.0, 0.25 + 0.1 * k as f64)));
    let e: Vec<f64> = pts.iter().map(|p| -0.2 * (p.0 / 3000.0 - 1.0) - p.1).collect();
    let s = &signatures(&data(&pts), &e, &[])[0];
    let (change, _, _) = rpm_trend(s).unwrap();
    assert!((change + 0.2).abs() < 5e-4, "{s:?}");
    assert_eq!(groups_confounded(s), None, "the groups are not compared: {s:?}");
}

#[test]
fn the_rpm_trend_is_measured_at_fixed_j() {
    // At each J the error falls by 5 % per doubling of RPM; across J it varies much more
    // (a J pattern the trend must not mistake for an RPM one).
    let mut pts = Vec::new();
    for (k, j) in [0.0, 0.2, 0.4].into_iter().enumerate() {
        for rpm in [3000.0f64, 6000.0] {
            let e = -0.3 * k as f64 - 0.05 * (rpm / 3000.0).log2();
            pts.push((j, rpm, 0, e));
        }
    }
    let t = rpm_trend_at_fixed_j(&pts).unwrap();
    assert!((t.change + 0.05).abs() < 1e-9, "{t:?}");
    assert_eq!((t.lo.round(), t.hi.round()), (3000.0, 6000.0));
    // J sweeps at 4000-6000 rpm with that trend, a static test at 2000-6000 rpm without
    // one (an 11x7 E's pattern): the sweeps' slope is told over their own range, not
    // stretched over the static test's, and the static trend beside it.
    let mut mixed = Vec::new();
    for k in 0..5 {
        for rpm in [4000.0f64, 5000.0, 6000.0] {
            mixed.push((0.1 + 0.1 * k as f64, rpm, 0, -0.1 * (rpm / 4000.0).ln()));
        }
    }
    for k in 0..5 {
        mixed.push((0.0, 2000.0 + 1000.0 * k as f64, 1, 0.08));
    }
    let t = rpm_trend_at_fixed_j(&mixed).unwrap();
    assert!((t.change + 0.1 * 1.5f64.ln()).abs() < 1e-9, "{t:?}");
    assert_eq!((t.lo.round(), t.hi.round()), (4000.0, 6000.0));
    let s = static_rpm_trend(&mixed).unwrap();
    assert!(
        s.change.abs() < 1e-9 && s.lo.round() == 2000.0 && s.hi.round() == 6000.0,
        "{s:?}"
    );
    let obs: Vec<(f64, f64)> = mixed.iter().map(|p| (p.1, p.0)).collect();
    let e: Vec<f64> = mixed.iter().map(|p| p.3).collect();
    let sig = &signatures(&data(&obs), &e, &[])[0];
    let found = sig.parts.iter().find_map(|p| match &p.shows {
        Shows::WithRpm {
            all_static,
            trend,
            statically,
            ..
        } => Some((*all_static, *trend, *statically)),
        _ => None,
    });
    let (all_static, trend, statically) = found.unwrap();
    assert!(!all_static && (trend.change + 0.041).abs() < 5e-4, "{sig:?}");
    let st = statically.unwrap();
    assert!(st.change.abs() < 1e-9 && st.lo.round() == 2000.0, "{st:?}");
    // A static test alone: its trend is said as static.
    let stat_only: Vec<(f64, f64)> = (0..5).map(|k| (2000.0 + 1000.0 * k as f64, 0.0)).collect();
    let e: Vec<f64> = stat_only.iter().map(|p| -0.1 * (p.0 / 2000.0).ln()).collect();
    let sig = &signatures(&data(&stat_only), &e, &[])[0];
    assert!(
        sig.parts.iter().any(|p| matches!(
            p.shows,
            Shows::WithRpm {
                all_static: true,
                statically: None,
                ..
            }
        )),
        "{sig:?}"
    );
    let (change, _, _) = rpm_trend(sig).unwrap();
    assert!((change + 0.110).abs() < 5e-4, "{sig:?}");
    // No static test: no static trend.
    let forward: Vec<_> = pts.iter().filter(|p| p.0 > 0.0).copied().collect();
    assert!(rpm_trend_at_fixed_j(&forward).is_some() && static_rpm_trend(&forward).is_none());
    // No bin spans 1.3x in RPM: no trend to tell.
    let narrow: Vec<_> = pts.iter().filter(|p| p.1 == 3000.0).copied().collect();
    assert!(rpm_trend_at_fixed_j(&narrow).is_none());
}

#[test]
fn the_effects_that_can_make_a_trend_come_from_their_responses() {
    // J sweeps at 3000-6000 rpm whose error falls with RPM, a static test at 2000-6000 rpm
    // without it: the trend is the J sweeps' alone.
    let mut pts: Vec<(f64, f64)> = Vec::new();
    for j in [0.2, 0.3, 0.4] {
        for rpm in [3000.0, 4500.0, 6000.0] {
            pts.push((rpm, j));
        }
    }
    for rpm in [2000.0, 3000.0, 4000.0, 5000.0, 6000.0] {
        pts.push((rpm, 0.0));
    }
    let e: Vec<f64> = pts
        .iter()
        .map(|&(rpm, j)| if j > 0.0 { -0.1 * (rpm / 3000.0).ln() } else { 0.0 })
        .collect();
    let probe = |f: &dyn Fn(f64, f64) -> f64| -> Vec<Vec<f64>> {
        [0.5, 1.0]
            .iter()
            .map(|s| pts.iter().map(|&(rpm, j)| s * f(rpm, j)).collect())
            .collect()
    };
    let responses = vec![
        // Moves the J sweeps' loads with RPM and not the static ones: can.
        Response {
            id: "forward".into(),
            probes: probe(&|rpm, j| if j > 0.0 { 0.1 * (rpm / 3000.0).ln() } else { 0.0 }),
        },
        // Moves every load alike with RPM: takes the J sweeps' trend and makes a static one
        // as large: cannot.
        Response {
            id: "everywhere".into(),
            probes: probe(&|rpm, _| 0.1 * (rpm / 3000.0).ln()),
        },
        // Takes the trend away but swamps one point: the error varies more, cannot.
        Response {
            id: "swamping".into(),
            probes: probe(&|rpm, j| {
                let base = if j > 0.0 { 0.1 * (rpm / 3000.0).ln() } else { 0.0 };
                if j == 0.4 && rpm == 3000.0 {
                    base + 5.0
                } else {
                    base
                }
            }),
        },
        // Moves nothing: cannot.
        Response {
            id: "nothing".into(),
            probes: probe(&|_, _| 0.0),
        },
    ];
    let s = &signatures(&data(&pts), &e, &responses)[0];
    let (_, regime, faster) = rpm_trend(s).unwrap();
    assert_eq!((regime, faster), (Regime::ForwardOnly, true), "{s:?}");
    let trend_effects = |s: &Signature| {
        s.parts
            .iter()
            .find(|p| matches!(p.shows, Shows::WithRpm { .. }))
            .and_then(|p| p.effects.clone())
    };
    let l = trend_effects(s).unwrap();
    assert_eq!(l.can, ["forward"]);
    assert_eq!(l.cannot, ["everywhere", "swamping", "nothing"]);
    // Without responses no list; with only those that cannot, none can.
    assert_eq!(trend_effects(&signatures(&data(&pts), &e, &[])[0]), None);
    let l = trend_effects(&signatures(&data(&pts), &e, &responses[1..])[0]).unwrap();
    assert!(l.can.is_empty(), "{l:?}");
}

#[test]
fn thrust_against_torque_names_what_can_make_both() {
    // Thrust 10 % high and torque 20 % low at every point: in opposite directions.
    let mut d = data(&[(3000.0, 0.0), (4000.0, 0.0), (5000.0, 0.0), (6000.0, 0.0)]);
    for o in &mut d.obs {
        o.torque = Some(1.0);
    }
    d.torque_floor = 0.05;
    let e: Vec<f64> = (0..8).map(|k| if k % 2 == 0 { 0.1 } else { -0.2 }).collect();
    let rows = |t: f64, q: f64| -> Vec<Vec<f64>> { vec![(0..8).map(|k| if k % 2 == 0 { t } else { q }).collect()] };
    let responses = vec![
        // More drag: less thrust, more torque.
        Response {
            id: "drag".into(),
            probes: rows(-0.05, 0.2),
        },
        // An angle: both the same way.
        Response {
            id: "angle".into(),
            probes: rows(0.1, 0.1),
        },
    ];
    let s = signatures(&d, &e, &responses);
    let pair = s[1].parts.last().unwrap();
    assert!(
        matches!(
            pair.shows,
            Shows::ThrustTorque {
                relation: Relation::Opposite,
                ..
            }
        ),
        "{pair:?}"
    );
    let l = pair.effects.clone().unwrap();
    assert_eq!(
        (l.object.as_str(), l.can, l.cannot),
        ("both", vec!["drag".to_string()], vec!["angle".to_string()])
    );
    // Both high by similar amounts: the angles, the air, the RPM.
    let e: Vec<f64> = (0..8).map(|k| if k % 2 == 0 { 0.1 } else { 0.12 }).collect();
    let s = signatures(&d, &e, &[]);
    let pair = s[1].parts.last().unwrap();
    assert!(
        matches!(
            pair.shows,
            Shows::ThrustTorque {
                relation: Relation::Similar,
                ..
            }
        ),
        "{:?}",
        shows(&s[1])
    );
    assert_eq!(pair.effects, None, "no candidates, no list");
}
