//! `propbet run CASE_DIR`: the main job. A case directory's `case.toml` names a scan (or a
//! prop file), the sections, the operating points, the measurements and the air; the run
//! chains scan → XFOIL polars at each station's Reynolds number → BEMT sweeps → comparison →
//! diagnosis in memory (`propbet_pipeline::run::run_case`), each stage the documented command
//! it is equivalent to, then writes every stage's outputs and one HTML report that holds them.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Result};
use clap::{Args, Parser};
use propbet_bemt::PointResult;
use propbet_compare::report::esc;
use propbet_pipeline::case::{read_case, RunPlan};
use propbet_pipeline::run::{run_case, Event, Finished, RunOutcome, StageRecord};
use propbet_pipeline::spec::StageSpec;
use propbet_plot::{Figure, Mark, Panel, Series};

use crate::output::write_atomic;
use crate::polar::{Bar, XfoilProcess};

/// Arguments of `propbet run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// Case directory holding `case.toml` (default: the shipped `props/apcsf_10x4.7`).
    pub case: Option<PathBuf>,
    /// Output directory (default: `run_<case directory name>` in the current directory).
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// XFOIL executable, polar cache, progress bars (passed on to the polars stage).
    #[command(flatten)]
    pub xfoil: XfoilProcess,
}

/// The shipped default case: `props/apcsf_10x4.7` under the current directory or beside the
/// executable's repository (`target/release/propbet` → `../../props`).
fn default_case() -> Result<PathBuf> {
    let rel = Path::new("props").join("apcsf_10x4.7");
    let mut tried = vec![rel.clone()];
    if rel.join("case.toml").is_file() {
        return Ok(rel);
    }
    if let Ok(exe) = std::env::current_exe() {
        for up in exe.ancestors().skip(1).take(4) {
            let c = up.join(&rel);
            if c.join("case.toml").is_file() {
                return Ok(c);
            }
            tried.push(c);
        }
    }
    bail!(
        "no case directory given and the default case is not at {}",
        tried
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    )
}

/// The scan flags of a case (`--units`, `--stations`, its `scan_args`) as the geometry
/// pipeline's options, read as `propbet scan` reads them.
fn scan_options(flags: &[String]) -> propbet_pipeline::Result<propbet_geometry::scan::ScanOptions> {
    let argv = ["propbet", "scan", "scan.stl", "-o", "out"]
        .into_iter()
        .map(String::from)
        .chain(flags.iter().cloned());
    let cli =
        crate::Cli::try_parse_from(argv).map_err(|e| propbet_pipeline::Error::Invalid(format!("scan_args: {e}")))?;
    match cli.command {
        crate::Command::Scan(a) => {
            crate::scan::options(&a).map_err(|e| propbet_pipeline::Error::Invalid(format!("{e:#}")))
        }
        _ => unreachable!("parsed as scan"),
    }
}

/// The plan of a case directory, writing under `out`.
pub fn plan(dir: &Path, out: &Path, xfoil: &XfoilProcess) -> Result<RunPlan> {
    let case = read_case(dir)?;
    Ok(case.plan(dir, out, &xfoil.spec(), &scan_options)?)
}

/// Runs `propbet run`.
pub fn run(a: &RunArgs) -> Result<bool> {
    let t_all = Instant::now();
    let dir = match &a.case {
        Some(d) => d.clone(),
        None => default_case()?,
    };
    if !dir.is_dir() {
        bail!("{}: not a case directory", dir.display());
    }
    let out = match &a.out {
        Some(o) => o.clone(),
        None => {
            let name = dir
                .canonicalize()
                .ok()
                .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
                .unwrap_or_else(|| "case".into());
            PathBuf::from(format!("run_{name}"))
        }
    };
    let plan = plan(&dir, &out, &a.xfoil)?;
    if let (Ok(o), Ok(d)) = (out.canonicalize(), dir.canonicalize()) {
        if o == d || d.starts_with(&o) {
            bail!(
                "{}: the output directory would hold the case's own files",
                out.display()
            );
        }
    }
    std::fs::create_dir_all(&out).map_err(|e| anyhow::anyhow!("{}: cannot create: {e}", out.display()))?;
    let bar = Bar::new(a.xfoil.quiet);
    let mut pages: Vec<(&'static str, String)> = Vec::new();
    let mut write_err: Option<anyhow::Error> = None;
    let outcome = run_case(&plan, &|d, t| bar.tick(d, t), &mut |e| match e {
        Event::Start { n, total, spec } => {
            eprintln!("propbet [{n}/{total}] {}: {}", spec.name(), spec.command());
        }
        Event::Done { n, total, record, made } => {
            if write_err.is_none() {
                match write_stage(record, &made) {
                    Ok(Some(page)) => pages.push((record.spec.name(), page)),
                    Ok(None) => {}
                    Err(e) => write_err = Some(e),
                }
            }
            eprintln!(
                "propbet [{n}/{total}] {}: {:.1} s{}",
                record.spec.name(),
                record.seconds,
                if record.clean { "" } else { " (with reported problems)" }
            );
        }
    })?;
    if let Some(e) = write_err {
        return Err(e);
    }

    // The report.
    let t0 = Instant::now();
    let total = outcome.stages.len() + 1;
    let html = report(&plan, &outcome, &pages)?;
    let report_path = out.join("report.html");
    write_atomic(&report_path, &[html.as_bytes()], &[dir.join("case.toml").as_path()])?;
    eprintln!("propbet [{total}/{total}] report: {:.1} s", t0.elapsed().as_secs_f64());
    println!(
        "{}: {} stages in {:.1} s; report: {}",
        plan.name,
        total,
        t_all.elapsed().as_secs_f64(),
        report_path.display()
    );
    Ok(outcome.clean())
}

fn create_parent(path: &Path) -> Result<()> {
    if let Some(d) = path.parent() {
        std::fs::create_dir_all(d).map_err(|e| anyhow::anyhow!("{}: cannot create: {e}", d.display()))?;
    }
    Ok(())
}

/// Writes a finished stage's outputs and prints its summary, as its own command does; the
/// compare and diagnose pages come back for the report.
fn write_stage(record: &StageRecord, made: &Finished) -> Result<Option<String>> {
    match (&record.spec, made) {
        (StageSpec::Scan(spec), Finished::Scan(s)) => {
            crate::scan::write(spec, s)?;
            crate::scan::print_summary(s);
        }
        (StageSpec::Polars(spec), Finished::Polars(p, input)) => {
            crate::polar::print_polars(spec, input, p);
            create_parent(&spec.out_prop)?;
            crate::polar::write_polars(spec, p)?;
        }
        (StageSpec::Predict(spec), Finished::Predict(points, model)) => {
            for w in &model.loaded.warnings {
                eprintln!("propbet: warning: {w}");
            }
            if let Some(o) = &spec.out {
                create_parent(o)?;
            }
            crate::predict::write_sweep(spec, points)?;
        }
        (StageSpec::Compare(spec), Finished::Compare(c, model)) => {
            let page = crate::compare::write(spec, model, c)?;
            crate::compare::print(spec, c);
            return Ok(Some(page));
        }
        (StageSpec::Diagnose(spec), Finished::Diagnose(d)) => {
            let page = crate::diagnose::write(spec, d)?;
            crate::diagnose::print(spec, d);
            return Ok(Some(page));
        }
        _ => unreachable!("a stage's record and artifact match"),
    }
    Ok(None)
}

/// `<style>` and `<body>` of a report page written by another stage.
fn parts_of(page: &str) -> (String, String) {
    let style = page
        .split_once("<style>")
        .and_then(|(_, r)| r.split_once("</style>"))
        .map_or(String::new(), |(s, _)| s.to_string());
    let body = page
        .split_once("<body>")
        .and_then(|(_, r)| r.rsplit_once("</body>"))
        .map_or(String::new(), |(b, _)| b.to_string());
    // One level down: the stage's h1 becomes a section heading.
    let body = body
        .replace("<h3", "<h4")
        .replace("</h3>", "</h4>")
        .replace("<h2", "<h3")
        .replace("</h2>", "</h3>")
        .replace("<h1", "<h2")
        .replace("</h1>", "</h2>");
    (style, body)
}

fn report(plan: &RunPlan, run: &RunOutcome, pages: &[(&'static str, String)]) -> Result<String> {
    let font = propbet_plot::font_face_css();
    let mut styles = vec![font.clone()];
    let mut bodies = Vec::new();
    for (id, page) in pages {
        let (style, body) = parts_of(page);
        styles.push(style.replace(&font, ""));
        bodies.push((*id, body));
    }
    let mut h = String::with_capacity(4_000_000);
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>propbet run: {}</title>\n<style>{}\n\
         body{{max-width:1200px;margin:auto;font-family:sans-serif}} nav a{{margin-right:1em}} \
         section{{border-top:2px solid #888;margin-top:2em}} svg{{max-width:100%;height:auto}} \
         svg text{{font-family:{},sans-serif}}</style></head><body>\n",
        esc(&plan.name),
        styles.join("\n"),
        propbet_plot::FONT_FAMILY
    );
    let _ = writeln!(h, "<h1>{}</h1>", esc(&plan.name));
    if !plan.description.is_empty() {
        let _ = writeln!(h, "<p>{}</p>", esc(&plan.description));
    }
    let _ = writeln!(
        h,
        "<nav><a href=\"#geometry\">geometry</a><a href=\"#polars\">polars</a><a href=\"#prediction\">prediction</a>{}</nav>",
        if bodies.is_empty() {
            String::new()
        } else {
            "<a href=\"#compare\">measured vs predicted</a><a href=\"#diagnose\">what is missing</a>".into()
        }
    );
    // Stages.
    h.push_str("<h2>How this report was made</h2>\n<table><tr><th>stage</th><th>time [s]</th><th>status</th><th>equivalent command</th></tr>\n");
    for s in &run.stages {
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{:.1}</td><td>{}</td><td><code>{}</code></td></tr>",
            s.spec.name(),
            s.seconds,
            if s.clean { "ok" } else { "problems reported (see below)" },
            esc(&s.spec.command())
        );
    }
    let _ = writeln!(
        h,
        "</table>\n<p class=\"note\">case directory <code>{}</code>; outputs of each stage beside this report.</p>",
        esc(&plan.dir.display().to_string())
    );

    // Geometry.
    h.push_str("<section id=\"geometry\"><h2>Geometry</h2>\n");
    match &run.scanned {
        Some(sc) => {
            let g = &sc.geometry;
            let _ = writeln!(
                h,
                "<p>{} blades, tip radius {:.2} mm, hub radius {}, blades from {:.2} mm; {} stations measured, {} failed.</p>",
                g.blades,
                g.tip_radius,
                g.hub_radius.map_or("none".into(), |x| format!("{x:.2} mm")),
                g.root_radius,
                g.stations.len(),
                g.failed.len(),
            );
            h.push_str("<ul>");
            for n in &g.notes {
                let _ = write!(h, "<li>{}</li>", esc(n));
            }
            h.push_str("</ul>\n");
            for f in &g.failed {
                let _ = writeln!(h, "<p class=\"note\">r/R {:.3}: {}</p>", f.r_r, esc(&f.reason));
            }
            h.push_str("<h3>Along the radius (with the reference table where the case has one)</h3>\n");
            let svg = |f: &Figure| propbet_plot::svg_inline(f).map_err(|e| anyhow::anyhow!("{e}"));
            h.push_str(&svg(&crate::scan::distributions_figure(g, sc.reference.as_deref()))?);
            h.push_str("<h3>The sections: scan points and fits</h3>\n");
            h.push_str(&svg(&crate::scan::sections_figure(g))?);
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

    // Polars.
    h.push_str("<section id=\"polars\"><h2>Section polars</h2>\n");
    match &run.polars {
        Some(p) => {
            let b = &p.blade;
            let _ = writeln!(
                h,
                "<p>XFOIL at each station's Reynolds and Mach numbers at {:.0} rpm, {} m/s; sections: {}.</p>",
                b.rpm,
                b.v,
                esc(&b.airfoil)
            );
            h.push_str("<table><tr><th>r [mm]</th><th>chord [mm]</th><th>Re</th><th>Mach</th><th>α [deg]</th><th>CL0</th><th>CL_a [/rad]</th><th>CLmax</th><th>CD0</th><th>CD2u</th><th>problem</th></tr>\n");
            for s in &b.stations {
                let c = s.fit.as_ref().map(|f| f.coeffs.to_array());
                let cell = |k: usize, p: usize| c.map_or("–".into(), |v| format!("{:.*}", p, v[k]));
                let _ = writeln!(
                    h,
                    "<tr><td>{:.1}</td><td>{:.1}</td><td>{:.0}</td><td>{:.3}</td><td>{:.1}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                    1000.0 * s.r,
                    1000.0 * s.chord,
                    s.re,
                    s.mach,
                    s.alpha_deg,
                    cell(0, 3),
                    cell(1, 2),
                    cell(3, 2),
                    cell(4, 4),
                    cell(5, 4),
                    esc(s.problem.as_deref().unwrap_or(""))
                );
            }
            h.push_str("</table>\n");
        }
        None => h.push_str("<p>The prop file's own QPROP coefficients (no XFOIL stage in this case).</p>\n"),
    }
    h.push_str("</section>\n");

    // Prediction.
    h.push_str("<section id=\"prediction\"><h2>Prediction</h2>\n");
    h.push_str(&propbet_plot::svg_inline(&sweep_figure(&run.sweep)).map_err(|e| anyhow::anyhow!("{e}"))?);
    h.push_str("</section>\n");

    for (id, body) in bodies {
        let _ = writeln!(h, "<section id=\"{id}\">\n{body}\n</section>");
    }
    h.push_str("</body></html>\n");
    Ok(h)
}

/// CT, CP and efficiency against J, one line per RPM.
fn sweep_figure(points: &[PointResult]) -> Figure {
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
