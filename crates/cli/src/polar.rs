//! `propbet polar` (polars of one section) and `propbet polars` (polars of every station of a
//! blade at its operating Reynolds and Mach numbers, reduced to a QPROP prop file).

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use clap::Args;
use propbet_bemt::{OperatingPoint, Solver, SolverOptions};
use propbet_polar::{
    fit_qprop, naca4_from_name, Airfoil, AlphaWeights, BladePolars, Polar, PolarCache, PolarEngine, PolarJob, QpropFit,
    StationPolars,
};
use propbet_qprop::{write_prop, PropFile, RadiusReading};
use xfoil_runner::{find_xfoil, Xfoil, XfoilConfig};

use crate::output::emit;
use crate::predict::{load_prop, FluidArgs};
use crate::values::parse_list;
use propbet_plot::{Figure, Mark, Panel, Series};

/// The XFOIL executable, the polar cache and the progress bar (shared by every command that
/// runs XFOIL, and passed on by `run` and `validate` to their `polars` stages).
#[derive(Debug, Args)]
pub struct XfoilProcess {
    /// XFOIL executable (default: `xfoil` on PATH).
    #[arg(long)]
    pub xfoil: Option<PathBuf>,
    /// Polar cache directory (default: $PROPBET_CACHE_DIR, $XDG_CACHE_HOME/propbet/polars or
    /// ~/.cache/propbet/polars).
    #[arg(long, conflicts_with = "no_cache")]
    pub cache: Option<PathBuf>,
    /// Compute every polar afresh and store nothing.
    #[arg(long)]
    pub no_cache: bool,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

impl XfoilProcess {
    /// The same settings as command-line flags, for a stage's command.
    pub fn flags(&self) -> Vec<String> {
        let mut v = Vec::new();
        if let Some(x) = &self.xfoil {
            v.extend(["--xfoil".into(), x.display().to_string()]);
        }
        if let Some(c) = &self.cache {
            v.extend(["--cache".into(), c.display().to_string()]);
        }
        if self.no_cache {
            v.push("--no-cache".into());
        }
        if self.quiet {
            v.push("--quiet".into());
        }
        v
    }
}

/// How XFOIL runs, and the cache.
#[derive(Debug, Args)]
pub struct XfoilArgs {
    /// Executable, cache, progress.
    #[command(flatten)]
    pub process: XfoilProcess,
    /// Transition amplification ratio Ncrit (9: average wind tunnel; 5-7 for turbulent air).
    #[arg(long, default_value_t = 9.0)]
    pub ncrit: f64,
    /// Angles of attack [deg]: `start:stop:step`, `start:stop/N` or a list.
    #[arg(long, default_value = "-8:16:1", allow_hyphen_values = true)]
    pub alpha: String,
    /// XFOIL panel nodes (default: XFOIL's 160 for `polar`, 120 for `polars`).
    #[arg(long)]
    pub panels: Option<u32>,
    /// XFOIL's viscous iteration limit per angle.
    #[arg(long, default_value_t = xfoil_runner::DEFAULT_MAX_ITER)]
    pub iter: u32,
}

impl XfoilArgs {
    fn engine(&self) -> Result<PolarEngine> {
        let p = &self.process;
        let exe = find_xfoil(p.xfoil.as_deref(), std::env::var_os("PATH").as_deref())?;
        let xfoil = Xfoil::new(XfoilConfig::new(exe))?;
        let cache = if p.no_cache {
            None
        } else {
            match p.cache.clone().or_else(PolarCache::default_dir) {
                Some(dir) => Some(PolarCache::open(&dir)?),
                None => None,
            }
        };
        Ok(PolarEngine::new(xfoil, cache))
    }

    fn alphas(&self) -> Result<Vec<f64>> {
        let mut a = parse_list("--alpha", &self.alpha)?;
        a.sort_by(f64::total_cmp);
        a.dedup();
        if let Some(bad) = a.iter().find(|x| x.abs() > 90.0) {
            bail!("--alpha: {bad} deg is outside -90..90");
        }
        Ok(a)
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
    /// The section, normalised (and scaled), with what was repaired in the file.
    pub fn load(&self) -> Result<Airfoil> {
        let mut foil = match naca4_from_name(&self.airfoil) {
            Some(r) => {
                let mut foil = r.map_err(|e| anyhow::anyhow!("--airfoil {}: {e}", self.airfoil))?;
                foil.normalise();
                foil
            }
            None => {
                let path = Path::new(&self.airfoil);
                let (foil, repairs) = read_airfoil(path)?;
                for r in repairs {
                    eprintln!("propbet: {}: {}", path.display(), r.0);
                }
                foil
            }
        };
        if let Some(t) = &self.thickness {
            let v = parse_fraction(t).with_context(|| format!("--thickness {t}"))?;
            foil = foil.scale_thickness(v)?;
        }
        Ok(foil)
    }
}

/// An airfoil coordinate file, parsed and normalised, with what was repaired in it.
pub fn read_airfoil(path: &Path) -> Result<(Airfoil, Vec<propbet_polar::airfoil::Repair>)> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("{}: cannot read the airfoil file", path.display()))?;
    let (mut foil, repairs) = Airfoil::parse(&text, &path.display().to_string())?;
    foil.normalise();
    Ok((foil, repairs))
}

fn parse_fraction(text: &str) -> Result<f64> {
    let t = text.trim();
    let (num, scale) = match t.strip_suffix('%') {
        Some(n) => (n, 0.01),
        None => (t, 1.0),
    };
    let v: f64 = num.trim().parse().with_context(|| format!("{t:?} is not a number"))?;
    Ok(v * scale)
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
    let foil = args.section.load()?;
    let res = parse_list("--re", &args.re)?;
    if let Some(bad) = res.iter().find(|r| !(r.is_finite() && **r > 0.0)) {
        bail!("--re: Reynolds number must be positive, found {bad}");
    }
    if !(args.mach.is_finite() && (0.0..0.9).contains(&args.mach)) {
        bail!("--mach: {} must be in [0, 0.9)", args.mach);
    }
    let alphas = args.xfoil.alphas()?;
    let engine = args.xfoil.engine()?;
    let jobs: Vec<PolarJob> = res
        .iter()
        .map(|&re| PolarJob {
            panels: args.xfoil.panels.unwrap_or(xfoil_runner::DEFAULT_PANELS),
            max_iter: args.xfoil.iter,
            ..PolarJob::new(foil.clone(), re, args.mach, args.xfoil.ncrit, alphas.clone())
        })
        .collect();
    let mut ok = true;
    let mut polars: Vec<Polar> = Vec::new();
    for (job, r) in jobs.iter().zip(engine.compute_all(&jobs, !args.xfoil.process.quiet)) {
        match r {
            Ok((p, _)) => {
                report_failures(&format!("Re {:.0}", job.re), &p);
                polars.push(p);
            }
            Err(e) => {
                eprintln!("propbet: error: {e}");
                ok = false;
            }
        }
    }
    if polars.is_empty() {
        bail!("no polar could be computed for {}", foil.name);
    }
    let mut fits = Vec::new();
    for p in &polars {
        match fit_qprop(&polars, p.re, &AlphaWeights::Uniform, -0.5) {
            Ok(f) => {
                eprintln!("{}", fit_summary(p.re, &f));
                fits.push(f);
            }
            Err(e) => eprintln!("propbet: Re {:.0}: no QPROP fit: {e}", p.re),
        }
    }
    let inputs = input_paths(&args.section);
    let mut csv = format!("{}\n", propbet_polar::table::CSV_HEADER);
    for p in &polars {
        csv.push_str(&p.csv_rows());
    }
    emit(args.out.as_deref(), &[csv.as_bytes()], &inputs)?;
    if let Some(path) = &args.fit_out {
        let json = serde_json::to_vec_pretty(&fits)?;
        crate::output::write_atomic(path, &[json.as_slice()], &inputs)?;
    }
    if let Some(path) = &args.plot {
        let fig = Figure {
            panels: polar_panels(&foil.name, &polars, &fits),
            columns: 2,
            width: 1400,
            height: 560,
        };
        crate::output::write_figure(path, &fig, &inputs)?;
    }
    Ok(ok)
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
    for f in &p.faults {
        eprintln!("propbet: {what}: {f}");
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

fn polar_panels(name: &str, polars: &[Polar], fits: &[QpropFit]) -> Vec<Panel> {
    let mut lift = Vec::new();
    let mut drag = Vec::new();
    for (k, p) in polars.iter().enumerate() {
        let label = format!("XFOIL Re {:.0}", p.re);
        lift.push(Series::new(
            label.clone(),
            p.points.iter().map(|q| (q.alpha_deg, q.cl)).collect(),
            Mark::Dots,
            Some(k),
        ));
        drag.push(Series::new(
            label,
            p.points.iter().map(|q| (q.cd, q.cl)).collect(),
            Mark::Dots,
            Some(k),
        ));
    }
    for f in fits {
        let k = polars.iter().position(|p| p.re == f.coeffs.re_ref);
        let label = format!("QPROP fit Re {:.0}", f.coeffs.re_ref);
        let lin: Vec<_> = f.residuals.iter().filter(|r| r.linear).collect();
        lift.push(Series::new(
            label.clone(),
            lin.iter().map(|r| (r.alpha_deg, r.cl_fit)).collect(),
            Mark::Line,
            k,
        ));
        drag.push(Series::new(
            label,
            lin.iter().map(|r| (r.cd_fit, r.cl_xfoil)).collect(),
            Mark::Line,
            k,
        ));
    }
    vec![
        Panel {
            title: format!("{name}: lift"),
            x_label: "angle of attack [deg]".into(),
            y_label: "cl".into(),
            series: lift,
            zero_line: false,
        },
        Panel {
            title: format!("{name}: drag polar"),
            x_label: "cd".into(),
            y_label: "cl".into(),
            series: drag,
            zero_line: false,
        },
    ]
}

/// Panels for a blade's polars: 1.9x faster than XFOIL's 160, and close to it (NACA 4412 at
/// 4 deg, Debian XFOIL 6.99: Re 1e5 cl 0.8896 vs 0.8880, cd 0.0196 vs 0.01965; Re 5e4 cl 0.6062
/// vs 0.6108, cd 0.04977 vs 0.04952 — at Re 5e4 XFOIL itself moves by 3 % between 100 and 160).
const BLADE_PANELS: u32 = 120;

/// Arguments of `propbet polars`.
#[derive(Debug, Args)]
pub struct PolarsArgs {
    /// Blade geometry: a QPROP prop file (its radii, chords and twists are used; its
    /// coefficients only for the first estimate of each station's inflow).
    #[arg(long)]
    pub geometry: PathBuf,
    /// Length unit of the geometry's radii and chords (overrides its Rfac/Cfac): m, cm, mm, in.
    #[arg(long)]
    pub units: Option<String>,
    /// The section used at every station.
    #[command(flatten)]
    pub section: AirfoilArgs,
    /// Per-station sections: a directory of `station_NN.dat` (NN = 00, 01, ... in the
    /// geometry's station order, as `propbet scan` writes them); a station without its file
    /// uses `--airfoil`.
    #[arg(long)]
    pub station_airfoils: Option<PathBuf>,
    /// Operating point: rotation speed [rpm].
    #[arg(long)]
    pub rpm: f64,
    /// Operating point: axial speed [m/s].
    #[arg(long, default_value_t = 0.0)]
    pub v: f64,
    /// Further polars at these multiples of each station's Re, for REexp (`none`: one Re per
    /// station, REexp kept at -0.5).
    #[arg(long, default_value = "0.7,1.4")]
    pub re_factors: String,
    /// Air properties.
    #[command(flatten)]
    pub air: FluidArgs,
    /// XFOIL settings.
    #[command(flatten)]
    pub xfoil: XfoilArgs,
    /// QPROP prop file with the fitted per-station coefficients.
    #[arg(long)]
    pub out_prop: PathBuf,
    /// Every station's polars and fit (JSON), for `propbet predict --polars`.
    #[arg(long)]
    pub out_polars: Option<PathBuf>,
}

/// Runs `propbet polars`; false when a station has no fit (its coefficients are kept from the
/// geometry file, and it is reported).
pub fn run_polars(args: &PolarsArgs) -> Result<bool> {
    let loaded = load_prop(&args.geometry, args.units.as_deref())?;
    for w in &loaded.warnings {
        eprintln!("propbet: warning: {w}");
    }
    let (fluid, _) = args.air.fluid()?;
    if !(args.rpm.is_finite() && args.rpm > 0.0) {
        bail!("--rpm: {} must be positive", args.rpm);
    }
    if !args.v.is_finite() || args.v < 0.0 {
        bail!("--v: {} must be a non-negative speed", args.v);
    }
    let factors = if args.re_factors.trim() == "none" {
        Vec::new()
    } else {
        parse_list("--re-factors", &args.re_factors)?
    };
    if let Some(bad) = factors.iter().find(|f| !(**f > 0.0 && f.is_finite())) {
        bail!("--re-factors: {bad} must be positive");
    }
    let foil = args.section.load()?;
    let mut foils = vec![foil.clone()];
    if let Some(dir) = &args.station_airfoils {
        foils = station_foils(dir, loaded.file.rows.len(), &foil)?;
    }
    let engine = args.xfoil.engine()?;
    let req = BladeRequest {
        file: &loaded.file,
        geometry: &args.geometry,
        foils: &foils,
        rpm: args.rpm,
        v: args.v,
        factors,
        fluid,
        engine: &engine,
        xfoil: &args.xfoil,
    };
    let (mut file, b, all_ok) = blade_polars(&req)?;
    let inputs: Vec<&Path> = std::iter::once(args.geometry.as_path())
        .chain(input_paths(&args.section))
        .collect();
    file.name = format!(
        "{} / {} polars at {:.0} rpm, {} m/s",
        file.name, foil.name, args.rpm, args.v
    );
    crate::output::write_atomic(&args.out_prop, &[write_prop(&file).as_bytes()], &inputs)?;
    if let Some(path) = &args.out_polars {
        let json = serde_json::to_vec(&b)?;
        crate::output::write_atomic(path, &[json.as_slice()], &inputs)?;
    }
    Ok(all_ok)
}

/// The sections `station_NN.dat` of a directory, one per station; `fallback` where missing.
fn station_foils(dir: &Path, n: usize, fallback: &Airfoil) -> Result<Vec<Airfoil>> {
    if !dir.is_dir() {
        bail!("--station-airfoils {}: not a directory", dir.display());
    }
    let mut missing = Vec::new();
    let foils = (0..n)
        .map(|i| {
            let path = dir.join(format!("station_{i:02}.dat"));
            if !path.exists() {
                missing.push(i);
                return Ok(fallback.clone());
            }
            Ok(read_airfoil(&path)?.0)
        })
        .collect::<Result<Vec<_>>>()?;
    if !missing.is_empty() {
        eprintln!(
            "propbet: {}: no section file for station(s) {missing:?}: {} used there",
            dir.display(),
            fallback.name
        );
    }
    Ok(foils)
}

/// What [`blade_polars`] needs.
pub struct BladeRequest<'a> {
    /// The blade (radii, chords, twists; its coefficients give the first inflow estimate).
    pub file: &'a PropFile,
    /// Where it came from (for messages).
    pub geometry: &'a Path,
    /// One section for every station, or one per input station.
    pub foils: &'a [Airfoil],
    /// Operating point [rpm].
    pub rpm: f64,
    /// Operating point [m/s].
    pub v: f64,
    /// Further multiples of each station's Re.
    pub factors: Vec<f64>,
    /// Air.
    pub fluid: propbet_bemt::Fluid,
    /// XFOIL and the cache.
    pub engine: &'a PolarEngine,
    /// Angles, panels, iterations, Ncrit, progress.
    pub xfoil: &'a XfoilArgs,
}

/// Polars of every input station at its Re and Mach at the operating point, fitted to QPROP's
/// coefficients: the prop file with the fitted coefficients, every station's polars, and false
/// when a station has no fit (its coefficients are kept, and it is reported).
pub fn blade_polars(q: &BladeRequest) -> Result<(PropFile, BladePolars, bool)> {
    let blade = q.file.to_blade(RadiusReading::Documented);
    let rotor = blade
        .to_rotor(propbet_bemt::Discretization::default())
        .map_err(|e| anyhow::anyhow!("{}: {e}", q.geometry.display()))?;
    let fluid = q.fluid;
    if q.foils.is_empty() {
        bail!("{}: no section given", q.geometry.display());
    }
    let alphas = q.xfoil.alphas()?;

    // Each input station's inflow at the operating point, from the solver on the file's model.
    let opts = SolverOptions {
        keep_stations: true,
        ..SolverOptions::default()
    };
    let point = Solver::new(&rotor, &fluid, &opts).solve(OperatingPoint::from_rpm(q.v, q.rpm));
    let st = &point.stations;
    let at = |r: f64, f: &dyn Fn(&propbet_bemt::StationResult) -> f64| -> f64 {
        let i = st.partition_point(|s| s.r <= r).clamp(1, st.len() - 1);
        let (a, b) = (&st[i - 1], &st[i]);
        let t = ((r - a.r) / (b.r - a.r)).clamp(-0.5, 1.5);
        f(a) + t * (f(b) - f(a))
    };
    let mut jobs = Vec::new();
    let mut stations = Vec::new();
    for (i, &r) in blade.r.iter().enumerate() {
        let w = at(r, &|s| s.w);
        let chord = blade.chord[i];
        let re = fluid.rho * w * chord / fluid.mu;
        let mach = (w / fluid.a).min(0.85);
        let alpha_deg = at(r, &|s| s.alpha).to_degrees();
        let first = jobs.len();
        if re > 0.0 && chord > 0.0 {
            let foil = &q.foils[i.min(q.foils.len() - 1)];
            for f in std::iter::once(1.0).chain(q.factors.iter().copied()) {
                jobs.push(PolarJob {
                    panels: q.xfoil.panels.unwrap_or(BLADE_PANELS),
                    max_iter: q.xfoil.iter,
                    ..PolarJob::new(foil.clone(), re * f, mach, q.xfoil.ncrit, alphas.clone())
                });
            }
        }
        stations.push((r, chord, re, mach, alpha_deg, first..jobs.len()));
    }
    let results = q.engine.compute_all(&jobs, !q.xfoil.process.quiet);
    let mut results: Vec<Option<Result<Polar, String>>> = results
        .into_iter()
        .map(|r| Some(r.map(|(p, _)| p).map_err(|e| e.to_string())))
        .collect();

    let mut file: PropFile = q.file.clone();
    let mut out_stations = Vec::new();
    let mut all_ok = true;
    for (i, (r, chord, re, mach, alpha_deg, range)) in stations.into_iter().enumerate() {
        let mut polars = Vec::new();
        let mut problems = Vec::new();
        for k in range {
            match results[k].take() {
                Some(Ok(p)) => {
                    report_failures(&format!("station r = {r:.4} m, Re {:.0}", p.re), &p);
                    polars.push(p);
                }
                Some(Err(e)) => problems.push(e),
                None => {}
            }
        }
        let weights = AlphaWeights::Around {
            alphas_deg: vec![alpha_deg],
            sigma_deg: 3.0,
        };
        let fit = if polars.is_empty() {
            problems.push(format!("no polar at r = {r:.4} m (Re {re:.0})"));
            None
        } else {
            match fit_qprop(&polars, re, &weights, -0.5) {
                Ok(f) => Some(f),
                Err(e) => {
                    problems.push(e.to_string());
                    None
                }
            }
        };
        match &fit {
            Some(f) => {
                eprintln!(
                    "station {} (r = {r:.4} m, alpha {alpha_deg:.1} deg): {}",
                    i + 1,
                    fit_summary(re, f)
                );
                file.set_station_coeffs(i, &f.coeffs);
            }
            None => {
                all_ok = false;
                eprintln!(
                    "propbet: station {} (r = {r:.4} m): no fit, coefficients kept from {}: {}",
                    i + 1,
                    q.geometry.display(),
                    problems.join("; ")
                );
            }
        }
        out_stations.push(StationPolars {
            r,
            chord,
            re,
            mach,
            alpha_deg,
            polars,
            fit,
            problem: (!problems.is_empty()).then(|| problems.join("; ")),
        });
    }
    let names: Vec<&str> = q.foils.iter().map(|f| f.name.as_str()).collect();
    let b = BladePolars {
        format: propbet_polar::blade::FORMAT.into(),
        geometry: q.geometry.display().to_string(),
        airfoil: if names.len() == 1 {
            names[0].to_string()
        } else {
            format!("{} sections, {} ... {}", names.len(), names[0], names[names.len() - 1])
        },
        rpm: q.rpm,
        v: q.v,
        air: [fluid.rho, fluid.mu, fluid.a],
        stations: out_stations,
    };
    Ok((file, b, all_ok))
}
