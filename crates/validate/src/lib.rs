//! `validate_prop`: one UIUC propeller predicted from its UIUC geometry (or APC's design chord
//! and twist at UIUC's stations, [`GeometrySource`]) with APC's sections
//! (PE0 file: airfoils blended across APC's transition, scaled to the PE0 thickness ratio),
//! XFOIL polars at each station's Re, compared with every static and J-sweep file of it,
//! diagnosed, and compared again with the diagnosis' ladder of effects.

use std::path::{Path, PathBuf};

use propbet_compare::metrics::{
    static_figure_of_merit_error, static_rise, window_errors, zero_thrust_shift, Regimes, VALIDATION_J_WINDOW,
};
use propbet_qprop::{PropFile, PropRow};

use propbet_model::{as_written, LoadedProp, Model};
use propbet_model::{Error, Result};
use propbet_pipeline::run::{timed, StageRecord};
use propbet_pipeline::stages::{self, Compared, Diagnosed, Polars, PolarsInput};
use propbet_settings::spec::{
    AirSpec, CompareSpec, DiagnoseSpec, MeasuredSpec, ModelSpec, PolarsSpec, StageSpec, XfoilSpec,
};

mod all;
mod blade;
mod families;
mod files;
mod held_out;
mod hidden;
mod row;

pub use all::{sections_for, select_props, validate_all, PropSections, Validation};
pub use blade::pe0_table;
use blade::{blade, Blade};
pub use families::summarise;
use files::measured_files;
pub use files::{find_apc_file, uiuc_name, uiuc_props};
use held_out::held_out;
pub use hidden::{hidden_measured, hidden_prop};
use row::{band_coverage, beyond_polars, ladder_text, median_p90};
pub use row::{
    family_groups, forward_rpm_trend, line_groups, per3_score, twist_gap, BeforeAfter, Per3Score, Row, Spread,
};

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
    /// How the polars are asked for: XFOIL's executable, cache and progress; the transition
    /// (Ncrit, a trip), the angles, the panels and iterations.
    pub xfoil: XfoilSpec,
    /// Section model: the polars as tables (true) or QPROP's law fitted to them.
    pub tables: bool,
    /// More Ncrit values of the same polars, for the `transition` effect in the calibration
    /// ladders (empty: none).
    pub ncrit_effect: Vec<f64>,
    /// Rotational augmentation of the section lift.
    pub rotation: propbet_settings::Rotation,
    /// Drag multiplier of the section model.
    pub drag_factor: f64,
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
            _ => Err(Error::value("--geometry", s, "`uiuc` or `pe0`")),
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
    /// The uncertainty band's sources by name, each with the compared points predicted at its
    /// two ends (the band's makings, [`propbet_model::band::BandSpec::at_compared_by_source`]).
    pub band_sources: Vec<(&'static str, [Vec<propbet_compare::ComparedPoint>; 2])>,
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
                    return Err(Error::value(
                        "--generic-section",
                        &propbet_bemt::units::excerpt(t),
                        "the thickness ratio after ':' must be a number in 0.01..0.4",
                    ))
                }
            },
        };
        if name.trim().is_empty() {
            return Err(Error::value(
                "--generic-section",
                &propbet_bemt::units::excerpt(t),
                "an airfoil name, NAME or NAME:T/C, or `none`",
            ));
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

/// The blade written as validate predicts it: its prop file (UIUC's stations, generic
/// coefficients) and each station's section, as the polars stage takes them.
fn geometry_and_sections(
    prop: &str,
    dir: &Path,
    geometry_used: GeometrySource,
    assumed: Option<&str>,
    big_r: f64,
    rows: Vec<PropRow>,
    airfoils: &[(usize, String)],
) -> Result<(LoadedProp, PolarsInput)> {
    let file = PropFile::metric(
        format!(
            "{prop} ({}, {})",
            geometry_used.description(),
            assumed.map_or("APC PE0 sections".to_string(), |a| format!("sections assumed: {a}"))
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
    let first = propbet_model::design::parse_airfoil(&airfoils[0].1, &foil_dir.join("station_00.dat"))?.0;
    let foils = stages::station_foils(&foil_dir, texts, Some(&first), &mut notes)?;
    let input = PolarsInput {
        geometry: geometry.clone(),
        foils,
        foil_name: first.name.clone(),
        notes,
    };
    Ok((geometry, input))
}

/// The polars stage of one prop: the blade's stations and sections as written, over the
/// operating points its measurements cover (`omegas`, `js`), with the spec's XFOIL settings.
fn polars_spec(spec: &ValidateSpec, dir: &Path, omegas: Vec<f64>, js: Vec<f64>) -> Result<PolarsSpec> {
    let foil_dir = dir.join("airfoils");
    Ok(PolarsSpec {
        geometry: dir.join("geometry.qprop"),
        units: None,
        airfoil: Some(foil_dir.join("station_00.dat").display().to_string()),
        thickness: None,
        station_airfoils: Some(foil_dir),
        sections_from: None,
        airfoils: None,
        omegas,
        axis: propbet_settings::spec::SweepAxis::J(js),
        air: AirSpec::default(),
        xfoil: spec.xfoil.clone(),
        ncrit_effect: spec.ncrit_effect.clone(),
        out_prop: dir.join("prop.qprop"),
        out_polars: Some(dir.join("polars.json")),
    })
}

/// A comparison stage, timed and recorded.
fn compare_stage(spec: CompareSpec, model: &Model, records: &mut Vec<StageRecord>) -> Result<Compared> {
    timed(
        records,
        StageSpec::Compare(spec.clone()),
        || stages::load_batch(&spec.measured).and_then(|b| stages::compare(model, b)),
        |c: &Compared| c.clean(),
    )
}

/// What the calibration made: the diagnosis, the ladder's effects, and the comparison with
/// them and its model.
struct Calibration {
    diagnosed: Diagnosed,
    effects: Vec<String>,
    compared: Compared,
    model: Model,
}

/// The ladder validate (and `hidden`) runs on a prop's files: every effect, the defaults of a
/// diagnosis, its report into `dir/diagnose`.
pub fn ladder_spec(model_spec: &ModelSpec, measured: &MeasuredSpec, dir: &Path) -> DiagnoseSpec {
    DiagnoseSpec {
        model: model_spec.clone(),
        measured: measured.clone(),
        effects: vec!["all".into()],
        folds: propbet_settings::FOLDS.default,
        max_steps: propbet_settings::MAX_STEPS.default,
        window: VALIDATION_J_WINDOW,
        out: dir.join("diagnose"),
    }
}

/// The diagnosis of the prop's measurements with `model` (`dspec`), and the comparison with
/// its ladder's effects (as the command line gives them).
fn calibrate(
    model_spec: ModelSpec,
    dspec: &DiagnoseSpec,
    model: &Model,
    polars: &Polars,
    measured: &MeasuredSpec,
    dir: &Path,
    records: &mut Vec<StageRecord>,
) -> Result<Calibration> {
    let diagnosed = timed(
        records,
        StageSpec::Diagnose(dspec.clone()),
        || stages::diagnose(model, dspec),
        |_| true,
    )?;
    // Calibrated: the rung of the ladder that scores lowest on the measurements by validate's
    // metric (as the held-out halves carry theirs), as the command line gives its effects.
    let rung = held_out::best_rung(model, diagnosed.air, &diagnosed.sets, &diagnosed.diagnosis)?;
    let effects = held_out::added_effects(model, &rung);
    let cal_spec = ModelSpec {
        effects: effects.clone(),
        ..model_spec
    };
    let cal_model = Model::from_parts(&cal_spec, polars.prop.clone(), Some(&polars.blade), false)?;
    let calibrated = compare_stage(
        CompareSpec {
            per3: None,
            qprop_output: None,
            motor: None,
            model: cal_spec,
            measured: measured.clone(),
            out: dir.join("calibrated"),
        },
        &cal_model,
        records,
    )?;
    Ok(Calibration {
        diagnosed,
        effects,
        compared: calibrated,
        model: cal_model,
    })
}

/// One prop as validate predicts it, before any comparison: its blade, the files measured, the
/// polars and the model.
struct Prepared {
    dir: PathBuf,
    blade: Blade,
    geometry: LoadedProp,
    input: PolarsInput,
    measured: MeasuredSpec,
    left_out: Vec<(String, String)>,
    records: Vec<StageRecord>,
    polars: Polars,
    model_spec: ModelSpec,
    model: Model,
}

/// The blade of `prop` with its `sections`, its measured files, its polars (over the operating
/// points the files cover) and the model.
fn prepare(
    spec: &ValidateSpec,
    prop: &str,
    sections: &Sections,
    progress: &propbet_polar::Progress<'_>,
) -> Result<Prepared> {
    let dir = spec.out.join(prop);
    let blade = blade(spec, prop, sections)?;
    let (geometry, input) = geometry_and_sections(
        prop,
        &dir,
        blade.geometry_used,
        blade.assumed.as_deref(),
        blade.big_r,
        blade.rows.clone(),
        &blade.airfoils,
    )?;
    let mut records = Vec::new();
    let files::MeasuredFiles {
        files: measured,
        left_out,
    } = measured_files(spec, prop)?;
    let measured = MeasuredSpec::files(measured);
    let (omegas, js) = propbet_pipeline::stages::cover(&measured)?;
    let polars_spec = polars_spec(spec, &dir, omegas, js)?;
    let engine = stages::polar_engine(&spec.xfoil.process)?;
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
    Ok(Prepared {
        dir,
        blade,
        geometry,
        input,
        measured,
        left_out,
        records,
        polars,
        model_spec,
        model,
    })
}

/// Validates one prop with its `sections`.
pub fn validate_prop(
    spec: &ValidateSpec,
    prop: &str,
    sections: &Sections,
    progress: &propbet_polar::Progress<'_>,
) -> Result<Validated> {
    let Prepared {
        dir,
        blade:
            Blade {
                big_r,
                table,
                pe0,
                assumed,
                uiuc_geometry,
                airfoils,
                ..
            },
        geometry,
        input,
        measured,
        left_out,
        mut records,
        polars,
        model_spec,
        model,
    } = prepare(spec, prop, sections, progress)?;
    // APC's own prediction of the prop, drawn beside propbet's in its comparison.
    let per3_file = spec
        .per3
        .as_ref()
        .and_then(|dir| find_apc_file(dir, &propbet_qprop::apc::per3_name(prop)?));
    let compared = compare_stage(
        CompareSpec {
            per3: per3_file.clone(),
            qprop_output: None,
            motor: None,
            model: model_spec.clone(),
            measured: measured.clone(),
            out: dir.join("compare"),
        },
        &model,
        &mut records,
    )?;
    // The ladder on every file and the held-out ladders on each half run side by side.
    let dspec = ladder_spec(&model_spec, &measured, &dir);
    let (calibration, held) = rayon::join(
        || calibrate(model_spec, &dspec, &model, &polars, &measured, &dir, &mut records),
        || held_out(&model, &dspec, &measured.files, compared.air, &compared.sets, &dir),
    );
    let cal = calibration?;
    let (ct1, cp1, held_out_ladders) = held?;
    let (ct0, cp0) = window_errors(&compared.points, VALIDATION_J_WINDOW);
    let (bands, band_sources) = propbet_model::band::BandSpec::for_model(&model).with_sources(
        &model,
        compared.air,
        &compared.sets,
        &compared.points,
    )?;
    let per3 = per3_file
        .as_ref()
        .map(|f| propbet_pipeline::stages::read_per3(f))
        .transpose()?;
    let row = Row {
        prop: prop.to_string(),
        points: ct0.len(),
        implausible: compared.points.iter().filter(|p| !p.model_flags.is_empty()).count(),
        beyond_polars: beyond_polars(&compared.points),
        ct: BeforeAfter {
            before: median_p90(&ct0),
            after: median_p90(&ct1),
        },
        cp: BeforeAfter {
            before: median_p90(&cp0),
            after: median_p90(&cp1),
        },
        per3: per3.map(|p| per3_score(&p, &compared.points)),
        ladder: ladder_text(&cal.effects),
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
        regimes: Regimes::of(&compared.points, VALIDATION_J_WINDOW),
        static_rise: static_rise(&compared.points),
        forward_rpm_trend: forward_rpm_trend(&compared.points, VALIDATION_J_WINDOW),
        zero_thrust_shift: zero_thrust_shift(&compared.points),
        repeatability: cal.diagnosed.diagnosis.repeatability.as_ref().map(|r| r.sd),
        band: band_coverage(
            &compared.points,
            &bands,
            cal.diagnosed.diagnosis.repeatability.as_ref().map(|r| r.sd),
        ),
    };
    Ok(Validated {
        geometry,
        airfoils,
        polars: (polars, input),
        compared: (compared, model),
        diagnosed: cal.diagnosed,
        effects: cal.effects,
        calibrated: (cal.compared, cal.model),
        stages: records,
        row,
        band_sources,
    })
}

#[cfg(test)]
mod tests;
