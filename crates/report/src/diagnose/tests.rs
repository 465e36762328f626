//! Unit tests of `diagnose.rs`.

use super::signature_html;
use propbet_diagnose::signature::{EffectList, Part, Signature};

fn sig(parts: Vec<Part>) -> Signature {
    Signature {
        quantity: "thrust".into(),
        mean: -0.211,
        rms: 0.287,
        text: String::new(),
        parts,
    }
}

#[test]
fn a_pattern_is_a_list_with_its_effects_in_bold() {
    let list = |lead: &str, can: &[&str], rest: &str| EffectList {
        lead: lead.into(),
        can: can.iter().map(|c| c.to_string()).collect(),
        rest: rest.into(),
    };
    let h = signature_html(&sig(vec![
        Part {
            text: "thrust under-predicted by 21.1 % on average (RMS 28.7 %)".into(),
            effects: None,
        },
        Part {
            text: "Largest at J > 0.32 (-35.1 % there, -7.7 % elsewhere): from the angles".into(),
            effects: Some(list(
                "Effects that can make it (from the model's response to each, within its bounds): ",
                &["pitch-offset", "rpm-scale"],
                "; not density",
            )),
        },
        Part {
            text: "At fixed J the error changes by -4.3 % from 4014 to 6512 rpm".into(),
            effects: Some(list("No candidate effect can make it within its bounds", &[], "")),
        },
    ]));
    assert_eq!(
            h,
            "<li>thrust under-predicted by 21.1 % on average (RMS 28.7 %)<ul>\
             <li>Largest at J &gt; 0.32 (-35.1 % there, -7.7 % elsewhere): from the angles.<br>Effects that can make \
             it (from the model's response to each, within its bounds): <b>pitch-offset, rpm-scale</b><br>\
             <span class=\"note\">Cannot: density</span></li><li>At fixed J the error changes by -4.3 % from 4014 to 6512 rpm.<br>No candidate effect \
             can make it within its bounds</li></ul></li>\n"
        );
    // One part: one item, nothing nested.
    let one = Part {
        text: "thrust within 2 % everywhere".into(),
        effects: None,
    };
    assert_eq!(
        signature_html(&sig(vec![one])),
        "<li>thrust within 2 % everywhere</li>\n"
    );
}
