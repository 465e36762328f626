//! The comparison as people read it: figures (CT, CP and efficiency against J per RPM;
//! static thrust and torque against RPM; residuals against J, RPM, Re at 0.75 R and tip Mach),
//! one self-contained HTML page (inline SVG, the font embedded, no script, no network), a
//! Markdown summary and a JSON document of everything.

use std::fmt::Write as _;

use propbet_compare::curves::Curves;
use propbet_compare::metrics::{group_points, static_rise, sweep_group, zero_thrust_shift, MetricGroup, Metrics};
use propbet_compare::{ComparedPoint, QUANTITIES};
use propbet_measure::{MeasuredSet, Refused};
use propbet_plot::{Figure, Mark, Panel, PlotError, Series, ERROR_AXIS};
use serde::Serialize;

use crate::page::{esc, page, sig};

/// A measured file as the report names it.
pub struct FileEntry<'a> {
    /// Path as given.
    pub path: String,
    /// Its points, drops and notes.
    pub set: &'a MeasuredSet,
}

/// Everything a report is made of.
pub struct ReportInput<'a> {
    /// Prop file path.
    pub prop: String,
    /// Notes about how the prop file was read (warnings, compatibility reading).
    pub prop_notes: Vec<String>,
    /// Measured files.
    pub files: Vec<FileEntry<'a>>,
    /// Measured files that were not read, with why.
    pub refused: &'a [Refused],
    /// The command's warnings about the measurements (refused files, logs that cannot be a
    /// propeller's, another propeller's size), as the terminal says them.
    pub warnings: Vec<String>,
    /// Compared points.
    pub points: &'a [ComparedPoint],
    /// Their scores.
    pub metrics: &'a Metrics,
    /// Propeller diameter of the coefficients [m].
    pub diameter: f64,
    /// The model's curves (from `propbet_compare::curves`).
    pub curves: &'a Curves,
    /// The uncertainty band along them (shaded in the figures), if computed.
    pub band: Option<&'a propbet_compare::band::BandCurves>,
    /// The band's sources in words (`propbet_model::band::BandSpec::sources_text`).
    pub band_sources: String,
    /// The command that made the report.
    pub command: String,
    /// Another prediction drawn and scored beside propbet's (APC's own, `--per3`).
    pub reference: Option<ReferenceInput<'a>>,
    /// The log's electrical columns against a motor (`--motor`).
    pub electric: Option<&'a propbet_compare::electric::Electric>,
}

/// Another prediction for the report: its name and its (CT, CP) at (rpm, J).
pub struct ReferenceInput<'a> {
    /// What it is, for legends and the headline ("APC's prediction (PER3_10x47SF.dat)").
    pub name: String,
    /// (CT, CP) at (rpm, J); None outside its range.
    pub at: propbet_compare::curves::Reference<'a>,
}

/// A reference's curves and scores, as the figures and the headline use them.
struct Scored {
    score: ReferenceScore,
    curves: Curves,
}

/// The report in its three forms, and its figures.
pub struct Report {
    /// Self-contained HTML page.
    pub html: String,
    /// The page's body, to be placed in another page (headings from h1).
    pub body: String,
    /// Markdown summary.
    pub markdown: String,
    /// Everything, as JSON.
    pub json: serde_json::Value,
    /// The other code's scores, when the input named one.
    pub reference: Option<ReferenceScore>,
    /// Figures by file stem ("coefficients", "static", "residuals").
    pub figures: Vec<(String, Figure)>,
}

const LABELS: [(&str, &str, &str); 6] = [
    ("thrust", "thrust", "N"),
    ("torque", "torque", "N·m"),
    ("power", "power", "W"),
    ("ct", "CT", ""),
    ("cp", "CP", ""),
    ("eta", "efficiency", ""),
];

fn label(q: &str) -> (&'static str, &'static str) {
    LABELS.iter().find(|l| l.0 == q).map_or(("?", ""), |l| (l.1, l.2))
}

use crate::answer::{headline_json, pct, ReferenceScore};

/// The accuracy as `propbet validate` measures it: the median |predicted / measured − 1| of CT
/// and CP over the points below 85 % of each sweep's zero-thrust J (the same points and numbers
/// as a validation row's "before" columns), with the points counted.
pub fn accuracy(points: &[ComparedPoint]) -> (f64, f64, usize) {
    use propbet_compare::metrics::{window_errors, VALIDATION_J_WINDOW};
    use propbet_units::stats::median;
    let (ct, cp) = window_errors(points, VALIDATION_J_WINDOW);
    let n = ct.len();
    (median(ct), median(cp), n)
}

/// [`accuracy`] as JSON (null where no point has the quantity).
pub fn accuracy_json(points: &[ComparedPoint]) -> serde_json::Value {
    let (ct, cp, n) = accuracy(points);
    let num = |x: f64| {
        if x.is_finite() {
            serde_json::json!(x)
        } else {
            serde_json::Value::Null
        }
    };
    serde_json::json!({"ct_median_error": num(ct), "cp_median_error": num(cp), "points": n,
        "measure": "median |predicted / measured - 1| below 85 % of the zero-thrust J (propbet validate's)"})
}

/// `summary.json` of `propbet compare`: the command, the headline, the points outside the
/// scored window, and the problems (rows dropped as faulty, station solutions that did not
/// converge, points where the prediction is physically implausible); another code's score
/// beside propbet's (`reference`) and the electrical comparison (`electric`) where there are.
pub fn summary_json(
    command: &str,
    m: &Metrics,
    points: &[ComparedPoint],
    problems: (usize, usize),
    warnings: &[String],
    reference: Option<&crate::answer::ReferenceScore>,
    electric: Option<&propbet_compare::electric::Electric>,
) -> serde_json::Value {
    let implausible = points.iter().filter(|p| !p.model_flags.is_empty()).count();
    let mut summary = serde_json::json!({
        "format": "propbet-compare-summary-1",
        "command": command,
        "clean": problems == (0, 0) && implausible == 0 && warnings.is_empty(),
        "warnings": warnings,
        "points": points.len(),
        "outside_window": m.outside_window,
        "headline": headline_json(m),
        "accuracy": accuracy_json(points),
        "problems": {
            "dropped_rows": problems.0,
            "unconverged_stations": problems.1,
            "implausible_points": implausible,
        },
    });
    if let (Some(r), serde_json::Value::Object(o)) = (reference, &mut summary) {
        o.insert("reference".into(), r.json());
    }
    if let (Some(e), serde_json::Value::Object(o)) = (electric, &mut summary) {
        o.insert(
            "electric".into(),
            serde_json::json!({
                "motor": e.motor,
                "points": e.points.len(),
                "current_median_error": e.current_median,
                "current_median_abs_error": e.current_median_abs,
                "motor_only_current_median_abs_error": e.motor_only_median_abs,
                "electrical_power_median_error": e.power_median,
                "rpm_at_throttle_median_error": e.rpm_median,
            }),
        );
    }
    summary
}

#[derive(Serialize)]
struct FileJson<'a> {
    path: &'a str,
    #[serde(flatten)]
    set: &'a MeasuredSet,
}

#[derive(Serialize)]
struct Json<'a> {
    prop: &'a str,
    prop_notes: &'a [String],
    diameter_m: f64,
    command: &'a str,
    files: Vec<FileJson<'a>>,
    metrics: &'a Metrics,
    /// [`speed_trends`]' sentences.
    speed_trends: &'a [String],
    points: &'a [ComparedPoint],
}

fn metric_rows(out: &mut String, g: &MetricGroup, html: bool) {
    for q in QUANTITIES {
        let Some(m) = g.metrics.get(q) else { continue };
        let (name, unit) = label(q);
        let unit = if unit.is_empty() {
            String::new()
        } else {
            format!(" {unit}")
        };
        let cells = [
            name.to_string(),
            m.n.to_string(),
            format!("{}{unit}", sig(m.bias)),
            format!("{}{unit}", sig(m.rmse)),
            pct(m.mean_rel),
            pct(m.mean_abs_rel),
            format!("{} ({})", pct(m.max_rel), m.max_rel_at),
        ];
        if html {
            out.push_str("<tr>");
            for c in cells {
                let _ = write!(out, "<td>{}</td>", esc(&c));
            }
            out.push_str("</tr>\n");
        } else {
            let _ = writeln!(out, "| {} |", cells.join(" | "));
        }
    }
}

const METRIC_HEAD: [&str; 7] = [
    "quantity",
    "n",
    "bias",
    "RMSE",
    "mean rel.",
    "mean |rel.|",
    "max rel. (at)",
];

fn html_metric_table(out: &mut String, groups: &[&MetricGroup]) {
    for g in groups {
        let _ = write!(
            out,
            "<h3>{} <small>({} points)</small></h3>\n<table><tr>",
            esc(&g.name),
            g.points
        );
        for h in METRIC_HEAD {
            let _ = write!(out, "<th>{h}</th>");
        }
        out.push_str("</tr>\n");
        metric_rows(out, g, true);
        out.push_str("</table>\n");
    }
}

/// What the measurements show as the speed changes, beside the model, in sentences: the static
/// CT's rise from the lowest to the highest static RPM ([`static_rise`]) and the J sweeps'
/// zero-thrust J at their lowest and highest RPM ([`zero_thrust_shift`]), each read for what
/// it says of the blade. Empty where the points span too little RPM for either.
pub fn speed_trends(points: &[ComparedPoint]) -> Vec<String> {
    let mut out = Vec::new();
    if let Some(s) = static_rise(points) {
        let gap = s.measured - s.predicted;
        let reading = if gap.abs() <= 0.03 {
            "as the model's does (within 3 points)".to_string()
        } else {
            format!(
                "{} than the model's ({}; the diagnosis's RPM trend names what can make it)",
                if gap > 0.0 { "faster" } else { "slower" },
                pct(s.predicted)
            )
        };
        out.push(format!(
            "Static CT grows by {} from {:.0} to {:.0} rpm, {reading}.",
            pct(s.measured),
            s.rpm_lo,
            s.rpm_hi
        ));
    }
    if let Some(z) = zero_thrust_shift(points) {
        let mc = z.measured_change();
        let mut s = format!(
            "The J sweeps' zero-thrust J moves from {:.3} at {:.0} rpm to {:.3} at {:.0} rpm ({})",
            z.measured.0,
            z.rpm_lo,
            z.measured.1,
            z.rpm_hi,
            pct(mc)
        );
        match (z.predicted, z.predicted_change()) {
            (Some(q), Some(pc)) => {
                let _ = write!(s, "; the model's from {:.3} to {:.3} ({})", q.0, q.1, pct(pc));
                let offset = 0.5 * (q.0 + q.1 - z.measured.0 - z.measured.1);
                if mc < -0.01 && pc > mc + 0.02 {
                    s.push_str(
                        ". The measured blade loses pitch as it speeds up where the sections' Reynolds numbers give \
                         the model a little more: a blade that twists nose-down under load (a flexible blade's \
                         washout, the diagnosis's elastic-twist), which no section model makes",
                    );
                } else if offset.abs() > 0.02 {
                    let _ = write!(
                        s,
                        ". The model's is {} by {:.3} at every speed: the blade's pitch (or its sections' zero-lift \
                         angle) is off, not its change with speed",
                        if offset < 0.0 { "lower" } else { "higher" },
                        offset.abs()
                    );
                }
            }
            _ => s.push_str("; the model's thrust does not reach zero in the measured J range of two sweeps"),
        }
        s.push('.');
        out.push(s);
    }
    out
}

/// The other prediction, scored on the same points, window and measure as propbet's.
fn scored_reference(input: &ReportInput) -> Option<Scored> {
    let pts = input.points;
    input.reference.as_ref().map(|r| {
        let stat: Vec<f64> = pts.iter().filter(|p| p.is_static()).map(|p| p.air.fluid.rho).collect();
        let rho = if stat.is_empty() {
            pts.iter().map(|p| p.air.fluid.rho).sum::<f64>() / pts.len().max(1) as f64
        } else {
            stat.iter().sum::<f64>() / stat.len() as f64
        };
        Scored {
            score: ReferenceScore {
                name: r.name.clone(),
                metrics: propbet_compare::metrics::metrics(&propbet_compare::curves::with_reference(
                    pts,
                    r.at,
                    input.diameter,
                )),
            },
            curves: propbet_compare::curves::reference_curves(input.curves, r.at, input.diameter, rho),
        }
    })
}

/// The air of the points in one line: the density, or its range.
fn air_line(pts: &[ComparedPoint]) -> String {
    let rho: Vec<f64> = pts.iter().map(|p| p.air.fluid.rho).collect();
    let (rho_lo, rho_hi) = rho
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), r| (a.min(*r), b.max(*r)));
    if (rho_hi - rho_lo) < 1e-9 {
        format!("ρ = {:.4} kg/m³", rho_lo)
    } else {
        format!("ρ = {:.4}–{:.4} kg/m³", rho_lo, rho_hi)
    }
}

/// What the reader is warned of: standard air assumed, points not scored, rows dropped, the
/// prop file's notes.
fn warnings(input: &ReportInput) -> Vec<String> {
    let (pts, m) = (input.points, input.metrics);
    let standard = pts.iter().filter(|p| p.air.standard).count();
    let mut warnings: Vec<String> = Vec::new();
    if standard > 0 {
        warnings.push(format!(
            "{standard} of {} points: no air temperature or pressure was logged or given, standard air (ISA sea level, 15 °C, 101 325 Pa, dry) was assumed. Give --atmosphere T,P,RH for a real comparison.",
            pts.len()
        ));
    }
    if m.unscored > 0 {
        warnings.push(format!(
            "{} flagged points are shown but not scored (see the point table).",
            m.unscored
        ));
    }
    warnings.extend(input.warnings.iter().cloned());
    let faults: usize = input.files.iter().map(|f| f.set.faults()).sum();
    if faults > 0 {
        warnings.push(format!(
            "{faults} rows were dropped as faulty (listed under Measured files)."
        ));
    }
    warnings.extend(input.prop_notes.iter().cloned());

    warnings
}

/// "120 / 14 / 14": the readings of RPM, thrust and torque that made a point.
fn readings(s: &propbet_compare::Samples) -> String {
    let opt = |n: Option<usize>| n.map_or("–".to_string(), |n| n.to_string());
    format!("{} / {} / {}", s.rpm, opt(s.thrust), opt(s.torque))
}

/// The points' table rows, one per point: measured with its spread, predicted, errors, flags.
fn points_table_html(h: &mut String, pts: &[ComparedPoint]) {
    h.push_str("<table><tr><th>file</th><th>point</th><th>lines</th><th title=\"readings of RPM / thrust / torque that made the point\">readings</th><th>RPM</th><th>V [m/s]</th><th>J</th><th>ρ</th><th>thrust meas. [N]</th><th>pred.</th><th>err.</th><th>torque meas. [N·m]</th><th>pred.</th><th>err.</th><th>CT meas.</th><th>CP meas.</th><th>η meas.</th><th>η pred.</th><th>Re 0.75R</th><th>M tip</th><th>flags</th></tr>\n");
    for p in pts {
        let pm = |q: &str| {
            let v = p.measured.get(q).map_or("–".into(), sig);
            match p.measured_sd.get(q) {
                Some(s) if s > 0.0 => format!("{v} ± {}", sig(s)),
                _ => v,
            }
        };
        let _ = writeln!(
            h,
            "<tr{}><td>{}</td><td>{}</td><td>{}–{}</td><td>{}</td><td>{:.0}</td><td>{}</td><td>{}</td><td>{:.4}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.0}</td><td>{:.3}</td><td>{}</td></tr>",
            if p.scored() { "" } else { " class=\"flagged\"" },
            p.file + 1,
            esc(&p.label),
            p.lines.0,
            p.lines.1,
            readings(&p.samples),
            p.rpm,
            sig(p.v),
            sig(p.j),
            p.air.fluid.rho,
            pm("thrust"),
            p.predicted.thrust.map_or("–".into(), sig),
            p.relative_error("thrust").map_or("–".into(), pct),
            pm("torque"),
            p.predicted.torque.map_or("–".into(), sig),
            p.relative_error("torque").map_or("–".into(), pct),
            pm("ct"),
            pm("cp"),
            pm("eta"),
            p.predicted.eta.map_or("–".into(), sig),
            p.re75,
            p.mach_tip,
            esc(&p.flags.iter().chain(&p.model_flags).cloned().collect::<Vec<_>>().join("; "))
        );
    }
}

/// The report's figures, by name: the coefficients, the static sweep, the hover figure of merit
/// (where there are static points) and the residuals.
fn figures(input: &ReportInput, reference: Option<&Scored>) -> Vec<(String, Figure)> {
    let pts = input.points;
    let mut figures = Vec::new();
    if let Some(f) = coefficient_figure(input.curves, input.band, pts, reference) {
        figures.push(("coefficients".to_string(), f));
    }
    if let Some(f) = static_figure(input.curves, input.band, pts, reference) {
        figures.push(("static".to_string(), f));
    }
    if let Some(f) = crate::answer::hover_figure(input.curves, pts) {
        figures.push(("hover".to_string(), f));
    }
    figures.push(("residuals".to_string(), residual_figure(pts)));
    figures
}

/// The figure a report leads with, from its figures: measured against predicted CT and CP over
/// J (the J sweeps, with the band), or thrust and torque over RPM for static data alone; compact
/// (two panels, 900 x 380 px) for the first screen.
pub fn lead_figure(figures: &[(String, Figure)]) -> Option<Figure> {
    let (_, f) = figures.iter().find(|(n, _)| n == "coefficients" || n == "static")?;
    let mut f = f.clone();
    f.panels.truncate(2);
    f.columns = 2;
    f.width = 900;
    f.height = 380;
    Some(f)
}

/// What the shaded band is, for the figures' captions.
fn band_caption(sources: &str) -> String {
    format!("shaded: the prediction's uncertainty band ({sources}; each solved at both ends, their root-sum-square)")
}

/// The figures as inline SVG, each with its caption.
fn figures_html(
    h: &mut String,
    figures: &[(String, Figure)],
    reference: Option<&Scored>,
    band: Option<&str>,
) -> Result<(), PlotError> {
    h.push_str("<h2>Figures</h2>\n");
    for (name, f) in figures {
        let caption = match name.as_str() {
            "coefficients" => format!(
                "<figcaption>Dots: measured, one colour per sweep (legend); solid lines: propbet's prediction at the sweep's mean speed, in its colour{}{}.</figcaption>",
                band.map_or(String::new(), |b| format!("; {}", esc(&band_caption(b)))),
                reference.map_or(String::new(), |r| format!("; dashed: {}", esc(&r.score.name)))
            ),
            "static" => band.map_or(String::new(), |b| format!("<figcaption>{}.</figcaption>", esc(&band_caption(b)))),
            _ => String::new(),
        };
        let _ = writeln!(
            h,
            "<figure id=\"fig-{name}\">{}{caption}</figure>",
            propbet_plot::svg_inline(f)?
        );
    }
    Ok(())
}

/// Builds the report.
pub fn build(input: &ReportInput) -> Result<Report, PlotError> {
    let pts = input.points;
    let m = input.metrics;
    let reference = scored_reference(input);
    let figures = figures(input, reference.as_ref());

    let air_sources: std::collections::BTreeSet<&str> = pts.iter().map(|p| p.air.source.as_str()).collect();
    let air_line = air_line(pts);
    let warnings = warnings(input);

    // ---------- HTML ----------
    let mut h = String::with_capacity(2_000_000);
    let _ = write!(
        h,
        "<h1>Prediction vs measurement</h1>\n<p class=\"note\">prop <code>{}</code> (D = {} m) against {} file(s); {} points ({} scored); air: {}.</p>\n",
        esc(&input.prop),
        sig(input.diameter),
        input.files.len(),
        pts.len(),
        pts.len() - m.unscored,
        air_line,
    );
    // The headline: the scored window (validate's and diagnose's), static and forward flight
    // apart, per quantity, with the worst point named and the other code's error beside it;
    // then the hover metrics where there are static points.
    // Measurements of another propeller make every number below meaningless: said first.
    let mismatch = propbet_compare::plausible::of_points(pts).map(|m| m.message());
    if let Some(w) = &mismatch {
        let _ = writeln!(h, "<p class=\"warn\"><strong>{}</strong></p>", esc(w));
    }
    h.push_str(&crate::answer::headline_html(
        m,
        reference.as_ref().map(|r| &r.score),
        pts,
    ));
    if m.outside_window > 0 {
        let _ = writeln!(
            h,
            "<p class=\"note\">{} point(s) at or beyond 85 % of their sweep's zero-thrust J are shown in the figures and tables but not in these numbers: near zero thrust a relative error says nothing.</p>",
            m.outside_window
        );
    }
    for w in &warnings {
        let _ = writeln!(h, "<p class=\"warn\">{}</p>", esc(w));
    }
    let _ = writeln!(h, "<p class=\"note\">command: <code>{}</code></p>", esc(&input.command));
    let mut figures = figures;
    if let Some(e) = input.electric {
        let fig = electric::figure(e);
        electric::html(&mut h, e, &fig)?;
        figures.push(("electric".to_string(), fig));
    }
    let trends = speed_trends(pts);
    if !trends.is_empty() {
        h.push_str("<h2>With speed</h2>\n<ul>");
        for t in &trends {
            let _ = write!(h, "<li>{}</li>", esc(t));
        }
        h.push_str("</ul>\n");
    }
    figures_html(
        &mut h,
        &figures,
        reference.as_ref(),
        input.band.map(|_| input.band_sources.as_str()),
    )?;
    let _ = write!(h, "<h2>Metrics</h2>\n<p class=\"note\">error = predicted − measured; relative error = error / measured, computed where |measured| is at least {:.0} % of its largest value (near zero thrust a ratio says nothing).</p>\n", 100.0 * propbet_compare::RELATIVE_FLOOR);
    let mut top: Vec<&MetricGroup> = vec![&m.overall];
    top.extend(m.static_points.iter());
    top.extend(m.forward.iter());
    html_metric_table(&mut h, &top);
    h.push_str("<h2>By RPM</h2>\n");
    html_metric_table(&mut h, &m.per_rpm.iter().collect::<Vec<_>>());
    h.push_str("<h2>By advance ratio</h2>\n");
    html_metric_table(&mut h, &m.per_j.iter().collect::<Vec<_>>());
    let flagged = pts
        .iter()
        .filter(|p| !p.flags.is_empty() || !p.model_flags.is_empty())
        .count();
    let _ = write!(
        h,
        "<h2>Points</h2>\n<details><summary>{} points, {flagged} flagged (the reader's flags and the prediction's, such as thrust beyond momentum theory): open the table</summary>\n",
        pts.len()
    );
    points_table_html(&mut h, pts);
    h.push_str("</table></details>\n");
    h.push_str(&measured_files_html(&input.files, input.refused));
    h.push_str("<h2>Air</h2>\n<ul>");
    for s in &air_sources {
        let _ = write!(h, "<li>{}</li>", esc(s));
    }
    h.push_str("</ul>\n<p class=\"note\">Density of moist air from T, p, RH (ideal-gas mixture, Buck saturation pressure); viscosity by Sutherland's law; speed of sound of dry air.</p>\n");

    let md = markdown(
        input,
        &air_line,
        mismatch.as_ref(),
        &warnings,
        reference.as_ref(),
        &trends,
        &top,
    );

    let json = json(input, reference.as_ref().map(|r| &r.score), &trends)?;
    Ok(Report {
        html: page(&format!("propbet: {}", input.prop), "", &h),
        body: h,
        markdown: crate::md_safe(&md),
        json,
        reference: reference.map(|r| r.score),
        figures,
    })
}

mod electric;
mod figures;
mod files;
mod text;

pub use electric::sentence as electric_sentence;
use figures::{coefficient_figure, residual_figure, static_figure};
pub use files::{dropped_ranges, measured_files_html, measured_files_md};
use text::{json, markdown};

#[cfg(test)]
mod tests;
