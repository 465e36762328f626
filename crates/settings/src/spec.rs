//! Stage specs: what each stage of the data flow is asked to do, in SI and typed. The CLI
//! fills them from its flags and prints each as the `propbet` command that does the same (one
//! formatter in the CLI, tested to parse back to the same spec).

use std::path::{Path, PathBuf};

use propbet_bemt::Fluid;

use propbet_atmosphere::AirState;
use propbet_geometry::scan::ScanOptions;
use propbet_measure::RpmSource;

use crate::Rotation;

/// The XFOIL executable, the polar cache and progress.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct XfoilProcessSpec {
    /// XFOIL executable (None: `xfoil` on PATH).
    pub xfoil: Option<PathBuf>,
    /// Polar cache directory (None: the default one).
    pub cache: Option<PathBuf>,
    /// Compute every polar afresh and store nothing.
    pub no_cache: bool,
    /// No progress bar.
    pub quiet: bool,
    /// Total XFOIL time of the command [s] (None: [`crate::XFOIL_BUDGET`]'s default).
    pub budget: Option<f64>,
    /// Which program makes the polars.
    pub engine: propbet_polar::Engine,
    /// NeuralFoil's network size (None: [`crate::NEURALFOIL_SIZE`]'s default).
    pub neuralfoil_size: Option<String>,
}

/// How XFOIL is asked: transition, angles, panels, iterations, and the process.
#[derive(Debug, Clone, PartialEq)]
pub struct XfoilSpec {
    /// Executable, cache, progress.
    pub process: XfoilProcessSpec,
    /// Transition (Ncrit; a trip, `docs/studies/transition-trip.md`), angles (ascending, no
    /// duplicates), iterations, and panels (None: the command's default).
    pub section: xfoil_runner::SectionSettings,
}

impl XfoilSpec {
    /// The angles are ones XFOIL can be asked for.
    pub fn check(&self) -> crate::Result<()> {
        crate::NCRIT.check(self.section.ncrit)?;
        if let Some(x) = self.section.trip {
            crate::TRIP.check(x)?;
        }
        if let Some(bad) = self.section.alphas_deg.iter().find(|x| x.abs() > 90.0) {
            return Err(crate::Error::Range(format!("--alpha: {bad} deg is outside -90..90")));
        }
        Ok(())
    }

    /// The settings every polar is asked with, `default_panels` where none are given (the
    /// command's: one section's or a blade's).
    pub fn section(&self, default_panels: u32) -> xfoil_runner::SectionSettings {
        xfoil_runner::SectionSettings {
            panels: Some(self.section.panels.unwrap_or(default_panels)),
            ..self.section.clone()
        }
    }
}

/// Air for the solver: QPROP's defaults, given values, or a measured state.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct AirSpec {
    /// Density [kg/m^3] (None: QPROP's 1.225 or the state's).
    pub rho: Option<f64>,
    /// Dynamic viscosity [Pa s].
    pub mu: Option<f64>,
    /// Speed of sound [m/s].
    pub a: Option<f64>,
    /// Temperature, pressure, humidity.
    pub state: Option<AirState>,
}

/// Where a blade file's sections come from beside the file, and how its polars are made: what a
/// command needs to predict from APC's design file (PE0), a UIUC geometry table or a blade table.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DesignSpec {
    /// The user's sections (`--airfoil`: one airfoil, or `E63@0.25,APC12@0.45`).
    pub airfoil: Option<String>,
    /// APC's design file whose sections a table takes (`--sections-from`).
    pub sections_from: Option<std::path::PathBuf>,
    /// Airfoil coordinates looked in before propbet's library (`--airfoils`).
    pub airfoils: Option<std::path::PathBuf>,
    /// The polar engine, XFOIL's executable and the cache.
    pub process: XfoilProcessSpec,
}

/// The propeller model: a prop file, how to read it, and what to change in it.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelSpec {
    /// QPROP prop file.
    pub prop: PathBuf,
    /// Collective blade-angle change [rad].
    pub dbeta: f64,
    /// Length unit of the radii and chords [m per unit], replacing the file's Rfac and Cfac.
    pub units: Option<f64>,
    /// Read as QPROP 1.22 does.
    pub qprop_compat: bool,
    /// No tip-loss factor.
    pub no_tip_loss: bool,
    /// Tabulated polars (`propbet polars --out-polars`) as the section model.
    pub polars: Option<PathBuf>,
    /// Rotational augmentation of every section's lift.
    pub rotation: Rotation,
    /// Every section's drag times this (1: as the section model gives it).
    pub drag_factor: f64,
    /// Effects added to the model (`id:param=value,...`).
    pub effects: Vec<String>,
    /// TOML file of user-defined effects.
    pub user_effects: Option<PathBuf>,
    /// Where `prop` is a blade file other than QPROP's (APC's PE0, a UIUC table, a blade
    /// table): its sections and how its polars are made (the pipeline's `design_model`).
    pub design: Option<DesignSpec>,
}

impl ModelSpec {
    /// A prop file as it is.
    pub fn prop(prop: PathBuf) -> Self {
        ModelSpec {
            prop,
            dbeta: 0.0,
            units: None,
            qprop_compat: false,
            no_tip_loss: false,
            polars: None,
            rotation: Rotation::Off,
            drag_factor: 1.0,
            effects: Vec::new(),
            user_effects: None,
            design: None,
        }
    }

    /// The section model is tables (polars given, or computed for a blade file without
    /// coefficients): the defaults of rotation and drag factor follow it.
    pub fn tabulated(&self) -> bool {
        self.polars.is_some() || self.design.is_some()
    }
}

/// What a sweep varies besides the rotation speed.
#[derive(Debug, Clone, PartialEq)]
pub enum SweepAxis {
    /// Advance ratios J = V/(nD) [-].
    J(Vec<f64>),
    /// Axial speeds [m/s].
    V(Vec<f64>),
}

/// Output format of `propbet predict`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TableFormat {
    /// One row per operating point.
    Csv,
    /// All results, with the inputs, as one JSON document.
    Json,
}

/// `propbet predict`.
#[derive(Debug, Clone, PartialEq)]
pub struct PredictSpec {
    /// The model.
    pub model: ModelSpec,
    /// Rotation speeds [rad/s].
    pub omegas: Vec<f64>,
    /// J or V values.
    pub axis: SweepAxis,
    /// Air.
    pub air: AirSpec,
    /// Output format.
    pub format: TableFormat,
    /// Output file (None: standard output).
    pub out: Option<PathBuf>,
    /// Per-station table.
    pub stations: Option<PathBuf>,
    /// Also the uncertainty band of CT, CP and efficiency (the pipeline's `BandSpec`'s
    /// default sources).
    pub band: bool,
}

/// `propbet predict --motor`: the propeller on its motor (and battery), one row per driver
/// value and airspeed.
#[derive(Debug, Clone, PartialEq)]
pub struct PoweredSpec {
    /// The model.
    pub model: ModelSpec,
    /// The QPROP motor file.
    pub motor: PathBuf,
    /// What sets each operating point, one kind for all ([`propbet_motor::Drive`]).
    pub drives: Vec<propbet_motor::Drive>,
    /// The battery and ESC (with a battery).
    pub supply: Option<propbet_motor::Supply>,
    /// Airspeeds [m/s].
    pub speeds: Vec<f64>,
    /// Air.
    pub air: AirSpec,
    /// Output format.
    pub format: TableFormat,
    /// Output file (None: standard output).
    pub out: Option<PathBuf>,
    /// Per-station table of every operating point found.
    pub stations: Option<PathBuf>,
    /// Also the propeller's uncertainty band at each operating point.
    pub band: bool,
}

/// Measured files and how to read them.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredSpec {
    /// The files.
    pub files: Vec<PathBuf>,
    /// Motor poles.
    pub poles: Option<u32>,
    /// RPM column of thrust-stand logs.
    pub rpm_source: Option<RpmSource>,
    /// Air state overriding what the files log.
    pub atmosphere: Option<AirState>,
    /// Air density overriding everything [kg/m^3].
    pub rho: Option<f64>,
    /// Column map of generic CSV files.
    pub columns: Option<PathBuf>,
}

impl MeasuredSpec {
    /// Files read as they are.
    pub fn files(files: Vec<PathBuf>) -> Self {
        MeasuredSpec {
            files,
            poles: None,
            rpm_source: None,
            atmosphere: None,
            rho: None,
            columns: None,
        }
    }
}

/// `propbet compare`.
#[derive(Debug, Clone, PartialEq)]
pub struct CompareSpec {
    /// The model.
    pub model: ModelSpec,
    /// The measurements.
    pub measured: MeasuredSpec,
    /// APC's predictions (a PER3 file) drawn and scored beside propbet's.
    pub per3: Option<PathBuf>,
    /// A QPROP output (its printed sweep) drawn and scored beside propbet's.
    pub qprop_output: Option<PathBuf>,
    /// A QPROP motor file: the log's current and electrical power scored against it.
    pub motor: Option<PathBuf>,
    /// Output directory.
    pub out: PathBuf,
}

/// `propbet diagnose`.
#[derive(Debug, Clone, PartialEq)]
pub struct DiagnoseSpec {
    /// The model (its effects are part of the baseline).
    pub model: ModelSpec,
    /// The measurements.
    pub measured: MeasuredSpec,
    /// Candidate effects (`all` or ids).
    pub effects: Vec<String>,
    /// Folds of the k-fold cross-validation.
    pub folds: usize,
    /// Most effects the ladder adds.
    pub max_steps: usize,
    /// Scored window: points below this fraction of their file's measured zero-thrust J
    /// (validate's and the report's window, [`propbet_compare::metrics::in_window`]).
    pub window: f64,
    /// Output directory.
    pub out: PathBuf,
}

/// `propbet polars`.
#[derive(Debug, Clone, PartialEq)]
pub struct PolarsSpec {
    /// Blade geometry (QPROP prop file).
    pub geometry: PathBuf,
    /// Its length unit [m per unit].
    pub units: Option<f64>,
    /// The section at every station (at the stations without their own with
    /// `station_airfoils`): a coordinate file or a NACA 4-digit name. None only with
    /// `station_airfoils`: a station without its own section takes the nearest station's.
    pub airfoil: Option<String>,
    /// Thickness ratio the section is scaled to [-].
    pub thickness: Option<f64>,
    /// Per-station sections (`station_NN.dat`).
    pub station_airfoils: Option<PathBuf>,
    /// APC's design file (PE0) whose sections a blade table takes (`--sections-from`).
    pub sections_from: Option<PathBuf>,
    /// A directory of airfoil coordinates looked in before propbet's library (`--airfoils`).
    pub airfoils: Option<PathBuf>,
    /// Rotation speeds whose Reynolds numbers the polars cover [rad/s].
    pub omegas: Vec<f64>,
    /// With the advance ratios or axial speeds.
    pub axis: SweepAxis,
    /// Air.
    pub air: AirSpec,
    /// XFOIL.
    pub xfoil: XfoilSpec,
    /// More Ncrit values at which the same polars are computed, for the `transition` effect
    /// (Ncrit fitted between them; `propbet_effects::transition`). Empty: none.
    pub ncrit_effect: Vec<f64>,
    /// Output prop file with the fitted coefficients.
    pub out_prop: PathBuf,
    /// Output polars (JSON).
    pub out_polars: Option<PathBuf>,
}

/// `propbet scan`.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanSpec {
    /// The scan file.
    pub input: PathBuf,
    /// What the geometry pipeline does.
    pub options: ScanOptions,
    /// A UIUC-style geometry table to compare with.
    pub reference: Option<PathBuf>,
    /// Name written in the prop file.
    pub name: Option<String>,
    /// Output directory.
    pub out: PathBuf,
}

/// One stage of the data flow.
#[derive(Debug, Clone, PartialEq)]
pub enum StageSpec {
    /// Geometry from a scan.
    Scan(ScanSpec),
    /// XFOIL polars of every station.
    Polars(PolarsSpec),
    /// Sweeps.
    Predict(PredictSpec),
    /// The propeller on its motor.
    Powered(PoweredSpec),
    /// Measured against predicted.
    Compare(CompareSpec),
    /// What is missing.
    Diagnose(DiagnoseSpec),
}

impl StageSpec {
    /// The stage's name (the subcommand).
    pub fn name(&self) -> &'static str {
        match self {
            StageSpec::Scan(_) => "scan",
            StageSpec::Polars(_) => "polars",
            StageSpec::Predict(_) => "predict",
            StageSpec::Powered(_) => "motor",
            StageSpec::Compare(_) => "compare",
            StageSpec::Diagnose(_) => "diagnose",
        }
    }
}

impl ModelSpec {
    /// The files the model reads (never to be overwritten).
    pub fn inputs(&self) -> Vec<&Path> {
        std::iter::once(self.prop.as_path())
            .chain(self.polars.as_deref())
            .chain(self.user_effects.as_deref())
            .collect()
    }
}

impl AirSpec {
    /// The fluid, and a note of where it came from.
    pub fn fluid(&self) -> crate::Result<(Fluid, String)> {
        use propbet_units::air;
        for (flag, x, range, unit) in [
            ("--rho", self.rho, &air::DENSITY, "kg/m^3"),
            ("--mu", self.mu, &air::VISCOSITY, "Pa s"),
            ("--a", self.a, &air::SOUND_SPEED, "m/s"),
        ] {
            if let Some(x) = x {
                air::check(flag, x, range, unit).map_err(crate::Error::Range)?;
            }
        }
        if let Some(state) = &self.state {
            let mut f = state.fluid();
            if let Some(rho) = self.rho {
                f.rho = rho;
            }
            if let Some(mu) = self.mu {
                f.mu = mu;
            }
            if let Some(a) = self.a {
                f.a = a;
            }
            return Ok((
                f,
                format!(
                    "from T = {:.2} K, p = {:.0} Pa, RH = {:.0} %",
                    state.temperature,
                    state.pressure,
                    state.relative_humidity * 100.0
                ),
            ));
        }
        let d = Fluid::QPROP_DEFAULT;
        let f = Fluid {
            rho: self.rho.unwrap_or(d.rho),
            mu: self.mu.unwrap_or(d.mu),
            a: self.a.unwrap_or(d.a),
        };
        f.validate().map_err(|e| crate::Error::Range(format!("air: {e}")))?;
        let source = if self.rho.is_none() && self.mu.is_none() && self.a.is_none() {
            "QPROP defaults (standard air, not measured)".to_string()
        } else {
            "given".to_string()
        };
        Ok((f, source))
    }
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

#[cfg(test)]
mod tests;
