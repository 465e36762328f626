//! `propbet polar` (polars of one section at given Reynolds numbers) and `propbet polars`
//! (polars of every station of a blade at its operating Reynolds and Mach numbers, reduced to
//! a QPROP prop file): computed, written, every fault and fit told.

use std::path::{Path, PathBuf};

use propbet_pipeline::stages::{self, Polars, PolarsInput, SectionSpec};
use propbet_plot::Figure;
use propbet_settings::spec::PolarsSpec;
use propbet_settings::values::parse_fraction;
use propbet_settings::values::parse_list;

use crate::console::{emit, Console};
use crate::polar::{Polar, QpropFit};
use crate::qprop::write_prop;
use crate::CommandResult as Result;

/// What `propbet polar` is asked: a section, its Reynolds and Mach numbers, how XFOIL runs,
/// and where its table, fit and figure go.
#[derive(Debug, Clone)]
pub struct PolarCommand {
    /// Coordinate file (Selig or Lednicer), or a NACA 4-digit name.
    pub airfoil: String,
    /// The thickness ratio the section is scaled to (`0.06` or `6%`).
    pub thickness: Option<String>,
    /// Reynolds numbers: a list or a range, as text.
    pub re: String,
    /// Mach number.
    pub mach: f64,
    /// How XFOIL is asked.
    pub xfoil: crate::SectionRequest,
    /// The polar table (CSV; None: standard output).
    pub out: Option<PathBuf>,
    /// The figure of the polars and their QPROP fit.
    pub plot: Option<PathBuf>,
    /// The QPROP fit at each Reynolds number, as JSON.
    pub fit_out: Option<PathBuf>,
}

/// Runs `propbet polar`; false when some polar failed (the others are written).
pub fn polar(c: &PolarCommand, console: &dyn Console) -> Result<bool> {
    let outputs: Vec<&Path> = [&c.out, &c.fit_out, &c.plot]
        .into_iter()
        .flatten()
        .map(|p| p.as_path())
        .collect();
    let inputs: Vec<&Path> = Some(Path::new(&c.airfoil)).filter(|p| p.exists()).into_iter().collect();
    crate::files::refuse_outputs_over_inputs(&outputs, &inputs)?;
    let t = c.thickness.as_deref().map(parse_fraction).transpose()?;
    let (foil, notes) = stages::load_airfoil(&c.airfoil, t)?;
    for n in notes {
        console.err(&format!("propbet: {n}"));
    }
    let spec = SectionSpec {
        res: parse_list("--re", &c.re)?,
        mach: c.mach,
        xfoil: c.xfoil.spec(crate::settings::AIRFOIL_NCRIT.default, None)?,
    };
    let process = spec.xfoil.process.clone();
    let section = stages::section(&spec, &foil, &|d, t| console.progress(&process, d, t));
    console.progress_done();
    let section = section?;
    for (re, r) in &section.runs {
        match r {
            Ok(p) => {
                report_failures(&format!("Re {re:.0}"), p, console);
                // An XFOIL that was killed (hung) or crashed leaves a polar with holes: said,
                // and the exit code is 1.
                if p.points.is_empty() {
                    console.err(&format!(
                        "propbet: Re {re:.0}: XFOIL converged at no angle: the polar is empty"
                    ));
                }
            }
            Err(e) => console.err(&format!("propbet: error: {e}")),
        }
    }
    if let Some(e) = &section.cache_error {
        console.err(&format!(
            "propbet: warning: {e}: the cache could not store the polars XFOIL computed; they were used, and the next run computes them again"
        ));
    }
    section.check()?;
    for (re, f) in &section.fits {
        match f {
            Ok(f) => console.err(&fit_summary(*re, f)),
            Err(e) => console.err(&format!("propbet: Re {re:.0}: no QPROP fit: {e}")),
        }
    }
    emit(console, c.out.as_deref(), &[section.csv().as_bytes()], &inputs)?;
    let fits = section.fitted();
    if let Some(path) = &c.fit_out {
        let json = serde_json::to_vec_pretty(&fits)?;
        crate::files::write_atomic(path, &[json.as_slice()], &inputs)?;
    }
    if let Some(path) = &c.plot {
        let fig = Figure {
            panels: propbet_report::polar::panels(&foil.name, &section.polars(), &fits),
            columns: 2,
            width: 1400,
            height: 560,
        };
        crate::files::write_figure(path, &fig, &inputs)?;
    }
    Ok(section.clean())
}

/// The files `polars` reads: the geometry, the airfoil file (not a NACA name) and the scanned
/// sections' directory.
fn polars_inputs(spec: &PolarsSpec) -> Vec<&Path> {
    let mut inputs: Vec<&Path> = vec![spec.geometry.as_path()];
    if let Some(foil) = spec.airfoil.as_deref().map(Path::new).filter(|f| f.exists()) {
        inputs.push(foil);
    }
    inputs.extend(spec.station_airfoils.as_deref());
    inputs
}

fn report_failures(what: &str, p: &Polar, console: &dyn Console) {
    if !p.unconverged_deg.is_empty() {
        let list: Vec<String> = p.unconverged_deg.iter().map(|a| format!("{a}")).collect();
        console.err(&format!(
            "propbet: {what}: XFOIL did not converge at alpha {} deg",
            list.join(", ")
        ));
    }
    if let Some(text) = p.hysteresis_text() {
        console.err(&format!("propbet: {what}: {text}"));
    }
    for f in &p.faults {
        console.err(&format!("propbet: {what}: {f}"));
    }
    if let Some(why) = &p.not_filled {
        console.err(&format!("propbet: {what}: {why}: XFOIL's polar kept with its gaps"));
    }
}

fn fit_summary(re: f64, f: &QpropFit) -> String {
    let c = &f.coeffs;
    let mut s = format!(
        "Re {re:.0}: CL0 {:.4} CL_a {:.4}/rad CLmin {:.3} CLmax {:.3} CD0 {:.5} CD2u {:.5} CD2l {:.5} CLCD0 {:.3} REref {:.0} REexp {:.3}\n  linear range {:.1}..{:.1} deg ({} points): cl error <= {:.3}, cd error <= {:.1} %",
        c.cl0,
        c.cl_a,
        c.cl_min,
        c.cl_max,
        c.cd0,
        c.cd2u,
        c.cd2l,
        c.clcd0,
        c.re_ref,
        c.re_exp,
        f.linear_range_deg[0],
        f.linear_range_deg[1],
        f.linear_points,
        f.cl_max_error,
        f.cd_max_rel_error * 100.0
    );
    for u in &f.unfit {
        s.push_str(&format!("\n  UNFIT: {u}"));
    }
    for n in &f.notes {
        s.push_str(&format!("\n  note: {n}"));
    }
    s
}

/// Runs a polars stage: its files written, every station's fit told; false when a station
/// has no fit (its coefficients are kept from the geometry file, and it is told).
pub fn polars(spec: &PolarsSpec, console: &dyn Console) -> Result<bool> {
    let outputs: Vec<&Path> = std::iter::once(spec.out_prop.as_path())
        .chain(spec.out_polars.as_deref())
        .collect();
    crate::files::refuse_outputs_over_inputs(&outputs, &polars_inputs(spec))?;
    let input = stages::polars_input(spec)?;
    for w in &input.geometry.warnings {
        console.err(&format!("propbet: warning: {w}"));
    }
    let engine = stages::polar_engine(&spec.xfoil.process)?;
    let p = stages::polars(spec, &input, &engine, &|d, t| {
        console.progress(&spec.xfoil.process, d, t)
    });
    console.progress_done();
    let p = p?;
    print_polars(spec, &input, &p, console);
    write_polars(spec, &p)?;
    Ok(p.clean())
}

/// Every station's polar faults and fit.
pub fn print_polars(spec: &PolarsSpec, input: &PolarsInput, p: &Polars, console: &dyn Console) {
    for n in &input.notes {
        console.err(&format!("propbet: {n}"));
    }
    for (i, s) in p.blade.stations.iter().enumerate() {
        for pol in &s.polars {
            report_failures(&format!("station r = {:.4} m, Re {:.0}", s.r, pol.re), pol, console);
        }
        let line = match &s.fit {
            Some(f) => format!(
                "station {} (r = {:.4} m, alpha {:.1} deg): {}",
                i + 1,
                s.r,
                s.alpha_deg,
                fit_summary(s.re, f)
            ),
            None => format!(
                "propbet: station {} (r = {:.4} m, Re {:.0}-{:.0}, alpha {:.1}..{:.1} deg): {}; fallback: {}, and the exported prop file keeps the coefficients of {} there",
                i + 1,
                s.r,
                s.re_range[0],
                s.re_range[1],
                s.alpha_range_deg[0],
                s.alpha_range_deg[1],
                s.problem.as_deref().unwrap_or("no fit"),
                if s.polars.is_empty() {
                    "the tables use the neighbouring stations' polars"
                } else {
                    "the tables use this station's polars as XFOIL gave them"
                },
                spec.geometry.display()
            ),
        };
        console.err_sentence(&line, "", "  ");
    }
    if let Some(e) = &p.export {
        console.err(&e.sentence());
    }
    if let Some(w) = &p.cache_warning {
        console.err(&format!("propbet: warning: {w}"));
    }
}

/// Writes the polars stage's outputs: the fitted prop file and the polars (JSON).
pub fn write_polars(spec: &PolarsSpec, p: &Polars) -> Result<()> {
    let inputs = polars_inputs(spec);
    crate::files::write_atomic(&spec.out_prop, &[write_prop(&p.prop.file).as_bytes()], &inputs)?;
    if let Some(path) = &spec.out_polars {
        let json = serde_json::to_vec(&p.blade)?;
        crate::files::write_atomic(path, &[json.as_slice()], &inputs)?;
    }
    Ok(())
}
