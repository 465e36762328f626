//! The answer a page leads with: how far the prediction is from the measurements (static and
//! forward flight, thrust and torque, the maker's prediction beside it), the hover metrics a
//! stand user reads (figure of merit, thrust per watt), and what the diagnosis found, step by
//! step. `run` and `compare` open with it; the details follow below it.

use std::fmt::Write as _;

use propbet_compare::curves::Curves;
use propbet_compare::metrics::{figure_of_merit, Metric, Metrics};
use propbet_compare::ComparedPoint;
use propbet_measure::MeasuredSet;
use propbet_plot::{Figure, Mark, Panel, Series};
use propbet_units::stats::median;
use propbet_units::STANDARD_GRAVITY as G0;

use crate::page::{esc, sig};

/// A signed relative error in percent ("+1.2 %"), a dash where it is not finite.
pub fn pct(x: f64) -> String {
    if x.is_finite() {
        format!("{:+.1} %", 100.0 * x)
    } else {
        "–".into()
    }
}

/// Figure of merit and thrust per watt [g/W] of thrust `t` [N] and power `p` [W], with the
/// point's coefficients; None where thrust or power is not positive.
fn hover_of(ct: Option<f64>, cp: Option<f64>, t: Option<f64>, p: Option<f64>) -> Option<(f64, f64)> {
    let (ct, cp, t, p) = (ct?, cp?, t?, p?);
    (ct > 0.0 && cp > 0.0 && t > 0.0 && p > 0.0).then(|| (figure_of_merit(ct, cp), 1000.0 * t / G0 / p))
}

/// The hover metrics over the static points with thrust and power measured.
#[derive(Debug, Clone, PartialEq)]
pub struct Hover {
    /// Static points used.
    pub points: usize,
    /// Median figure of merit, measured and predicted.
    pub fm: (f64, f64),
    /// Thrust per watt [g/W] at the point of highest measured thrust, measured and predicted.
    pub g_per_w: (f64, f64),
    /// That point's measured thrust [N].
    pub at_thrust: f64,
}

/// The hover metrics of the static points (None without a static point with thrust and power
/// measured and predicted).
pub fn hover(points: &[ComparedPoint]) -> Option<Hover> {
    // (measured thrust, measured (FM, g/W), predicted (FM, g/W)) per static point.
    type Pair = (f64, (f64, f64), (f64, f64));
    let pairs: Vec<Pair> = points
        .iter()
        .filter(|p| p.is_static() && p.scored())
        .filter_map(|p| {
            let (m, q) = (&p.measured, &p.predicted);
            Some((
                m.thrust?,
                hover_of(m.ct, m.cp, m.thrust, m.power)?,
                hover_of(q.ct, q.cp, q.thrust, q.power)?,
            ))
        })
        .collect();
    let top = pairs.iter().max_by(|a, b| a.0.total_cmp(&b.0))?;
    Some(Hover {
        points: pairs.len(),
        fm: (
            median(pairs.iter().map(|p| p.1 .0).collect()),
            median(pairs.iter().map(|p| p.2 .0).collect()),
        ),
        g_per_w: (top.1 .1, top.2 .1),
        at_thrust: top.0,
    })
}

/// Figure of merit and thrust per watt against thrust at the static points: measured dots,
/// the prediction's static curve as a line (None without static points with power).
pub fn hover_figure(curves: &Curves, points: &[ComparedPoint]) -> Option<Figure> {
    let measured: Vec<(f64, (f64, f64))> = points
        .iter()
        .filter(|p| p.is_static())
        .filter_map(|p| {
            let m = &p.measured;
            Some((m.thrust?, hover_of(m.ct, m.cp, m.thrust, m.power)?))
        })
        .collect();
    if measured.is_empty() {
        return None;
    }
    let line: Vec<(f64, (f64, f64))> = curves
        .statics
        .as_deref()
        .unwrap_or_default()
        .iter()
        .filter_map(|(_, q)| Some((q.thrust?, hover_of(q.ct, q.cp, q.thrust, q.power)?)))
        .collect();
    let panel = |k: usize, title: &str, y: &str| Panel {
        title: title.into(),
        x_label: "thrust [N]".into(),
        y_label: y.into(),
        series: vec![
            Series::new(
                "measured",
                measured
                    .iter()
                    .map(|(t, h)| (*t, if k == 0 { h.0 } else { h.1 }))
                    .collect(),
                Mark::Dots,
                Some(0),
            ),
            Series::new(
                "predicted",
                line.iter().map(|(t, h)| (*t, if k == 0 { h.0 } else { h.1 })).collect(),
                Mark::Line,
                Some(1),
            ),
        ],
        zero_line: false,
        y_clip: None,
        equal_aspect: false,
    };
    Some(Figure {
        panels: vec![
            panel(0, "Hover: figure of merit against thrust", "figure of merit"),
            panel(
                1,
                "Hover: thrust per watt against thrust",
                "thrust per shaft power [g/W]",
            ),
        ],
        columns: 2,
        width: 1200,
        height: 420,
    })
}

/// The headline table: per group (static, forward flight) propbet's mean thrust and torque
/// errors with the worst point, the reference's beside them; then the hover metrics.
pub fn headline_html(m: &Metrics, reference: Option<&ReferenceScore>, points: &[ComparedPoint]) -> String {
    let rows = headline_rows(m, reference);
    let mut h = String::new();
    if rows.is_empty() {
        h.push_str(
            "<p class=\"warn\">No measured point could be scored (every point is flagged: see the point table).</p>\n",
        );
        return h;
    }
    let theirs = reference.map(ReferenceScore::short_name);
    h.push_str("<table class=\"headline\"><tr><th class=\"text\">points</th><th>n</th>");
    for q in ["thrust", "torque"] {
        let _ = write!(h, "<th>{q}, propbet</th>");
        if let Some(t) = &theirs {
            let _ = write!(h, "<th>{q}, {}</th>", esc(t));
        }
    }
    h.push_str("</tr>\n");
    for r in &rows {
        let _ = write!(h, "<tr><td class=\"text\">{}</td><td>{}</td>", esc(&r.name), r.points);
        for q in ["thrust", "torque"] {
            match r.errors.iter().find(|e| e.0 == q) {
                Some((_, x, other)) => {
                    let _ = write!(
                        h,
                        "<td><b>{}</b> <span class=\"note\">(worst {} at {})</span></td>",
                        pct(x.mean_rel),
                        pct(x.max_rel),
                        esc(&x.max_rel_at)
                    );
                    if theirs.is_some() {
                        let _ = write!(h, "<td>{}</td>", other.map_or("–".into(), pct));
                    }
                }
                None => {
                    h.push_str("<td>–</td>");
                    if theirs.is_some() {
                        h.push_str("<td>–</td>");
                    }
                }
            }
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</table>\n<p class=\"note\">Mean relative error, predicted − measured over measured; forward flight below 85 % of each sweep's zero-thrust J, where a relative error means something.</p>\n");
    if let Some(hv) = hover(points) {
        let _ = writeln!(
            h,
            "<p>Hover ({} static points): figure of merit measured {}, predicted {} ({}); thrust per watt at the highest thrust ({} N) measured {} g/W, predicted {} g/W ({}).</p>",
            hv.points,
            sig(hv.fm.0),
            sig(hv.fm.1),
            pct(hv.fm.1 / hv.fm.0 - 1.0),
            sig(hv.at_thrust),
            sig(hv.g_per_w.0),
            sig(hv.g_per_w.1),
            pct(hv.g_per_w.1 / hv.g_per_w.0 - 1.0),
        );
    }
    h
}

/// Another code's prediction scored on the same points, window and measure as propbet's: what
/// the headline, the terminal and `summary.json` say beside propbet's numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceScore {
    /// What it is ("APC's prediction (PER3_10x7.dat)").
    pub name: String,
    /// Its scores.
    pub metrics: Metrics,
}

impl ReferenceScore {
    /// Its mean relative error of `quantity` (thrust, torque) over the headline group named
    /// `group`; None where it has none (or not a finite one).
    pub fn mean_error(&self, group: &str, quantity: &str) -> Option<f64> {
        let g = self.metrics.headline.iter().find(|g| g.name == group)?;
        Some(g.metrics.get(quantity)?.mean_rel).filter(|x| x.is_finite())
    }

    /// Its short name ("APC's prediction" of "APC's prediction (PER3_10x47SF.dat)").
    pub fn short_name(&self) -> &str {
        self.name.split(" (").next().unwrap_or(&self.name)
    }

    /// As `metrics.json` and `summary.json` hold it: its name and [`headline_json`].
    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({"name": self.name, "headline": headline_json(&self.metrics)})
    }
}

/// The headline as JSON (`summary.json` of `propbet compare` and `propbet run`): per group of
/// points (static, forward flight), the scored points' count and, per quantity, the mean and
/// mean absolute relative error and the worst point.
pub fn headline_json(m: &Metrics) -> serde_json::Value {
    use serde_json::json;
    let groups: Vec<_> = m
        .headline
        .iter()
        .map(|g| {
            let q: serde_json::Map<String, serde_json::Value> = ["thrust", "torque"]
                .iter()
                .filter_map(|q| {
                    g.metrics.get(*q).map(|m| {
                        (
                            (*q).to_string(),
                            json!({"n": m.n, "mean_error": m.mean_rel, "mean_abs_error": m.mean_abs_rel,
                                   "worst_error": m.max_rel, "worst_at": m.max_rel_at}),
                        )
                    })
                })
                .collect();
            json!({"points": g.name, "count": g.points, "errors": q})
        })
        .collect();
    json!(groups)
}

/// The headline groups with another code's beside them: per group (static, forward flight) its
/// name, scored points, and per quantity (thrust, torque) propbet's mean relative error and the
/// other code's on the same points, where there is one.
pub struct HeadlineRow {
    /// "static", "forward flight, below 85 % of the zero-thrust J".
    pub name: String,
    /// Scored points.
    pub points: usize,
    /// (quantity, propbet's metric, the other code's mean relative error).
    pub errors: Vec<(&'static str, Metric, Option<f64>)>,
}

/// The rows of [`HeadlineRow`] from the metrics and another code's scores, if any.
pub fn headline_rows(m: &Metrics, reference: Option<&ReferenceScore>) -> Vec<HeadlineRow> {
    m.headline
        .iter()
        .map(|g| HeadlineRow {
            name: g.name.clone(),
            points: g.points,
            errors: ["thrust", "torque"]
                .into_iter()
                .filter_map(|q| {
                    let x = g.metrics.get(q)?.clone();
                    let other = reference.and_then(|r| r.mean_error(&g.name, q));
                    Some((q, x, other))
                })
                .collect(),
        })
        .collect()
}

/// The comparison in a few short lines (the terminal of `propbet run`): the files read and rows
/// dropped, then per headline group the mean thrust and torque error, another code's beside.
pub fn brief(sets: &[MeasuredSet], m: &Metrics, reference: Option<&ReferenceScore>) -> Vec<String> {
    let rows: usize = sets.iter().map(|s| s.rows).sum();
    let points: usize = sets.iter().map(|s| s.points.len()).sum();
    let faults: usize = sets.iter().map(MeasuredSet::faults).sum();
    let dropped: usize = sets.iter().map(|s| s.dropped.len()).sum();
    let mut out = vec![format!(
        "{} file{}, {rows} rows -> {points} points{}",
        sets.len(),
        if sets.len() == 1 { "" } else { "s" },
        match (dropped, faults) {
            (0, _) => ", none dropped".to_string(),
            (1, 0) => ", 1 row dropped (why: in the report)".to_string(),
            (d, 0) => format!(", {d} rows dropped (why: in the report)"),
            (d, f) => format!(", {d} rows dropped, {f} of them as faulty (in the report)"),
        }
    )];
    for r in headline_rows(m, reference) {
        let ours: Vec<String> = r
            .errors
            .iter()
            .map(|(q, x, _)| format!("{q} {}", pct(x.mean_rel)))
            .collect();
        let theirs: Vec<String> = r.errors.iter().filter_map(|(_, _, o)| o.map(pct)).collect();
        let name = r.name.split(',').next().unwrap_or(&r.name).to_string();
        out.push(format!(
            "{name} ({} points): {} mean error{}",
            r.points,
            ours.join(", "),
            match (reference, theirs.is_empty()) {
                (Some(rf), false) => format!("; {}: {}", rf.short_name(), theirs.join(", ")),
                _ => String::new(),
            }
        ));
    }
    if m.overall.points == 0 {
        out.push("no point could be scored (every point is flagged: see the report)".into());
    }
    out
}
