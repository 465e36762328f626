//! The comparison in Markdown and JSON, beside the page.

use super::*;

/// The Markdown summary: the headline (and the other code's), the trends, the metrics, the
/// measured files.
pub(super) fn markdown(
    input: &ReportInput,
    air_line: &str,
    mismatch: Option<&String>,
    warnings: &[String],
    reference: Option<&Scored>,
    trends: &[String],
    top: &[&MetricGroup],
) -> String {
    let (pts, m) = (input.points, input.metrics);
    let mut md = String::new();
    let _ = writeln!(md, "# Prediction vs measurement\n");
    let _ = writeln!(
        md,
        "prop `{}` (D = {} m); {} file(s); {} points, {} scored; air: {}.\n",
        input.prop,
        sig(input.diameter),
        input.files.len(),
        pts.len(),
        pts.len() - m.unscored,
        air_line
    );
    for w in mismatch.into_iter().chain(warnings) {
        let _ = writeln!(md, "> {w}\n");
    }
    let md_table = |md: &mut String, g: &MetricGroup| {
        let _ = writeln!(md, "### {} ({} points)\n", g.name, g.points);
        let _ = writeln!(md, "| {} |", METRIC_HEAD.join(" | "));
        let _ = writeln!(md, "|{}", "---|".repeat(METRIC_HEAD.len()));
        metric_rows(md, g, false);
        md.push('\n');
    };
    md.push_str("## Headline (the scored window)\n\n");
    for g in &m.headline {
        md_table(&mut md, g);
    }
    if let Some(r) = reference {
        let _ = writeln!(md, "## {}, on the same points\n", r.score.name);
        for g in &r.score.metrics.headline {
            md_table(&mut md, g);
        }
    }
    if !trends.is_empty() {
        md.push_str("## With speed\n\n");
        for t in trends {
            let _ = writeln!(md, "- {t}");
        }
        md.push('\n');
    }
    md.push_str("## Metrics\n\n");
    for g in top {
        md_table(&mut md, g);
    }
    md.push_str("## By RPM\n\n");
    for g in &m.per_rpm {
        md_table(&mut md, g);
    }
    md.push_str(&measured_files_md(&input.files, input.refused));

    md
}

/// The report as JSON: the prop, its files, the metrics (and the other code's headline), the
/// trends, every point.
pub(super) fn json(
    input: &ReportInput,
    reference: Option<&ReferenceScore>,
    trends: &[String],
) -> Result<serde_json::Value, PlotError> {
    let (pts, m) = (input.points, input.metrics);
    let json = serde_json::to_value(Json {
        prop: &input.prop,
        prop_notes: &input.prop_notes,
        diameter_m: input.diameter,
        command: &input.command,
        files: input
            .files
            .iter()
            .map(|f| FileJson {
                path: &f.path,
                set: f.set,
            })
            .collect(),
        metrics: m,
        speed_trends: trends,
        points: pts,
    })
    .map_err(|e| PlotError::from_message(format!("JSON: {e}")))?;
    Ok(match (reference, json) {
        (Some(r), serde_json::Value::Object(mut o)) => {
            o.insert("reference".into(), r.json());
            serde_json::Value::Object(o)
        }
        (_, j) => j,
    })
}
