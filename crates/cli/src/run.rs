//! `propbet run CASE_DIR`: the main job. A case directory's `case.toml` names a scan (or a
//! prop file), the sections, the operating points, the measurements and the air; the run
//! chains scan → XFOIL polars at each station's Reynolds number → BEMT sweeps → comparison →
//! diagnosis, each stage as the documented command it is equivalent to, and writes one HTML
//! report that holds them all.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::{Args, Parser};
use propbet_compare::report::esc;
use propbet_plot::{Figure, Mark, Panel, Series};
use serde::Deserialize;

use crate::output::{write_atomic, CsvTable};
use crate::polar::XfoilProcess;

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

/// `case.toml`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// What the case is.
    pub name: String,
    /// A sentence or two on where it comes from.
    #[serde(default)]
    pub description: String,
    /// Blade count, checked against the scan when given.
    pub blades: Option<usize>,
    /// The blade.
    pub geometry: GeometrySpec,
    /// XFOIL polars (without: the prop file's coefficients are used).
    pub polars: Option<PolarSpec>,
    /// Prediction sweeps.
    pub sweep: SweepSpec,
    /// Measurements (without: no comparison, no diagnosis).
    pub measured: Option<MeasuredSpec>,
    /// Air of the measurements and sweeps.
    #[serde(default)]
    pub atmosphere: AtmosphereSpec,
}

/// `[geometry]`: a scan or a prop file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GeometrySpec {
    /// A scan (STL, PLY, points3D.txt, XYZ) for `propbet scan`.
    pub scan: Option<String>,
    /// Or a QPROP prop file.
    pub prop: Option<String>,
    /// Length unit of the scan or prop file.
    pub units: Option<String>,
    /// Stations as r/R (`propbet scan --stations`).
    pub stations: Option<String>,
    /// A UIUC-style table (r/R c/R beta) to set the scan against.
    pub reference: Option<String>,
    /// Further `propbet scan` flags, for example `["--crop=-80,-200,-200,200,200,200"]`.
    #[serde(default)]
    pub scan_args: Vec<String>,
}

/// `[polars]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PolarSpec {
    /// `scan`: each station's section as the scan fitted it (the airfoil where the scan gave
    /// none); `airfoil`: the airfoil at every station.
    #[serde(default = "default_sections")]
    pub sections: String,
    /// Coordinate file (relative to the case) or a NACA 4-digit name: the airfoil hint.
    pub airfoil: String,
    /// Scale the airfoil to this thickness ratio.
    pub thickness: Option<String>,
    /// Operating point whose Reynolds numbers the polars are computed at [rpm].
    pub rpm: f64,
    /// Its axial speed [m/s].
    #[serde(default)]
    pub v: f64,
    /// Transition amplification ratio.
    pub ncrit: Option<f64>,
    /// Angles of attack (`propbet polars --alpha`).
    pub alpha: Option<String>,
    /// Multiples of each station's Re for REexp.
    pub re_factors: Option<String>,
}

fn default_sections() -> String {
    "scan".into()
}

/// `[sweep]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    /// Rotation speeds [rpm]: a list or a range.
    pub rpm: String,
    /// Advance ratios: a list or a range.
    pub j: String,
}

/// `[measured]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeasuredSpec {
    /// Files relative to the case directory.
    pub files: Vec<String>,
    /// Motor poles (electrical RPM of thrust-stand logs).
    pub poles: Option<u32>,
    /// `optical` or `electrical`.
    pub rpm_source: Option<String>,
    /// Column map of generic CSV files.
    pub columns: Option<String>,
    /// Diagnosis: folds and ladder steps.
    pub folds: Option<usize>,
    /// Most effects the ladder adds.
    pub max_steps: Option<usize>,
}

/// `[atmosphere]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AtmosphereSpec {
    /// `T,P,RH` as `--atmosphere` takes it (overrides what the logs say).
    pub air: Option<String>,
    /// Air density [kg/m^3] (overrides everything).
    pub rho: Option<f64>,
}

/// Reads and checks `case.toml`.
pub fn read_case(dir: &Path) -> Result<Case> {
    let path = dir.join("case.toml");
    let text = std::fs::read_to_string(&path).with_context(|| format!("{}: cannot read", path.display()))?;
    let case: Case = toml::from_str(&text).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let g = &case.geometry;
    if g.scan.is_some() == g.prop.is_some() {
        bail!("{}: [geometry] needs exactly one of `scan` and `prop`", path.display());
    }
    if let Some(p) = &case.polars {
        if p.sections != "scan" && p.sections != "airfoil" {
            bail!(
                "{}: [polars] sections = {:?}: `scan` or `airfoil`",
                path.display(),
                p.sections
            );
        }
        if p.sections == "scan" && g.scan.is_none() {
            bail!(
                "{}: [polars] sections = \"scan\" needs a [geometry] scan",
                path.display()
            );
        }
        if !(p.rpm.is_finite() && p.rpm > 0.0) {
            bail!("{}: [polars] rpm = {}: must be positive", path.display(), p.rpm);
        }
    }
    // Every file the case names must be there before anything runs.
    let named = [g.scan.as_ref(), g.prop.as_ref(), g.reference.as_ref()]
        .into_iter()
        .flatten()
        .chain(
            case.measured
                .iter()
                .flat_map(|m| m.files.iter().chain(m.columns.as_ref())),
        );
    for f in named {
        if !dir.join(f).is_file() {
            bail!("{}: names {f}, which is not in {}", path.display(), dir.display());
        }
    }
    Ok(case)
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

/// One stage: the command it is equivalent to, how long it took, whether it ran clean.
pub(crate) struct Stage {
    name: &'static str,
    argv: Vec<String>,
    seconds: f64,
    /// Ran without reported problems.
    pub(crate) clean: bool,
}

/// Runs one `propbet` command line in this process.
pub(crate) fn stage(name: &'static str, argv: Vec<String>, n: usize, total: usize) -> Result<Stage> {
    eprintln!("propbet [{n}/{total}] {name}: propbet {}", shell_words(&argv));
    let t0 = Instant::now();
    let cli = crate::Cli::try_parse_from(std::iter::once("propbet".to_string()).chain(argv.iter().cloned()))
        .map_err(|e| anyhow::anyhow!("{name}: {e}"))?;
    let clean = crate::dispatch(cli.command).with_context(|| format!("{name} stage"))?;
    let seconds = t0.elapsed().as_secs_f64();
    eprintln!(
        "propbet [{n}/{total}] {name}: {seconds:.1} s{}",
        if clean { "" } else { " (with reported problems)" }
    );
    Ok(Stage {
        name,
        argv,
        seconds,
        clean,
    })
}

fn shell_words(argv: &[String]) -> String {
    argv.iter()
        .map(|a| {
            if a.is_empty() || a.contains(|c: char| c.is_whitespace() || "'\"$`\\*?;&|<>()".contains(c)) {
                format!("'{}'", a.replace('\'', "'\\''"))
            } else {
                a.clone()
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

fn path_str(p: &Path) -> String {
    p.display().to_string()
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
    let case = read_case(&dir)?;
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
    if let (Ok(o), Ok(d)) = (out.canonicalize(), dir.canonicalize()) {
        if o == d || d.starts_with(&o) {
            bail!(
                "{}: the output directory would hold the case's own files",
                out.display()
            );
        }
    }
    std::fs::create_dir_all(&out).with_context(|| format!("{}: cannot create", out.display()))?;
    let f = |rel: &str| path_str(&dir.join(rel));
    let o = |rel: &str| path_str(&out.join(rel));
    let g = &case.geometry;
    let total = 2
        + usize::from(g.scan.is_some())
        + usize::from(case.polars.is_some())
        + 2 * usize::from(case.measured.is_some());
    let mut n = 0;
    let mut stages = Vec::new();
    let mut next = || {
        n += 1;
        n
    };

    // 1. Geometry.
    let mut prop = match (&g.scan, &g.prop) {
        (Some(scan), _) => {
            let mut argv = vec![
                "scan".to_string(),
                f(scan),
                "-o".into(),
                o("scan"),
                "--name".into(),
                case.name.clone(),
            ];
            if let Some(u) = &g.units {
                argv.extend(["--units".into(), u.clone()]);
            }
            if let Some(s) = &g.stations {
                argv.extend(["--stations".into(), s.clone()]);
            }
            if let Some(r) = &g.reference {
                argv.extend(["--reference".into(), f(r)]);
            }
            argv.extend(g.scan_args.iter().cloned());
            let s = stage("scan", argv, next(), total)?;
            stages.push(s);
            o("scan/prop.qprop")
        }
        (None, Some(p)) => f(p),
        (None, None) => unreachable!("read_case checks the geometry"),
    };
    let units_flag: Vec<String> = match (&g.prop, &g.units) {
        (Some(_), Some(u)) => vec!["--units".into(), u.clone()],
        _ => Vec::new(),
    };
    let scan_summary: Option<serde_json::Value> = if g.scan.is_some() {
        let text = std::fs::read_to_string(out.join("scan/scan.json")).context("scan.json")?;
        let v: serde_json::Value = serde_json::from_str(&text)?;
        if let (Some(want), Some(got)) = (case.blades, v["blades"].as_u64()) {
            if want as u64 != got {
                bail!(
                    "{}: case.toml says {want} blades, the scan found {got}",
                    dir.join("case.toml").display()
                );
            }
        }
        Some(v)
    } else {
        None
    };

    // 2. Polars.
    let xfoil_flags = a.xfoil.flags();
    if let Some(p) = &case.polars {
        let airfoil = if naca_name(&p.airfoil) {
            p.airfoil.clone()
        } else {
            f(&p.airfoil)
        };
        let mut argv = vec!["polars".into(), "--geometry".into(), prop.clone()];
        argv.extend(units_flag.iter().cloned());
        argv.extend(["--airfoil".into(), airfoil]);
        if let Some(t) = &p.thickness {
            argv.extend(["--thickness".into(), t.clone()]);
        }
        if p.sections == "scan" {
            argv.extend(["--station-airfoils".into(), o("scan/airfoils")]);
        }
        argv.extend(["--rpm".into(), p.rpm.to_string(), "--v".into(), p.v.to_string()]);
        if let Some(x) = p.ncrit {
            argv.extend(["--ncrit".into(), x.to_string()]);
        }
        if let Some(x) = &p.alpha {
            argv.push(format!("--alpha={x}"));
        }
        if let Some(x) = &p.re_factors {
            argv.extend(["--re-factors".into(), x.clone()]);
        }
        argv.extend(xfoil_flags.iter().cloned());
        argv.extend([
            "--out-prop".into(),
            o("polars/prop.qprop"),
            "--out-polars".into(),
            o("polars/polars.json"),
        ]);
        std::fs::create_dir_all(out.join("polars"))?;
        stages.push(stage("polars", argv, next(), total)?);
        prop = o("polars/prop.qprop");
    }
    // The fitted prop file is in metres; a case's own prop file keeps its units flag.
    let model_units = if case.polars.is_some() {
        Vec::new()
    } else {
        units_flag.clone()
    };

    // 3. Sweeps.
    std::fs::create_dir_all(out.join("predict"))?;
    let mut argv = vec!["predict".into(), "--prop".into(), prop.clone()];
    argv.extend(model_units.iter().cloned());
    argv.extend([format!("--rpm={}", case.sweep.rpm), format!("--j={}", case.sweep.j)]);
    argv.extend(air_flags_predict(&case.atmosphere)?);
    argv.extend(["--out".into(), o("predict/sweep.csv")]);
    stages.push(stage("predict", argv, next(), total)?);

    // 4-5. Comparison and diagnosis.
    if let Some(m) = &case.measured {
        let mut data = vec!["--measured".to_string()];
        data.extend(m.files.iter().map(|x| f(x)));
        if let Some(p) = m.poles {
            data.extend(["--poles".into(), p.to_string()]);
        }
        if let Some(s) = &m.rpm_source {
            data.extend(["--rpm-source".into(), s.clone()]);
        }
        if let Some(c) = &m.columns {
            data.extend(["--columns".into(), f(c)]);
        }
        if let Some(air) = &case.atmosphere.air {
            data.extend(["--atmosphere".into(), air.clone()]);
        }
        if let Some(rho) = case.atmosphere.rho {
            data.extend(["--rho".into(), rho.to_string()]);
        }
        let mut argv = vec!["compare".into(), "--prop".into(), prop.clone()];
        argv.extend(model_units.iter().cloned());
        argv.extend(data.iter().cloned());
        argv.extend(["--out".into(), o("compare")]);
        stages.push(stage("compare", argv, next(), total)?);
        let mut argv = vec!["diagnose".into(), "--prop".into(), prop.clone()];
        argv.extend(model_units.iter().cloned());
        argv.extend(data);
        if let Some(k) = m.folds {
            argv.extend(["--folds".into(), k.to_string()]);
        }
        if let Some(k) = m.max_steps {
            argv.extend(["--max-steps".into(), k.to_string()]);
        }
        argv.extend(["--out".into(), o("diagnose")]);
        stages.push(stage("diagnose", argv, next(), total)?);
    }

    // 6. The report.
    let t0 = Instant::now();
    let html = report(&case, &dir, &out, &stages, scan_summary.as_ref())?;
    let report_path = out.join("report.html");
    write_atomic(&report_path, &[html.as_bytes()], &[dir.join("case.toml").as_path()])?;
    let n_report = next();
    eprintln!(
        "propbet [{n_report}/{total}] report: {:.1} s",
        t0.elapsed().as_secs_f64()
    );
    println!(
        "{}: {} stages in {:.1} s; report: {}",
        case.name,
        stages.len() + 1,
        t_all.elapsed().as_secs_f64(),
        report_path.display()
    );
    Ok(stages.iter().all(|s| s.clean))
}

fn naca_name(s: &str) -> bool {
    propbet_polar::naca4_from_name(s).is_some()
}

/// `[atmosphere] air = "T,P,RH"` as `propbet predict`'s air flags.
fn air_flags_predict(a: &AtmosphereSpec) -> Result<Vec<String>> {
    let mut v = Vec::new();
    if let Some(air) = &a.air {
        let [t, p, rh] = crate::compare::split_atmosphere(air).context("[atmosphere] air")?;
        v.extend([format!("--temp={t}"), "--pressure".into(), p, "--humidity".into(), rh]);
    }
    if let Some(rho) = a.rho {
        v.extend(["--rho".into(), rho.to_string()]);
    }
    Ok(v)
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

/// An SVG file's markup without its XML declaration, for inlining.
fn inline_svg(path: &Path) -> Option<String> {
    let s = std::fs::read_to_string(path).ok()?;
    let start = s.find("<svg")?;
    Some(s[start..].to_string())
}

fn report(case: &Case, dir: &Path, out: &Path, stages: &[Stage], scan: Option<&serde_json::Value>) -> Result<String> {
    let font = propbet_plot::font_face_css();
    let mut styles = vec![font.clone()];
    let mut bodies = Vec::new();
    for (id, file) in [("compare", "compare/report.html"), ("diagnose", "diagnose/report.html")] {
        if let Ok(page) = std::fs::read_to_string(out.join(file)) {
            let (style, body) = parts_of(&page);
            styles.push(style.replace(&font, ""));
            bodies.push((id, body));
        }
    }
    let mut h = String::with_capacity(4_000_000);
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>propbet run: {}</title>\n<style>{}\n\
         body{{max-width:1200px;margin:auto;font-family:sans-serif}} nav a{{margin-right:1em}} \
         section{{border-top:2px solid #888;margin-top:2em}} svg{{max-width:100%;height:auto}} \
         svg text{{font-family:{},sans-serif}}</style></head><body>\n",
        esc(&case.name),
        styles.join("\n"),
        propbet_plot::FONT_FAMILY
    );
    let _ = writeln!(h, "<h1>{}</h1>", esc(&case.name));
    if !case.description.is_empty() {
        let _ = writeln!(h, "<p>{}</p>", esc(&case.description));
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
    for s in stages {
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{:.1}</td><td>{}</td><td><code>propbet {}</code></td></tr>",
            s.name,
            s.seconds,
            if s.clean { "ok" } else { "problems reported (see below)" },
            esc(&shell_words(&s.argv))
        );
    }
    let _ = writeln!(
        h,
        "</table>\n<p class=\"note\">case directory <code>{}</code>; outputs of each stage beside this report.</p>",
        esc(&dir.display().to_string())
    );

    // Geometry.
    h.push_str("<section id=\"geometry\"><h2>Geometry</h2>\n");
    match scan {
        Some(v) => {
            let _ = writeln!(
                h,
                "<p>{} blades, tip radius {:.2} mm, hub radius {}, blades from {:.2} mm; {} stations measured, {} failed.</p>",
                v["blades"],
                v["tip_radius_mm"].as_f64().unwrap_or(f64::NAN),
                v["hub_radius_mm"].as_f64().map_or("none".into(), |x| format!("{x:.2} mm")),
                v["root_radius_mm"].as_f64().unwrap_or(f64::NAN),
                v["stations"].as_array().map_or(0, Vec::len),
                v["failed"].as_array().map_or(0, Vec::len),
            );
            if let Some(notes) = v["notes"].as_array() {
                h.push_str("<ul>");
                for n in notes {
                    let _ = write!(h, "<li>{}</li>", esc(n.as_str().unwrap_or_default()));
                }
                h.push_str("</ul>\n");
            }
            if let Some(failed) = v["failed"].as_array() {
                for f in failed {
                    let _ = writeln!(
                        h,
                        "<p class=\"note\">r/R {:.3}: {}</p>",
                        f["r_r"].as_f64().unwrap_or(f64::NAN),
                        esc(f["reason"].as_str().unwrap_or_default())
                    );
                }
            }
            h.push_str("<h3>Along the radius (with the reference table where the case has one)</h3>\n");
            if let Some(svg) = inline_svg(&out.join("scan/plots/distributions.svg")) {
                h.push_str(&svg);
            }
            h.push_str("<h3>The sections: scan points and fits</h3>\n");
            if let Some(svg) = inline_svg(&out.join("scan/plots/sections.svg")) {
                h.push_str(&svg);
            }
        }
        None => {
            let _ = writeln!(
                h,
                "<p>From the prop file <code>{}</code> (no scan in this case).</p>",
                esc(case.geometry.prop.as_deref().unwrap_or_default())
            );
        }
    }
    h.push_str("</section>\n");

    // Polars.
    h.push_str("<section id=\"polars\"><h2>Section polars</h2>\n");
    match std::fs::read(out.join("polars/polars.json")) {
        Ok(bytes) => {
            let b: propbet_polar::BladePolars = serde_json::from_slice(&bytes).context("polars.json")?;
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
        Err(_) => h.push_str("<p>The prop file's own QPROP coefficients (no XFOIL stage in this case).</p>\n"),
    }
    h.push_str("</section>\n");

    // Prediction.
    h.push_str("<section id=\"prediction\"><h2>Prediction</h2>\n");
    let sweep = std::fs::read_to_string(out.join("predict/sweep.csv")).context("sweep.csv")?;
    h.push_str(&propbet_plot::svg_inline(&sweep_figure(&sweep)?).map_err(|e| anyhow::anyhow!("{e}"))?);
    h.push_str("</section>\n");

    for (id, body) in bodies {
        let _ = writeln!(h, "<section id=\"{id}\">\n{body}\n</section>");
    }
    h.push_str("</body></html>\n");
    Ok(h)
}

/// CT, CP and efficiency against J, one line per RPM, from `propbet predict`'s CSV.
fn sweep_figure(csv: &str) -> Result<Figure> {
    let t = CsvTable::parse(csv, "sweep.csv");
    let (ci, cj, cct, ccp, ceta) = (t.col("rpm")?, t.col("j")?, t.col("ct")?, t.col("cp")?, t.col("eta")?);
    // Per RPM: (CT, CP, efficiency) against J.
    type Curves = [Vec<(f64, f64)>; 3];
    let mut by_rpm: Vec<(String, Curves)> = Vec::new();
    for v in &t.rows {
        let num = |k: usize| CsvTable::num(v, k);
        let rpm = format!("{:.0} rpm", num(ci));
        if by_rpm.last().is_none_or(|b| b.0 != rpm) {
            by_rpm.push((rpm.clone(), Default::default()));
        }
        let e = &mut by_rpm.last_mut().expect("pushed").1;
        let j = num(cj);
        e[0].push((j, num(cct)));
        e[1].push((j, num(ccp)));
        if num(cct) > 0.0 {
            e[2].push((j, num(ceta)));
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
    Ok(Figure {
        panels: vec![
            panel(0, "Thrust coefficient CT = T/(ρn²D⁴)", "CT"),
            panel(1, "Power coefficient CP = P/(ρn³D⁵)", "CP"),
            panel(2, "Efficiency η = J CT/CP (where CT > 0)", "η"),
        ],
        columns: 3,
        width: 1200,
        height: 400,
    })
}
