//! The diagnosis page's parts: the before/after residual panels, the ladder's falling error,
//! a signature in words and the trend cells of the ranking.

use std::fmt::Write as _;

use super::*;

pub(super) fn residual_panels(data: &Data, d: &Diagnosis) -> Vec<Panel> {
    let rows = data.rows();
    // Static data (every point at J = 0) get no panel against J.
    let forward = data.obs.iter().any(|o| o.j >= 0.01);
    let mut panels = Vec::new();
    for torque in [false, true] {
        if !rows.iter().any(|r| r.torque == torque) {
            continue;
        }
        let q = if torque { "torque" } else { "thrust" };
        for (x_name, x_of) in [
            (
                "J",
                (|o: &propbet_diagnose::Observation| o.j) as fn(&propbet_diagnose::Observation) -> f64,
            ),
            ("RPM", |o: &propbet_diagnose::Observation| o.rpm()),
        ] {
            if x_name == "J" && !forward {
                continue;
            }
            let pts = |res: &[f64]| -> Vec<(f64, f64)> {
                rows.iter()
                    .zip(res)
                    .filter(|(r, _)| r.torque == torque)
                    .map(|(r, e): (&Row, &f64)| (x_of(&data.obs[r.point]), 100.0 * e))
                    .collect()
            };
            panels.push(Panel {
                title: format!("{q} error against {x_name}"),
                x_label: x_name.into(),
                y_label: format!("{q} error [%]"),
                series: vec![
                    Series::new("baseline", pts(&d.baseline_residuals), Mark::Dots, Some(0)),
                    Series::new(
                        "with the ladder's effects",
                        pts(&d.final_residuals),
                        Mark::Dots,
                        Some(1),
                    ),
                ],
                zero_line: true,
                y_clip: Some(ERROR_AXIS),
                equal_aspect: false,
            });
        }
    }
    panels
}

/// One quantity's pattern as a list item: its first part (the bias), the others (the J trend,
/// the RPM trend, thrust against torque) as a list under it, each with the effects it names on
/// a line of its own, the ones that can make it in bold.
pub(super) fn signature_html(s: &Signature) -> String {
    let part = |i: usize, p: &Part| -> String {
        let (text, _) = words::part_words(s, i, p);
        let mut h = esc(&text);
        if let Some(e) = &p.effects {
            let w = words::EffectWords::of(e);
            let can = if w.can.is_empty() {
                String::new()
            } else {
                format!("<b>{}</b>", esc(&w.can.join(", ")))
            };
            // The effects that cannot make it go on a line of their own, in small print: the
            // sentence names what can.
            let tail = p.unaffected.as_ref().map(words::unaffected_words).unwrap_or_default();
            let _ = write!(h, ".<br>{}{can}{}", esc(&w.lead), esc(&tail));
            if !w.cannot.is_empty() {
                let _ = write!(
                    h,
                    "<br><span class=\"note\">Cannot: {}</span>",
                    esc(&w.cannot.join(", "))
                );
            }
        }
        h
    };
    let Some((first, rest)) = s.parts.split_first() else {
        return format!("<li>{}</li>\n", esc(&words::signature_text(s)));
    };
    let mut h = format!("<li>{}", part(0, first));
    if !rest.is_empty() {
        h.push_str("<ul>");
        for (i, p) in rest.iter().enumerate() {
            let _ = write!(h, "<li>{}</li>", part(i + 1, p));
        }
        h.push_str("</ul>");
    }
    h.push_str("</li>\n");
    h
}

/// A rung's trend, signed, or a dash where the points show none.
pub(super) fn trend(t: Option<f64>) -> String {
    t.map_or("–".into(), |t| format!("{:+.1} %", 100.0 * t))
}

pub(super) fn ladder_figure(d: &Diagnosis) -> Figure {
    let k: Vec<(f64, f64)> = d
        .ladder
        .iter()
        .enumerate()
        .map(|(i, r)| (i as f64, 100.0 * r.kfold_rms))
        .collect();
    let s: Vec<(f64, f64)> = d
        .ladder
        .iter()
        .enumerate()
        .map(|(i, r)| (i as f64, 100.0 * r.rms))
        .collect();
    let mut series = vec![
        Series::new("held-out (k-fold)", k, Mark::Line, Some(0)),
        Series::new("in-sample", s, Mark::Dashed, Some(1)),
    ];
    if d.ladder.iter().all(|r| r.loro_rms.is_some()) {
        let l = d
            .ladder
            .iter()
            .enumerate()
            .map(|(i, r)| (i as f64, 100.0 * r.loro_rms.unwrap_or(f64::NAN)))
            .collect();
        series.push(Series::new("held-out (leave one RPM out)", l, Mark::Dots, Some(2)));
    }
    Figure {
        panels: vec![Panel {
            title: format!(
                "error after each step: {}",
                d.ladder
                    .iter()
                    .map(|r| r.added.as_str())
                    .collect::<Vec<_>>()
                    .join(" → ")
            ),
            x_label: "step".into(),
            y_label: "RMS relative error [%]".into(),
            series,
            zero_line: true,
            y_clip: None,
            equal_aspect: false,
        }],
        columns: 1,
        width: 900,
        height: 420,
    }
}
