//! `validate_prop`: one UIUC propeller predicted from its UIUC geometry (or APC's design chord
//! and twist at UIUC's stations, [`GeometrySource`]) with APC's sections
//! (PE0 file: airfoils blended across APC's transition, scaled to the PE0 thickness ratio),
//! XFOIL polars at each station's Re, compared with every static and J-sweep file of it,
//! diagnosed, and compared again with the diagnosis' ladder of effects.

use std::path::{Path, PathBuf};

use propbet_compare::metrics::{
    in_window, quantile, regime_errors, static_figure_of_merit_error, static_rise, window_errors, zero_thrust_shift,
    RegimeError, StaticRise, ZeroThrustShift, VALIDATION_J_WINDOW,
};
use propbet_compare::ComparedPoint;
use propbet_diagnose::signature::{rpm_trend_at_fixed_j, RpmTrend};
use propbet_polar::{naca4_from_name, Airfoil};
use propbet_qprop::apc::{read_pe0, uiuc_diameter, Pe0};
use propbet_qprop::{PropFile, PropRow};

use crate::model::{as_written, LoadedProp, Model};
use crate::run::{timed, StageRecord};
use crate::spec::{
    AirSpec, CompareSpec, DiagnoseSpec, MeasuredSpec, ModelSpec, PolarsSpec, StageSpec, XfoilProcessSpec, XfoilSpec,
};
use crate::stages::{self, Compared, Diagnosed, Polars, PolarsInput};
use crate::{read_text, Error, Result};

/// Where validate reads and what it asks.
#[derive(Debug, Clone)]
pub struct ValidateSpec {
    /// UIUC directory: `<prop>_geom.txt` and the prop's static and J-sweep files.
    pub uiuc: PathBuf,
    /// APC PE0 directory.
    pub pe0: PathBuf,
    /// Airfoil coordinates (`e63.dat`, `clarky.dat`).
    pub airfoils: PathBuf,
    /// Output directory (one directory per prop below it).
    pub out: PathBuf,
    /// XFOIL executable, cache, progress.
    pub xfoil: XfoilProcessSpec,
    /// Section model: the polars as tables (true) or QPROP's law fitted to them.
    pub tables: bool,
    /// Transition amplification ratio Ncrit of the polars.
    pub ncrit: f64,
    /// More Ncrit values of the same polars, for the `transition` effect in the calibration
    /// ladders (empty: none).
    pub ncrit_effect: Vec<f64>,
    /// Rotational augmentation of the section lift.
    pub rotation: crate::spec::Rotation,
    /// Drag multiplier of the section model.
    pub drag_factor: f64,
    /// Forced transition x/c of the polars (None: free).
    pub trip: Option<f64>,
    /// APC's PER3 directory: its predictions scored beside propbet's on the same points.
    pub per3: Option<PathBuf>,
    /// Where each station's chord and twist come from.
    pub geometry: GeometrySource,
    /// TOML file of user-defined effects: candidates of every ladder beside the built-ins.
    pub user_effects: Option<PathBuf>,
}

/// Where validate takes the blade's chord and twist from (the stations are UIUC's either way).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GeometrySource {
    /// UIUC's measured r/R, c/R, β (`<prop>_geom.txt`).
    Uiuc,
    /// APC's design chord and twist (the PE0 file) at UIUC's stations.
    Pe0,
}

impl GeometrySource {
    /// Parses `uiuc` or `pe0`.
    pub fn parse(s: &str) -> Result<Self> {
        match s {
            "uiuc" => Ok(Self::Uiuc),
            "pe0" => Ok(Self::Pe0),
            _ => Err(Error::Invalid(format!("geometry {s:?}: `uiuc` or `pe0`"))),
        }
    }

    /// What the blade is, in words (the validation table's intro, the prop file's title).
    pub fn description(self) -> &'static str {
        match self {
            Self::Uiuc => "UIUC's measured chord and twist",
            Self::Pe0 => "APC's design chord and twist (PE0) at UIUC's stations",
        }
    }
}

/// The UIUC name of a file of a UIUC directory: `<family>_<D>x<P>` from `<family>_<D>x<P>_*.txt`
/// (`apcsf_10x4.7_static_kt0835.txt` → `apcsf_10x4.7`); None for a file that is not one.
pub fn uiuc_name(file: &str) -> Option<String> {
    let stem = file.strip_suffix(".txt")?;
    let mut parts = stem.splitn(3, '_');
    let (family, size, rest) = (parts.next()?, parts.next()?, parts.next()?);
    let (d, p) = size.split_once('x')?;
    let number = |s: &str| s.parse::<f64>().is_ok_and(|x| x.is_finite() && x > 0.0);
    (!family.is_empty() && number(d) && number(p) && !rest.is_empty()).then(|| format!("{family}_{size}"))
}

/// The props of a UIUC directory: every name with a geometry file (`<prop>_geom.txt`) or a
/// static or J-sweep file, sorted; a prop without a geometry file is still validated (from
/// APC's design blade) or listed with the reason, never dropped.
pub fn uiuc_props(uiuc: &Path) -> Result<Vec<String>> {
    let mut props: Vec<String> = std::fs::read_dir(uiuc)
        .map_err(|reason| Error::Read {
            path: uiuc.to_path_buf(),
            reason,
        })?
        .filter_map(|e| uiuc_name(e.ok()?.file_name().to_str()?))
        .collect();
    props.sort();
    props.dedup();
    Ok(props)
}

/// The file of `dir` named `name` as APC names it, or as it is often saved: in another case, or
/// with the size's decimal point (`10x4.7SF-PERF.PE0`, `10x47sf-perf.pe0` for
/// `10x47SF-PERF.PE0`); the exact name first. None where the directory has none.
pub fn find_apc_file(dir: &Path, name: &str) -> Option<PathBuf> {
    let exact = dir.join(name);
    if exact.is_file() {
        return Some(exact);
    }
    let key = |s: &str| s.to_ascii_uppercase().replace('.', "");
    let want = key(name);
    first_file(dir, |n| key(n) == want).ok().flatten()
}

/// The first (by name) file of `dir` whose name passes `wanted`.
fn first_file(dir: &Path, wanted: impl Fn(&str) -> bool) -> Result<Option<PathBuf>> {
    let mut found: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|reason| Error::Read {
            path: dir.to_path_buf(),
            reason,
        })?
        .filter_map(|e| {
            let e = e.ok()?;
            (wanted(e.file_name().to_str()?) && e.path().is_file()).then(|| e.path())
        })
        .collect();
    found.sort();
    Ok(found.into_iter().next())
}

/// UIUC's stations (r/R 0.15 to 1 in steps of 0.05, as its geometry files give them), in
/// hundredths (k / 100 is the double a file's "0.35" reads as): where a prop has no UIUC
/// geometry file, the blade validate predicts is APC's design chord and twist there.
const UIUC_STATIONS: (u32, u32, u32) = (15, 5, 18);

/// APC's design blade (PE0 chord and twist) at UIUC's stations, as a UIUC geometry table: the
/// stations from one step inboard of APC's first (whose chord and twist are held there, as
/// `--geometry pe0` holds them) to the tip.
pub fn pe0_table(pe0: &propbet_qprop::apc::Pe0, big_r: f64) -> Vec<propbet_measure::uiuc::GeometryRow> {
    let (start, step, n) = UIUC_STATIONS;
    let first = pe0.chord.first().map_or(0.0, |c| c.0 / big_r);
    (0..n)
        .map(|k| f64::from(start + step * k) / 100.0)
        .filter(|&x| x > first - f64::from(step) / 100.0 - 1e-9)
        .map(|x| propbet_measure::uiuc::GeometryRow {
            r_r: x,
            c_r: pe0.chord_at(x * big_r) / big_r,
            beta: pe0.twist_at(x * big_r).to_radians(),
        })
        .collect()
}

/// APC's airfoil name → a section: `APC12` is NACA 4412 (APC's note), a NACA 4-digit name is
/// generated, and any other name is looked for in the directory as coordinates whose file
/// stem is the name without case, spaces, hyphens or underscores (`CLARK-Y` → `clarky.dat`,
/// `E63` → `e63.dat`, `SD7037` → `sd7037.dat`).
fn apc_airfoil(name: &str, dir: &Path) -> Result<Airfoil> {
    let key = |s: &str| -> String {
        s.chars()
            .filter(|c| c.is_ascii_alphanumeric())
            .map(|c| c.to_ascii_lowercase())
            .collect()
    };
    let k = key(name);
    let naca = if k == "apc12" {
        "naca4412".to_string()
    } else {
        k.clone()
    };
    if let Some(foil) = naca4_from_name(&naca) {
        return foil.map_err(|e| Error::Invalid(e.to_string()));
    }
    let coordinates = first_file(dir, |n| {
        let p = Path::new(n);
        p.extension().is_some_and(|x| x.eq_ignore_ascii_case("dat"))
            && p.file_stem().and_then(|s| s.to_str()).is_some_and(|s| key(s) == k)
    })?;
    match coordinates {
        Some(file) => Ok(stages::read_airfoil(&file)?.0),
        None => Err(Error::Invalid(format!(
            "APC airfoil {name:?}: no coordinates for it in {} (a file {k}.dat; APC12 and NACA 4-digit names are generated)",
            dir.display()
        ))),
    }
}

/// The operating points a prop's polars cover: its measured RPM range (three speeds, rounded
/// out to 100 rpm) with J from 0 to the largest measured, in steps of 0.05.
fn cover(measured: &MeasuredSpec) -> Result<(Vec<f64>, Vec<f64>)> {
    let (_, sets) = stages::load_measured(measured)?;
    let points = sets.iter().flat_map(|s| &s.points);
    let (mut lo, mut hi, mut j_max) = (f64::INFINITY, 0.0f64, 0.0f64);
    for p in points {
        lo = lo.min(p.rpm());
        hi = hi.max(p.rpm());
        if let propbet_measure::Speed::AdvanceRatio(j) = p.speed {
            j_max = j_max.max(j);
        }
    }
    if !(lo.is_finite() && hi > 0.0) {
        return Err(Error::Invalid("no measured point to cover".into()));
    }
    let (lo, hi) = ((lo / 100.0).floor().max(1.0) * 100.0, (hi / 100.0).ceil() * 100.0);
    let rpms = vec![lo, (0.5 * (lo + hi) / 100.0).round() * 100.0, hi];
    let mut rpms: Vec<f64> = rpms.into_iter().map(propbet_bemt::units::rpm_to_omega).collect();
    rpms.dedup();
    let steps = (j_max / 0.05).ceil() as usize;
    let js = (0..=steps).map(|k| 0.05 * k as f64).collect();
    Ok((rpms, js))
}

/// One row of the validation table: |pred/meas − 1| of CT and CP below 85 % of each sweep's
/// zero-thrust J, before and after calibration.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Row {
    /// The UIUC name.
    pub prop: String,
    /// Points scored.
    pub points: usize,
    /// Points (of all compared) where the prediction is physically implausible (scored, and
    /// named in the prop's points.csv).
    pub implausible: usize,
    /// CT (median, p90) before and after.
    pub ct: [(f64, f64); 2],
    /// CP (median, p90) before and after.
    pub cp: [(f64, f64); 2],
    /// APC's own prediction (PER3) on the same points: CT and CP (median, p90), and the points
    /// it covers; None without `--per3` or its file.
    pub per3: Option<Per3Score>,
    /// The ladder's effects (fitted to all the prop's files: the calibration in `calibrated/`).
    pub ladder: String,
    /// The ladders fitted to each half of the files, whose predictions of the other half are
    /// the "after" columns.
    pub held_out_ladders: [String; 2],
    /// APC's design twist minus UIUC's measured β [deg], the mean over UIUC's stations at
    /// r/R 0.6-0.9 (where most of the thrust is made): what a `pitch-offset` fitted on UIUC's
    /// geometry is to be compared with (docs/studies/geometry-source.md).
    pub twist_gap: f64,
    /// UIUC has a geometry file of the prop; without one the blade is APC's design (PE0) at
    /// UIUC's stations, whatever `--geometry` asks.
    pub uiuc_geometry: bool,
    /// The section assumed for a prop without APC's sections, and why ("sd7037 t/c 0.092 (UIUC
    /// family gwsdd: not an APC propeller)"); None for APC's (PE0).
    pub assumed_section: Option<String>,
    /// The prop's files that did not read (file name, why): left out of every stage.
    pub left_out: Vec<(String, String)>,
    /// The static points' predicted figure of merit over the measured, minus 1 (median;
    /// [`static_figure_of_merit_error`]): the hover efficiency's error, whatever its split
    /// between thrust and power (docs/studies/section-scaling.md: +11 to +19 % on every shared
    /// prop). NaN without static points.
    pub static_fm: f64,
    /// Before calibration, the median signed errors by regime (static, forward flight below and
    /// above half the zero-thrust J: [`propbet_compare::metrics::REGIMES`]): which way and where.
    pub regimes: [RegimeError; 3],
    /// The static CT's rise from the lowest to the highest static RPM, measured and predicted
    /// ([`static_rise`]); None without a static test spanning 1.3x.
    pub static_rise: Option<StaticRise>,
    /// Before calibration, the CT error's change with RPM at fixed J over the J sweeps' points
    /// in the window ([`forward_rpm_trend`]): the sections' Reynolds-number dependence in
    /// forward flight, where the static rise shows it statically; None where no J bin's RPMs
    /// span 1.3x.
    pub forward_rpm_trend: Option<RpmTrend>,
    /// How the J sweeps' zero-thrust J moves with RPM, measured and predicted
    /// ([`zero_thrust_shift`]): a blade that twists nose-down as it speeds up moves the
    /// measured one down where the sections' Reynolds numbers move the model's up; None with
    /// fewer than two sweeps reaching zero thrust.
    pub zero_thrust_shift: Option<ZeroThrustShift>,
}

/// The CT error's (predicted / measured − 1) change with RPM at fixed J over the J sweeps'
/// points inside the validation window ([`propbet_diagnose::signature::rpm_trend_at_fixed_j`]:
/// the median over J bins of the slope against ln RPM, over the range the bins typically span).
pub fn forward_rpm_trend(points: &[ComparedPoint], window: f64) -> Option<RpmTrend> {
    let ok = |x: Option<f64>| x.filter(|v| v.is_finite() && *v > 0.0);
    let pts: Vec<(f64, f64, i64, f64)> = points
        .iter()
        .zip(in_window(points, window))
        .filter(|(p, inside)| *inside && !p.is_static() && p.rpm.is_finite() && p.rpm > 0.0)
        .filter_map(|(p, _)| {
            Some((
                p.j,
                p.rpm,
                0,
                p.predicted.ct.filter(|c| c.is_finite())? / ok(p.measured.ct)? - 1.0,
            ))
        })
        .collect();
    rpm_trend_at_fixed_j(&pts)
}

/// Where [`Row::twist_gap`] is averaged: r/R from 0.6 to 0.9.
pub const TWIST_GAP_SPAN: (f64, f64) = (0.6, 0.9);

/// Mean of APC's design twist minus the measured β [deg] over the stations of `table` within
/// [`TWIST_GAP_SPAN`] (NaN if none is).
pub fn twist_gap(table: &[propbet_measure::uiuc::GeometryRow], pe0: &propbet_qprop::apc::Pe0, big_r: f64) -> f64 {
    let d: Vec<f64> = table
        .iter()
        .filter(|row| row.r_r >= TWIST_GAP_SPAN.0 - 1e-9 && row.r_r <= TWIST_GAP_SPAN.1 + 1e-9)
        .map(|row| pe0.twist_at(row.r_r * big_r) - row.beta.to_degrees())
        .collect();
    if d.is_empty() {
        f64::NAN
    } else {
        d.iter().sum::<f64>() / d.len() as f64
    }
}

/// The two halves of a prop's files for the held-out calibration: sorted by the RPM in their
/// names (static files, which have none, first), alternately to each half, so that each half
/// has sweeps across the RPM range and every sweep is predicted by a ladder that did not see it.
pub fn halves(files: &[PathBuf]) -> [Vec<PathBuf>; 2] {
    let rpm = |p: &PathBuf| propbet_measure::uiuc::rpm_from_name(&p.to_string_lossy()).unwrap_or(0.0);
    let mut sorted = files.to_vec();
    sorted.sort_by(|a, b| rpm(a).total_cmp(&rpm(b)).then(a.cmp(b)));
    let mut out = [Vec::new(), Vec::new()];
    for (k, f) in sorted.into_iter().enumerate() {
        out[k % 2].push(f);
    }
    out
}

/// The ladder of one fold as the command line gives it ("none" without an effect).
fn ladder_text(effects: &[String]) -> String {
    if effects.is_empty() {
        "none".into()
    } else {
        effects.join(" + ")
    }
}

/// The median and 90th percentile of errors: the table's two numbers per quantity.
fn median_p90(v: &[f64]) -> (f64, f64) {
    (quantile(v.to_vec(), 0.5), quantile(v.to_vec(), 0.9))
}

/// APC's PER3 prediction scored as propbet's is.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Per3Score {
    /// Points scored (those inside the PER3 file's RPM and J range).
    pub points: usize,
    /// CT (median, p90).
    pub ct: (f64, f64),
    /// CP (median, p90).
    pub cp: (f64, f64),
}

/// The UIUC family of a prop name, as APC names the line: `apce_10x5` → `E`, `apcsf` → `SF`,
/// `apcsp` → `SP`, `apcff` → `FF`; other makers: their prefix.
pub fn family(prop: &str) -> String {
    let prefix = prop.split('_').next().unwrap_or(prop);
    match prefix {
        "apce" => "E".into(),
        "apcsf" => "SF".into(),
        "apcsp" => "SP".into(),
        "apcff" => "FF".into(),
        other => other.to_string(),
    }
}

/// Scores APC's PER3 prediction on the compared points: each point's predicted CT and CP
/// replaced by PER3's at its RPM and J (points outside PER3's range left out), then the same
/// window and errors as propbet's.
pub fn per3_score(per3: &propbet_qprop::apc::Per3, points: &[propbet_compare::ComparedPoint]) -> Per3Score {
    let replaced: Vec<propbet_compare::ComparedPoint> = points
        .iter()
        .map(|p| {
            let mut q = p.clone();
            let at = per3.at(p.rpm, p.j);
            q.predicted.ct = at.map(|x| x.0);
            q.predicted.cp = at.map(|x| x.1);
            q
        })
        .collect();
    let (ct, cp) = window_errors(&replaced, VALIDATION_J_WINDOW);
    Per3Score {
        points: ct.len(),
        ct: median_p90(&ct),
        cp: median_p90(&cp),
    }
}

/// Everything one prop's validation made.
pub struct Validated {
    /// The geometry's prop file (UIUC stations, generic coefficients), as written.
    pub geometry: LoadedProp,
    /// Each station's section as a Selig file: (station, text).
    pub airfoils: Vec<(usize, String)>,
    /// The polars and their inputs.
    pub polars: (Polars, PolarsInput),
    /// The prediction against the measurements, and its model.
    pub compared: (Compared, Model),
    /// The diagnosis.
    pub diagnosed: Diagnosed,
    /// The ladder's effects (as `--effect` takes them).
    pub effects: Vec<String>,
    /// The prediction with them, and its model.
    pub calibrated: (Compared, Model),
    /// The stages.
    pub stages: Vec<StageRecord>,
    /// The table's row.
    pub row: Row,
}

impl Validated {
    /// Every file read and every stage ran clean.
    pub fn clean(&self) -> bool {
        self.row.left_out.is_empty() && self.stages.iter().all(|s| s.clean)
    }
}

/// Where a prop's sections come from.
#[derive(Debug, Clone, PartialEq)]
pub enum Sections {
    /// APC's PE0 file: its airfoils across the transition, scaled to its thickness ratios.
    Apc(PathBuf),
    /// No section data (another maker's prop): one airfoil from `--airfoils` at every station,
    /// at this thickness ratio (None: the airfoil's own), on UIUC's measured blade.
    Assumed {
        /// The airfoil's name, as `--generic-section` gives it.
        airfoil: String,
        /// Thickness ratio (None: as drawn).
        thickness: Option<f64>,
        /// Why APC's are not used (another maker; no PE0 file in the directory).
        why: String,
    },
}

impl Sections {
    /// Parses `--generic-section`: `none`, `NAME` or `NAME:T/C` (the airfoil from
    /// `--airfoils`, or a NACA 4-digit name); None for `none`. `why` is left empty.
    pub fn parse_generic(text: &str) -> Result<Option<Sections>> {
        let t = text.trim();
        if t.eq_ignore_ascii_case("none") {
            return Ok(None);
        }
        let (name, tc) = match t.split_once(':') {
            None => (t, None),
            Some((n, x)) => match x.trim().parse::<f64>() {
                Ok(v) if (0.01..=0.4).contains(&v) => (n, Some(v)),
                _ => {
                    return Err(Error::Invalid(format!(
                        "--generic-section '{}': the thickness ratio after ':' must be a number in 0.01..0.4",
                        propbet_bemt::units::excerpt(t)
                    )))
                }
            },
        };
        if name.trim().is_empty() {
            return Err(Error::Invalid(format!(
                "--generic-section '{}': an airfoil name, NAME or NAME:T/C, or `none`",
                propbet_bemt::units::excerpt(t)
            )));
        }
        Ok(Some(Sections::Assumed {
            airfoil: name.trim().to_string(),
            thickness: tc,
            why: String::new(),
        }))
    }
}

/// The default of `--generic-section`: SD7037 as drawn (t/c 0.092), the best of four thin
/// low-Re sections on the two shared props of other makers (docs/studies/other-makers.md).
pub const DEFAULT_GENERIC_SECTION: &str = "sd7037";

/// A PE0 file in memory for a prop whose sections are assumed: UIUC's chord and twist, one
/// airfoil from root to tip at one thickness ratio.
fn assumed_pe0(table: &[propbet_measure::uiuc::GeometryRow], big_r: f64, airfoil: &str, tc: f64) -> Pe0 {
    let at = |f: &dyn Fn(&propbet_measure::uiuc::GeometryRow) -> f64| -> Vec<(f64, f64)> {
        table.iter().map(|row| (row.r_r * big_r, f(row))).collect()
    };
    let r0 = table.first().map_or(0.0, |row| row.r_r * big_r);
    Pe0 {
        thickness: at(&|_| tc),
        chord: at(&|row| row.c_r * big_r),
        twist: at(&|row| row.beta.to_degrees()),
        airfoils: [(r0, airfoil.to_string()), (r0, airfoil.to_string())],
    }
}

/// Validates one prop with its `sections`.
pub fn validate_prop(
    spec: &ValidateSpec,
    prop: &str,
    sections: &Sections,
    progress: &propbet_polar::Progress<'_>,
) -> Result<Validated> {
    let dir = spec.out.join(prop);
    let d = uiuc_diameter(prop).ok_or_else(|| Error::Invalid(format!("{prop}: no diameter in the name")))?;
    let big_r = 0.5 * d;
    let geom_path = spec.uiuc.join(format!("{prop}_geom.txt"));
    let uiuc_geometry = geom_path.exists();
    let uiuc_table = if uiuc_geometry {
        Some(stages::read_geometry_table(&geom_path)?)
    } else {
        None
    };
    let (pe0, assumed) = match sections {
        Sections::Apc(path) => (
            read_pe0(&read_text(path)?, &path.display().to_string()).map_err(|e| Error::Invalid(e.to_string()))?,
            None,
        ),
        Sections::Assumed {
            airfoil,
            thickness,
            why,
        } => {
            let Some(table) = &uiuc_table else {
                return Err(Error::Invalid(format!(
                    "{why}, and no UIUC geometry file: no blade to predict"
                )));
            };
            let tc = match thickness {
                Some(t) => *t,
                None => apc_airfoil(airfoil, &spec.airfoils)?.max_thickness().0,
            };
            let text = format!("{airfoil} t/c {tc:.3} ({why})");
            (assumed_pe0(table, big_r, airfoil, tc), Some(text))
        }
    };
    // UIUC's measured blade, or APC's design where UIUC has no geometry file of the prop.
    let (table, geometry_used) = match uiuc_table {
        Some(table) => (table, spec.geometry),
        None => (pe0_table(&pe0, big_r), GeometrySource::Pe0),
    };
    if table.len() < 2 {
        return Err(Error::Invalid(format!(
            "{prop}: no UIUC geometry file, and APC's PE0 blade covers fewer than two of UIUC's stations (r/R 0.15 to 1)"
        )));
    }
    let (f1, f2) = (
        apc_airfoil(&pe0.airfoils[0].1, &spec.airfoils)?,
        apc_airfoil(&pe0.airfoils[1].1, &spec.airfoils)?,
    );
    // The blade (metres) and each station's section scaled to the PE0 thickness there.
    let mut rows = Vec::new();
    let mut airfoils = Vec::new();
    for (i, row) in table.iter().enumerate() {
        let r = row.r_r * big_r;
        let (chord, beta) = match geometry_used {
            GeometrySource::Uiuc => (row.c_r * big_r, row.beta.to_degrees()),
            GeometrySource::Pe0 => (pe0.chord_at(r), pe0.twist_at(r)),
        };
        rows.push(PropRow {
            r,
            chord,
            beta,
            coeffs: Vec::new(),
        });
        let frac = pe0.blend_at(r);
        let base = if frac <= 0.0 {
            f1.clone()
        } else if frac >= 1.0 {
            f2.clone()
        } else {
            f1.blend(&f2, frac, 80).map_err(|e| Error::Invalid(e.to_string()))?
        };
        let tc = pe0.thickness_at(r);
        // APC scales its sections "based on thickness ratio" and defines pitch on a flat bottom
        // (`Airfoil::scale_as_apc`: thinned or flat-bottomed sections as a whole, thickened
        // cambered ones about their camber line; docs/studies/section-scaling.md).
        let scaled = base.scale_as_apc(tc);
        let mut foil = scaled.map_err(|e| Error::Invalid(e.to_string()))?;
        foil.name = format!("{} t/c {:.3}", base.name, tc);
        airfoils.push((i, foil.to_selig()));
    }
    let file = PropFile::metric(
        format!(
            "{prop} ({}, {})",
            geometry_used.description(),
            assumed
                .as_deref()
                .map_or("APC PE0 sections".to_string(), |a| format!("sections assumed: {a}"))
        ),
        2.0,
        big_r,
        rows,
    );
    let geometry_path = dir.join("geometry.qprop");
    let geometry = as_written(&file, &geometry_path)?;
    let foil_dir = dir.join("airfoils");
    let texts: Vec<Option<(PathBuf, String)>> = airfoils
        .iter()
        .map(|(i, t)| Some((foil_dir.join(format!("station_{i:02}.dat")), t.clone())))
        .collect();
    let mut notes = Vec::new();
    let first = stages::parse_airfoil(&airfoils[0].1, &foil_dir.join("station_00.dat"))?.0;
    let foils = stages::station_foils(&foil_dir, texts, Some(&first), &mut notes)?;
    let mut records = Vec::new();

    // The measurements: every file of this prop but the geometry.
    let mut measured: Vec<PathBuf> = std::fs::read_dir(&spec.uiuc)
        .map_err(|reason| Error::Read {
            path: spec.uiuc.clone(),
            reason,
        })?
        .filter_map(|e| {
            let n = e.ok()?.file_name().to_str()?.to_string();
            (n.starts_with(&format!("{prop}_")) && n.ends_with(".txt") && !n.ends_with("_geom.txt")).then_some(n)
        })
        .map(|n| spec.uiuc.join(n))
        .collect();
    measured.sort();
    if measured.is_empty() {
        return Err(Error::Invalid("no static or J-sweep file".into()));
    }
    // A file that does not read is left out with its reason (the row and the table say so,
    // and the command's exit is 1); the prop is validated from its others, if any.
    let mut left_out = Vec::new();
    measured.retain(|f| match stages::load_measured(&MeasuredSpec::files(vec![f.clone()])) {
        Ok(_) => true,
        Err(e) => {
            left_out.push((
                f.file_name().unwrap_or_default().to_string_lossy().into_owned(),
                e.to_string(),
            ));
            false
        }
    });
    if measured.is_empty() {
        return Err(Error::Invalid(format!(
            "no file of it reads: {}",
            left_out
                .iter()
                .map(|(_, why)| why.as_str())
                .collect::<Vec<_>>()
                .join("; ")
        )));
    }
    let measured = MeasuredSpec::files(measured);
    let (omegas, js) = cover(&measured)?;

    // Polars.
    let polars_spec = PolarsSpec {
        geometry: geometry_path,
        units: None,
        airfoil: Some(foil_dir.join("station_00.dat").display().to_string()),
        thickness: None,
        station_airfoils: Some(foil_dir),
        omegas,
        axis: crate::spec::SweepAxis::J(js),
        air: AirSpec::default(),
        xfoil: XfoilSpec {
            process: spec.xfoil.clone(),
            ncrit: spec.ncrit,
            trip: spec.trip,
            alphas_deg: crate::values::parse_list("", crate::spec::DEFAULT_ALPHA)?,
            panels: None,
            iter: xfoil_runner::DEFAULT_MAX_ITER,
        },
        ncrit_effect: spec.ncrit_effect.clone(),
        out_prop: dir.join("prop.qprop"),
        out_polars: Some(dir.join("polars.json")),
    };
    let input = PolarsInput {
        geometry: geometry.clone(),
        foils,
        foil_name: first.name.clone(),
        notes,
    };
    let engine = stages::polar_engine(&spec.xfoil)?;
    let polars = timed(
        &mut records,
        StageSpec::Polars(polars_spec.clone()),
        || stages::polars(&polars_spec, &input, &engine, progress),
        Polars::clean,
    )?;

    let model_spec = ModelSpec {
        polars: spec.tables.then(|| dir.join("polars.json")),
        rotation: spec.rotation,
        drag_factor: spec.drag_factor,
        user_effects: spec.user_effects.clone(),
        ..ModelSpec::prop(dir.join("prop.qprop"))
    };
    let model = Model::from_parts(&model_spec, polars.prop.clone(), Some(&polars.blade), false)?;
    let compare_stage = |spec: CompareSpec, model: &Model, records: &mut Vec<StageRecord>| {
        timed(
            records,
            StageSpec::Compare(spec.clone()),
            || stages::compare(model, &spec.measured),
            |c: &Compared| c.clean(),
        )
    };
    // APC's own prediction of the prop, drawn beside propbet's in its comparison.
    let per3_file = spec
        .per3
        .as_ref()
        .and_then(|dir| find_apc_file(dir, &propbet_qprop::apc::per3_name(prop)?));
    let compared = compare_stage(
        CompareSpec {
            per3: per3_file.clone(),
            qprop_output: None,
            model: model_spec.clone(),
            measured: measured.clone(),
            out: dir.join("compare"),
        },
        &model,
        &mut records,
    )?;
    let dspec = DiagnoseSpec {
        model: model_spec.clone(),
        measured: measured.clone(),
        effects: vec!["all".into()],
        folds: crate::spec::DEFAULT_FOLDS,
        max_steps: crate::spec::DEFAULT_MAX_STEPS,
        window: VALIDATION_J_WINDOW,
        out: dir.join("diagnose"),
    };
    let diagnosed = timed(
        &mut records,
        StageSpec::Diagnose(dspec.clone()),
        || stages::diagnose(&model, &dspec),
        |_| true,
    )?;
    // Calibrated: the ladder's effects as the command line gives them.
    let effects = diagnosed.diagnosis.final_effects();
    let model_spec_all = model_spec.clone();
    let cal_spec = ModelSpec {
        effects: effects.clone(),
        ..model_spec
    };
    let cal_model = Model::from_parts(&cal_spec, polars.prop.clone(), Some(&polars.blade), false)?;
    let calibrated = compare_stage(
        CompareSpec {
            per3: None,
            qprop_output: None,
            model: cal_spec,
            measured: measured.clone(),
            out: dir.join("calibrated"),
        },
        &cal_model,
        &mut records,
    )?;
    let (ct0, cp0) = window_errors(&compared.points, VALIDATION_J_WINDOW);
    // Held out: a ladder fitted to each half of the files predicts the other half; "after" is
    // scored on those predictions only.
    let (mut ct1, mut cp1) = (Vec::new(), Vec::new());
    let mut held_out_ladders = [String::new(), String::new()];
    let folds = halves(&measured.files);
    for k in 0..2 {
        let (train, test) = (&folds[k], &folds[1 - k]);
        if train.is_empty() || test.is_empty() {
            held_out_ladders[k] = "none (a single file: nothing to hold out)".into();
            continue;
        }
        let fold_spec = DiagnoseSpec {
            measured: MeasuredSpec::files(train.clone()),
            out: dir.join(format!("held_out_{k}")),
            ..dspec.clone()
        };
        let fitted = stages::diagnose(&model, &fold_spec)?;
        let fx = fitted.diagnosis.final_effects();
        held_out_ladders[k] = ladder_text(&fx);
        let fold_model_spec = ModelSpec {
            effects: fx,
            ..model_spec_all.clone()
        };
        let fold_model = Model::from_parts(&fold_model_spec, polars.prop.clone(), Some(&polars.blade), false)?;
        let predicted = stages::compare(&fold_model, &MeasuredSpec::files(test.clone()))?;
        let (a, b) = window_errors(&predicted.points, VALIDATION_J_WINDOW);
        ct1.extend(a);
        cp1.extend(b);
    }
    let per3 = match &per3_file {
        None => None,
        Some(path) => Some(per3_score(&crate::stages::read_per3(path)?, &compared.points)),
    };
    let row = Row {
        prop: prop.to_string(),
        points: ct0.len(),
        implausible: compared.points.iter().filter(|p| !p.model_flags.is_empty()).count(),
        ct: [median_p90(&ct0), median_p90(&ct1)],
        cp: [median_p90(&cp0), median_p90(&cp1)],
        per3,
        ladder: ladder_text(&effects),
        held_out_ladders,
        twist_gap: if uiuc_geometry && assumed.is_none() {
            twist_gap(&table, &pe0, big_r)
        } else {
            f64::NAN
        },
        uiuc_geometry,
        assumed_section: assumed,
        left_out,
        static_fm: static_figure_of_merit_error(&compared.points),
        regimes: regime_errors(&compared.points, VALIDATION_J_WINDOW),
        static_rise: static_rise(&compared.points),
        forward_rpm_trend: forward_rpm_trend(&compared.points, VALIDATION_J_WINDOW),
        zero_thrust_shift: zero_thrust_shift(&compared.points),
    };
    Ok(Validated {
        geometry,
        airfoils,
        polars: (polars, input),
        compared: (compared, model),
        diagnosed,
        effects,
        calibrated: (calibrated, cal_model),
        stages: records,
        row,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_forward_rpm_trend_is_the_j_sweeps_in_the_window() {
        use propbet_compare::Quantities;
        // (file, rpm, J, measured CT, CT error)
        let mk = |file: usize, rpm: f64, j: f64, ct: f64, e: f64| ComparedPoint {
            file,
            rpm,
            j,
            measured: Quantities {
                ct: Some(ct),
                ..Default::default()
            },
            predicted: Quantities {
                ct: Some(ct * (1.0 + e)),
                ..Default::default()
            },
            ..Default::default()
        };
        // Two sweeps whose CT error falls by 0.1 per e-fold of RPM at every J, each with a
        // point past 85 % of its zero-thrust J (J0 = 0.5) whose error is huge, and a static
        // test with a trend of its own: only the sweeps' points in the window count.
        let mut pts = Vec::new();
        for (file, rpm) in [(1, 3000.0f64), (2, 6000.0)] {
            let e = -0.1 * (rpm / 3000.0).ln();
            for j in [0.1, 0.2, 0.3] {
                pts.push(mk(file, rpm, j, 0.1 * (1.0 - 2.0 * j), e));
            }
            pts.push(mk(file, rpm, 0.45, 0.01, 5.0 * rpm / 3000.0));
            pts.push(mk(file, rpm, 0.55, -0.01, 0.0));
        }
        for rpm in [2000.0, 4000.0, 6000.0] {
            pts.push(mk(0, rpm, 0.0, 0.1, 0.3 * (rpm / 2000.0).ln()));
        }
        let t = forward_rpm_trend(&pts, VALIDATION_J_WINDOW).unwrap();
        assert!((t.change + 0.1 * 2f64.ln()).abs() < 1e-9, "{t:?}");
        assert_eq!((t.lo.round(), t.hi.round()), (3000.0, 6000.0));
        // One sweep: no trend.
        assert!(forward_rpm_trend(&pts[..5], VALIDATION_J_WINDOW).is_none());
    }

    #[test]
    fn halves_alternate_by_rpm_static_first() {
        let f = |n: &str| PathBuf::from(format!("uiuc/{n}.txt"));
        let files = [
            f("p_kt1_6000"),
            f("p_static_kt0"),
            f("p_kt2_4000"),
            f("p_kt3_5000"),
            f("p_kt4_5010"),
        ];
        let [a, b] = halves(&files);
        assert_eq!(a, vec![f("p_static_kt0"), f("p_kt3_5000"), f("p_kt1_6000")]);
        assert_eq!(b, vec![f("p_kt2_4000"), f("p_kt4_5010")]);
    }

    /// A temporary directory with an empty file of each name.
    fn dir_of(names: &[&str]) -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        for f in names {
            std::fs::write(dir.path().join(f), "").unwrap();
        }
        dir
    }

    #[test]
    fn every_uiuc_file_names_its_prop() {
        assert_eq!(
            uiuc_name("apcsf_10x4.7_static_kt0835.txt").as_deref(),
            Some("apcsf_10x4.7")
        );
        assert_eq!(uiuc_name("apcff_4.2x4_0617rd_6043.txt").as_deref(), Some("apcff_4.2x4"));
        assert_eq!(uiuc_name("apce_10x5_geom.txt").as_deref(), Some("apce_10x5"));
        for not in [
            "README.txt",
            "apce_10x5.txt",
            "apce_tenx5_geom.txt",
            "apce_10x5_geom.dat",
            "_10x5_a.txt",
        ] {
            assert_eq!(uiuc_name(not), None, "{not}");
        }
        // A prop with J sweeps and no geometry file is a prop of the directory, once.
        let dir = dir_of(&[
            "apce_10x5_kt0821_5000.txt",
            "apce_10x5_static_pg0819.txt",
            "apcsf_9x4.7_geom.txt",
            "notes.txt",
        ]);
        assert_eq!(uiuc_props(dir.path()).unwrap(), ["apce_10x5", "apcsf_9x4.7"]);
    }

    #[test]
    fn pe0_blade_at_uiucs_stations() {
        let inch = 0.0254;
        let pe0 = propbet_qprop::apc::Pe0 {
            thickness: vec![(1.0 * inch, 0.1), (5.0 * inch, 0.1)],
            chord: vec![(1.0 * inch, 1.0 * inch), (5.0 * inch, 0.5 * inch)],
            twist: vec![(1.0 * inch, 30.0), (5.0 * inch, 10.0)],
            airfoils: [(1.0 * inch, "E63".into()), (2.0 * inch, "E63".into())],
        };
        // R = 5 in: APC's first station at r/R 0.2, so 0.15 is the one held inboard of it.
        let t = pe0_table(&pe0, 5.0 * inch);
        assert_eq!(t.len(), 18);
        assert!((t[0].r_r - 0.15).abs() < 1e-12 && (t[17].r_r - 1.0).abs() < 1e-12);
        assert!((t[0].c_r - 0.2).abs() < 1e-12 && (t[0].beta.to_degrees() - 30.0).abs() < 1e-9);
        // r/R 0.6 = 3 in: halfway, chord 0.75 in, twist 20 deg.
        assert!((t[9].c_r - 0.15).abs() < 1e-12 && (t[9].beta.to_degrees() - 20.0).abs() < 1e-9);
        // R = 3 in: the first station at r/R 1/3, the table from 0.3.
        let t = pe0_table(&pe0, 3.0 * inch);
        assert!((t[0].r_r - 0.3).abs() < 1e-12, "{:?}", t[0]);
    }

    #[test]
    fn apc_files_are_found_as_they_are_often_saved() {
        let dir = dir_of(&[
            "10x4.7SF-PERF.PE0",
            "per3_10x47sf.dat",
            "11x7E-PERF.PE0",
            "11X7E-PERF.PE0",
        ]);
        let found =
            |n: &str| find_apc_file(dir.path(), n).map(|p| p.file_name().unwrap().to_string_lossy().into_owned());
        assert_eq!(found("10x47SF-PERF.PE0").as_deref(), Some("10x4.7SF-PERF.PE0"));
        assert_eq!(found("PER3_10x47SF.dat").as_deref(), Some("per3_10x47sf.dat"));
        // The exact name first where several match.
        assert_eq!(found("11x7E-PERF.PE0").as_deref(), Some("11x7E-PERF.PE0"));
        assert_eq!(found("10x6-PERF.PE0"), None);
        assert_eq!(find_apc_file(&dir.path().join("missing"), "10x6-PERF.PE0"), None);
    }

    #[test]
    fn apc_airfoil_names_find_their_sections() {
        let foils = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../props/airfoils");
        let name = |n: &str| apc_airfoil(n, &foils).map(|a| a.name);
        // APC12 and NACA names are generated (the same section), the others read from files.
        let apc12 = apc_airfoil("APC12", &foils).unwrap();
        let naca = apc_airfoil("NACA 4412", &foils).unwrap();
        assert_eq!(apc12.points, naca.points);
        for n in ["E63", "CLARK-Y", "Clark Y", "SD7037", "e387"] {
            assert!(name(n).is_ok(), "{n}: {:?}", name(n));
        }
        let e = name("APC-X9").unwrap_err().to_string();
        assert!(e.contains("APC airfoil \"APC-X9\"") && e.contains("apcx9.dat"), "{e}");
    }

    #[test]
    fn generic_sections_parse() {
        let assumed = |t: &str| match Sections::parse_generic(t).unwrap() {
            Some(Sections::Assumed { airfoil, thickness, .. }) => Some((airfoil, thickness)),
            _ => None,
        };
        assert_eq!(assumed("sd7037"), Some(("sd7037".into(), None)));
        assert_eq!(assumed(" naca4412:0.08 "), Some(("naca4412".into(), Some(0.08))));
        assert!(Sections::parse_generic("none").unwrap().is_none());
        for bad in ["clarky:0.9", "clarky:x", ":0.1", ""] {
            let e = Sections::parse_generic(bad).unwrap_err().to_string();
            assert!(e.contains("--generic-section"), "{bad}: {e}");
        }
    }

    #[test]
    fn an_assumed_section_rides_on_uiucs_blade() {
        let rows = [
            propbet_measure::uiuc::GeometryRow {
                r_r: 0.2,
                c_r: 0.1,
                beta: 0.5,
            },
            propbet_measure::uiuc::GeometryRow {
                r_r: 1.0,
                c_r: 0.05,
                beta: 0.2,
            },
        ];
        let p = assumed_pe0(&rows, 0.1, "sd7037", 0.092);
        assert_eq!(p.thickness_at(0.05), 0.092);
        assert!((p.chord_at(0.1) - 0.005).abs() < 1e-15 && (p.twist_at(0.02) - 0.5f64.to_degrees()).abs() < 1e-12);
        assert_eq!(p.airfoils[0].1, "sd7037");
        assert_eq!(
            p.blend_at(0.05),
            1.0,
            "one airfoil: the blend is all the second, the same"
        );
    }
}
