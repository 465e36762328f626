//! The run report's first screen: the verdict beside one figure, measured against predicted.

use std::fmt::Write as _;

use propbet_pipeline::run::RunOutcome;
use propbet_plot::{Figure, PlotError};

use crate::page::esc;

/// The first screen: the verdict in a few sentences (how close, validate's measure; what is
/// missing; where the calibrated model is worse than the prediction) beside one figure,
/// measured against predicted (`lead`, with the band).
pub(super) fn lead_html(
    h: &mut String,
    plan: &propbet_pipeline::case::RunPlan,
    run: &RunOutcome,
    lead: Option<&Figure>,
    reference: Option<&crate::answer::ReferenceScore>,
) -> Result<(), PlotError> {
    let Some(c) = &run.compared else { return Ok(()) };
    h.push_str("<div id=\"verdict\" style=\"display:flex;gap:1.5em;align-items:flex-start;flex-wrap:wrap\">\n<div style=\"flex:1 1 360px;font-size:1.05em\">\n");
    let (ct, cp, n) = crate::compare::accuracy(&c.points);
    if n > 0 {
        let _ = writeln!(
            h,
            "<p><strong>The prediction's median error: {:.1} % in CT, {:.1} % in CP</strong> (|predicted / measured − 1| over {n} points below 85 % of the zero-thrust J, as <code>propbet validate</code> scores).</p>",
            100.0 * ct,
            100.0 * cp
        );
    }
    if let Some(e) = &plan.expected {
        let _ = writeln!(h, "<p class=\"note\">{}</p>", esc(e));
    }
    for r in crate::answer::headline_rows(&c.metrics, None) {
        let errs: Vec<String> = r
            .errors
            .iter()
            .map(|(q, m, _)| format!("{q} {:+.1} %", 100.0 * m.mean_rel))
            .collect();
        let name = r.name.split(',').next().unwrap_or(&r.name).to_string();
        let _ = writeln!(
            h,
            "<p>{} ({} points): {} mean error.</p>",
            esc(&name),
            r.points,
            errs.join(", ")
        );
    }
    if let Some(d) = &run.diagnosed {
        let _ = writeln!(h, "<p>{}</p>", esc(&crate::diagnose::verdict(&d.diagnosis)));
    }
    if let Some(cal) = &run.calibrated {
        let worse = calibrated_worse(&c.metrics, cal);
        if !worse.is_empty() {
            let _ = writeln!(
                h,
                "<p class=\"warn\">The calibrated model (the prediction with these effects) is worse than the prediction in {}: it fits the measurements as a whole, not each regime.</p>",
                esc(&worse.join("; "))
            );
        }
    }
    h.push_str("</div>\n");
    if let Some(f) = lead {
        let _ = writeln!(
            h,
            "<figure style=\"flex:0 1 900px;margin:0\">{}<figcaption class=\"note\">Dots: measured, one colour per speed; lines: propbet's prediction; shaded: its uncertainty band{}.</figcaption></figure>",
            propbet_plot::svg_inline(f)?,
            reference.map_or(String::new(), |r| format!("; dashed: {}", esc(r.short_name())))
        );
    }
    h.push_str("</div>\n");
    Ok(())
}

/// The regimes and quantities where the calibrated model's mean |error| is larger than the
/// prediction's by more than a point: "static thrust (mean error −10.4 % → +17.0 %)".
pub fn calibrated_worse(
    prediction: &propbet_compare::metrics::Metrics,
    calibrated: &propbet_compare::metrics::Metrics,
) -> Vec<String> {
    let before = crate::answer::headline_rows(prediction, None);
    let after = crate::answer::headline_rows(calibrated, None);
    let mut out = Vec::new();
    for (b, a) in before.iter().zip(&after) {
        for ((q, mb, _), (_, ma, _)) in b.errors.iter().zip(&a.errors) {
            if ma.mean_abs_rel > mb.mean_abs_rel + 0.01 {
                let name = b.name.split(',').next().unwrap_or(&b.name);
                out.push(format!(
                    "{name} {q} (mean error {:+.1} % → {:+.1} %)",
                    100.0 * mb.mean_rel,
                    100.0 * ma.mean_rel
                ));
            }
        }
    }
    out
}
