//! Case files (`case.toml`): what a case directory holds and asks for, checked before anything
//! runs, and the plan of stages it turns into.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::{read_text, Error, Result};
use propbet_settings::scan::ScanSettings;
use propbet_settings::spec::{CompareSpec, DiagnoseSpec, PolarsSpec, PoweredSpec, PredictSpec, ScanSpec, StageSpec};
use propbet_settings::values::parse_list;

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
    /// Effects added to the model of every stage, as `--effect` writes them
    /// (`["pitch-offset:deg=-0.8"]`): what the workbench's Save keeps.
    #[serde(default)]
    pub effects: Vec<String>,
    /// The blade.
    pub(crate) geometry: GeometrySection,
    /// XFOIL polars (without: the prop file's coefficients are used).
    pub(crate) polars: Option<PolarSection>,
    /// Prediction sweeps.
    pub(crate) sweep: SweepSection,
    /// Measurements (without: no comparison, no diagnosis).
    pub(crate) measured: Option<MeasuredSection>,
    /// Air of the measurements and sweeps.
    #[serde(default)]
    pub(crate) atmosphere: AtmosphereSection,
    /// The motor of the measurements (its current and electrical power scored against the
    /// log's), and of the powered table (with a driver: `volts`, `amps`, `thrust` or
    /// `throttle`).
    pub(crate) motor: Option<MotorSection>,
    /// The battery in front of the motor (with `[motor]`).
    pub(crate) battery: Option<BatterySection>,
    /// The ESC between the battery and the motor (with `[battery]`).
    pub(crate) esc: Option<EscSection>,
}

/// `[motor]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct MotorSection {
    /// A QPROP motor file relative to the case directory.
    pub file: String,
    /// Terminal voltages [V] of the powered table (`propbet predict --motor --volts`).
    pub volts: Option<NumberOrList>,
    /// Motor currents [A] of the powered table.
    pub amps: Option<NumberOrList>,
    /// Thrusts [N] of the powered table (hover: the weight this propeller carries).
    pub thrust: Option<NumberOrList>,
    /// Throttles (0 to 1) of the powered table, with `[battery]`.
    pub throttle: Option<NumberOrList>,
    /// Airspeeds [m/s] of the powered table (default: 0, static).
    pub v: Option<NumberOrList>,
}

/// `[battery]`: cells in series, each an open-circuit voltage behind a resistance
/// (`propbet predict --battery`; LiPo defaults for what is not given).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BatterySection {
    /// Cells in series.
    pub cells: u32,
    /// Capacity [mAh] (without: no endurance).
    pub capacity_mah: Option<f64>,
    /// Open-circuit voltage of a cell [V].
    pub cell_volts: Option<f64>,
    /// Internal resistance of a cell [ohm].
    pub cell_ohms: Option<f64>,
    /// The lowest loaded cell voltage allowed [V].
    pub cutoff_volts: Option<f64>,
    /// The fraction of the capacity used (0 to 1).
    pub usable: Option<f64>,
}

/// `[esc]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct EscSection {
    /// Resistance in the motor's current path [ohm] (`--esc-ohms`).
    pub ohms: f64,
}

/// `[geometry]`: a scan or a prop file, and the scan's settings.
#[derive(Debug, Deserialize)]
#[serde(try_from = "toml::Table")]
pub(crate) struct GeometrySection {
    /// A scan (STL, PLY, points3D.txt, XYZ) for `propbet scan`.
    pub scan: Option<String>,
    /// Or a blade file: a QPROP prop file, APC's design file (PE0), a UIUC geometry table or
    /// a blade table (CSV).
    pub prop: Option<String>,
    /// APC's design file (PE0): the blade and its sections, or with `prop` (UIUC's measured
    /// table of the same prop) the sections alone, as `propbet validate` models APC's props.
    pub pe0: Option<String>,
    /// A UIUC-style table (r/R c/R beta) to set the scan against.
    pub reference: Option<String>,
    /// The scan's settings, each a key named as its `propbet scan` flag (`units` and
    /// `stations`, `crop`, `outliers`, `box`, ...; `units` is a prop file's unit too). Any
    /// other key is refused.
    pub settings: ScanSettings,
}

impl TryFrom<toml::Table> for GeometrySection {
    type Error = String;

    /// The section's own keys, then the rest as the scan's settings (an unknown key is
    /// refused there, with the keys it takes).
    fn try_from(mut t: toml::Table) -> std::result::Result<Self, String> {
        fn text(t: &mut toml::Table, key: &str) -> std::result::Result<Option<String>, String> {
            match t.remove(key) {
                None => Ok(None),
                Some(toml::Value::String(s)) => Ok(Some(s)),
                Some(v) => Err(format!("[geometry] {key}: expected a string, found {}", v.type_str())),
            }
        }
        let scan = text(&mut t, "scan")?;
        let prop = text(&mut t, "prop")?;
        let pe0 = text(&mut t, "pe0")?;
        let reference = text(&mut t, "reference")?;
        if t.contains_key("scan_args") {
            return Err("[geometry] scan_args: removed in 0.2.0; write each flag of `propbet scan` as a key of [geometry] (`--outliers 8,3` as `outliers = \"8,3\"`, `--planar` as `planar = true`)".into());
        }
        let settings = toml::Value::Table(t.clone()).try_into().map_err(|e: toml::de::Error| {
            // The key whose value is refused (serde names an unknown one, not a wrong one).
            let wrong = t.iter().find(|(k, v)| {
                let one = toml::Table::from_iter([((*k).clone(), (*v).clone())]);
                toml::Value::Table(one).try_into::<ScanSettings>().is_err()
            });
            match wrong {
                Some((k, _)) if !e.message().starts_with("unknown field") => {
                    format!("[geometry] {k}: {}", e.message())
                }
                _ => format!("[geometry]: {} (or `scan`, `prop`, `pe0`, `reference`)", e.message()),
            }
        })?;
        Ok(GeometrySection {
            scan,
            prop,
            pe0,
            reference,
            settings,
        })
    }
}

/// `[polars]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PolarSection {
    /// `scan`: each station's section as the scan fitted it (the airfoil where the scan gave
    /// none); `airfoil`: the airfoil at every station (or airfoils blended along the blade,
    /// `E63@0.25,APC12@0.45`); `design`: the sections the blade file names (APC's PE0, a
    /// table's airfoil column). Default: the geometry's (a scan's, a PE0's, else `airfoil`).
    pub sections: Option<String>,
    /// Coordinate file (relative to the case) or a NACA 4-digit name: the section at every
    /// station (`sections = "airfoil"`, where it is required) or where the scan gave none
    /// (`sections = "scan"`; without it such a station takes the nearest station's section).
    pub airfoil: Option<String>,
    /// Scale the airfoil to this thickness ratio.
    pub thickness: Option<String>,
    /// Rotation speeds whose Reynolds numbers the polars cover [rpm]: a number or a list as
    /// `propbet polars --rpm` takes it (default: the sweep's).
    pub rpm: Option<NumberOrList>,
    /// Advance ratios they cover, as `--j` takes them (default: the sweep's, unless `v` is
    /// given).
    pub j: Option<String>,
    /// Axial speeds they cover [m/s] instead of advance ratios: a number or a list.
    pub v: Option<NumberOrList>,
    /// Transition amplification ratio.
    pub ncrit: Option<f64>,
    /// More Ncrit values to compute the same polars at, for the `transition` effect (a number
    /// or a list, `"3,9"`); each doubles the XFOIL time.
    pub ncrit_effect: Option<NumberOrList>,
    /// Forced transition x/c on both surfaces, or `"free"` (default:
    /// [`propbet_settings::TRIP`]).
    pub trip: Option<NumberOrList>,
    /// Angles of attack (`propbet polars --alpha`).
    pub alpha: Option<String>,
    /// The section model of the sweeps, comparison and diagnosis: `tables` (the polars
    /// themselves, interpolated in alpha and Re; the default) or `qprop` (QPROP's law fitted
    /// to them, as the exported prop file holds it).
    #[serde(default = "default_model")]
    pub model: String,
    /// Rotational augmentation of the section lift: `off` or `snel` (default: the tabulated
    /// model's default; off with `model = "qprop"`).
    pub rotation: Option<String>,
    /// Which program makes the polars: `xfoil`, `neuralfoil` or `auto`
    /// ([`propbet_settings::ENGINE`]; default: the command line's).
    pub engine: Option<String>,
    /// NeuralFoil's network size ([`propbet_settings::NEURALFOIL_SIZE`]).
    pub neuralfoil_size: Option<String>,
    /// Every section's drag times this (default: the tabulated model's default,
    /// [`propbet_settings::DRAG_FACTOR`]; 1 with `model = "qprop"`).
    pub drag_factor: Option<f64>,
}

/// A number, or a list as the command line writes it (`"2000:7000:1000"`).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(crate) enum NumberOrList {
    /// `rpm = 5000`.
    Number(f64),
    /// `rpm = "2000:7000:1000"`.
    List(String),
}

impl NumberOrList {
    fn values(&self, flag: &str) -> Result<Vec<f64>> {
        match self {
            NumberOrList::Number(x) => Ok(vec![*x]),
            NumberOrList::List(t) => Ok(parse_list(flag, t)?),
        }
    }
}

fn default_model() -> String {
    "tables".into()
}

/// `[sweep]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SweepSection {
    /// Rotation speeds [rpm]: a list or a range.
    pub rpm: String,
    /// Advance ratios: a list or a range.
    pub j: String,
}

/// `[measured]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct MeasuredSection {
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
    /// APC's predictions for the prop (a PER3 file), drawn and scored beside propbet's.
    pub per3: Option<String>,
    /// User-defined effects (TOML, docs/effects.md): candidates of the diagnosis beside the
    /// built-ins.
    pub user_effects: Option<String>,
}

/// `[atmosphere]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct AtmosphereSection {
    /// `T,P,RH` as `--atmosphere` takes it (overrides what the logs say).
    pub air: Option<String>,
    /// Air density [kg/m^3] (overrides everything).
    pub rho: Option<f64>,
}

/// Reads and checks `case.toml`.
pub fn read_case(dir: &Path) -> Result<Case> {
    let path = dir.join("case.toml");
    let text = read_text(&path)?;
    let mut case: Case = toml::from_str(&text).map_err(|e| {
        let at = e
            .span()
            .map_or_else(String::new, |s| format!("{}: ", propbet_units::place(&text, s.start)));
        Error::input(&path, format!("{at}{}", e.message()))
    })?;
    case.name = propbet_units::printable(&case.name);
    let g = &case.geometry;
    if g.scan.is_some() == (g.prop.is_some() || g.pe0.is_some()) {
        return Err(Error::input(
            &path,
            "[geometry] needs a `scan`, or a `prop` and / or a `pe0` (APC's design file)",
        ));
    }
    // Every file the case names must be there before anything runs.
    let named = [g.scan.as_ref(), g.prop.as_ref(), g.pe0.as_ref(), g.reference.as_ref()]
        .into_iter()
        .flatten()
        .chain(
            case.measured
                .iter()
                .flat_map(|m| m.files.iter().chain(m.columns.as_ref())),
        );
    for f in named {
        if !dir.join(f).is_file() {
            return Err(Error::input(
                &path,
                format!("names {f}, which is not in {}", dir.display()),
            ));
        }
    }
    // A blade file other than QPROP's has no section coefficients: its polars are computed.
    let design = g.pe0.is_some()
        || g.prop.as_ref().is_some_and(|p| {
            propbet_model::design::format_of_file(&dir.join(p)) != propbet_model::design::BladeFormat::Qprop
        });
    if design && case.polars.is_none() {
        case.polars = Some(toml::from_str("").map_err(|e| Error::input(&path, e.message()))?);
    }
    let g = &case.geometry;
    if let Some(p) = &mut case.polars {
        let default = if g.scan.is_some() {
            "scan"
        } else if g.pe0.is_some() || (design && p.airfoil.is_none()) {
            "design"
        } else {
            "airfoil"
        };
        let sections = p.sections.get_or_insert_with(|| default.to_string()).clone();
        if !["scan", "airfoil", "design"].contains(&sections.as_str()) {
            return Err(Error::input(
                &path,
                format!("[polars] sections = {sections:?}: `scan`, `airfoil` or `design`"),
            ));
        }
        if sections == "airfoil" && p.airfoil.is_none() {
            return Err(Error::input(
                &path,
                "[polars] sections = \"airfoil\" needs `airfoil`, the section of every station",
            ));
        }
        if sections == "scan" && g.scan.is_none() {
            return Err(Error::input(
                &path,
                "[polars] sections = \"scan\" needs a [geometry] scan",
            ));
        }
        if sections == "design" && !design {
            return Err(Error::input(
                &path,
                "[polars] sections = \"design\" needs a [geometry] pe0, or a prop that is a PE0 file or a table naming its airfoils",
            ));
        }
        propbet_settings::SECTION_MODEL
            .choose(&p.model)
            .map_err(|e| at_key(&path, "[polars] model", e))?;
        if let Some(e) = &p.engine {
            propbet_settings::ENGINE
                .choose(e)
                .map_err(|e| at_key(&path, "[polars] engine", e))?;
        }
        if let Some(s) = &p.neuralfoil_size {
            propbet_settings::NEURALFOIL_SIZE
                .choose(s)
                .map_err(|e| at_key(&path, "[polars] neuralfoil_size", e))?;
        }
        if let Some(x) = p.ncrit {
            propbet_settings::NCRIT
                .check(x)
                .map_err(|e| at_key(&path, "[polars] ncrit", e))?;
        }
        if let Some(x) = p.drag_factor {
            propbet_settings::DRAG_FACTOR
                .check(x)
                .map_err(|e| at_key(&path, "[polars] drag_factor", e))?;
        }
        if p.j.is_some() && p.v.is_some() {
            return Err(Error::input(&path, "[polars] takes `j` or `v`, not both"));
        }
    }
    Ok(case)
}

/// The stages a case asks for, as specs.
#[derive(Debug, Clone, PartialEq)]
pub struct RunPlan {
    /// The case's name.
    pub name: String,
    /// Its description.
    pub description: String,
    /// The case directory.
    pub dir: PathBuf,
    /// The output directory.
    pub out: PathBuf,
    /// Blade count the scan must find.
    pub blades: Option<usize>,
    /// Geometry from a scan (None: the case's prop file).
    pub scan: Option<ScanSpec>,
    /// XFOIL polars; `true` with each station's scanned section.
    pub polars: Option<(PolarsSpec, bool)>,
    /// Sweeps.
    pub predict: PredictSpec,
    /// The propeller on its motor (a case with `[motor]` and a driver).
    pub powered: Option<PoweredSpec>,
    /// Comparison and diagnosis.
    pub compare: Option<(CompareSpec, DiagnoseSpec)>,
    /// How close a prediction of this kind of blade has come on propbet's validation, before
    /// any measurement ([`propbet_compare::expected::sentence`] of the blade's file: its APC family, or
    /// all the props for a scan or a table of no named family).
    pub expected: Option<String>,
}

impl RunPlan {
    /// The files the plan reads from the case (not those its own stages write).
    pub fn inputs(&self) -> Vec<PathBuf> {
        let mut v = Vec::new();
        match &self.scan {
            Some(s) => {
                v.push(s.input.clone());
                v.extend(s.reference.clone());
            }
            // Without a scan, the case's own prop file is the polars stage's geometry, or the
            // sweep's blade when there is no polars stage (whose fitted file is an output).
            None => match &self.polars {
                Some((p, _)) => v.push(p.geometry.clone()),
                None => v.push(self.predict.model.prop.clone()),
            },
        }
        if let Some(a) = self.polars.as_ref().and_then(|(p, _)| p.airfoil.as_ref()) {
            // Its names that are files (the plan wrote them as paths), not propbet's own.
            v.extend(propbet_model::design::resolve_in(a, Path::new("")).1);
        }
        if let Some(s) = self.polars.as_ref().and_then(|(p, _)| p.sections_from.as_ref()) {
            v.push(s.clone());
        }
        if let Some((c, d)) = &self.compare {
            v.extend(c.measured.inputs().into_iter().map(Path::to_path_buf));
            v.extend(c.per3.clone());
            v.extend(c.motor.clone());
            v.extend(d.model.user_effects.clone());
        }
        if let Some(p) = &self.powered {
            v.push(p.motor.clone());
        }
        v
    }

    /// The files the case names that lie outside its folder, links followed (`/etc/passwd`,
    /// `../../x`, a link to a system file): a case reads its own files unless its run says
    /// otherwise (`run --inputs-anywhere`).
    pub fn outside_inputs(&self) -> Vec<PathBuf> {
        let Ok(root) = self.dir.canonicalize() else {
            return Vec::new();
        };
        self.inputs()
            .into_iter()
            .filter(|f| f.canonicalize().is_ok_and(|c| !c.starts_with(&root)))
            .collect()
    }

    /// The files the case names that do not exist (a NACA name instead of an airfoil file is
    /// not a file): checked before the first stage runs, so a copied case whose relative paths
    /// no longer resolve fails at once, with nothing written.
    pub fn missing_inputs(&self) -> Vec<PathBuf> {
        self.inputs().into_iter().filter(|f| !f.exists()).collect()
    }

    /// The specs in the order they run.
    pub fn stages(&self) -> Vec<StageSpec> {
        let mut v = Vec::new();
        if let Some(s) = &self.scan {
            v.push(StageSpec::Scan(s.clone()));
        }
        if let Some((p, _)) = &self.polars {
            v.push(StageSpec::Polars(p.clone()));
        }
        v.push(StageSpec::Predict(self.predict.clone()));
        if let Some(p) = &self.powered {
            v.push(StageSpec::Powered(p.clone()));
        }
        if let Some((c, d)) = &self.compare {
            v.push(StageSpec::Compare(c.clone()));
            v.push(StageSpec::Diagnose(d.clone()));
        }
        v
    }
}

/// An error of a case key, naming the case file and the key; a declared setting's wrong value
/// as the key writes it (`[polars] ncrit = 25: ...`).
fn at_key(case_file: &Path, key: &str, e: impl Into<Error>) -> Error {
    // A key of its own (`[polars] ncrit`, not the section `[geometry]`): its value as the key
    // writes it.
    let one_key = key.contains("] ");
    match e.into() {
        Error::Settings(propbet_settings::Error::Setting(b)) if one_key => {
            Error::input(case_file, format!("{key} = {}: {}", b.value, b.meaning))
        }
        Error::Settings(propbet_settings::Error::Value { text, problem, .. }) if one_key => {
            Error::input(case_file, format!("{key} = '{text}': {problem}"))
        }
        e => Error::input(case_file, format!("{key}: {e}")),
    }
}

mod plan;

#[cfg(test)]
mod tests;
