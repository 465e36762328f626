//! The diagnosis as people read it: the verdict, where the baseline fails in words, the
//! ranking with fitted values and intervals, the ladder with its falling error, before/after
//! residual plots; one self-contained HTML page, a Markdown summary and JSON.

use std::fmt::Write as _;

use propbet_diagnose::discover::{Diagnosis, Scored};
use propbet_diagnose::fit::FittedParam;
use propbet_diagnose::limits::AnswerKind;
use propbet_diagnose::signature::{Part, Signature};
use propbet_diagnose::{Data, Row};
use propbet_effects::fmt_value;
use propbet_plot::{Figure, Mark, Panel, PlotError, Series, ERROR_AXIS};
use serde::Serialize;

use crate::compare::{measured_files_html, measured_files_md, FileEntry};
use crate::page::{esc, page, sig};
use propbet_measure::Refused;

/// The report in its forms.
pub struct Report {
    /// Self-contained HTML page.
    pub html: String,
    /// The page's body, to be placed in another page (headings from h1).
    pub body: String,
    /// Markdown summary.
    pub markdown: String,
    /// Figures by file stem.
    pub figures: Vec<(String, Figure)>,
}

/// What the JSON file holds.
#[derive(Serialize)]
pub struct JsonOut<'a> {
    /// Prop file.
    pub prop: &'a str,
    /// Measured files.
    pub measured: &'a [String],
    /// The command.
    pub command: &'a str,
    /// The diagnosis, each residual pattern with its words (`text`).
    #[serde(serialize_with = "worded")]
    pub diagnosis: &'a Diagnosis,
    /// The final model's parameters.
    pub final_params: Vec<FittedParam>,
    /// The final model as `--effect` arguments.
    pub final_effects: Vec<String>,
}

/// The diagnosis as JSON, each residual pattern (`before`, `after`) with its words beside its
/// findings.
fn worded<S: serde::Serializer>(d: &&Diagnosis, ser: S) -> Result<S::Ok, S::Error> {
    let mut v = serde_json::to_value(d).map_err(serde::ser::Error::custom)?;
    for (key, sigs) in [("before", &d.before), ("after", &d.after)] {
        if let Some(list) = v.get_mut(key).and_then(serde_json::Value::as_array_mut) {
            for (j, s) in list.iter_mut().zip(sigs) {
                if let Some(o) = j.as_object_mut() {
                    o.insert("text".into(), signature_text(s).into());
                }
            }
        }
    }
    v.serialize(ser)
}

fn pct(x: f64) -> String {
    format!("{:.2} %", 100.0 * x)
}

fn params_text(ps: &[FittedParam], only: Option<&str>) -> String {
    ps.iter()
        .filter(|p| only.is_none_or(|id| p.effect == id))
        .map(|p| {
            let ci = match p.ci95 {
                Some(c) => format!(" ± {}", fmt_value(c)),
                None => " (not determined by the data)".into(),
            };
            let bound = if p.at_bound { " [at bound]" } else { "" };
            let unit = if p.unit.is_empty() || p.unit == "-" {
                String::new()
            } else {
                format!(" {}", p.unit)
            };
            format!("{} = {}{ci}{unit}{bound}", p.name, fmt_value(p.value))
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The diagnosis' answer as JSON (`summary.json` of `propbet diagnose` and `propbet run`): the
/// verdict as the report words it, whether an effect was found, the ladder's final effects,
/// the error left unexplained and the measurements' repeatability (relative, or null where the
/// data have no repeated points).
pub fn diagnosis_json(d: &Diagnosis) -> serde_json::Value {
    serde_json::json!({
        "verdict": verdict(d),
        "found": d.found,
        "effects": d.final_effects(),
        "unexplained": d.noise_estimate,
        "repeatability": d.repeatability.as_ref().map(|r| r.sd),
    })
}

/// The verdict where nothing passes the tests: the candidates that hit a physical bound (how far
/// the first would go there), then the best within its bounds.
fn nothing_found(d: &Diagnosis) -> String {
    let base = &d.ladder[0];
    // Candidates whose fits ended on a physical bound are not answers: said first, with
    // how far the first of them would go at its bound; then the best within its bounds.
    let helpful = d.bounded_helpful();
    let bounded: Vec<&str> = helpful.iter().map(|s| s.id.as_str()).collect();
    let mut text = format!("Nothing significant: no effect passes the tests ({}).", d.unexplained());
    if let Some(first) = helpful.first() {
        text.push_str(&format!(
            " {} hit {} physical bound{} ({}): the data want more than {} can give (at its bound {} takes \
             the held-out error from {} to {}). The model is further from these measurements than a missing \
             effect explains: check the geometry, the sections and the units.",
            if bounded.len() == 1 {
                "One candidate".to_string()
            } else {
                format!("{} candidates", bounded.len())
            },
            if bounded.len() == 1 { "its" } else { "their" },
            if bounded.len() == 1 { "" } else { "s" },
            bounded.join(", "),
            if bounded.len() == 1 { "it" } else { "they" },
            first.id,
            pct(base.kfold_rms),
            pct(first.kfold_rms),
        ));
    }
    let inside = d
        .ranking
        .iter()
        .find(|s| s.fit.is_some() && !s.hit_bound() && s.kfold_rms.is_finite());
    if let Some(s) = inside {
        text.push_str(&format!(
            " The best candidate{}, {}, lowers the held-out error only from {} to {} (p = {}).",
            if bounded.is_empty() { "" } else { " within its bounds" },
            s.id,
            pct(base.kfold_rms),
            pct(s.kfold_rms),
            sig(s.p_value)
        ));
    }
    // Never without a lead: the largest pattern in the errors, as the signatures say it.
    let largest = d
        .before
        .iter()
        .filter(|s| !s.parts.is_empty())
        .max_by(|a, b| a.rms.total_cmp(&b.rms));
    if let Some(s) = largest {
        text.push_str(&format!(
            " The largest signature of the errors: {}.",
            words::part_sentence(s, &s.parts[0].shows)
        ));
    }
    text
}

/// The one-paragraph verdict: the ladder's effects as [`Diagnosis::verdict`] answers them
/// (found, one of a group the data cannot separate, a calibration factor, or below the
/// detection limit and not named), the fall of the held-out error, what is left, and how much
/// of the error is within what the model usually misses.
pub fn verdict(d: &Diagnosis) -> String {
    let base = &d.ladder[0];
    if !d.found {
        let mut text = nothing_found(d);
        if let Some(w) = &d.verdict.within_model_error {
            let _ = write!(text, " {w}.");
        }
        return text;
    }
    let last = d.ladder.last().expect("found implies a rung");
    let (physics, calibration) = answer_parts(d);
    let named = |v: &[&str]| -> Vec<String> {
        v.iter()
            .map(|id| format!("{id} ({})", params_text(&last.params, Some(id))))
            .collect()
    };
    let mut text = String::new();
    if !physics.is_empty() {
        let _ = write!(text, "Missing: {}.", named(&physics).join(" and "));
    }
    for a in d.verdict.answers.iter().filter(|a| a.kind == AnswerKind::Group) {
        let _ = write!(
            text,
            "{}Missing: one of {} ({}) or {}: these data cannot tell them apart; {} would.",
            if text.is_empty() { "" } else { " " },
            a.id,
            params_text(&last.params, Some(&a.id)),
            others(&a.group[1..]),
            a.tell_apart.as_deref().unwrap_or("another measurement")
        );
    }
    if !calibration.is_empty() {
        let ranges: Vec<String> = calibration
            .iter()
            .flat_map(|id| {
                last.params
                    .iter()
                    .filter(move |p| p.effect == *id && p.outside_expected)
            })
            .map(|p| {
                format!(
                    "{}:{} expected {}-{}",
                    p.effect,
                    p.name,
                    fmt_value(p.expected.0),
                    fmt_value(p.expected.1)
                )
            })
            .collect();
        let _ =
            write!(
            text,
            "{}{} {}: outside the physically expected range ({}), {} a calibration factor: the model misses something \
             {} only imitate{}.",
            if text.is_empty() { "" } else { " " },
            if physics.is_empty() { "Found no physics;" } else { "Also" },
            named(&calibration).join(" and "),
            ranges.join(", "),
            if calibration.len() == 1 { "it is" } else { "each is" },
            if calibration.len() == 1 { "this effect" } else { "these effects" },
            if calibration.len() == 1 { "s" } else { "" },
        );
        for a in d
            .verdict
            .answers
            .iter()
            .filter(|a| a.kind == AnswerKind::Calibration && a.group.len() > 1)
        {
            let _ = write!(
                text,
                " {}: the physical cause may be {} instead; {} would tell.",
                stand_ins(&others(&a.group[1..]), a.group.len() - 1, &format!("{}'s", a.id)),
                if a.group.len() == 2 { "that" } else { "one of those" },
                a.tell_apart.as_deref().unwrap_or("another measurement")
            );
        }
    }
    let below: Vec<String> = d
        .verdict
        .answers
        .iter()
        .filter(|a| a.kind == AnswerKind::BelowLimit)
        .map(|a| format!("{} ({})", a.id, params_text(&last.params, Some(&a.id))))
        .collect();
    if !below.is_empty() {
        let _ = write!(
            text,
            "{}Not named: {}: {} change of the loads is below what these data can detect (the detection limits \
             below), so {} may be the model's own error or the scatter.",
            if text.is_empty() { "" } else { " " },
            below.join(" and "),
            if below.len() == 1 { "its" } else { "their" },
            if below.len() == 1 { "it" } else { "they" },
        );
    }
    let _ = write!(
        text,
        " With {} the held-out error falls from {} to {} ({:.0} % less); {}.",
        if d.ladder.len() == 2 { "it" } else { "them" },
        pct(base.kfold_rms),
        pct(last.kfold_rms),
        100.0 * (1.0 - last.kfold_rms / base.kfold_rms.max(1e-300)),
        d.unexplained()
    );
    if let Some(w) = &d.verdict.within_model_error {
        let _ = write!(text, " {w}.");
    }
    text
}

/// One step of the ladder as the verdict shows it.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// The effect added.
    pub id: String,
    /// Its fitted values in the final model, with their intervals ("deg = 1.817 ± 0.056 deg").
    pub values: String,
    /// Its physically expected ranges ("deg -2-2").
    pub expected: String,
    /// A value lies outside its expected range: a calibration factor, not found physics.
    pub calibration: bool,
    /// Held-out error before and after the step [-].
    pub before: f64,
    /// Held-out error after it [-].
    pub after: f64,
}

/// The ladder's steps, first first, with the final model's values.
pub fn steps(d: &Diagnosis) -> Vec<Step> {
    let Some(last) = d.ladder.last() else {
        return Vec::new();
    };
    d.ladder
        .windows(2)
        .map(|w| {
            let id = w[1].added.clone();
            let own: Vec<&FittedParam> = last.params.iter().filter(|p| p.effect == id).collect();
            Step {
                values: params_text(&last.params, Some(&id)),
                expected: own
                    .iter()
                    .map(|p| {
                        let range = format!("{} to {}", fmt_value(p.expected.0), fmt_value(p.expected.1));
                        if own.len() == 1 {
                            range
                        } else {
                            format!("{} {range}", p.name)
                        }
                    })
                    .collect::<Vec<_>>()
                    .join(", "),
                calibration: own.iter().any(|p| p.outside_expected),
                before: w[0].kfold_rms,
                after: w[1].kfold_rms,
                id,
            }
        })
        .collect()
}

/// The diagnosis in a few short lines (the terminal of `propbet run`): one per step, then
/// what the data cannot tell apart and what is left.
pub fn brief(d: &Diagnosis) -> Vec<String> {
    let mut out = Vec::new();
    if !d.found {
        out.push(format!("nothing significant; {}", d.unexplained()));
        return out;
    }
    let steps = steps(d);
    let calibration = steps.iter().filter(|s| s.calibration).count();
    out.push(format!(
        "held-out error {} -> {} with {} effect{}{}",
        pct(d.ladder[0].kfold_rms),
        pct(d.ladder.last().map_or(f64::NAN, |r| r.kfold_rms)),
        steps.len(),
        if steps.len() == 1 { "" } else { "s" },
        match calibration {
            0 => String::new(),
            1 if steps.len() == 1 => ", a calibration factor".to_string(),
            1 => " (one a calibration factor, outside its expected range)".to_string(),
            n if n == steps.len() => " (all calibration factors, outside their expected ranges)".to_string(),
            n => format!(" ({n} calibration factors, outside their expected ranges)"),
        }
    ));
    for (i, s) in steps.iter().enumerate() {
        out.push(format!(
            "{}. {} {} (expected {}){}: {} -> {}",
            i + 1,
            s.id,
            s.values,
            s.expected,
            if s.calibration { ", a calibration factor" } else { "" },
            pct(s.before),
            pct(s.after)
        ));
    }
    out.extend(group_clauses(d));
    out.push(unexplained_clause(d));
    out
}

/// The first clause of [`Diagnosis::unexplained`] ("2.2 % unexplained, above the 0.3 % ...").
fn unexplained_clause(d: &Diagnosis) -> String {
    let left = d.unexplained();
    left.split(": ").next().unwrap_or(&left).to_string()
}

/// The ladder's effects the verdict names alone: found physics (told apart from every other
/// candidate, above its detection limit, every fitted value inside its physically expected
/// range) and calibration factors (the same, some value outside it), in ladder order. Effects
/// answered as a group or below the detection limit are in neither.
pub fn answer_parts(d: &Diagnosis) -> (Vec<&str>, Vec<&str>) {
    let pick = |kind: AnswerKind| -> Vec<&str> {
        d.verdict
            .answers
            .iter()
            .filter(|a| a.kind == kind)
            .map(|a| a.id.as_str())
            .collect()
    };
    (pick(AnswerKind::Found), pick(AnswerKind::Calibration))
}

/// What the ranking's line of a candidate (fitted alone on the baseline) must add when the
/// candidate is on the ladder: that its note (a bound, too weak, its neutral value) is about it
/// alone, or that its fitted value changes sign once the ladder's earlier effects are in. None
/// for a candidate not on the ladder, or whose line needs no word.
pub fn ladder_remark(d: &Diagnosis, s: &Scored) -> Option<String> {
    let k = d.ladder.iter().position(|r| r.added == s.id).filter(|&k| k > 0)?;
    let last = d.ladder.last()?;
    let before: Vec<&str> = d.ladder[1..k].iter().map(|r| r.added.as_str()).collect();
    let after = if before.is_empty() {
        "first".to_string()
    } else {
        format!("after {}", before.join(" and "))
    };
    let values = params_text(&last.params, Some(&s.id));
    if s.note.is_some() {
        return Some(format!(
            "That is it alone on the baseline; on the ladder (step {k}, {after}) it fits {values}, inside its bounds and \
             stronger than the repeatability: the earlier effects take what it could not."
        ));
    }
    let alone = s.params.iter().find(|p| p.effect == s.id)?;
    let final_value = last.params.iter().find(|p| p.effect == s.id && p.name == alone.name)?;
    (alone.value * final_value.value < 0.0).then(|| {
        format!(
            "Alone it fits {} = {}; on the ladder (step {k}, {after}) {} = {}: alone it imitates part of what the earlier \
             effects do, and the sign it takes then is not its own.",
            alone.name,
            fmt_value(alone.value),
            alone.name,
            fmt_value(final_value.value)
        )
    })
}

fn ranking_row(i: usize, s: &Scored, remark: Option<String>) -> String {
    let loro = s.loro_rms.map_or("–".into(), pct);
    let remark = remark.map_or(String::new(), |r| {
        format!("<br><span class=\"note\">{}</span>", esc(&r))
    });
    match &s.note {
        Some(n) => format!(
            "<tr><td>{}</td><td><b>{}</b></td><td colspan=\"7\" class=\"text\">{}{remark}</td></tr>\n",
            i + 1,
            esc(&s.id),
            esc(n)
        ),
        None => format!(
            "<tr class=\"{}\"><td>{}</td><td><b>{}</b></td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{:+.0} %</td><td>{}</td><td>{}</td></tr>\n\
             <tr><td></td><td colspan=\"8\" class=\"note text\">{}{remark}</td></tr>\n",
            if s.significant { "sig" } else { "" },
            i + 1,
            esc(&s.id),
            esc(&params_text(&s.params, Some(&s.id))),
            pct(s.rms),
            pct(s.kfold_rms),
            loro,
            100.0 * s.gain,
            sig(s.p_value),
            if s.significant { "yes" } else { "no" },
            esc(&s.explanation)
        ),
    }
}

/// The diagnosis in Markdown: the verdict, where the model fails, the ranking, the ladder, what
/// is left, the measured files.
fn markdown(d: &Diagnosis, verdict: &str, files: &[FileEntry], refused: &[Refused]) -> String {
    let mut md = format!("# Diagnosis\n\n{verdict}\n\n## Where the model fails\n\n");
    for s in &d.before {
        let _ = writeln!(md, "- {}", signature_text(s));
    }
    md.push_str("\n## Ranking\n\n| # | effect | fitted | RMS | held-out | leave-RPM-out | p | significant |\n|---|---|---|---|---|---|---|---|\n");
    for (i, s) in d.ranking.iter().enumerate() {
        match &s.note {
            Some(n) => {
                let remark = ladder_remark(d, s).map_or(String::new(), |r| format!(" {r}"));
                let _ = writeln!(md, "| {} | {} | {n}{remark} | | | | | |", i + 1, s.id);
            }
            None => {
                let _ = writeln!(
                    md,
                    "| {} | {} | {} | {} | {} | {} | {} | {} |",
                    i + 1,
                    s.id,
                    params_text(&s.params, Some(&s.id)),
                    pct(s.rms),
                    pct(s.kfold_rms),
                    s.loro_rms.map_or("–".into(), pct),
                    sig(s.p_value),
                    if s.significant { "yes" } else { "no" }
                );
            }
        }
    }
    md.push_str(
        "\n## Ladder\n\n| step | model | RMS | held-out | thrust: J trend | thrust: RPM trend at fixed J |\n|---|---|---|---|---|---|\n",
    );
    for (i, r) in d.ladder.iter().enumerate() {
        let _ = writeln!(
            md,
            "| {i} | {} | {} | {} | {} | {} |",
            r.stack,
            pct(r.rms),
            pct(r.kfold_rms),
            trend(r.thrust_j_trend),
            trend(r.thrust_rpm_trend)
        );
    }
    md.push_str("\n## What is left\n\n");
    for s in &d.after {
        let _ = writeln!(md, "- {}", signature_text(s));
    }
    md.push('\n');
    md.push_str(&measured_files_md(files, refused));
    md
}

/// Builds the report. The measured files (with their dropped rows) are listed on the page and
/// in the Markdown, not in the body that the run's page nests (its compare section lists them).
pub fn build(
    data: &Data,
    d: &Diagnosis,
    prop: &str,
    files: &[FileEntry],
    refused: &[Refused],
    command: &str,
    effect_args: &str,
) -> Result<Report, PlotError> {
    let measured: Vec<&str> = files.iter().map(|f| f.path.as_str()).collect();
    let panels = residual_panels(data, d);
    let rows = panels.len().div_ceil(2) as u32;
    let residuals = Figure {
        panels,
        columns: 2,
        width: 1400,
        height: 450 * rows,
    };
    let ladder = ladder_figure(d);
    let verdict = verdict(d);
    let mut h = String::new();
    let _ = write!(
        h,
        "<h1>Which effect is missing?</h1>\n<p class=\"note\">prop <code>{}</code> against {}; {} points, {} residual rows \
         (relative thrust and torque errors).<br>command: <code>{}</code></p>\n<p class=\"note\">{}</p>\n{}<p>{}</p>\n",
        esc(prop),
        esc(&measured.join(", ")),
        d.points,
        d.rows,
        esc(command),
        esc(&can_tell(d)),
        diagnosis_html(d),
        esc(&verdict)
    );
    h.push_str(&limits_html(d));
    h.push_str("<h2>Where the model fails</h2>\n<ul>\n");
    for s in &d.before {
        h.push_str(&signature_html(s));
    }
    h.push_str("</ul>\n<h2>Candidate effects, ranked</h2>\n<p class=\"note\">Each effect fitted on its own on top of the baseline \
        (Levenberg-Marquardt; ± is the 95 % interval). Held-out errors: 5-fold and leave-one-RPM-out. Ranked by \
        n ln(held-out MSE) + k ln(n); significant: F test p &lt; 0.01/(number of candidates) and the held-out error falls by at least 10 %.</p>\n\
        <table><tr><th>#</th><th>effect</th><th>fitted</th><th>RMS</th><th>held-out</th><th>leave-RPM-out</th><th>gain</th><th>p</th><th>significant</th></tr>\n");
    for (i, s) in d.ranking.iter().enumerate() {
        h.push_str(&ranking_row(i, s, ladder_remark(d, s)));
    }
    h.push_str("</table>\n<h2>Ladder: effects added while they help</h2>\n<p class=\"note\">The last two columns: the thrust error's \
        change with J at fixed RPM (mean above the median J minus below: what an angle or the inflow makes) and with RPM at fixed J \
        (what the sections' Reynolds number makes), with each rung's effects: which step takes which.</p>\n\
        <table><tr><th>step</th><th>added</th><th>model</th><th>RMS</th><th>held-out</th><th>leave-RPM-out</th><th>p</th>\
        <th>thrust: J trend</th><th>thrust: RPM trend at fixed J</th></tr>\n");
    for (i, r) in d.ladder.iter().enumerate() {
        let _ = writeln!(
            h,
            "<tr><td>{i}</td><td>{}</td><td>{}<br><span class=\"note\">{}</span></td><td class=\"num\">{}</td><td class=\"num\">{}</td>\
             <td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td></tr>",
            esc(&r.added),
            esc(&r.stack),
            esc(&params_text(&r.params, None)),
            pct(r.rms),
            pct(r.kfold_rms),
            r.loro_rms.map_or("–".into(), pct),
            r.p_value.map_or("–".into(), sig),
            trend(r.thrust_j_trend),
            trend(r.thrust_rpm_trend)
        );
    }
    h.push_str("</table>\n");
    h.push_str(&propbet_plot::svg_inline(&ladder)?);
    h.push_str("\n<h2>Before and after</h2>\n");
    h.push_str(&propbet_plot::svg_inline(&residuals)?);
    h.push_str("\n<h3>What is left</h3>\n<ul>\n");
    for s in &d.after {
        h.push_str(&signature_html(s));
    }
    let _ = write!(
        h,
        "</ul>\n<h2>Use it</h2>\n<p>Add the effects to any prediction or comparison: <code>{}</code></p>\n",
        esc(effect_args)
    );

    let md = markdown(d, &verdict, files, refused);
    Ok(Report {
        html: page(
            &format!("propbet diagnosis: {prop}"),
            "",
            &format!("{h}{}", measured_files_html(files, refused)),
        ),
        body: h,
        markdown: crate::md_safe(&md),
        figures: vec![("ladder".into(), ladder), ("residuals".into(), residuals)],
    })
}

/// What the diagnosis found, as a table of its steps (effect, fitted value, physically expected
/// range, held-out error after it) and the verdict's sentence.
pub fn diagnosis_html(d: &Diagnosis) -> String {
    let mut h = String::new();
    let steps = steps(d);
    if !steps.is_empty() {
        let _ = write!(
            h,
            "<table class=\"steps\"><tr><th>step</th><th class=\"text\">effect added</th><th class=\"text\">fitted value (95 %)</th><th class=\"text\">physically expected</th><th>held-out error after</th></tr>\n<tr><td>0</td><td class=\"text\">the prediction as it is</td><td></td><td></td><td>{:.2} %</td></tr>\n",
            100.0 * d.ladder[0].kfold_rms
        );
        for (i, s) in steps.iter().enumerate() {
            let _ = writeln!(
                h,
                "<tr{}><td>{}</td><td class=\"text\"><b>{}</b>{}</td><td class=\"text\">{}</td><td class=\"text\">{}</td><td>{:.2} %</td></tr>",
                if s.calibration { " class=\"calibration\"" } else { "" },
                i + 1,
                esc(&s.id),
                step_note(d, s),
                esc(&s.values),
                esc(&s.expected),
                100.0 * s.after
            );
        }
        h.push_str("</table>\n");
    }
    let _ = writeln!(h, "<p class=\"verdict\">{}</p>", esc(&meaning(d)));
    h
}

/// The note under a step's effect: how the verdict answers it when not as found physics.
fn step_note(d: &Diagnosis, s: &Step) -> String {
    let answer = d.verdict.answers.iter().find(|a| a.id == s.id);
    let note = match answer.map(|a| a.kind) {
        Some(AnswerKind::Group) => format!(
            "one of {}: these data cannot tell them apart",
            answer.map_or(String::new(), |a| a.group.join(", "))
        ),
        Some(AnswerKind::BelowLimit) => "below the detection limit: not named".into(),
        Some(AnswerKind::Calibration) if answer.is_some_and(|a| a.group.len() > 1) => {
            let others = answer.map_or(&[][..], |a| &a.group[1..]);
            format!(
                "a calibration factor, not found physics; {} too",
                stand_ins(&others.join(", "), others.len(), "its")
            )
        }
        _ if s.calibration => "a calibration factor, not found physics".into(),
        _ => return String::new(),
    };
    format!("<br><span class=\"note\">{}</span>", esc(&note))
}

/// What the diagnosis means, in one sentence: what the model misses, what only imitates it,
/// and what is left; the verdict where nothing was found.
pub fn meaning(d: &Diagnosis) -> String {
    if !d.found {
        return verdict(d);
    }
    let (physics, calibration) = answer_parts(d);
    let mut parts = Vec::new();
    if !physics.is_empty() {
        parts.push(format!("the model misses {}", physics.join(" and ")));
    }
    if !calibration.is_empty() {
        parts.push(format!(
            "{} only imitate{} something {} misses (fitted outside the physically expected range)",
            calibration.join(" and "),
            if calibration.len() == 1 { "s" } else { "" },
            if physics.is_empty() { "the model" } else { "it" }
        ));
    }
    parts.extend(group_clauses(d));
    let mut text = parts.join("; ");
    if let Some(first) = text.get(..1) {
        text = first.to_uppercase() + &text[1..];
    }
    format!("{text}. {}.", unexplained_clause(d))
}

mod limits;
mod parts;
mod words;

pub use limits::{can_tell, tied_pairs};
use limits::{group_clauses, limits_html, others, stand_ins};
use parts::{ladder_figure, residual_panels, signature_html, trend};
pub use words::{part_words, signature_text, EffectWords};

#[cfg(test)]
mod tests;
