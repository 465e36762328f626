//! Unit tests of `diagnose.rs` and its words.

use super::{signature_html, signature_text};
use propbet_diagnose::signature::{
    EffectList, GroupMean, Part, Regime, Relation, RpmTrend, Shows, Signature, Unaffected,
};

fn sig(quantity: &str, parts: Vec<Part>) -> Signature {
    Signature {
        quantity: quantity.into(),
        mean: -0.211,
        rms: 0.287,
        parts,
    }
}

fn part(shows: Shows, effects: Option<EffectList>) -> Part {
    Part {
        shows,
        effects,
        unaffected: None,
    }
}

fn list(can: &[&str], cannot: &[&str]) -> Option<EffectList> {
    Some(EffectList {
        object: "it".into(),
        can: can.iter().map(|c| c.to_string()).collect(),
        cannot: cannot.iter().map(|c| c.to_string()).collect(),
        as_for_thrust: false,
    })
}

fn against_j() -> Shows {
    Shows::AgainstJ {
        median_j: 0.32,
        above: true,
        there: -0.351,
        elsewhere: -0.077,
        cause: true,
    }
}

fn with_rpm(regime: Regime, statically: Option<RpmTrend>) -> Shows {
    Shows::WithRpm {
        all_static: false,
        trend: RpmTrend {
            change: -0.043,
            lo: 4014.0,
            hi: 6512.0,
        },
        statically,
        faster: true,
        regime,
        cause: true,
    }
}

#[test]
fn a_pattern_is_a_list_with_its_effects_in_bold() {
    let h = signature_html(&sig(
        "thrust",
        vec![
            part(Shows::Bias, None),
            part(against_j(), list(&["pitch-offset", "rpm-scale"], &["density"])),
            part(with_rpm(Regime::Both, None), list(&[], &["density"])),
        ],
    ));
    assert_eq!(
        h,
        "<li>thrust under-predicted by 21.1 % on average (RMS 28.7 %)<ul>\
         <li>Largest at J &gt; 0.32 (-35.1 % there, -7.7 % elsewhere): an error that changes with J at fixed RPM \
         comes from the angles or the inflow.<br>Effects that can make it (from the model's response to each, \
         within its bounds): <b>pitch-offset, rpm-scale</b><br><span class=\"note\">Cannot: density</span></li>\
         <li>At fixed J the error changes by -4.3 % from 4014 to 6512 rpm: the measured thrust grows faster with \
         RPM than the model's (a Reynolds-number effect on the sections; Mach at high tip speeds).<br>No \
         candidate effect can make it within its bounds (from the model's response to each)</li></ul></li>\n"
    );
    // One part: one item, nothing nested.
    let mut quiet = sig("thrust", vec![part(Shows::Quiet, None)]);
    quiet.rms = 0.012;
    assert_eq!(
        signature_html(&quiet),
        "<li>thrust within 2 % everywhere (RMS 1.2 %)</li>\n"
    );
}

#[test]
fn each_finding_is_said_with_its_numbers_and_its_cause() {
    let text = signature_text(&sig(
        "thrust",
        vec![
            part(Shows::Bias, None),
            part(
                with_rpm(
                    Regime::ForwardOnly,
                    Some(RpmTrend {
                        change: 0.004,
                        lo: 2000.0,
                        hi: 6000.0,
                    }),
                ),
                list(&["forward"], &["everywhere", "nothing"]),
            ),
        ],
    ));
    assert_eq!(
        text,
        "thrust under-predicted by 21.1 % on average (RMS 28.7 %). At fixed J the error changes by -4.3 % from \
         4014 to 6512 rpm (statically by +0.4 % from 2000 to 6000 rpm): the measured thrust grows faster with RPM \
         than the model's in forward flight, not statically (what moves with Reynolds number at the small angles \
         of forward flight and not near stall: the sections' zero-lift angle, a laminar bubble's camber; or an \
         airspeed off by a constant, J off by dv/(nD), nothing statically; propbet's \
         docs/studies/re-zero-lift.toml and airspeed-offset.toml are user effects to test each). Effects that can \
         make it (from the model's response to each, within its bounds): forward; not everywhere, nothing"
    );
    let groups = |confounded: bool, power: Option<f64>| {
        signature_text(&sig(
            "thrust",
            vec![part(
                Shows::RpmGroups {
                    growing: true,
                    low: GroupMean {
                        rpm: 3000.0,
                        error: -0.05,
                        j: 0.12,
                    },
                    high: GroupMean {
                        rpm: 6000.0,
                        error: -0.2,
                        j: 0.67,
                    },
                    confounded,
                    power,
                },
                None,
            )],
        ))
    };
    assert_eq!(
        groups(true, None),
        "growing with RPM (-5.0 % at 3000 rpm, -20.0 % at 6000 rpm; at mean J 0.12 and 0.67: RPM and J are not \
         told apart)"
    );
    assert_eq!(
        groups(false, Some(2.0)),
        "growing with RPM (-5.0 % at 3000 rpm, -20.0 % at 6000 rpm, about RPM^2)"
    );
}

#[test]
fn torque_refers_to_thrusts_effects_and_says_what_is_unaffected() {
    let mut same = list(&["drag-scale"], &[]).unwrap();
    same.as_for_thrust = true;
    let mut last = part(
        Shows::ThrustTorque {
            relation: Relation::Opposite,
            thrust: 0.1,
            torque: -0.2,
        },
        Some(EffectList {
            object: "both".into(),
            ..list(&["drag"], &["angle"]).unwrap()
        }),
    );
    let text = |last: &Part| {
        signature_text(&sig(
            "torque",
            vec![
                part(Shows::Bias, None),
                part(against_j(), Some(same.clone())),
                last.clone(),
            ],
        ))
    };
    let t = text(&last);
    assert!(
        t.contains("The effects named for thrust can make it. Thrust and torque are off in opposite directions"),
        "{t}"
    );
    assert!(
        t.ends_with(
            "(+10.0 % and -20.0 % on average). Effects that can make both (from the model's response to each, \
             within its bounds): drag; not angle"
        ),
        "{t}"
    );
    // Only torque off: thrust unaffected, after the last words of the pattern.
    last.unaffected = Some(Unaffected {
        kept: "thrust".into(),
        moved: "torque".into(),
        alone: Some(vec!["drag-scale".into()]),
    });
    assert!(text(&last).ends_with(
        "drag; not angle; thrust unaffected: what moves torque alone (drag-scale can, from the model's response \
         to each within its bounds), not what changes the angles, the air or the RPM, which move both"
    ));
    last.effects = None;
    last.unaffected.as_mut().unwrap().alone = Some(Vec::new());
    assert!(text(&last).ends_with(
        "on average); thrust unaffected: what moves torque alone (no candidate does, in the model within its \
         bounds), not what changes the angles, the air or the RPM, which move both"
    ));
}
