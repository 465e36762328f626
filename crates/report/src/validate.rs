//! The validation table of `propbet validate`: Markdown (for the README and the terminal) and
//! an HTML page. One row per prop (a prop that could not be validated keeps its row, with the
//! reason), then the median over the props of each family (E, SF, SP, FF) and over all.

use std::fmt::Write as _;

use propbet_compare::expected::family;
use propbet_compare::metrics::REGIMES;
use propbet_units::stats::median;
use propbet_validate::{family_groups, Row};

use crate::page::{esc, page};

/// A prop that was not validated: its name and why.
pub type Skipped = (String, String);

fn pct(x: f64) -> String {
    if x.is_finite() {
        format!("{:.1} %", 100.0 * x)
    } else {
        "–".into()
    }
}

/// Column heads; the APC columns only when some row has them.
fn head(apc: bool) -> Vec<&'static str> {
    let mut h = vec!["prop", "family", "points", "CT median", "CT p90", "CP median", "CP p90"];
    if apc {
        h.extend(["APC CT median", "APC CT p90", "APC CP median", "APC CP p90"]);
    }
    h.extend([
        "CT median after",
        "CT p90 after",
        "CP median after",
        "CP p90 after",
        "static figure of merit, predicted / measured − 1",
        "APC design − measured twist, r/R 0.6-0.9",
        "calibration (all files)",
        "held-out calibrations (each half)",
        "why an outlier (CT or CP median above 15 %)",
    ]);
    h
}

/// A prop whose CT or CP median error is above this is an outlier whose row says why.
pub const OUTLIER: f64 = 0.15;

/// Why a prop's error is far above the rest, from what its data show (None below
/// [`OUTLIER`]): a blade nobody measured, a measured twist far from APC's design, assumed
/// sections, repeat runs that disagree, the hover efficiency; always the largest signature
/// of its errors, so that an outlier is never without a reason.
pub fn outlier_reason(r: &Row) -> Option<String> {
    if !(r.ct.before.median > OUTLIER || r.cp.before.median > OUTLIER) {
        return None;
    }
    let mut why = Vec::new();
    if let Some(a) = &r.assumed_section {
        why.push(format!("sections assumed ({})", a.split(' ').next().unwrap_or(a)));
    } else if !r.uiuc_geometry {
        why.push("APC's design blade: no UIUC geometry to check its twist and chord against".into());
    } else if r.twist_gap.abs() > 2.0 {
        why.push(format!(
            "UIUC's measured twist is {:+.1}° from APC's design (r/R 0.6-0.9)",
            -r.twist_gap
        ));
    }
    if let Some(sd) = r.repeatability.filter(|sd| *sd > 0.02) {
        why.push(format!("its repeated points disagree by {:.1} %", 100.0 * sd));
    }
    if r.static_fm.abs() > OUTLIER {
        why.push(format!("static figure of merit {:+.0} %", 100.0 * r.static_fm));
    }
    // The regime and coefficient with the largest signed error.
    let largest = REGIMES
        .iter()
        .zip(r.regimes.all())
        .filter(|(_, g)| g.points > 0)
        .flat_map(|(name, g)| [("CT", g.ct, *name), ("CP", g.cp, *name)])
        .filter(|(_, e, _)| e.is_finite())
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()));
    if let Some((coef, e, regime)) = largest {
        why.push(format!("largest error {coef} {:+.0} % ({regime})", 100.0 * e));
    }
    Some(why.join("; "))
}

/// The numeric columns of a row, in table order (NaN where missing).
fn numbers(r: &Row, apc: bool) -> Vec<f64> {
    let (ct, cp) = (r.ct, r.cp);
    let mut v = vec![ct.before.median, ct.before.p90, cp.before.median, cp.before.p90];
    if apc {
        let p = r.per3.as_ref();
        v.extend([
            p.map_or(f64::NAN, |p| p.ct.median),
            p.map_or(f64::NAN, |p| p.ct.p90),
            p.map_or(f64::NAN, |p| p.cp.median),
            p.map_or(f64::NAN, |p| p.cp.p90),
        ]);
    }
    v.extend([ct.after.median, ct.after.p90, cp.after.median, cp.after.p90]);
    v
}

/// The cells of one prop's row.
fn cells(r: &Row, apc: bool) -> Vec<String> {
    let mut v = vec![r.prop.clone(), family(&r.prop), r.points.to_string()];
    v.extend(numbers(r, apc).into_iter().map(pct));
    v.push(if r.static_fm.is_finite() {
        format!("{:+.1} %", 100.0 * r.static_fm)
    } else {
        "–".into()
    });
    v.push(if let Some(a) = &r.assumed_section {
        format!("sections assumed: {a}")
    } else if !r.uiuc_geometry {
        "no UIUC geometry file: APC's design blade used".into()
    } else if r.twist_gap.is_finite() {
        format!("{:+.1}°", r.twist_gap)
    } else {
        "–".into()
    });
    v.push(r.ladder.clone());
    v.push(format!("{} / {}", r.held_out_ladders[0], r.held_out_ladders[1]));
    v.push(outlier_reason(r).unwrap_or_default());
    v
}

/// A summary row: the median over `rows` of each column.
fn median_row(label: String, rows: &[&Row], apc: bool) -> Vec<String> {
    let mut v = vec![
        label,
        String::new(),
        rows.iter().map(|r| r.points).sum::<usize>().to_string(),
    ];
    let cols: Vec<Vec<f64>> = rows.iter().map(|r| numbers(r, apc)).collect();
    for k in 0..cols.first().map_or(0, Vec::len) {
        let col: Vec<f64> = cols.iter().map(|c| c[k]).filter(|x| x.is_finite()).collect();
        v.push(pct(median(col)));
    }
    // The signed columns (figure of merit, twist), the ladders and the reasons have no median.
    v.extend([
        String::new(),
        String::new(),
        String::new(),
        String::new(),
        String::new(),
    ]);
    v
}

/// Every row of the table: props, skipped props, per-family medians (families with two or more
/// props), the median over all.
fn table(rows: &[Row], skipped: &[Skipped]) -> (Vec<&'static str>, Vec<(Vec<String>, bool)>) {
    let apc = rows.iter().any(|r| r.per3.is_some());
    let h = head(apc);
    let mut out: Vec<(Vec<String>, bool)> = rows.iter().map(|r| (cells(r, apc), false)).collect();
    for (prop, why) in skipped {
        let mut v = vec![prop.clone(), family(prop), "0".into()];
        v.resize(h.len() - 4, "–".into());
        v.push(String::new());
        v.push(format!("not validated: {why}"));
        v.push(String::new());
        v.push(String::new());
        out.push((v, false));
    }
    // The medians are over props predicted with their maker's sections; those whose section
    // was assumed get a median of their own.
    let apc_rows: Vec<&Row> = rows.iter().filter(|r| r.assumed_section.is_none()).collect();
    for (f, members) in family_groups(rows) {
        out.push((
            median_row(format!("{f} (median of {})", members.len()), &members, apc),
            true,
        ));
    }
    for (f, members) in propbet_validate::line_groups(rows) {
        out.push((
            median_row(format!("{f} (median of {})", members.len()), &members, apc),
            true,
        ));
    }
    if !apc_rows.is_empty() {
        out.push((median_row("all (median over props)".into(), &apc_rows, apc), true));
    }
    (h, out)
}

/// The second table: each prop's median signed error (predicted / measured − 1) of CT and CP
/// by regime, before calibration, with the points in each.
fn regime_table(rows: &[Row]) -> (Vec<String>, Vec<Vec<String>>) {
    let mut h = vec!["prop".to_string()];
    h.extend(REGIMES.iter().map(|r| format!("{r}: CT / CP (points)")));
    h.push("static CT rise with RPM: measured / predicted".into());
    h.push("CT error's change with RPM at fixed J, J sweeps".into());
    h.push("zero-thrust J from the lowest to the highest sweep RPM: measured / predicted".into());
    h.push("station solves beyond the polars' Re range".into());
    h.push("band: measured CT / CP inside (median half-width)".into());
    let signed = |x: f64| {
        if x.is_finite() {
            format!("{:+.1}", 100.0 * x)
        } else {
            "–".into()
        }
    };
    let body = rows
        .iter()
        .map(|r| {
            let mut v = vec![r.prop.clone()];
            v.extend(r.regimes.all().iter().map(|g| {
                if g.points == 0 {
                    "–".into()
                } else {
                    format!("{} / {} % ({})", signed(g.ct), signed(g.cp), g.points)
                }
            }));
            v.push(match r.static_rise {
                Some(s) => format!(
                    "{} / {} % ({:.0}-{:.0} rpm)",
                    signed(s.measured),
                    signed(s.predicted),
                    s.rpm_lo,
                    s.rpm_hi
                ),
                None => "–".into(),
            });
            v.push(match r.forward_rpm_trend {
                Some(t) => format!("{} % ({:.0}-{:.0} rpm)", signed(t.change), t.lo, t.hi),
                None => "–".into(),
            });
            v.push(match r.zero_thrust_shift {
                Some(z) => format!(
                    "{:.3} → {:.3} ({} %) / {} ({:.0}-{:.0} rpm)",
                    z.measured.0,
                    z.measured.1,
                    signed(z.measured_change()),
                    match (z.predicted, z.predicted_change()) {
                        (Some(q), Some(c)) => format!("{:.3} → {:.3} ({} %)", q.0, q.1, signed(c)),
                        _ => "the model's beyond the measured J".into(),
                    },
                    z.rpm_lo,
                    z.rpm_hi
                ),
                None => "–".into(),
            });
            let (beyond, solves) = r.beyond_polars;
            v.push(format!("{beyond} of {solves}"));
            v.push(match r.band {
                [Some(t), Some(p)] => format!(
                    "{:.0} / {:.0} % (±{:.1} / ±{:.1} %)",
                    100.0 * t.inside,
                    100.0 * p.inside,
                    100.0 * t.half_width,
                    100.0 * p.half_width
                ),
                _ => "–".into(),
            });
            v
        })
        .collect();
    (h, body)
}

const REGIME_INTRO: &str =
    "Where the error is, before calibration: the median signed error (predicted / measured − 1) \
     of CT and CP over the same points, static, in forward flight below half the prop's zero-thrust J, \
     J0 (the median of its sweeps'), and from there to 85 % of J0. A hover-efficiency error sits in the \
     static column; a pitch error (or a section's zero-lift angle) grows towards zero thrust, in the third. \
     Then: how much the static CT grows from the lowest to the highest static RPM, measured and \
     predicted (the sections' Reynolds-number dependence, and whatever else grows with RPM); and in \
     forward flight, how the CT error changes with RPM at fixed J over the J sweeps (the median over J \
     bins of its slope against ln RPM, over the RPM range they typically span: negative where the \
     measured CT grows faster with RPM than the model's). Then, where the J sweeps reach zero thrust, \
     how their zero-thrust J moves from the lowest to the highest sweep RPM (a line against ln RPM \
     through the sweeps'), measured and predicted: the blade's effective pitch at each speed. The \
     sections' Reynolds numbers move it up a little as the RPM rises; a measured one that falls \
     while the model's rises is a blade that twists nose-down as it speeds up (a flexible blade's \
     elastic washout, the diagnosis's elastic-twist), which no section model makes. Last, how many \
     of the station solves at the compared points fell beyond their polars' Reynolds-number range \
     (below the ladder's lowest rung or above its highest, where the end rung is extrapolated): \
     whether the ladder reaches every station at every operating point.";

/// [`REGIME_INTRO`] with its last column, the band's.
fn regime_intro() -> String {
    format!(
        "{REGIME_INTRO} Last, the uncertainty band's ({}, each solved at both ends, their root-sum-square, \
         with twice the measurements' repeatability where they repeat a point): the share of the \
         measured CT and CP inside it over the scored points, and its median half-width relative to \
         the prediction.",
        propbet_model::band::SOURCES_TEXT
    )
}

fn intro(model: &str) -> String {
    format!(
        "Relative errors |pred/meas − 1| of CT and CP, points below 85 % of each sweep's zero-thrust J \
         (static points included). Before: the blade + APC sections + their polars covering each \
         prop's measured RPM and J range ({model}); APC: APC's own predictions (PER3 files, not \
         measurements) on the same points; after: held out, each half of a prop's measurements (whole \
         sweeps alternately by RPM, the static points alternately) predicted with the rung of the \
         other half's ladder that scores lowest on that half without raising its leave-one-RPM-out \
         error; the calibration column is the rung of \
         the ladder on all files that scores lowest on them (the diagnosis's whole ladder is its own \
         report's). The static \
         figure of merit (CT^1.5 / CP · sqrt(2/π)) column is the median over the static points of the \
         predicted over the measured, minus 1: the hover efficiency's error, whatever its split \
         between thrust and power. The twist column is APC's design twist (PE0) minus UIUC's measured β, averaged over r/R 0.6-0.9: a \
         pitch-offset fitted on UIUC's geometry near it is that difference found from the loads."
    )
}

/// What the intro adds where some prop's sections were assumed.
const ASSUMED_NOTE: &str = "Props without APC's sections (other makers, or no PE0 file) are predicted \
     with one assumed airfoil at every station of UIUC's blade (--generic-section), marked in the \
     twist column and kept out of the family medians and the median over props: a prediction from \
     a guessed section, not a validation of propbet's section model.";

/// The intro, with [`ASSUMED_NOTE`] where a row needs it.
fn intro_for(rows: &[Row], model: &str) -> String {
    let mut s = intro(model);
    if rows.iter().any(|r| r.assumed_section.is_some()) {
        s.push(' ');
        s.push_str(ASSUMED_NOTE);
    }
    s
}

/// The answer in one sentence: the medians over the props predicted with their maker's
/// sections (validate's medians), APC's beside them, the held-out calibration's and the band's;
/// None without such a prop.
pub fn headline(rows: &[Row]) -> Option<String> {
    let apc: Vec<&Row> = rows.iter().filter(|r| r.assumed_section.is_none()).collect();
    if apc.is_empty() {
        return None;
    }
    let med = |f: &dyn Fn(&Row) -> Option<f64>| {
        let v: Vec<f64> = apc.iter().filter_map(|r| f(r)).filter(|x| x.is_finite()).collect();
        (!v.is_empty()).then(|| median(v))
    };
    let p = |x: Option<f64>| x.map_or("–".to_string(), pct);
    let mut s = format!(
        "{} predicted with {} maker's sections, the median error is {} in CT and {} in CP",
        match apc.len() {
            1 => "For the one prop".to_string(),
            n => format!("Over the {n} props"),
        },
        if apc.len() == 1 { "its" } else { "their" },
        p(med(&|r| Some(r.ct.before.median))),
        p(med(&|r| Some(r.cp.before.median)))
    );
    if apc.iter().any(|r| r.per3.is_some()) {
        let _ = write!(
            s,
            " (APC's own code on the same points: {} and {})",
            p(med(&|r| r.per3.as_ref().map(|a| a.ct.median))),
            p(med(&|r| r.per3.as_ref().map(|a| a.cp.median)))
        );
    }
    let _ = write!(
        s,
        "; after the held-out calibration {} and {}",
        p(med(&|r| Some(r.ct.after.median))),
        p(med(&|r| Some(r.cp.after.median)))
    );
    if let (Some(inside), Some(width)) = (
        med(&|r| r.band[0].map(|c| c.inside)),
        med(&|r| r.band[0].map(|c| c.half_width)),
    ) {
        let _ = write!(
            s,
            "; the uncertainty band holds {} of the measured CT at a half-width of {}",
            pct(inside),
            pct(width)
        );
    }
    s.push('.');
    Some(s)
}

/// The table as Markdown.
pub fn markdown(rows: &[Row], skipped: &[Skipped], model: &str) -> String {
    let (h, body) = table(rows, skipped);
    let mut md = format!(
        "{}{}\n\n| {} |\n|{}\n",
        headline(rows).map_or(String::new(), |h| format!("**{h}**\n\n")),
        intro_for(rows, model),
        h.join(" | "),
        "---|".repeat(h.len())
    );
    for (cells, summary) in body {
        let mut cells = cells;
        if summary {
            cells[0] = format!("**{}**", cells[0]);
        }
        let _ = writeln!(md, "| {} |", cells.join(" | "));
    }
    let lost = left_out(rows);
    if !lost.is_empty() {
        let _ = writeln!(md, "\n{LEFT_OUT_INTRO}\n");
        for l in &lost {
            let _ = writeln!(md, "- {l}");
        }
    }
    let (h, body) = regime_table(rows);
    if !body.is_empty() {
        let _ = write!(
            md,
            "\n{}\n\n| {} |\n|{}\n",
            regime_intro(),
            h.join(" | "),
            "---|".repeat(h.len())
        );
        for cells in body {
            let _ = writeln!(md, "| {} |", cells.join(" | "));
        }
    }
    md
}

/// The files left out of the props' validation, one line each ("prop: file: why", the file
/// named once); empty where every file read.
fn left_out(rows: &[Row]) -> Vec<String> {
    rows.iter()
        .flat_map(|r| {
            r.left_out.iter().map(move |(f, why)| {
                // The reader's message names the file as a rule: once is enough.
                if why.contains(f.as_str()) {
                    format!("{}: {why}", r.prop)
                } else {
                    format!("{}: {f}: {why}", r.prop)
                }
            })
        })
        .collect()
}

/// What precedes the list of files left out.
const LEFT_OUT_INTRO: &str = "Files left out (they did not read; each prop was validated from its other files):";

/// The table as a page.
pub fn html(rows: &[Row], skipped: &[Skipped], model: &str) -> String {
    let (h, body) = table(rows, skipped);
    let mut s = format!(
        "<h1>Validation on measured propellers</h1>\n{}<p class=\"note\">{}</p>\n<table><tr>",
        headline(rows).map_or(String::new(), |h| format!("<p><b>{}</b></p>\n", esc(&h))),
        esc(&intro_for(rows, model))
    );
    // The last two columns (the ladders) are text: left-aligned; numbers keep their "%" on
    // their line. A note where a number would be (a row not validated, a section assumed, no
    // UIUC geometry) is text too: it wraps instead of widening its column.
    let text = |k: usize| k + 2 >= h.len();
    let class = |k: usize, c: &str| {
        if text(k) || c.split_whitespace().count() > 3 {
            " class=\"text\""
        } else {
            " style=\"white-space:nowrap\""
        }
    };
    for (k, c) in h.iter().enumerate() {
        let _ = write!(s, "<th{}>{}</th>", if text(k) { " class=\"text\"" } else { "" }, esc(c));
    }
    s.push_str("</tr>\n");
    for (cells, summary) in &body {
        s.push_str(if *summary { "<tr class=\"sig\">" } else { "<tr>" });
        for (k, c) in cells.iter().enumerate() {
            let _ = write!(s, "<td{}>{}</td>", class(k, c), esc(c));
        }
        s.push_str("</tr>\n");
    }
    s.push_str("</table>\n");
    let lost = left_out(rows);
    if !lost.is_empty() {
        let _ = write!(s, "<p class=\"note\">{}</p>\n<ul>", esc(LEFT_OUT_INTRO));
        for l in &lost {
            let _ = write!(s, "<li>{}</li>", esc(l));
        }
        s.push_str("</ul>\n");
    }
    let (h, body) = regime_table(rows);
    if !body.is_empty() {
        let _ = write!(
            s,
            "<h2>Where the error is</h2>\n<p class=\"note\">{}</p>\n<table><tr>",
            esc(&regime_intro())
        );
        for c in &h {
            let _ = write!(s, "<th>{}</th>", esc(c));
        }
        s.push_str("</tr>\n");
        for cells in body {
            s.push_str("<tr>");
            for c in cells {
                let _ = write!(s, "<td style=\"white-space:nowrap\">{}</td>", esc(&c));
            }
            s.push_str("</tr>\n");
        }
        s.push_str("</table>\n");
    }
    // A wide table: the page takes the window's width, so that the ladders are seen without
    // scrolling on a desktop screen.
    page("propbet validate", "body{max-width:none}", &s)
}

#[cfg(test)]
mod tests;
