//! Case files (`case.toml`): what a case directory holds and asks for, checked before anything
//! runs, and the plan of stages it turns into.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use propbet_bemt::units::rpm_to_omega;
use propbet_geometry::scan::ScanOptions;
use propbet_measure::RpmSource;

use crate::spec::{
    AirSpec, CompareSpec, DiagnoseSpec, MeasuredSpec, ModelSpec, PolarsSpec, PredictSpec, ScanSpec, StageSpec,
    SweepAxis, TableFormat, XfoilProcessSpec, XfoilSpec,
};
use crate::values::{parse_atmosphere, parse_length_unit, parse_list};
use crate::{read_text, Error, Result};

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
    pub geometry: GeometrySection,
    /// XFOIL polars (without: the prop file's coefficients are used).
    pub polars: Option<PolarSection>,
    /// Prediction sweeps.
    pub sweep: SweepSection,
    /// Measurements (without: no comparison, no diagnosis).
    pub measured: Option<MeasuredSection>,
    /// Air of the measurements and sweeps.
    #[serde(default)]
    pub atmosphere: AtmosphereSection,
}

/// `[geometry]`: a scan or a prop file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GeometrySection {
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
pub struct PolarSection {
    /// `scan`: each station's section as the scan fitted it (the airfoil where the scan gave
    /// none); `airfoil`: the airfoil at every station.
    #[serde(default = "default_sections")]
    pub sections: String,
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
    /// [`crate::settings::TRIP`]).
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
    /// Every section's drag times this (default: the tabulated model's default,
    /// [`crate::settings::DRAG_FACTOR`]; 1 with `model = "qprop"`).
    pub drag_factor: Option<f64>,
}

/// A number, or a list as the command line writes it (`"2000:7000:1000"`).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum NumberOrList {
    /// `rpm = 5000`.
    Number(f64),
    /// `rpm = "2000:7000:1000"`.
    List(String),
}

impl NumberOrList {
    fn values(&self, flag: &str) -> Result<Vec<f64>> {
        match self {
            NumberOrList::Number(x) => Ok(vec![*x]),
            NumberOrList::List(t) => parse_list(flag, t),
        }
    }
}

fn default_model() -> String {
    "tables".into()
}

fn default_sections() -> String {
    "scan".into()
}

/// `[sweep]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSection {
    /// Rotation speeds [rpm]: a list or a range.
    pub rpm: String,
    /// Advance ratios: a list or a range.
    pub j: String,
}

/// `[measured]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeasuredSection {
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
pub struct AtmosphereSection {
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
    if g.scan.is_some() == g.prop.is_some() {
        return Err(Error::input(&path, "[geometry] needs exactly one of `scan` and `prop`"));
    }
    if let Some(p) = &case.polars {
        if p.sections != "scan" && p.sections != "airfoil" {
            return Err(Error::input(
                &path,
                format!("[polars] sections = {:?}: `scan` or `airfoil`", p.sections),
            ));
        }
        if p.sections == "airfoil" && p.airfoil.is_none() {
            return Err(Error::input(
                &path,
                "[polars] sections = \"airfoil\" needs `airfoil`, the section of every station",
            ));
        }
        if p.sections == "scan" && g.scan.is_none() {
            return Err(Error::input(
                &path,
                "[polars] sections = \"scan\" needs a [geometry] scan",
            ));
        }
        crate::settings::SECTION_MODEL
            .choose(&p.model)
            .map_err(|e| at_key(&path, "[polars] model", e))?;
        if let Some(x) = p.ncrit {
            crate::settings::NCRIT
                .check(x)
                .map_err(|e| at_key(&path, "[polars] ncrit", e))?;
        }
        if let Some(x) = p.drag_factor {
            crate::settings::DRAG_FACTOR
                .check(x)
                .map_err(|e| at_key(&path, "[polars] drag_factor", e))?;
        }
        if p.j.is_some() && p.v.is_some() {
            return Err(Error::input(&path, "[polars] takes `j` or `v`, not both"));
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
            return Err(Error::input(
                &path,
                format!("names {f}, which is not in {}", dir.display()),
            ));
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
    /// Comparison and diagnosis.
    pub compare: Option<(CompareSpec, DiagnoseSpec)>,
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
            v.push(PathBuf::from(a));
        }
        if let Some((c, _)) = &self.compare {
            v.extend(c.measured.inputs().into_iter().map(Path::to_path_buf));
            v.extend(c.per3.clone());
        }
        v
    }

    /// The files the case names that do not exist (a NACA name instead of an airfoil file is
    /// not a file): checked before the first stage runs, so a copied case whose relative paths
    /// no longer resolve fails at once, with nothing written.
    pub fn missing_inputs(&self) -> Vec<PathBuf> {
        let naca = self
            .polars
            .as_ref()
            .and_then(|(p, _)| p.airfoil.as_ref())
            .filter(|a| propbet_polar::naca4_from_name(a).is_some())
            .map(PathBuf::from);
        self.inputs()
            .into_iter()
            .filter(|f| Some(f) != naca.as_ref() && !f.exists())
            .collect()
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
        if let Some((c, d)) = &self.compare {
            v.push(StageSpec::Compare(c.clone()));
            v.push(StageSpec::Diagnose(d.clone()));
        }
        v
    }
}

impl Case {
    /// The scan stage's spec, where the case has a scan: its options from `[geometry]`.
    fn scan_spec(
        &self,
        dir: &Path,
        out: &Path,
        scan_options: &dyn Fn(&[String]) -> Result<ScanOptions>,
    ) -> Result<Option<ScanSpec>> {
        let g = &self.geometry;
        let f = |rel: &str| dir.join(rel);
        let case_file = dir.join("case.toml");
        let at = |key: &str, e: Error| at_key(&case_file, key, e);
        Ok(match &g.scan {
            Some(file) => {
                let mut flags = Vec::new();
                if let Some(u) = &g.units {
                    flags.extend(["--units".to_string(), u.clone()]);
                }
                if let Some(s) = &g.stations {
                    flags.extend(["--stations".to_string(), s.clone()]);
                }
                // The flags that name a file or the output have keys of their own in a case:
                // refused here rather than read and ignored.
                for (flag, key) in [
                    ("--reference", "`reference` in [geometry]"),
                    ("--name", "the case's `name`"),
                    ("--out", "`propbet run -o`"),
                    ("-o", "`propbet run -o`"),
                ] {
                    if g.scan_args
                        .iter()
                        .any(|a| a == flag || a.starts_with(&format!("{flag}=")))
                    {
                        return Err(at(
                            "[geometry] scan_args",
                            Error::Invalid(format!("{flag} is set by {key}")),
                        ));
                    }
                }
                flags.extend(g.scan_args.iter().cloned());
                Some(ScanSpec {
                    input: f(file),
                    options: scan_options(&flags).map_err(|e| at("[geometry]", e))?,
                    reference: g.reference.as_deref().map(f),
                    name: Some(self.name.clone()),
                    out: out.join("scan"),
                })
            }
            None => None,
        })
    }

    /// The polars stage's spec, where the case has `[polars]`, and whether its sections are the
    /// scan's.
    fn polars_spec(
        &self,
        dir: &Path,
        out: &Path,
        geometry: &Path,
        units: Option<f64>,
        xfoil: &XfoilProcessSpec,
    ) -> Result<Option<(PolarsSpec, bool)>> {
        let f = |rel: &str| dir.join(rel);
        let case_file = dir.join("case.toml");
        let at = |key: &str, e: Error| at_key(&case_file, key, e);
        Ok(match &self.polars {
            None => None,
            Some(p) => {
                let airfoil = p.airfoil.as_ref().map(|a| {
                    if propbet_polar::naca4_from_name(a).is_some() {
                        a.clone()
                    } else {
                        f(a).display().to_string()
                    }
                });
                let alpha = p.alpha.as_deref().unwrap_or(crate::settings::ALPHA.default);
                let mut alphas = parse_list("--alpha", alpha).map_err(|e| at("[polars] alpha", e))?;
                alphas.sort_by(f64::total_cmp);
                alphas.dedup();
                // The operating points the polars cover: the sweep's, unless the case says.
                let rpms = match &p.rpm {
                    Some(r) => r.values("--rpm").map_err(|e| at("[polars] rpm", e))?,
                    None => parse_list("--rpm", &self.sweep.rpm).map_err(|e| at("[sweep] rpm", e))?,
                };
                let axis = match (&p.j, &p.v) {
                    (_, Some(v)) => SweepAxis::V(v.values("--v").map_err(|e| at("[polars] v", e))?),
                    (Some(j), None) => SweepAxis::J(parse_list("--j", j).map_err(|e| at("[polars] j", e))?),
                    (None, None) => SweepAxis::J(parse_list("--j", &self.sweep.j).map_err(|e| at("[sweep] j", e))?),
                };
                let thickness = p
                    .thickness
                    .as_deref()
                    .map(parse_fraction)
                    .transpose()
                    .map_err(|e| at("[polars] thickness", e))?;
                let scanned = p.sections == "scan";
                Some((
                    PolarsSpec {
                        geometry: geometry.to_path_buf(),
                        units,
                        airfoil,
                        thickness,
                        station_airfoils: scanned.then(|| out.join("scan/airfoils")),
                        omegas: rpms.into_iter().map(rpm_to_omega).collect(),
                        axis,
                        air: AirSpec::default(),
                        xfoil: XfoilSpec {
                            process: xfoil.clone(),
                            ncrit: p.ncrit.unwrap_or(crate::settings::NCRIT.default),
                            trip: match &p.trip {
                                None => Some(crate::settings::TRIP.default),
                                Some(NumberOrList::Number(x)) => {
                                    crate::values::parse_trip(&x.to_string()).map_err(|e| at("[polars] trip", e))?
                                }
                                Some(NumberOrList::List(t)) => {
                                    crate::values::parse_trip(t).map_err(|e| at("[polars] trip", e))?
                                }
                            },
                            alphas_deg: alphas,
                            panels: None,
                            iter: xfoil_runner::DEFAULT_MAX_ITER,
                        },
                        ncrit_effect: match &p.ncrit_effect {
                            None => Vec::new(),
                            Some(n) => n
                                .values("--ncrit-effect")
                                .and_then(|v| {
                                    crate::spec::check_ncrit_effect(
                                        &v,
                                        p.ncrit.unwrap_or(crate::settings::NCRIT.default),
                                    )
                                })
                                .map_err(|e| at("[polars] ncrit_effect", e))?,
                        },
                        out_prop: out.join("polars/prop.qprop"),
                        out_polars: Some(out.join("polars/polars.json")),
                    },
                    scanned,
                ))
            }
        })
    }

    /// The compare and diagnose stages' specs, where the case has `[measured]`.
    fn compare_specs(
        &self,
        dir: &Path,
        out: &Path,
        model: ModelSpec,
        state: Option<propbet_atmosphere::AirState>,
    ) -> Result<Option<(CompareSpec, DiagnoseSpec)>> {
        let a = &self.atmosphere;
        let f = |rel: &str| dir.join(rel);
        let case_file = dir.join("case.toml");
        let at = |key: &str, e: Error| at_key(&case_file, key, e);
        Ok(match &self.measured {
            None => None,
            Some(m) => {
                let rpm_source = match m.rpm_source.as_deref() {
                    None => None,
                    Some(x) => match crate::settings::RPM_SOURCE
                        .choose(x)
                        .map_err(|e| at("[measured] rpm_source", e.into()))?
                    {
                        "optical" => Some(RpmSource::Optical),
                        _ => Some(RpmSource::Electrical),
                    },
                };
                // A user-effects file that does not read stops the run before its first stage.
                let user_effects = m.user_effects.as_deref().map(f);
                crate::model::effect_registry(user_effects.as_deref()).map_err(|e| at("[measured] user_effects", e))?;
                let measured = MeasuredSpec {
                    files: m.files.iter().map(|x| f(x)).collect(),
                    poles: m.poles,
                    rpm_source,
                    atmosphere: state,
                    rho: a.rho,
                    columns: m.columns.as_deref().map(f),
                };
                Some((
                    CompareSpec {
                        model: model.clone(),
                        measured: measured.clone(),
                        per3: m.per3.as_deref().map(f),
                        qprop_output: None,
                        out: out.join("compare"),
                    },
                    DiagnoseSpec {
                        model: ModelSpec { user_effects, ..model },
                        measured,
                        effects: vec!["all".into()],
                        folds: crate::settings::FOLDS
                            .check(m.folds.unwrap_or(crate::settings::FOLDS.default))
                            .map_err(|e| at("[measured] folds", e.into()))?,
                        max_steps: m.max_steps.unwrap_or(crate::settings::MAX_STEPS.default),
                        window: propbet_compare::metrics::VALIDATION_J_WINDOW,
                        out: out.join("diagnose"),
                    },
                ))
            }
        })
    }

    /// The plan of stages: each stage's spec, reading from `dir` and writing under `out`.
    /// `scan_options` turns the scan's flags (`--units`, `--stations` and the case's
    /// `scan_args`) into the geometry pipeline's options: flags are the CLI's to read.
    pub fn plan(
        &self,
        dir: &Path,
        out: &Path,
        xfoil: &XfoilProcessSpec,
        scan_options: &dyn Fn(&[String]) -> Result<ScanOptions>,
    ) -> Result<RunPlan> {
        let g = &self.geometry;
        let f = |rel: &str| dir.join(rel);
        let case_file = dir.join("case.toml");
        let at = |key: &str, e: Error| at_key(&case_file, key, e);
        let units = match (&g.prop, &g.units) {
            (Some(_), Some(u)) => Some(parse_length_unit(u).map_err(|e| at("[geometry] units", e))?),
            _ => None,
        };
        let scan = self.scan_spec(dir, out, scan_options)?;
        let geometry = match &g.scan {
            Some(_) => out.join("scan/prop.qprop"),
            None => f(g.prop.as_deref().unwrap_or_default()),
        };
        let polars = self.polars_spec(dir, out, &geometry, units, xfoil)?;
        // The fitted prop file is in metres; a case's own prop file keeps its units. With
        // tables, the polars are the section model (the prop file gives the blade).
        let (prop, model_units) = match &polars {
            Some(_) => (out.join("polars/prop.qprop"), None),
            None => (geometry, units),
        };
        let tables = self.polars.as_ref().is_some_and(|p| p.model == "tables");
        let rotation = self
            .polars
            .as_ref()
            .and_then(|p| p.rotation.as_deref())
            .map(crate::spec::Rotation::parse)
            .transpose()
            .map_err(|e| at("[polars] rotation", e.into()))?;
        let model = ModelSpec {
            units: model_units,
            polars: tables.then(|| out.join("polars/polars.json")),
            rotation: crate::spec::Rotation::or_default(rotation, tables),
            drag_factor: crate::spec::drag_factor_or_default(self.polars.as_ref().and_then(|p| p.drag_factor), tables),
            ..ModelSpec::prop(prop)
        };
        let a = &self.atmosphere;
        let state = a
            .air
            .as_deref()
            .map(parse_atmosphere)
            .transpose()
            .map_err(|e| at("[atmosphere] air", e))?;
        let rpms = parse_list("--rpm", &self.sweep.rpm).map_err(|e| at("[sweep] rpm", e))?;
        let js = parse_list("--j", &self.sweep.j).map_err(|e| at("[sweep] j", e))?;
        let predict = PredictSpec {
            model: model.clone(),
            omegas: rpms.into_iter().map(rpm_to_omega).collect(),
            axis: SweepAxis::J(js),
            air: AirSpec {
                rho: a.rho,
                state,
                ..AirSpec::default()
            },
            format: TableFormat::Csv,
            out: Some(out.join("predict/sweep.csv")),
            stations: None,
        };
        let compare = self.compare_specs(dir, out, model, state)?;
        Ok(RunPlan {
            name: self.name.clone(),
            description: self.description.clone(),
            dir: dir.to_path_buf(),
            out: out.to_path_buf(),
            blades: self.blades,
            scan,
            polars,
            predict,
            compare,
        })
    }
}

/// An error of a case key, naming the case file and the key; a declared setting's wrong value
/// as the key writes it (`[polars] ncrit = 25: ...`).
fn at_key(case_file: &Path, key: &str, e: impl Into<Error>) -> Error {
    match e.into() {
        Error::Setting(b) => Error::input(case_file, format!("{key} = {}: {}", b.value, b.meaning)),
        e => Error::input(case_file, format!("{key}: {e}")),
    }
}

/// A fraction written as `0.06` or `6%`.
pub fn parse_fraction(text: &str) -> Result<f64> {
    let t = text.trim();
    let (num, scale) = match t.strip_suffix('%') {
        Some(n) => (n, 0.01),
        None => (t, 1.0),
    };
    let v: f64 = num
        .trim()
        .parse()
        .map_err(|_| Error::Invalid(format!("{t:?} is not a number")))?;
    Ok(v * scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan(polars: &str) -> RunPlan {
        let text = format!(
            "name = \"x\"\n[geometry]\nscan = \"x.stl\"\n[sweep]\nrpm = \"4000,6000\"\nj = \"0:0.5:0.1\"\n\
             [polars]\nairfoil = \"naca4412\"\nrpm = 5000\n{polars}\n[measured]\nfiles = [\"m.txt\"]\n"
        );
        let case: Case = toml::from_str(&text).unwrap();
        case.plan(
            Path::new("case"),
            Path::new("out"),
            &XfoilProcessSpec::default(),
            &|_| Ok(ScanOptions::default()),
        )
        .unwrap()
    }

    #[test]
    fn the_section_model_decides_what_the_stages_solve_with() {
        let q = plan("model = \"qprop\"");
        assert_eq!(q.predict.model.polars, None, "QPROP's law when asked");
        let t = plan("");
        let polars = Some(Path::new("out").join("polars/polars.json"));
        assert_eq!(t.predict.model.polars, polars);
        let (c, d) = t.compare.unwrap();
        assert_eq!(
            (c.model.polars.clone(), d.model.polars.clone()),
            (polars.clone(), polars)
        );
        // Every stage is its own command: the tables appear as --polars in the commands.
        assert!(StageSpec::Compare(c)
            .command()
            .contains("--polars out/polars/polars.json"));
    }

    #[test]
    fn the_polars_cover_the_sweep_unless_the_case_says() {
        let sweep = plan("");
        let (p, _) = sweep.polars.unwrap();
        assert_eq!(p.omegas, vec![rpm_to_omega(5000.0)], "rpm = 5000 as given");
        assert_eq!(p.axis, sweep.predict.axis, "the sweep's J");
        let text = "name = \"x\"\n[geometry]\nscan = \"x.stl\"\n[sweep]\nrpm = \"4000,6000\"\nj = \"0:0.5:0.1\"\n\
             [polars]\nairfoil = \"naca4412\"\nv = \"0,5\"\n";
        let case: Case = toml::from_str(text).unwrap();
        let plan = case
            .plan(
                Path::new("case"),
                Path::new("out"),
                &XfoilProcessSpec::default(),
                &|_| Ok(ScanOptions::default()),
            )
            .unwrap();
        let (p, _) = plan.polars.unwrap();
        assert_eq!(p.omegas, vec![rpm_to_omega(4000.0), rpm_to_omega(6000.0)]);
        assert_eq!(p.axis, SweepAxis::V(vec![0.0, 5.0]));
    }
}
