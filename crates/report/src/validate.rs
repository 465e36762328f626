//! The validation table of `propbet validate`: Markdown (for the README and the terminal) and
//! an HTML page.

use std::fmt::Write as _;

use propbet_compare::metrics::quantile;
use propbet_pipeline::validate::Row;

use crate::page::{esc, page};

/// Column heads of the table.
const HEAD: [&str; 11] = [
    "prop",
    "points",
    "CT median",
    "CT p90",
    "CP median",
    "CP p90",
    "CT median after",
    "CT p90 after",
    "CP median after",
    "CP p90 after",
    "ladder",
];

fn pct(x: f64) -> String {
    format!("{:.1} %", 100.0 * x)
}

/// The cells of one prop's row.
fn cells(r: &Row) -> Vec<String> {
    let mut v = vec![r.prop.clone(), r.points.to_string()];
    for (m, p) in [r.ct[0], r.cp[0], r.ct[1], r.cp[1]] {
        v.push(pct(m));
        v.push(pct(p));
    }
    v.push(r.ladder.clone());
    v
}

/// The last row: the median over props of each column (of the medians, of the p90s).
fn overall(rows: &[Row]) -> Vec<String> {
    let mut v = vec![
        "all (median over props)".to_string(),
        rows.iter().map(|r| r.points).sum::<usize>().to_string(),
    ];
    let cols = |r: &Row| [r.ct[0], r.cp[0], r.ct[1], r.cp[1]];
    for k in 0..4 {
        v.push(pct(quantile(rows.iter().map(|r| cols(r)[k].0).collect(), 0.5)));
        v.push(pct(quantile(rows.iter().map(|r| cols(r)[k].1).collect(), 0.5)));
    }
    v.push(String::new());
    v
}

fn intro(model: &str) -> String {
    format!(
        "Relative errors |pred/meas − 1| of CT and CP, points below 85 % of each sweep's zero-thrust J \
         (static points included). Before: UIUC geometry + APC sections + XFOIL polars covering each \
         prop's measured RPM and J range ({model}); after: with the effects the diagnosis' ladder \
         fitted to the same data (calibration)."
    )
}

/// The table as Markdown, with the props that were not validated and why.
pub fn markdown(rows: &[Row], skipped: &[String], model: &str) -> String {
    let mut md = format!(
        "{}\n\n| {} |\n|{}\n",
        intro(model),
        HEAD.join(" | "),
        "---|".repeat(HEAD.len())
    );
    for r in rows {
        let _ = writeln!(md, "| {} |", cells(r).join(" | "));
    }
    let mut last = overall(rows);
    last[0] = format!("**{}**", last[0]);
    let _ = writeln!(md, "| {} |", last.join(" | "));
    if !skipped.is_empty() {
        md.push_str("\nNot validated:\n");
        for s in skipped {
            let _ = writeln!(md, "- {s}");
        }
    }
    md
}

/// The table as a page.
pub fn html(rows: &[Row], skipped: &[String], model: &str) -> String {
    let mut h = format!(
        "<h1>Validation on measured propellers</h1>\n<p class=\"note\">{}</p>\n<table><tr>",
        esc(&intro(model))
    );
    // The last column (the ladder) is text: left-aligned.
    let class = |k: usize| if k + 1 == HEAD.len() { " class=\"text\"" } else { "" };
    for (k, c) in HEAD.iter().enumerate() {
        let _ = write!(h, "<th{}>{}</th>", class(k), esc(c));
    }
    h.push_str("</tr>\n");
    for (k, r) in rows.iter().map(cells).chain(std::iter::once(overall(rows))).enumerate() {
        h.push_str(if k == rows.len() { "<tr class=\"sig\">" } else { "<tr>" });
        for (k, c) in r.iter().enumerate() {
            let _ = write!(h, "<td{}>{}</td>", class(k), esc(c));
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</table>\n");
    if !skipped.is_empty() {
        h.push_str("<h2>Not validated</h2>\n<ul>");
        for s in skipped {
            let _ = write!(h, "<li>{}</li>", esc(s));
        }
        h.push_str("</ul>\n");
    }
    page("propbet validate", "", &h)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_have_a_row_per_prop_and_the_median_over_props() {
        let row = |p: &str, x: f64| Row {
            prop: p.into(),
            points: 10,
            ct: [(x, 2.0 * x), (x / 2.0, x)],
            cp: [(x, x), (x, x)],
            ladder: "none".into(),
        };
        let rows = [row("a", 0.1), row("b", 0.3), row("c", 0.2)];
        let md = markdown(&rows, &["d: no PE0 file".into()], "tables");
        assert!(md.contains("| a | 10 | 10.0 % | 20.0 % |"), "{md}");
        assert!(
            md.contains("| **all (median over props)** | 30 | 20.0 % | 40.0 % |"),
            "{md}"
        );
        assert!(md.contains("- d: no PE0 file"));
        let page = html(&rows, &[], "tables");
        assert_eq!(page.matches("<tr>").count() + page.matches("<tr class").count(), 5);
    }
}
