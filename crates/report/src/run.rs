//! The page of `propbet run`: the stages and their commands, the geometry, the section
//! polars, the sweeps, and the comparison and diagnosis.

use std::fmt::Write as _;

use propbet_bemt::PointResult;
use propbet_pipeline::case::RunPlan;
use propbet_pipeline::run::RunOutcome;
use propbet_plot::{Figure, Mark, Panel, PlotError, Series};

use crate::page::{esc, nest};

/// The equivalent commands a run's page and summary show, as the caller prints them.
#[derive(Debug, Clone, Default)]
pub struct Commands {
    /// Each stage's command, in the order of [`RunOutcome::stages`].
    pub stages: Vec<String>,
    /// The `propbet export` command of the run's prediction.
    pub export: String,
    /// The calibrated model's command (the prediction with the diagnosis's effects, written
    /// beside the sweep), when the diagnosis found something.
    pub calibrated: Option<String>,
}

/// The run's page: how it was made, the geometry, the polars, the sweeps, and the compare and
/// diagnose pages' bodies (`pages`: stage name and body) one level down.
pub fn page(
    plan: &RunPlan,
    run: &RunOutcome,
    pages: &[(&'static str, String)],
    reference: Option<&crate::answer::ReferenceScore>,
    lead: Option<&Figure>,
    commands: &Commands,
) -> Result<String, PlotError> {
    let mut h = String::with_capacity(4_000_000);
    let _ = writeln!(h, "<h1>{}</h1>", esc(&plan.name));
    lead_html(&mut h, plan, run, lead, reference)?;
    if !plan.description.is_empty() {
        let _ = writeln!(h, "<p class=\"note\">{}</p>", esc(&plan.description));
    }
    answer_html(&mut h, run, reference);
    h.push_str(&outputs_html(plan, run, commands));
    let _ = writeln!(
        h,
        "<p class=\"note\">What this run did: {}.</p>",
        esc(&what_it_does(plan))
    );
    let _ = writeln!(
        h,
        "<nav><a href=\"#geometry\">geometry</a><a href=\"#polars\">polars</a><a href=\"#prediction\">prediction</a>{}<a href=\"#problems\">every stage note</a></nav>",
        pages
            .iter()
            .map(|(id, _)| format!(
                "<a href=\"#{id}\">{}</a>",
                match *id {
                    "motor" => "on its motor",
                    "compare" => "measured vs predicted",
                    _ => "what is missing, in detail",
                }
            ))
            .collect::<String>()
    );
    let problems = problems(run);
    stages_html(&mut h, plan, run, &problems, commands);

    geometry_html(&mut h, plan, run)?;

    polars_html(&mut h, run);

    // Prediction.
    h.push_str("<section id=\"prediction\"><h2>Prediction</h2>\n");
    if let Some(e) = plan.expected.as_ref().filter(|_| run.compared.is_none()) {
        let _ = writeln!(h, "<p>{}</p>", esc(e));
    }
    h.push_str(&propbet_plot::svg_inline(&sweep_figure(&run.sweep))?);
    h.push_str("</section>\n");

    for (id, body) in pages {
        let _ = writeln!(h, "<section id=\"{id}\">\n{}\n</section>", nest(body));
    }
    notes_html(&mut h, &problems);
    Ok(crate::page::page(&format!("propbet run: {}", plan.name), "", &h))
}

/// The answer first: how close the prediction is and what is missing.
fn answer_html(h: &mut String, run: &RunOutcome, reference: Option<&crate::answer::ReferenceScore>) {
    if let Some(c) = &run.compared {
        h.push_str("<section id=\"answer\"><h2>How close the prediction is</h2>\n");
        h.push_str(&crate::answer::headline_html(&c.metrics, reference, &c.points));
        let standard = c.points.iter().filter(|p| p.air.standard).count();
        if standard > 0 {
            let _ = writeln!(
                h,
                "<p class=\"note\">The measurements log no air temperature or pressure: standard air is assumed at {standard} of {} points (<code>[atmosphere] air</code> in case.toml gives the real air).</p>",
                c.points.len()
            );
        }
        if let Some(d) = &run.diagnosed {
            h.push_str("<h2>What is missing</h2>\n");
            h.push_str(&crate::diagnose::diagnosis_html(&d.diagnosis));
        }
        h.push_str("</section>\n");
    }
}

/// How the report was made: each stage, its time, status and equivalent command.
fn stages_html(
    h: &mut String,
    plan: &RunPlan,
    run: &RunOutcome,
    problems: &[(&'static str, usize, String)],
    commands: &Commands,
) {
    h.push_str("<h2>How this report was made</h2>\n<table><tr><th>stage</th><th>time [s]</th><th>status</th><th>equivalent command</th></tr>\n");
    for (i, s) in run.stages.iter().enumerate() {
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{:.1}</td><td>{}</td><td class=\"cmd\"><code>{}</code></td></tr>",
            s.spec.name(),
            s.seconds,
            match (s.clean, problems.iter().any(|p| p.0 == s.spec.name())) {
                (true, false) => "ok",
                (true, true) => "ok, with notes",
                (false, _) => "problems",
            },
            esc(commands.stages.get(i).map_or("", String::as_str))
        );
    }
    let _ = writeln!(
        h,
        "</table>\n<p class=\"note\">case directory <code>{}</code>; outputs of each stage beside this report.</p>",
        esc(&plan.dir.display().to_string())
    );
}

/// The geometry: the scan's summary, notes and figures, or the prop file it came from.
fn geometry_html(h: &mut String, plan: &RunPlan, run: &RunOutcome) -> Result<(), PlotError> {
    h.push_str("<section id=\"geometry\"><h2>Geometry</h2>\n");
    match &run.scanned {
        Some(sc) => {
            let g = &sc.geometry;
            let _ = writeln!(
                h,
                "<p>{}; {}.</p>",
                esc(&crate::scan::summary(g)),
                esc(&crate::scan::accuracy(g))
            );
            if let Some(line) = sc.reference.as_deref().and_then(|t| crate::scan::reference_check(g, t)) {
                let _ = writeln!(h, "<p>{}.</p>", esc(&line));
            }
            h.push_str("<ul>");
            for n in &g.notes {
                let _ = write!(h, "<li>{}</li>", esc(n));
            }
            h.push_str("</ul>\n");
            for f in &g.failed {
                let _ = writeln!(h, "<p class=\"note\">r/R {:.3}: {}</p>", f.r_r, esc(&f.reason));
            }
            h.push_str("<h3>Along the radius (with the reference table where the case has one)</h3>\n");
            h.push_str(&propbet_plot::svg_inline(&crate::scan::distributions_figure(
                g,
                sc.reference.as_deref(),
            ))?);
            h.push_str("<h3>The sections: scan points and fits</h3>\n");
            h.push_str(&propbet_plot::svg_inline(&crate::scan::sections_figure(g))?);
        }
        None => {
            let _ = writeln!(
                h,
                "<p>From the prop file <code>{}</code> (no scan in this case).</p>",
                esc(&plan.predict.model.prop.display().to_string())
            );
        }
    }
    h.push_str("</section>\n");

    Ok(())
}

/// The section polars: what they cover and each station's QPROP fit.
fn polars_html(h: &mut String, run: &RunOutcome) {
    h.push_str("<section id=\"polars\"><h2>Section polars</h2>\n");
    match &run.polars {
        Some(p) => {
            let b = &p.blade;
            let makers = propbet_polar::Makers::of(b.stations.iter().flat_map(|s| &s.polars));
            let _ = writeln!(
                h,
                "<p>{} covering the Reynolds numbers each station sees from {:.0} to {:.0} rpm and {:.1} to {:.1} m/s (five per decade in Re), used as tables in α and Re; sections: {}. The QPROP columns are the exported prop file's fit (centred on the geometric mean of the Re range), with its fallbacks in the problem column.{}</p>",
                esc(&makers.words()),
                b.rpm[0],
                b.rpm[1],
                b.v[0],
                b.v[1],
                esc(&b.airfoil),
                makers.doubts().map_or(String::new(), |d| format!(" {}.", esc(&d)))
            );
            h.push_str("<table><tr><th>r [mm]</th><th>chord [mm]</th><th>Re range</th><th>Mach</th><th>α range [deg]</th><th>CL0</th><th>CL_a [/rad]</th><th>CLmax</th><th>CD0</th><th>CD2u</th><th class=\"text\">problem</th></tr>\n");
            for s in &b.stations {
                let c = s.fit.as_ref().map(|f| f.coeffs.to_array());
                let cell = |k: usize, p: usize| c.map_or("–".into(), |v| format!("{:.*}", p, v[k]));
                let _ = writeln!(
                    h,
                    "<tr><td>{:.1}</td><td>{:.1}</td><td>{:.0}–{:.0}</td><td>{:.3}</td><td>{:.1}–{:.1}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"text\">{}</td></tr>",
                    1000.0 * s.r,
                    1000.0 * s.chord,
                    s.re_range[0],
                    s.re_range[1],
                    s.mach,
                    s.alpha_range_deg[0],
                    s.alpha_range_deg[1],
                    cell(0, 3),
                    cell(1, 2),
                    cell(3, 2),
                    cell(4, 4),
                    cell(5, 4),
                    esc(&station_problems(s))
                );
            }
            h.push_str("</table>\n");
            if let Some(e) = &p.export {
                let _ = writeln!(h, "<p>{}</p>", esc(&e.sentence()));
            }
        }
        None => h.push_str("<p>The prop file's own QPROP coefficients (no XFOIL stage in this case).</p>\n"),
    }
    h.push_str("</section>\n");
}

/// Every stage's notes, grouped alike, collapsed at the end: each is also said beside the
/// result it affects (the QPROP fit's beside the exported file, XFOIL's in the polars table).
fn notes_html(h: &mut String, problems: &[(&'static str, usize, String)]) {
    h.push_str("<section id=\"problems\"><h2>Every note of the stages</h2>\n");
    if problems.is_empty() {
        h.push_str("<p class=\"note\">No stage reported a problem.</p>\n");
    } else {
        let _ = writeln!(
            h,
            "<details><summary>{} notes (grouped alike): open the list</summary>\n<ul class=\"problems\">",
            problems.len()
        );
        for (stage, n, text) in problems {
            let count = if *n > 1 {
                format!("{n}×, for example: ")
            } else {
                String::new()
            };
            let _ = writeln!(h, "<li><b>{}</b>: {count}{}</li>", esc(stage), esc(text));
        }
        h.push_str("</ul></details>\n");
    }
    h.push_str("</section>\n");
}

/// A path under the run's output folder as a link relative to its report.
fn link(out: &std::path::Path, path: &std::path::Path) -> String {
    let rel = path.strip_prefix(out).unwrap_or(path);
    let text = rel.display().to_string();
    format!("<a href=\"{}\"><code>{}</code></a>", esc(&text), esc(&text))
}

/// The outputs a user takes away, each with what it is: the prediction's table, the exported
/// QPROP file (with how far its law is from the prediction's tables and the notes on its fit,
/// which concern that file only), the calibrated model, and the stages' own pages.
fn outputs_html(plan: &RunPlan, run: &RunOutcome, commands: &Commands) -> String {
    let out = &plan.out;
    let mut h = String::from("<section id=\"outputs\"><h2>Outputs</h2>\n<ul>");
    if let Some(o) = &plan.predict.out {
        let _ = write!(
            h,
            "<li>{}: the prediction, thrust, torque, CT, CP and efficiency at every RPM and J of the sweep{}</li>",
            link(out, o),
            if plan.predict.band {
                format!(
                    ", with an uncertainty band for CT, CP and efficiency ({}: the columns ct_lo to eta_hi)",
                    propbet_model::band::BandSpec::sources_text(&run.model.loaded.file)
                )
            } else {
                String::new()
            }
        );
        match (&run.qprop_export, o.parent()) {
            (Ok(x), Some(dir)) => {
                let _ = write!(
                    h,
                    "<li>{}: the QPROP 1.22 prop file that carries this prediction (QPROP's law fitted at each of its stations to what the model's sections do there). {}.</li>",
                    link(out, &dir.join(propbet_qprop::export::FILE_NAME)),
                    esc(&x.fidelity.sentence())
                );
            }
            (Err(e), _) => {
                let _ = write!(h, "<li>No QPROP export: {}</li>", esc(e));
            }
            _ => {}
        }
    }
    if let (Some(spec), Some(t), Some(o)) = (
        &plan.powered,
        &run.powered,
        plan.powered.as_ref().and_then(|p| p.out.as_ref()),
    ) {
        let brief = crate::powered::brief(t, spec);
        let _ = write!(
            h,
            "<li>{}: the propeller on its motor{}, {} (<a href=\"#motor\">the table</a>)</li>",
            link(out, o),
            if spec.supply.is_some() { " and battery" } else { "" },
            esc(brief.get(1).map_or("no point has an operating point", String::as_str))
        );
    }
    if let (Some((spec, _)), Some(p)) = (&plan.polars, &run.polars) {
        let notes: Vec<String> = p
            .blade
            .stations
            .iter()
            .flat_map(|s| s.fit.iter().flat_map(|f| f.unfit.iter().cloned()))
            .chain(run.model.loaded.warnings.iter().cloned())
            .collect();
        let _ = write!(
            h,
            "<li>{}: the polars stage's own prop file, QPROP's law fitted to each station's polars (to run QPROP on this prediction, take the file above){}",
            link(out, &spec.out_prop),
            p.export.as_ref().map_or(String::new(), |e| format!(
                "; it differs from the tables this report's prediction uses by {:.1} % in CT and {:.1} % in CP (median; {:.1} % and {:.1} % at most)",
                100.0 * e.ct.median,
                100.0 * e.cp.median,
                100.0 * e.ct.largest,
                100.0 * e.cp.largest
            ))
        );
        let grouped = crate::page::group_alike(notes);
        if !grouped.is_empty() {
            let _ = write!(
                h,
                "<details><summary>{} notes on this file's fit (they concern the exported file, not the prediction above)</summary><ul>",
                grouped.len()
            );
            for (n, text) in &grouped {
                let count = if *n > 1 {
                    format!("{n} stations, for example: ")
                } else {
                    String::new()
                };
                let _ = write!(h, "<li>{count}{}</li>", esc(text));
            }
            h.push_str("</ul></details>");
        }
        h.push_str("</li>");
    }
    if let (Some((_, dspec)), Some(cmd)) = (&plan.compare, &commands.calibrated) {
        let _ = write!(
            h,
            "<li>the calibrated model (the prediction with the diagnosis's effects): {}; as a command: <code>{}</code></li>",
            link(out, &dspec.out.join("diagnosis.json")),
            esc(cmd)
        );
    }
    let _ = write!(
        h,
        "<li>for flight simulators (Gazebo's motor model, PX4 SIH's thruster, a JSBSim propeller) and a CT/CP map, each saying how well it reproduces this prediction: <code>{}</code></li>",
        esc(&commands.export)
    );
    if let Some((cspec, dspec)) = &plan.compare {
        let _ = write!(
            h,
            "<li>the stages' own pages: {} (every point), {} (every candidate effect); {} (this run, machine-readable)</li>",
            link(out, &cspec.out.join("report.html")),
            link(out, &dspec.out.join("report.html")),
            link(out, &out.join("summary.json"))
        );
    }
    h.push_str("</ul></section>\n");
    h
}

/// CT, CP and efficiency against J, one line per RPM.
pub fn sweep_figure(points: &[PointResult]) -> Figure {
    // Per RPM: (CT, CP, efficiency) against J.
    type Curves = [Vec<(f64, f64)>; 3];
    let mut by_rpm: Vec<(String, Curves)> = Vec::new();
    let nan = f64::NAN;
    for p in points {
        // The label as the sweep table prints the speed (7 significant digits).
        let rpm = format!("{:.0} rpm", p.rpm);
        if by_rpm.last().is_none_or(|b| b.0 != rpm) {
            by_rpm.push((rpm.clone(), Default::default()));
        }
        let e = &mut by_rpm.last_mut().expect("pushed").1;
        let (j, ct, cp) = (p.j.unwrap_or(nan), p.ct.unwrap_or(nan), p.cp.unwrap_or(nan));
        e[0].push((j, ct));
        e[1].push((j, cp));
        if ct > 0.0 {
            e[2].push((j, p.eta));
        }
    }
    let panel = |k: usize, title: &str, y: &str| Panel {
        title: title.into(),
        x_label: "J = V/(nD)".into(),
        y_label: y.into(),
        series: by_rpm
            .iter()
            .enumerate()
            .map(|(i, (name, s))| Series::new(name.clone(), s[k].clone(), Mark::Line, Some(i)))
            .collect(),
        zero_line: true,
        y_clip: None,
        equal_aspect: false,
    };
    Figure {
        panels: vec![
            panel(0, "Thrust coefficient CT = T/(ρn²D⁴)", "CT"),
            panel(1, "Power coefficient CP = P/(ρn³D⁵)", "CP"),
            panel(2, "Efficiency η = J CT/CP (where CT > 0)", "η"),
        ],
        columns: 3,
        width: 1200,
        height: 400,
    }
}

/// The run in a machine-readable summary (`summary.json` of `propbet run`): the stages with
/// their commands, every problem grouped alike, the comparison's headline (the scored window,
/// static and forward flight) and the diagnosis' answer.
pub fn summary_json(plan: &RunPlan, run: &RunOutcome, commands: &Commands) -> serde_json::Value {
    use serde_json::json;
    let stages: Vec<_> = run
        .stages
        .iter()
        .zip(&commands.stages)
        .map(|(s, command)| json!({"stage": s.spec.name(), "seconds": s.seconds, "clean": s.clean, "command": command}))
        .collect();
    let problems: Vec<_> = problems(run)
        .into_iter()
        .map(|(stage, count, example)| json!({"stage": stage, "count": count, "example": example}))
        .collect();
    let headline = run
        .compared
        .as_ref()
        .map_or(json!([]), |c| crate::answer::headline_json(&c.metrics));
    let diagnosis = run
        .diagnosed
        .as_ref()
        .map(|d| crate::diagnose::diagnosis_json(&d.diagnosis));
    // Which program made the polars, in counts (each point's own is in the polar table).
    let polars = plan.polars.as_ref().map(|(p, _)| {
        let made = run
            .polars
            .as_ref()
            .map(|r| propbet_polar::Makers::of(r.blade.stations.iter().flat_map(|s| &s.polars)));
        let text = made.map(|m| m.doubts().map_or(m.words(), |d| format!("{}; {d}", m.words())));
        json!({"engine": p.xfoil.process.engine.name(), "made": made, "text": text})
    });
    let mut summary = json!({
        "format": "propbet-run-summary-1",
        "case": plan.name,
        "case_dir": plan.dir.display().to_string(),
        "clean": run.clean(),
        "stages": stages,
        "problems": problems.iter().filter(|p| !run.stages.iter().any(|s| s.clean && s.spec.name() == p["stage"])).collect::<Vec<_>>(),
        "notes": problems.iter().filter(|p| run.stages.iter().any(|s| s.clean && s.spec.name() == p["stage"])).collect::<Vec<_>>(),
        "headline": headline,
        "accuracy": run.compared.as_ref().map(|c| crate::compare::accuracy_json(&c.points)),
        // How close a prediction of this kind of blade came on propbet's validation.
        "expected": plan.expected,
        // Where the calibrated model (the prediction with the diagnosis's effects) is worse
        // than the prediction (the report's first screen says it too).
        "calibrated_worse": match (&run.compared, &run.calibrated) {
            (Some(c), Some(cal)) => json!(calibrated_worse(&c.metrics, cal)),
            _ => json!([]),
        },
        "diagnosis": diagnosis,
        "polars": polars,
        "qprop_export": match &run.qprop_export {
            Ok(x) => json!({
                "file": plan.predict.out.as_ref().and_then(|o| o.parent()).map(|d| d.join(propbet_qprop::export::FILE_NAME).display().to_string()),
                "fidelity": x.fidelity,
            }),
            Err(e) => json!({"error": e}),
        },
    });
    // A case with a motor's powered table (the key absent without one).
    if let (Some(t), Some(o)) = (&run.powered, summary.as_object_mut()) {
        o.insert(
            "powered".into(),
            json!({
                "motor": t.motor.name,
                "file": plan.powered.as_ref().and_then(|p| p.out.as_ref()).map(|o| o.display().to_string()),
                "points": t.points.len(),
                "solved": t.points.iter().filter(|p| p.problem().is_none()).count(),
            }),
        );
    }
    summary
}

/// What the run does, from its plan (not from the case's own words, which may be out of date).
pub fn what_it_does(plan: &RunPlan) -> String {
    let name = |p: &std::path::Path| {
        p.file_name()
            .map_or(String::new(), |n| n.to_string_lossy().into_owned())
    };
    let mut parts = Vec::new();
    match &plan.scan {
        Some(s) => parts.push(format!("geometry scanned from {}", name(&s.input))),
        None => parts.push(format!(
            "geometry from the prop file {}",
            name(&plan.predict.model.prop)
        )),
    }
    match &plan.polars {
        Some((p, scan_sections)) => {
            let rpm: Vec<f64> = p.omegas.iter().map(|&w| propbet_bemt::units::omega_to_rpm(w)).collect();
            let (lo, hi) = rpm
                .iter()
                .fold((f64::INFINITY, 0.0f64), |a, &r| (a.0.min(r), a.1.max(r)));
            let airfoil = p.airfoil.as_deref().map(|a| name(std::path::Path::new(a)));
            let sections = match (*scan_sections, airfoil) {
                (true, Some(a)) => format!("each station's scanned section (the {a} where a fit failed)"),
                (true, None) => "each station's scanned section (the nearest station's where a fit failed)".to_string(),
                (false, a) => format!("the {} section at every station", a.unwrap_or_default()),
            };
            parts.push(format!(
                "{} polars (Ncrit {}, {}) of {sections}, covering {lo:.0}-{hi:.0} rpm, used as {}",
                engine_words(p.xfoil.process.engine),
                p.xfoil.section.ncrit,
                p.xfoil
                    .section
                    .trip
                    .map_or("free transition".to_string(), |x| format!("transition by x/c {x}")),
                if plan.predict.model.polars.is_some() {
                    "tables in alpha and Re"
                } else {
                    "QPROP's fitted law"
                }
            ));
            let m = &plan.predict.model;
            parts.push(format!(
                "rotational augmentation {}, section drag times {}",
                m.rotation.name(),
                m.drag_factor
            ));
        }
        None => parts.push("the prop file's own QPROP coefficients".into()),
    }
    let rpm: Vec<f64> = plan
        .predict
        .omegas
        .iter()
        .map(|&w| propbet_bemt::units::omega_to_rpm(w))
        .collect();
    parts.push(format!(
        "sweeps at {} rpm",
        rpm.iter().map(|r| format!("{r:.0}")).collect::<Vec<_>>().join(", ")
    ));
    if let Some(p) = &plan.powered {
        let drives: Vec<String> = p.drives.iter().map(|d| d.describe()).collect();
        parts.push(format!(
            "on the motor {}{} at {}",
            name(&p.motor),
            if p.supply.is_some() {
                " with its battery and ESC"
            } else {
                ""
            },
            drives.join(", ")
        ));
    }
    if let Some((c, _)) = &plan.compare {
        parts.push(format!(
            "compared with {} measured file(s) and diagnosed",
            c.measured.files.len()
        ));
    }
    parts.join("; ")
}

/// The problems of every stage, grouped alike: (stage, count, example).
fn problems(run: &RunOutcome) -> Vec<(&'static str, usize, String)> {
    let mut out = Vec::new();
    let mut add = |stage: &'static str, msgs: Vec<String>| {
        for (n, m) in crate::page::group_alike(msgs) {
            out.push((stage, n, m));
        }
    };
    if let Some(sc) = &run.scanned {
        let g = &sc.geometry;
        let mut v: Vec<String> = g
            .failed
            .iter()
            .map(|f| format!("station at r/R {:.2} failed: {}", f.r_r, f.reason))
            .collect();
        v.extend(g.notes.iter().filter(|n| n.contains("ASSUMED")).cloned());
        add("scan", v);
    }
    if let Some(p) = &run.polars {
        let mut v: Vec<String> = p.blade.stations.iter().flat_map(station_problem_list).collect();
        v.extend(p.cache_warning.clone());
        add("polars", v);
    }
    add("predict", run.model.loaded.warnings.clone());
    if let Some(c) = &run.compared {
        let (faults, unconverged) = c.problems();
        let mut v: Vec<String> = c.warnings();
        if faults > 0 {
            v.push(format!("{faults} measured rows dropped as faulty"));
        }
        if unconverged > 0 {
            v.push(format!("{unconverged} station solutions did not converge"));
        }
        let implausible = c.points.iter().filter(|p| !p.model_flags.is_empty()).count();
        if implausible > 0 {
            v.push(format!(
                "the prediction is physically implausible at {implausible} points"
            ));
        }
        let standard = c.points.iter().filter(|p| p.air.standard).count();
        if standard > 0 {
            v.push(format!(
                "standard air assumed at {standard} of {} points (no temperature or pressure logged or given)",
                c.points.len()
            ));
        }
        add("compare", v);
    }
    out
}

fn station_problems(s: &propbet_polar::blade::StationPolars) -> String {
    station_problem_list(s).join("; ")
}

/// The program a run's plan makes its polars with.
fn engine_words(e: propbet_polar::Engine) -> &'static str {
    match e {
        propbet_polar::Engine::Xfoil => "XFOIL",
        propbet_polar::Engine::NeuralFoil => "NeuralFoil",
        propbet_polar::Engine::Auto => "XFOIL (NeuralFoil where XFOIL fails)",
    }
}

/// Everything wrong at a station of the polars, for the table's problem column and the run's
/// summary: the stage's own note, angles XFOIL did not converge, the QPROP fit's verdicts and
/// fallbacks, XFOIL's faults (rungs without a polar: the tables interpolate across them).
fn station_problem_list(s: &propbet_polar::blade::StationPolars) -> Vec<String> {
    let mut v: Vec<String> = s.problem.iter().cloned().collect();
    let unconverged: usize = s.polars.iter().map(|p| p.unconverged_deg.len()).sum();
    // Worded so that the count's noun does not change with it: the report groups messages
    // that differ only in their numbers.
    if unconverged > 0 {
        v.push(format!(
            "XFOIL did not converge at {unconverged} of the angles of {} polars",
            s.polars.len()
        ));
    }
    let loops: usize = s.polars.iter().map(|p| p.hysteresis.len()).sum();
    if loops > 0 {
        v.push(format!(
            "two XFOIL solutions (hysteresis) at {loops} of the angles of {} polars: the lower-drag one kept",
            s.polars.len()
        ));
    }
    if let Some(f) = &s.fit {
        v.extend(f.unfit.iter().map(|u| format!("QPROP fit: {u}")));
    }
    if s.polars.iter().any(|p| !p.faults.is_empty()) {
        v.push("XFOIL faults (crash, hang or budget) at some Reynolds numbers".into());
    }
    if let Some(why) = s.polars.iter().find_map(|p| p.not_filled.as_ref()) {
        v.push(format!("{why}: XFOIL's polars kept with their gaps"));
    }
    let m = propbet_polar::Makers::of(&s.polars);
    if m.filled_points > 0 {
        v.push(format!(
            "NeuralFoil made {} of the angles of {} polars (where XFOIL did not converge)",
            m.filled_points,
            s.polars.len()
        ));
    }
    if m.unsure > 0 {
        v.push(format!(
            "NeuralFoil is unsure (confidence below {}) at {} of the angles of {} polars",
            propbet_polar::table::LOW_CONFIDENCE,
            m.unsure,
            s.polars.len()
        ));
    }
    v
}

pub mod brief;
mod lead;
pub use lead::calibrated_worse;
use lead::lead_html;

#[cfg(test)]
mod tests;
