//! `propbet polar` (polars of one section) and `propbet polars` (polars of every station of a
//! blade at its operating Reynolds and Mach numbers, reduced to a QPROP prop file).

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::Args;
use propbet_api::polar::{Airfoil, Polar, QpropFit};
use propbet_api::qprop::write_prop;
use propbet_api::settings::values::parse_list;
use propbet_pipeline::case::parse_fraction;
use propbet_pipeline::spec::{PolarsSpec, XfoilSpec};
use propbet_pipeline::stages::{self, Polars, PolarsInput, SectionSpec};
use propbet_plot::Figure;

pub use crate::engine::{Bar, DesignArgs, XfoilProcess};
use crate::output::emit;
use crate::predict::FluidArgs;

/// How XFOIL runs, and the cache.
#[derive(Debug, Args)]
pub struct XfoilArgs {
    /// Executable, cache, progress.
    #[command(flatten)]
    pub process: XfoilProcess,
    #[arg(long = propbet_api::settings::NCRIT.flag, help = propbet_api::settings::NCRIT.help)]
    pub ncrit: Option<f64>,
    #[arg(long = propbet_api::settings::TRIP.flag, help = propbet_api::settings::TRIP.help, value_name = "X/C|free")]
    pub trip: Option<String>,
    #[arg(long = propbet_api::settings::ALPHA.flag, help = propbet_api::settings::ALPHA.help, default_value = propbet_api::settings::ALPHA.default, allow_hyphen_values = true)]
    pub alpha: String,
    /// XFOIL panel nodes (default: XFOIL's 160 for `polar`, 120 for `polars`).
    #[arg(long)]
    pub panels: Option<u32>,
    /// XFOIL's viscous iteration limit per angle.
    #[arg(long, default_value_t = propbet_api::xfoil::DEFAULT_MAX_ITER)]
    pub iter: u32,
}

impl XfoilArgs {
    /// The spec (flags in SI); `default_ncrit` and `default_trip` when `--ncrit` and `--trip`
    /// are not given.
    pub fn spec(&self, default_ncrit: f64, default_trip: Option<f64>) -> Result<XfoilSpec> {
        Ok(self.request().spec(default_ncrit, default_trip)?)
    }

    /// What the flags ask for.
    pub fn request(&self) -> propbet_api::SectionRequest {
        propbet_api::SectionRequest {
            process: self.process.request(),
            ncrit: self.ncrit,
            trip: self.trip.clone(),
            alpha: Some(propbet_api::Values::Text(self.alpha.clone())),
            panels: self.panels,
            iter: Some(self.iter),
        }
    }
}

/// The section to analyse.
#[derive(Debug, Args)]
pub struct AirfoilArgs {
    /// Coordinate file (Selig or Lednicer), or a NACA 4-digit name such as `naca4412`.
    #[arg(long)]
    pub airfoil: String,
    /// Scale the section to this thickness ratio t/c (0.06 or 6%), keeping its camber line.
    #[arg(long)]
    pub thickness: Option<String>,
}

impl AirfoilArgs {
    /// The section, normalised (and scaled), printing what was repaired in the file.
    pub fn load(&self) -> Result<Airfoil> {
        let t = self.thickness.as_deref().map(parse_fraction).transpose()?;
        let (foil, notes) = stages::load_airfoil(&self.airfoil, t)?;
        for n in notes {
            eprintln!("propbet: {n}");
        }
        Ok(foil)
    }
}

/// Arguments of `propbet polar`.
#[derive(Debug, Args)]
pub struct PolarArgs {
    /// The section.
    #[command(flatten)]
    pub section: AirfoilArgs,
    /// Reynolds numbers: a list (5e4,1e5) or a range.
    #[arg(long)]
    pub re: String,
    /// Mach number.
    #[arg(long, default_value_t = 0.0)]
    pub mach: f64,
    /// XFOIL settings.
    #[command(flatten)]
    pub xfoil: XfoilArgs,
    /// Polar table (CSV; default: standard output).
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Figure of the polars and the QPROP fit (.svg or .png).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// The QPROP fit at each Re, with residuals, as JSON.
    #[arg(long)]
    pub fit_out: Option<PathBuf>,
}

/// Runs `propbet polar`; false when some polar failed (the others are written).
pub fn run_polar(args: &PolarArgs) -> Result<bool> {
    let outputs: Vec<&Path> = [&args.out, &args.fit_out, &args.plot]
        .into_iter()
        .flatten()
        .map(|p| p.as_path())
        .collect();
    propbet_api::files::refuse_outputs_over_inputs(&outputs, &input_paths(&args.section))?;
    let foil = args.section.load()?;
    let spec = SectionSpec {
        res: parse_list("--re", &args.re)?,
        mach: args.mach,
        xfoil: args.xfoil.spec(propbet_api::settings::AIRFOIL_NCRIT.default, None)?,
    };
    let bar = Bar::new(spec.xfoil.process.quiet, spec.xfoil.process.engine);
    let section = stages::section(&spec, &foil, &|d, t| bar.tick(d, t))?;
    for (re, r) in &section.runs {
        match r {
            Ok(p) => {
                report_failures(&format!("Re {re:.0}"), p);
                // An XFOIL that was killed (hung) or crashed leaves a polar with holes: said,
                // and the exit code is 1.
                if p.points.is_empty() {
                    eprintln!("propbet: Re {re:.0}: XFOIL converged at no angle: the polar is empty");
                }
            }
            Err(e) => eprintln!("propbet: error: {e}"),
        }
    }
    if let Some(e) = &section.cache_error {
        eprintln!(
            "propbet: warning: {e}: the cache could not store the polars XFOIL computed; they were used, and the next run computes them again"
        );
    }
    section.check()?;
    for (re, f) in &section.fits {
        match f {
            Ok(f) => eprintln!("{}", fit_summary(*re, f)),
            Err(e) => eprintln!("propbet: Re {re:.0}: no QPROP fit: {e}"),
        }
    }
    let inputs = input_paths(&args.section);
    emit(args.out.as_deref(), &[section.csv().as_bytes()], &inputs)?;
    let fits = section.fitted();
    if let Some(path) = &args.fit_out {
        let json = serde_json::to_vec_pretty(&fits)?;
        propbet_api::files::write_atomic(path, &[json.as_slice()], &inputs)?;
    }
    if let Some(path) = &args.plot {
        let fig = Figure {
            panels: propbet_report::polar::panels(&foil.name, &section.polars(), &fits),
            columns: 2,
            width: 1400,
            height: 560,
        };
        propbet_api::files::write_figure(path, &fig, &inputs)?;
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

fn input_paths(a: &AirfoilArgs) -> Vec<&Path> {
    let p = Path::new(&a.airfoil);
    if p.exists() {
        vec![p]
    } else {
        vec![]
    }
}

fn report_failures(what: &str, p: &Polar) {
    if !p.unconverged_deg.is_empty() {
        let list: Vec<String> = p.unconverged_deg.iter().map(|a| format!("{a}")).collect();
        eprintln!(
            "propbet: {what}: XFOIL did not converge at alpha {} deg",
            list.join(", ")
        );
    }
    if let Some(text) = p.hysteresis_text() {
        eprintln!("propbet: {what}: {text}");
    }
    for f in &p.faults {
        eprintln!("propbet: {what}: {f}");
    }
    if let Some(why) = &p.not_filled {
        eprintln!("propbet: {what}: {why}: XFOIL's polar kept with its gaps");
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

/// Arguments of `propbet polars`.
#[derive(Debug, Args)]
pub struct PolarsArgs {
    /// Blade geometry: a QPROP prop file (its radii, chords and twists are used; its
    /// coefficients only for the first estimate of each station's inflow), APC's design file
    /// (PE0: its blade and sections), a UIUC geometry table or a blade table (CSV).
    #[arg(long)]
    pub geometry: PathBuf,
    #[arg(long = propbet_api::settings::UNITS.flag, help = propbet_api::settings::UNITS.help)]
    pub units: Option<String>,
    /// The section used at every station (with --station-airfoils, at the stations without
    /// their own): a coordinate file (Selig or Lednicer), a NACA 4-digit name, APC12 or a name
    /// of propbet's library (e63, clarky, sd7037, ...), or airfoils blended along the blade
    /// (`E63@0.25,APC12@0.45`). Not needed for a PE0 file or a table naming its sections.
    #[arg(long)]
    pub airfoil: Option<String>,
    /// Scale the --airfoil section to this thickness ratio t/c (0.06 or 6%), keeping its
    /// camber line.
    #[arg(long, requires = "airfoil")]
    pub thickness: Option<String>,
    /// Per-station sections: a directory of `station_NN.dat` (NN = 00, 01, ... in the
    /// geometry's station order, as `propbet scan` writes them); a station without its file
    /// uses `--airfoil`, or without it the nearest station's section.
    #[arg(long)]
    pub station_airfoils: Option<PathBuf>,
    #[command(flatten)]
    pub design: DesignArgs,
    /// The operating points whose Reynolds numbers the polars cover (give the sweep's, or the
    /// measured range).
    #[command(flatten)]
    pub points: crate::predict::SweepArgs,
    /// Air properties.
    #[command(flatten)]
    pub air: FluidArgs,
    /// XFOIL settings.
    #[command(flatten)]
    pub xfoil: XfoilArgs,
    #[arg(long = propbet_api::settings::NCRIT_EFFECT.flag, help = propbet_api::settings::NCRIT_EFFECT.help, value_delimiter = ',')]
    pub ncrit_effect: Vec<f64>,
    /// QPROP prop file with the fitted per-station coefficients.
    #[arg(long)]
    pub out_prop: PathBuf,
    /// Every station's polars and fit (JSON), for `propbet predict --polars`.
    #[arg(long)]
    pub out_polars: Option<PathBuf>,
}

impl PolarsArgs {
    /// The stage's spec (flags in SI).
    pub fn spec(&self) -> Result<PolarsSpec> {
        let request = propbet_api::PolarsRequest {
            geometry: self.geometry.clone(),
            units: self.units.clone(),
            airfoil: self.airfoil.clone(),
            thickness: self.thickness.clone(),
            station_airfoils: self.station_airfoils.clone(),
            sections_from: self.design.sections_from.clone(),
            airfoils: self.design.airfoils.clone(),
            sweep: self.points.request(),
            air: self.air.request(),
            section: self.xfoil.request(),
            ncrit_effect: self.ncrit_effect.clone(),
            out_prop: self.out_prop.clone(),
            out_polars: self.out_polars.clone(),
        };
        Ok(request.spec()?)
    }
}

/// Runs `propbet polars`; false when a station has no fit (its coefficients are kept from the
/// geometry file, and it is reported).
pub fn run_polars(args: &PolarsArgs) -> Result<bool> {
    run_polars_spec(&args.spec()?)
}

/// Runs a polars stage: its files written, every station's fit printed.
pub fn run_polars_spec(spec: &PolarsSpec) -> Result<bool> {
    let outputs: Vec<&Path> = std::iter::once(spec.out_prop.as_path())
        .chain(spec.out_polars.as_deref())
        .collect();
    propbet_api::files::refuse_outputs_over_inputs(&outputs, &polars_inputs(spec))?;
    let input = stages::polars_input(spec)?;
    for w in &input.geometry.warnings {
        eprintln!("propbet: warning: {w}");
    }
    let engine = stages::polar_engine(&spec.xfoil.process)?;
    let bar = Bar::new(spec.xfoil.process.quiet, spec.xfoil.process.engine);
    let p = stages::polars(spec, &input, &engine, &|d, t| bar.tick(d, t))?;
    print_polars(spec, &input, &p);
    write_polars(spec, &p)?;
    Ok(p.clean())
}

/// Every station's polar faults and fit on the terminal.
pub fn print_polars(spec: &PolarsSpec, input: &PolarsInput, p: &Polars) {
    for n in &input.notes {
        eprintln!("propbet: {n}");
    }
    for (i, s) in p.blade.stations.iter().enumerate() {
        for pol in &s.polars {
            report_failures(&format!("station r = {:.4} m, Re {:.0}", s.r, pol.re), pol);
        }
        match &s.fit {
            Some(f) => eprintln!(
                "{}",
                crate::output::wrapped(
                    &format!(
                        "station {} (r = {:.4} m, alpha {:.1} deg): {}",
                        i + 1,
                        s.r,
                        s.alpha_deg,
                        fit_summary(s.re, f)
                    ),
                    "",
                    "  "
                )
            ),
            None => eprintln!(
                "{}",
                crate::output::wrapped(&format!(
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
                ), "", "  ")
            ),
        }
    }
    if let Some(e) = &p.export {
        eprintln!("{}", e.sentence());
    }
    if let Some(w) = &p.cache_warning {
        eprintln!("propbet: warning: {w}");
    }
}

/// Writes the polars stage's outputs: the fitted prop file and the polars (JSON).
pub fn write_polars(spec: &PolarsSpec, p: &Polars) -> Result<()> {
    let inputs = polars_inputs(spec);
    propbet_api::files::write_atomic(&spec.out_prop, &[write_prop(&p.prop.file).as_bytes()], &inputs)?;
    if let Some(path) = &spec.out_polars {
        let json = serde_json::to_vec(&p.blade)?;
        propbet_api::files::write_atomic(path, &[json.as_slice()], &inputs)?;
    }
    Ok(())
}
