//! What the data can tell, as the report says it before the answer: the one-sentence summary
//! and the table of detection limits.

use std::fmt::Write as _;

use propbet_diagnose::discover::Diagnosis;
use propbet_diagnose::limits::AnswerKind;
use propbet_effects::fmt_value;

use super::pct;
use crate::page::esc;

/// The pairs of candidates these data cannot tell apart (either way), each once.
pub fn tied_pairs(d: &Diagnosis) -> Vec<(String, String)> {
    let mut pairs: Vec<(String, String)> = Vec::new();
    for t in &d.separability.ties {
        let (a, b) = if t.effect < t.imitated_by {
            (t.effect.clone(), t.imitated_by.clone())
        } else {
            (t.imitated_by.clone(), t.effect.clone())
        };
        if !pairs.contains(&(a.clone(), b.clone())) {
            pairs.push((a, b));
        }
    }
    pairs
}

/// What these data can tell, in two sentences, before the answer: the sizes a change must
/// reach, and the pairs they cannot tell apart.
pub fn can_tell(d: &Diagnosis) -> String {
    let n = &d.separability.noise;
    let mut text = format!(
        "What these data can tell: a change of the thrust (torque) errors is seen above {} ({}) RMS",
        pct(n.shape_threshold[0]),
        if n.rows[1] > 0 {
            pct(n.shape_threshold[1])
        } else {
            "not measured".into()
        }
    );
    match n.model_error {
        Some(m) => {
            let _ = write!(
                text,
                " beyond a level and trends with RPM and J, which must exceed what the default model usually misses on \
                 {} props, {} ({}) (validate's median over {} props).",
                m.kind,
                pct(m.thrust),
                pct(m.torque),
                m.props
            );
        }
        None => text.push_str(
            "; propbet has no validated props of this kind, so the model's own error is not a term: an effect found \
             here may be some of the model's error.",
        ),
    }
    let pairs = tied_pairs(d);
    // The pairs of the ladder's effects by name, the others counted (the table lists them).
    let ladder: Vec<&str> = d.final_stack.active.iter().map(|a| a.effect.id()).collect();
    let (named, rest): (Vec<_>, Vec<_>) = pairs
        .iter()
        .partition(|(a, b)| ladder.contains(&a.as_str()) || ladder.contains(&b.as_str()));
    if pairs.is_empty() {
        text.push_str(" They tell every pair of candidates apart within physical sizes.");
    } else if named.is_empty() {
        let _ = write!(
            text,
            " They cannot tell apart {} pair{} of candidates within physical sizes (the table below).",
            rest.len(),
            if rest.len() == 1 { "" } else { "s" }
        );
    } else {
        let _ = write!(
            text,
            " They cannot tell apart, within physical sizes: {}{}.",
            named
                .iter()
                .map(|(a, b)| format!("{a} and {b}"))
                .collect::<Vec<_>>()
                .join("; "),
            if rest.is_empty() {
                String::new()
            } else {
                format!("; and {} other pairs (the table below)", rest.len())
            }
        );
    }
    text
}

/// The detection limit of every candidate parameter, as a table.
pub(super) fn limits_html(d: &Diagnosis) -> String {
    let mut h = String::from(
        "<h2>What these data can tell</h2>\n<p class=\"note\">Each candidate's smallest detectable size: its change of the \
         residual rows (from its Jacobian on these points) must exceed, load by load, the scatter (3 standard errors of the \
         fit's residuals, and 3 times the repeatability where the data show it) or, for its level and trends with RPM and \
         J, the model's usual error on props of this kind. An effect below its limit is never named as \
         found.</p>\n<table><tr><th class=\"text\">effect</th><th class=\"text\">parameter</th><th class=\"text\">moves</th>\
         <th>detectable from</th><th class=\"text\">physically expected</th><th class=\"text\">cannot be told from</th></tr>\n",
    );
    let pairs = tied_pairs(d);
    for l in &d.separability.limits {
        // Either way round: the candidates it cannot be told from.
        let ties: Vec<String> = pairs
            .iter()
            .filter_map(|(a, b)| {
                if *a == l.effect {
                    Some(b.clone())
                } else if *b == l.effect {
                    Some(a.clone())
                } else {
                    None
                }
            })
            .collect();
        let _ = writeln!(
            h,
            "<tr><td class=\"text\">{}</td><td class=\"text\">{}</td><td class=\"text\">{}</td><td class=\"num\">{}</td>\
             <td class=\"text\">{} to {}</td><td class=\"text\">{}</td></tr>",
            esc(&l.effect),
            esc(&l.param),
            esc(&l.moves),
            l.limit.map_or("not within its bounds".into(), |x| format!(
                "{} {} {}",
                if l.reference == 0.0 { "±".to_string() } else { format!("{} ±", fmt_value(l.reference)) },
                fmt_value(x),
                esc(if l.unit == "-" { "" } else { &l.unit })
            )),
            fmt_value(l.expected.0),
            fmt_value(l.expected.1),
            esc(&ties.join(", "))
        );
    }
    h.push_str("</table>\n");
    h
}

/// The closest of the candidates `ids` by name, the rest counted: "tip-loss, re-scaling or 5
/// others".
pub(super) fn others(ids: &[String]) -> String {
    const NAMED: usize = 2;
    match ids.len() {
        0 => String::new(),
        n if n <= NAMED + 1 => ids.join(" or "),
        n => format!("{} or {} others", ids[..NAMED].join(", "), n - NAMED),
    }
}

/// "`named` make(s) `whose` change inside its (their) expected range(s)": a calibration
/// factor's physical stand-ins, `count` of them, in words.
pub(super) fn stand_ins(named: &str, count: usize, whose: &str) -> String {
    let one = count == 1;
    format!(
        "{named} make{} {whose} change inside {} expected range{}",
        if one { "s" } else { "" },
        if one { "its" } else { "their" },
        if one { "" } else { "s" }
    )
}

/// "the data cannot tell a from b or c: <measurement> would tell them apart" for each group
/// the verdict answers, and "not named: x (below the detection limit)" for each effect below it.
pub(super) fn group_clauses(d: &Diagnosis) -> Vec<String> {
    d.verdict
        .answers
        .iter()
        .filter_map(|a| match a.kind {
            AnswerKind::Group => Some(format!(
                "the data cannot tell {} from {}: {} would tell them apart",
                a.id,
                others(&a.group[1..]),
                a.tell_apart.as_deref().unwrap_or("another measurement")
            )),
            AnswerKind::Calibration if a.group.len() > 1 => Some(format!(
                "{} is a calibration factor, and {}: {} would tell them apart",
                a.id,
                stand_ins(&others(&a.group[1..]), a.group.len() - 1, "its"),
                a.tell_apart.as_deref().unwrap_or("another measurement")
            )),
            AnswerKind::BelowLimit => Some(format!(
                "{} not named: its change is below what these data detect",
                a.id
            )),
            _ => None,
        })
        .collect()
}
