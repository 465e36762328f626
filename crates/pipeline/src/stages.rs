//! The stages as functions: each takes its spec (and, inside `run`, the artifact of the stage
//! before it, in memory) and returns typed artifacts. Files are read here when a spec names an
//! input; nothing is written here: the CLI writes the outputs.

use std::path::{Path, PathBuf};

use propbet_bemt::{grid_omega_j, grid_omega_v, Fluid, OperatingPoint, PointResult, Solver};
use propbet_compare::metrics::{metrics, Metrics};
use propbet_compare::{AirChoice, ComparedPoint, Setup};
use propbet_diagnose::discover::{diagnose as discover, Diagnosis, Options};
use propbet_diagnose::Data;
use propbet_effects::Stack;
use propbet_geometry::cloud::read_cloud;
use propbet_geometry::mesh::read_stl;
use propbet_geometry::scan::{scan_cloud, scan_mesh, Geometry};
use propbet_measure::uiuc::GeometryRow;
use propbet_measure::{MeasuredSet, ReadOptions};
use propbet_polar::blade::{compute_blade, BladeJob, XfoilSettings, BLADE_PANELS};
use propbet_polar::{naca4_from_name, Airfoil, BladePolars, PolarCache, PolarEngine, Progress};
use propbet_qprop::{PropFile, PropRow};
use rayon::prelude::*;

use crate::model::{as_written, load_prop, LoadedProp, Model};
use crate::spec::{DiagnoseSpec, MeasuredSpec, PolarsSpec, PredictSpec, ScanSpec, SweepAxis, XfoilProcessSpec};
use crate::{invalid, read_text, Error, Result};

// ---------------------------------------------------------------------------------------
// scan

/// What `propbet scan` makes.
pub struct Scanned {
    /// The geometry.
    pub geometry: Geometry,
    /// The reference table, when the spec names one.
    pub reference: Option<Vec<GeometryRow>>,
    /// Name of the propeller (prop file, airfoils).
    pub name: String,
    /// The prop file, as the file written for it holds it.
    pub prop: LoadedProp,
    /// Each station's fitted section as a Selig file: (station index, text).
    pub airfoils: Vec<(usize, String)>,
}

impl Scanned {
    /// Every station asked for was measured, and has its section file.
    pub fn clean(&self) -> bool {
        self.geometry.failed.is_empty() && self.airfoils.len() == self.geometry.stations.len()
    }
}

/// Reads a UIUC-style geometry table (r/R c/R β).
pub fn read_geometry_table(path: &Path) -> Result<Vec<GeometryRow>> {
    propbet_measure::uiuc::read_geometry(&read_text(path)?).map_err(|e| Error::input(path, e))
}

/// The most stations a scan cuts.
pub const MAX_STATIONS: usize = 200;

/// Runs the scan stage.
pub fn scan(spec: &ScanSpec) -> Result<Scanned> {
    let o = &spec.options;
    if o.stations.len() > MAX_STATIONS {
        invalid!(
            "--stations: {} stations; a blade is described by at most {MAX_STATIONS} (each one is a section fit and its polars)",
            o.stations.len()
        );
    }
    if let Some(x) = o.stations.iter().find(|&&x| !(x > 0.0 && x <= 1.0)) {
        invalid!("--stations: r/R {x} is outside (0, 1]");
    }
    if !(o.slab > 0.0 && o.slab.is_finite()) {
        invalid!("--slab {}: must be a positive thickness in mm", 1000.0 * o.slab);
    }
    let path = &spec.input;
    let bytes = crate::read_bytes(path)?;
    let label = path.display().to_string();
    let is_stl = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("stl"));
    let geometry = if is_stl {
        let mesh = read_stl(&bytes, &label).map_err(|e| Error::Invalid(e.to_string()))?;
        scan_mesh(&mesh, o)
    } else {
        let cloud = read_cloud(&bytes, &label).map_err(|e| Error::Invalid(e.to_string()))?;
        scan_cloud(&cloud, o)
    }
    .map_err(|e| Error::input(path, e))?;
    let reference = spec.reference.as_deref().map(read_geometry_table).transpose()?;
    let name = spec.name.clone().unwrap_or_else(|| {
        path.file_stem()
            .map_or("scan".into(), |s| s.to_string_lossy().into_owned())
    });
    let prop = as_written(&scan_prop_file(&name, &geometry), &spec.out.join("prop.qprop"))?;
    let (airfoils, notes) = station_airfoils(&name, &geometry);
    let mut geometry = geometry;
    geometry.notes.extend(notes);
    Ok(Scanned {
        geometry,
        reference,
        name,
        prop,
        airfoils,
    })
}

/// The scan's prop file: radii and chords in metres, β in degrees; CL0 from thin-airfoil theory
/// on the fitted camber, the rest [`propbet_qprop::GENERIC`] until `propbet polars` (XFOIL at
/// each station's Re) replaces them.
pub fn scan_prop_file(name: &str, g: &Geometry) -> PropFile {
    let generic = propbet_qprop::GENERIC;
    let rows = g
        .stations
        .iter()
        .map(|s| {
            let cl0 = propbet_polar::airfoil::naca4_cl0(s.naca.camber, s.naca.camber_pos);
            let c = propbet_bemt::QpropCoefficients {
                cl0,
                clcd0: cl0,
                ..generic
            };
            PropRow {
                r: s.r,
                chord: s.chord,
                beta: s.beta.to_degrees(),
                coeffs: c.to_array().to_vec(),
            }
        })
        .collect();
    PropFile::metric(name.to_string(), g.blades as f64, g.tip_radius, rows)
}

/// Each station's CST section as a Selig file (`airfoils/station_NN.dat`), with notes: where
/// the fit's surfaces were moved apart (a trailing edge that crossed itself, closed), and a
/// section that is still no airfoil XFOIL can take (checked as `polars` reads it: the station
/// gets no file and takes the airfoil or its neighbour's section).
pub fn station_airfoils(name: &str, g: &Geometry) -> (Vec<(usize, String)>, Vec<String>) {
    let mut notes = Vec::new();
    let mut files = Vec::new();
    for (i, s) in g.stations.iter().enumerate() {
        let Some(c) = s.cst.as_ref() else { continue };
        let (points, repaired) = c.selig_repaired(80);
        let mut t = format!("{name} r/R={:.4} (CST fit, rms {:.4} mm)\n", s.r_r, 1000.0 * c.rms);
        for (x, y) in points {
            t.push_str(&format!("{x:.6} {y:.6}\n"));
        }
        let file = format!("station_{i:02}.dat");
        match repaired {
            Some((from, _)) if from > 0.995 => notes.push(format!(
                "{file} (r/R {:.3}): the fitted trailing edge crossed itself (lower surface above the upper); closed",
                s.r_r
            )),
            Some((from, to)) => notes.push(format!(
                "{file} (r/R {:.3}): the fitted surfaces crossed or nearly touched at x/c {from:.2}-{to:.2}; set a \
                 wedge of {} % of chord apart there, the trailing edge closed",
                s.r_r,
                100.0 * propbet_geometry::fit::TE_WEDGE
            )),
            None => {}
        }
        match parse_airfoil(&t, Path::new(&file)) {
            Ok(_) => files.push((i, t)),
            Err(e) => notes.push(format!("{file} not written (r/R {:.3}): {e}", s.r_r)),
        }
    }
    (files, notes)
}

// ---------------------------------------------------------------------------------------
// polars

/// An airfoil file, parsed and normalised, with what was repaired in it.
pub fn read_airfoil(path: &Path) -> Result<(Airfoil, Vec<String>)> {
    let text = crate::error::read_titled_text(path)?;
    parse_airfoil(&text, path)
}

/// An airfoil file's text, parsed and normalised, with what was repaired in it.
pub fn parse_airfoil(text: &str, path: &Path) -> Result<(Airfoil, Vec<String>)> {
    let (mut foil, repairs) =
        Airfoil::parse(text, &path.display().to_string()).map_err(|e| Error::Invalid(e.to_string()))?;
    foil.normalise();
    Ok((
        foil,
        repairs
            .into_iter()
            .map(|r| format!("{}: {}", path.display(), r.0))
            .collect(),
    ))
}

/// A section: a NACA 4-digit name or a coordinate file, optionally scaled to a thickness ratio;
/// with the file's repairs.
pub fn load_airfoil(name: &str, thickness: Option<f64>) -> Result<(Airfoil, Vec<String>)> {
    let (mut foil, notes) = match naca4_from_name(name) {
        Some(r) => {
            let mut foil = r.map_err(|e| Error::Invalid(format!("--airfoil {name}: {e}")))?;
            foil.normalise();
            (foil, Vec::new())
        }
        None => read_airfoil(Path::new(name))?,
    };
    if let Some(t) = thickness {
        foil = foil
            .scale_thickness(t)
            .map_err(|e| Error::Invalid(format!("--thickness {}: {e}", propbet_units::show(t))))?;
    }
    Ok((foil, notes))
}

/// XFOIL and the polar cache, as the spec says.
pub fn polar_engine(p: &XfoilProcessSpec) -> Result<PolarEngine> {
    let exe = xfoil_runner::find_xfoil(p.xfoil.as_deref(), std::env::var_os("PATH").as_deref())?;
    let xfoil = xfoil_runner::Xfoil::new(xfoil_runner::XfoilConfig::new(exe))?;
    let cache = if p.no_cache {
        None
    } else {
        match p.cache.clone().or_else(PolarCache::default_dir) {
            Some(dir) => Some(PolarCache::open(&dir)?),
            None => None,
        }
    };
    let engine = PolarEngine::new(xfoil, cache);
    Ok(match p.budget.unwrap_or(crate::spec::DEFAULT_XFOIL_BUDGET) {
        b if b.is_finite() && b > 0.0 => engine.with_budget(b),
        b => invalid!(
            "--xfoil-budget {}: a positive number of seconds",
            propbet_units::show(b)
        ),
    })
}

/// What the polars stage reads: the blade and its sections.
pub struct PolarsInput {
    /// The blade.
    pub geometry: LoadedProp,
    /// One section for every station, or one per input station.
    pub foils: Vec<Airfoil>,
    /// The section at every station (the hint).
    pub foil_name: String,
    /// Notes for the user (repairs, stations without their own section).
    pub notes: Vec<String>,
}

/// Reads the polars stage's inputs from the files its spec names.
pub fn polars_input(spec: &PolarsSpec) -> Result<PolarsInput> {
    let geometry = load_prop(&spec.geometry, spec.units)?;
    let (foil, mut notes) = spec_airfoil(spec)?;
    let foils = match &spec.station_airfoils {
        None => vec![foil.clone().expect("spec_airfoil: an airfoil without station sections")],
        Some(dir) => {
            if !dir.is_dir() {
                invalid!("--station-airfoils {}: not a directory", dir.display());
            }
            let n = geometry.file.rows.len();
            let texts = (0..n)
                .map(|i| {
                    let path = dir.join(format!("station_{i:02}.dat"));
                    path.exists().then(|| read_text(&path).map(|t| (path, t))).transpose()
                })
                .collect::<Result<Vec<_>>>()?;
            station_foils(dir, texts, foil.as_ref(), &mut notes)?
        }
    };
    Ok(PolarsInput {
        geometry,
        foils,
        foil_name: foil_name(foil.as_ref()),
        notes,
    })
}

/// The spec's airfoil, loaded (and scaled) with its repair notes: None only when the stations
/// have their own sections; an error when neither is given.
pub fn spec_airfoil(spec: &PolarsSpec) -> Result<(Option<Airfoil>, Vec<String>)> {
    match (&spec.airfoil, &spec.station_airfoils) {
        (Some(a), _) => load_airfoil(a, spec.thickness).map(|(f, n)| (Some(f), n)),
        (None, None) => {
            invalid!("--airfoil: the section of every station (or --station-airfoils, the scanned sections)")
        }
        (None, Some(_)) if spec.thickness.is_some() => {
            invalid!(
                "--thickness scales the --airfoil section; without --airfoil each station keeps its scanned thickness"
            )
        }
        (None, Some(_)) => Ok((None, Vec::new())),
    }
}

/// What the polars' `airfoil` says: the airfoil's name, or that the scan gave every section.
pub fn foil_name(foil: Option<&Airfoil>) -> String {
    foil.map_or_else(|| "the scanned sections".to_string(), |f| f.name.clone())
}

/// One section per station from the texts of `station_NN.dat` files; a station without its
/// file takes `fallback`, or without one the nearest station's section (the outboard one of
/// two as near). An error when no station has a section and there is no fallback.
pub fn station_foils(
    dir: &Path,
    texts: Vec<Option<(PathBuf, String)>>,
    fallback: Option<&Airfoil>,
    notes: &mut Vec<String>,
) -> Result<Vec<Airfoil>> {
    let mut own: Vec<Option<Airfoil>> = Vec::new();
    for t in texts {
        own.push(match t {
            None => None,
            Some((path, text)) => {
                let (f, repairs) = parse_airfoil(&text, &path)?;
                notes.extend(repairs);
                Some(f)
            }
        });
    }
    let missing: Vec<usize> = (0..own.len()).filter(|&i| own[i].is_none()).collect();
    if missing.is_empty() {
        return Ok(own.into_iter().flatten().collect());
    }
    if let Some(f) = fallback {
        notes.push(format!(
            "{}: no section file for station(s) {missing:?}: {} used there",
            dir.display(),
            f.name
        ));
        return Ok(own.into_iter().map(|o| o.unwrap_or_else(|| f.clone())).collect());
    }
    let have: Vec<usize> = (0..own.len()).filter(|&i| own[i].is_some()).collect();
    if have.is_empty() {
        invalid!(
            "{}: no station has a section file and no airfoil was given for them (`airfoil` in [polars], --airfoil)",
            dir.display()
        );
    }
    let nearest = |i: usize| {
        *have
            .iter()
            .rev()
            .min_by_key(|&&k| k.abs_diff(i))
            .expect("have is not empty")
    };
    let taken: Vec<String> = missing.iter().map(|&i| format!("{i} from {}", nearest(i))).collect();
    notes.push(format!(
        "{}: no section file for station(s) {missing:?}: the nearest station's section used there (station {})",
        dir.display(),
        taken.join(", ")
    ));
    Ok((0..own.len())
        .map(|i| {
            own[i]
                .clone()
                .unwrap_or_else(|| own[nearest(i)].clone().expect("nearest has a section"))
        })
        .collect())
}

/// What the polars stage makes.
pub struct Polars {
    /// The prop file with each station's fitted coefficients (a station without a fit keeps
    /// the geometry's), as the file written for it holds it.
    pub prop: LoadedProp,
    /// Every station's polars and fit.
    pub blade: BladePolars,
    /// How far the exported prop file (QPROP's law) predicts from the tables over the points
    /// the polars cover (None when no station has a polar).
    pub export: Option<ExportCheck>,
    /// The cache could not store what XFOIL computed (read-only, full): the polars were
    /// used, and the next run computes them again.
    pub cache_warning: Option<String>,
}

/// The exported prop file against the tables it was fitted to: relative differences
/// |CT_qprop / CT_tables - 1| (and CP) over the operating points the polars cover where the
/// tables' thrust is at least a quarter of their largest (near zero thrust a ratio says
/// nothing, as in validate's window) and their power positive.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct ExportCheck {
    /// Points compared.
    pub points: usize,
    /// CT: median and largest relative difference [-].
    pub ct: [f64; 2],
    /// CP: median and largest relative difference [-].
    pub cp: [f64; 2],
}

impl ExportCheck {
    /// The check in one sentence (terminal and report).
    pub fn sentence(&self) -> String {
        format!(
            "The exported prop file (QPROP's law, for QPROP and other tools) against the tables over the {} operating points the polars cover (thrust at least a quarter of the largest): CT differs by {:.1} % (median), {:.1} % at most; CP by {:.1} %, {:.1} % at most.",
            self.points,
            100.0 * self.ct[0],
            100.0 * self.ct[1],
            100.0 * self.cp[0],
            100.0 * self.cp[1]
        )
    }

    /// Compares the prop file's QPROP law with the tables at `points`.
    fn new(
        file: &PropFile,
        blade: &BladePolars,
        fluid: &Fluid,
        points: &[OperatingPoint],
    ) -> Result<Option<ExportCheck>> {
        let law = file
            .to_blade(propbet_qprop::RadiusReading::Documented)
            .to_rotor(propbet_bemt::Discretization::default())
            .map_err(|e| Error::Invalid(e.to_string()))?;
        let mut tables = law.clone();
        let Ok((r, models)) = blade.models() else {
            return Ok(None);
        };
        propbet_polar::tabulated::apply_to_rotor(&mut tables, &r, &models);
        let opts = propbet_bemt::SolverOptions::default();
        let a = Solver::new(&law, fluid, &opts).solve_many(points);
        let b = Solver::new(&tables, fluid, &opts).solve_many(points);
        let (mut ct, mut cp) = (Vec::new(), Vec::new());
        let ct_max = b.iter().filter_map(|p| p.ct).fold(0.0, f64::max);
        for (x, y) in a.iter().zip(&b) {
            if let (Some(ct_a), Some(ct_b), Some(cp_a), Some(cp_b)) = (x.ct, y.ct, x.cp, y.cp) {
                if ct_b >= 0.25 * ct_max && ct_b > 0.0 && cp_b > 0.0 {
                    ct.push((ct_a / ct_b - 1.0).abs());
                    cp.push((cp_a / cp_b - 1.0).abs());
                }
            }
        }
        let stats = |v: &[f64]| {
            [
                propbet_compare::metrics::quantile(v.to_vec(), 0.5),
                v.iter().copied().fold(0.0, f64::max),
            ]
        };
        Ok(Some(ExportCheck {
            points: ct.len(),
            ct: stats(&ct),
            cp: stats(&cp),
        }))
    }
}

impl Polars {
    /// Nothing to report (exit 0): every station has a fit that describes it where the blade
    /// works, and XFOIL ran without a fault (a crash, a hang, unreadable output).
    pub fn clean(&self) -> bool {
        self.blade
            .stations
            .iter()
            .all(|s| s.fit.as_ref().is_some_and(|f| f.unfit.is_empty()) && s.polars.iter().all(|p| p.faults.is_empty()))
    }
}

/// Runs the polars stage: XFOIL on the rungs of the Re ladder covering every station's Re and
/// Mach over the spec's operating points, each station reduced to QPROP's coefficients.
pub fn polars(spec: &PolarsSpec, input: &PolarsInput, engine: &PolarEngine, progress: &Progress<'_>) -> Result<Polars> {
    let (fluid, _) = spec.air.fluid()?;
    let tip = input.geometry.file.tip_radius(propbet_qprop::RadiusReading::Documented);
    let points = grid(&spec.omegas, &spec.axis, tip)?;
    if points.is_empty() {
        invalid!("--rpm / --j / --v: no operating point for the polars to cover");
    }
    if let Some(p) = points.iter().find(|p| p.omega <= 0.0) {
        invalid!("--rpm: {} must be positive", crate::values::rpm_text(p.omega));
    }
    if let Some(p) = points.iter().find(|p| p.v < 0.0) {
        invalid!("--v / --j: {} m/s; the polars cover propeller states, V >= 0", p.v);
    }
    spec.xfoil.check()?;
    let ncrit_effect = crate::spec::check_ncrit_effect(&spec.ncrit_effect, spec.xfoil.ncrit)?;
    let blade = input.geometry.file.to_blade(propbet_qprop::RadiusReading::Documented);
    let settings = XfoilSettings {
        ncrit: spec.xfoil.ncrit,
        trip: spec.xfoil.trip,
        alphas_deg: spec.xfoil.alphas_deg.clone(),
        panels: spec.xfoil.panels.unwrap_or(BLADE_PANELS),
        max_iter: spec.xfoil.iter,
        ncrit_effect,
    };
    let job = BladeJob {
        blade: &blade,
        geometry: spec.geometry.display().to_string(),
        foils: &input.foils,
        points: &points,
        fluid,
        settings: &settings,
    };
    let b = compute_blade(&job, engine, progress).map_err(|e| Error::input(&spec.geometry, e))?;
    let mut file = input.geometry.file.clone();
    for (i, s) in b.stations.iter().enumerate() {
        if let Some(f) = &s.fit {
            file.set_station_coeffs(i, &f.coeffs);
        }
    }
    file.name = format!(
        "{} / {} polars for {:.0}-{:.0} rpm, {:.1}-{:.1} m/s",
        file.name, input.foil_name, b.rpm[0], b.rpm[1], b.v[0], b.v[1]
    );
    let prop = as_written(&file, &spec.out_prop)?;
    let export = ExportCheck::new(&prop.file, &b, &fluid, &points)?;
    let cache_warning = engine.cache_error().map(|e| {
        format!("{e}: the cache could not store the polars XFOIL computed; they were used, and the next run computes them again")
    });
    Ok(Polars {
        prop,
        blade: b,
        export,
        cache_warning,
    })
}

// ---------------------------------------------------------------------------------------
// predict

/// Most operating points one sweep may hold (RPM values times J or V values): about 200 MB of
/// results, 50 times the largest sweep of the benchmarks.
pub const MAX_POINTS: usize = 1_000_000;

/// The operating points of a predict spec, for a rotor of tip radius `tip_radius` [m].
pub fn operating_points(spec: &PredictSpec, tip_radius: f64) -> Result<Vec<OperatingPoint>> {
    grid(&spec.omegas, &spec.axis, tip_radius)
}

/// Every rotation speed with every J or V, checked, for a rotor of tip radius `tip_radius` [m].
pub fn grid(omegas: &[f64], axis: &SweepAxis, tip_radius: f64) -> Result<Vec<OperatingPoint>> {
    let other = match axis {
        SweepAxis::J(v) | SweepAxis::V(v) => v.len(),
    };
    let n = omegas.len().saturating_mul(other);
    if n > MAX_POINTS {
        invalid!(
            "the sweep has {} RPM values x {other} J or V values = {n} operating points; at most {MAX_POINTS} in one sweep",
            omegas.len()
        );
    }
    if let Some(bad) = omegas.iter().find(|&&w| w > propbet_measure::limits::OMEGA) {
        invalid!(
            "--rpm: {} is beyond any small propeller's speed (at most 500000)",
            propbet_units::show(propbet_units::omega_to_rpm(*bad))
        );
    }
    if let Some(bad) = omegas
        .iter()
        .find(|&&w| w > 0.0 && w < propbet_measure::limits::OMEGA_MIN)
    {
        invalid!(
            "--rpm: {} is below 1 rpm, where the coefficients divide by almost nothing (0 is allowed: the propeller at rest)",
            propbet_units::show(propbet_units::omega_to_rpm(*bad))
        );
    }
    let speeds = match axis {
        SweepAxis::J(j) => j.iter().any(|j| j.abs() > propbet_measure::limits::ADVANCE_RATIO),
        SweepAxis::V(v) => v.iter().any(|v| v.abs() > propbet_measure::limits::AIRSPEED),
    };
    if speeds {
        invalid!(
            "--j / --v: beyond any small propeller's operating range (|J| at most {}, |V| at most {} m/s)",
            propbet_measure::limits::ADVANCE_RATIO,
            propbet_measure::limits::AIRSPEED
        );
    }
    if let Some(bad) = omegas.iter().find(|&&w| w.is_nan() || w < 0.0) {
        invalid!(
            "--rpm: rotation speed must not be negative, found {}",
            crate::values::rpm_text(*bad)
        );
    }
    Ok(match axis {
        SweepAxis::J(j) => {
            if omegas.contains(&0.0) {
                invalid!("--j needs a non-zero --rpm (J = V/(nD) is undefined at 0 rpm)");
            }
            grid_omega_j(omegas, j, tip_radius)
        }
        SweepAxis::V(v) => grid_omega_v(omegas, v),
    })
}

/// Solves `points` with the model (its effects included), in order.
pub fn solve(model: &Model, fluid: &Fluid, points: &[OperatingPoint]) -> Result<Vec<PointResult>> {
    if model.effects.is_empty() {
        return Ok(Solver::new(&model.rotor, fluid, &model.opts).solve_many(points));
    }
    points
        .iter()
        .map(|&op| {
            let p = model
                .effects
                .predict(&model.rotor, &model.opts, fluid, model.diameter, op)?;
            Ok(p.result.with_loads(
                p.loads.thrust,
                p.loads.torque,
                op.omega,
                fluid.rho,
                model.rotor.tip_radius,
            ))
        })
        .collect()
}

/// Solves `points` in parallel chunks of 128 (in order).
pub fn sweep(model: &Model, fluid: &Fluid, points: &[OperatingPoint]) -> Result<Vec<PointResult>> {
    let chunks: Vec<Vec<PointResult>> = points
        .par_chunks(128)
        .map(|c| solve(model, fluid, c))
        .collect::<Result<_>>()?;
    Ok(chunks.into_iter().flatten().collect())
}

// ---------------------------------------------------------------------------------------
// measurements, compare, diagnose

/// Reads the measured files of a spec: the air choice and the measured sets.
pub fn load_measured(spec: &MeasuredSpec) -> Result<(AirChoice, Vec<MeasuredSet>)> {
    if let Some(p) = spec.poles {
        if p < 2 || p % 2 != 0 {
            invalid!("--poles {p}: a motor has an even number of poles, at least 2");
        }
    }
    if let Some(r) = spec.rho {
        let air = propbet_units::air::DENSITY;
        propbet_units::air::check("--rho", r, &air, "kg/m^3").map_err(Error::Invalid)?;
    }
    let air = AirChoice {
        given: spec.atmosphere,
        rho: spec.rho,
    };
    let column_map = spec.columns.as_deref().map(read_text).transpose()?;
    let opts = ReadOptions {
        poles: spec.poles,
        rpm_source: spec.rpm_source,
        column_map,
        ..Default::default()
    };
    // One file given twice would count its points twice (and cost a diagnosis its time).
    let mut seen: Vec<(PathBuf, &Path)> = Vec::new();
    for p in &spec.files {
        let real = std::fs::canonicalize(p).unwrap_or_else(|_| p.clone());
        if let Some((_, first)) = seen.iter().find(|(r, _)| *r == real) {
            return Err(Error::input(
                p,
                format!(
                    "given twice among the measured files (also as {}): each file once",
                    first.display()
                ),
            ));
        }
        seen.push((real, p));
    }
    let sets = spec
        .files
        .iter()
        .map(|p| read_measured(p, &opts))
        .collect::<Result<_>>()?;
    Ok((air, sets))
}

fn read_measured(path: &Path, opts: &ReadOptions) -> Result<MeasuredSet> {
    let text = read_text(path).map_err(|e| match e {
        Error::Input { path, message } => Error::input(path, format!("{message}; export the log as CSV")),
        e => e,
    })?;
    let opts = ReadOptions {
        name: path.file_name().map(|n| n.to_string_lossy().into_owned()),
        ..opts.clone()
    };
    propbet_measure::read(&text, &opts).map_err(|e| Error::input(path, e))
}

impl MeasuredSpec {
    /// The files read (never to be overwritten).
    pub fn inputs(&self) -> Vec<&Path> {
        self.files
            .iter()
            .map(PathBuf::as_path)
            .chain(self.columns.as_deref())
            .collect()
    }
}

/// What the compare stage makes.
pub struct Compared {
    /// The measured sets as read.
    pub sets: Vec<MeasuredSet>,
    /// The air choice.
    pub air: AirChoice,
    /// Every point, measured and predicted.
    pub points: Vec<ComparedPoint>,
    /// Metrics by group.
    pub metrics: Metrics,
}

impl Compared {
    /// Measurements that cannot be of this propeller (a warning, exit 1).
    pub fn mismatch(&self) -> Option<propbet_compare::plausible::Mismatch> {
        propbet_compare::plausible::of_points(&self.points)
    }

    /// Nothing to report: no faulty row, every station converged, measurements of this
    /// propeller's size.
    pub fn clean(&self) -> bool {
        self.problems() == (0, 0) && self.mismatch().is_none()
    }

    /// Rows dropped as faulty and stations that did not converge (all reported).
    pub fn problems(&self) -> (usize, usize) {
        (
            self.sets.iter().map(MeasuredSet::faults).sum(),
            self.points.iter().map(|p| p.not_converged).sum(),
        )
    }
}

/// The solver setup of a model for the comparison (with the model's effects or without).
pub fn setup<'a>(model: &'a Model, air: AirChoice, effects: Stack) -> Setup<'a> {
    Setup {
        rotor: &model.rotor,
        diameter: model.diameter,
        opts: model.opts,
        air,
        effects,
    }
}

/// Runs the compare stage.
pub fn compare(model: &Model, measured: &MeasuredSpec) -> Result<Compared> {
    let (air, sets) = load_measured(measured)?;
    let points = propbet_compare::compare(&setup(model, air, model.effects.clone()), &sets)?;
    let metrics = metrics(&points);
    Ok(Compared {
        sets,
        air,
        points,
        metrics,
    })
}

/// What the diagnose stage makes.
pub struct Diagnosed {
    /// The measured sets as read.
    pub sets: Vec<MeasuredSet>,
    /// The residual rows.
    pub data: Data,
    /// The diagnosis.
    pub diagnosis: Diagnosis,
}

/// Bounds of the RPM scale when every file's RPM is optical (the wide bounds hold the
/// pole-count ratios of an electrical reading, 12/14 and 14/12). An optical tachometer times
/// pulses against a quartz clock: a handheld one is specified to ±0.02 % of the reading ± 1
/// count (Ono Sokki HT-5500's data sheet), so ±1 % is fifty times that and still not a
/// miscount, which would be a factor of 2 (two reflections a turn). The bounds were once ±3 %
/// with no source; validate's held-out columns with each are in `README.md` (Validation on
/// real propellers).
pub const OPTICAL_RPM_SCALE: (f64, f64) = (0.99, 1.01);

/// Bounds of the density ratio when every file gives coefficients (UIUC's CT and CP): the lab
/// reduced its loads with the density it measured, so the ratio is only that measurement's
/// error. Density from a barometer and a thermometer (ideal gas) is good to a few tenths of a
/// percent (1 hPa is 0.1 %, 1 K 0.35 %); humidity left out makes dry-air density up to about
/// 1 % high at 30 C and 60 % RH (moist air's gas constant): ±2 % holds both with room. The
/// wide bounds (0.75-1.2) are those of a stand log whose air nobody wrote down.
pub const LAB_DENSITY_RATIO: (f64, f64) = (0.98, 1.02);

/// Runs the diagnose stage.
pub fn diagnose(model: &Model, spec: &DiagnoseSpec) -> Result<Diagnosed> {
    if spec.folds < 2 {
        invalid!("--folds {}: at least 2", spec.folds);
    }
    let list: Vec<String> = spec
        .effects
        .iter()
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .collect();
    let mut candidates = model
        .registry
        .select(&list)
        .map_err(|e| Error::Invalid(e.to_string()))?;
    // Effects already in the baseline are not candidates.
    candidates.retain(|c| !model.effects.active.iter().any(|a| a.effect.id() == c.id()));
    let (air, sets) = load_measured(&spec.measured)?;
    // An optical RPM sensor (a wind tunnel's, a thrust stand's optical probe) has no pole count
    // to get wrong: an RPM scale is then only its calibration.
    let uiuc = |s: &MeasuredSet| {
        matches!(
            s.format,
            propbet_measure::Format::UiucStatic | propbet_measure::Format::UiucSweep
        )
    };
    let optical = sets
        .iter()
        .all(|s| uiuc(s) || s.rpm_source == Some(propbet_measure::RpmSource::Optical));
    // Coefficients reduced with the lab's measured air: a density ratio is only its error.
    let lab_air = sets.iter().all(uiuc);
    for c in &mut candidates {
        let narrowed = match c.id() {
            "rpm-scale" if optical => Some((
                "factor",
                OPTICAL_RPM_SCALE,
                "an optical RPM sensor: no pole count to get wrong",
            )),
            "density" if lab_air => Some((
                "ratio",
                LAB_DENSITY_RATIO,
                "coefficients the lab reduced with the density it measured",
            )),
            _ => None,
        };
        if let Some((param, (lo, hi), why)) = narrowed {
            *c = std::sync::Arc::new(propbet_effects::Narrowed::new(c.clone(), &[(param, lo, hi, why)]));
        }
    }
    let points = propbet_compare::compare(&setup(model, air, Stack::baseline()), &sets)?;
    if !(spec.window.is_finite() && spec.window > 0.0 && spec.window <= 2.0) {
        invalid!("--window {}: a fraction of the zero-thrust J in (0, 2]", spec.window);
    }
    let data = Data::from_points(&points, spec.window).map_err(|e| Error::Invalid(e.to_string()))?;
    // The model's own effects stay in the model, under the candidates.
    let dmodel = propbet_diagnose::Model {
        rotor: &model.rotor,
        opts: model.opts,
        diameter: model.diameter,
        fixed: model.effects.clone(),
    };
    let opts = Options {
        folds: spec.folds,
        max_steps: spec.max_steps,
        ..Options::default()
    };
    let diagnosis = discover(&dmodel, &data, &candidates, &opts).map_err(|e| Error::Invalid(e.to_string()))?;
    Ok(Diagnosed { sets, data, diagnosis })
}

/// Reads a QPROP output file (its printed sweep), naming the file in every error.
pub fn read_qprop_output(path: &Path) -> Result<propbet_qprop::output::QpropOutput> {
    let text = read_text(path)?;
    propbet_qprop::output::parse_output(&text).map_err(|e| Error::input(path, e))
}

/// Reads APC's predictions (a PER3 file), naming the file in every error.
pub fn read_per3(path: &Path) -> Result<propbet_qprop::apc::Per3> {
    let text = read_text(path)?;
    propbet_qprop::apc::read_per3(&text, &path.display().to_string()).map_err(|e| Error::input(path, e))
}

#[cfg(test)]
mod tests;
