//! The requests and the one place each becomes a spec.

use std::path::PathBuf;

use crate::motor::{Battery, Drive, Supply};
use propbet_model::{Error, Result};
use propbet_settings::spec::{
    AirSpec, DesignSpec, DiagnoseSpec, MeasuredSpec, ModelSpec, PolarsSpec, SweepAxis, XfoilProcessSpec, XfoilSpec,
};
use propbet_settings::values::{
    parse_atmosphere, parse_humidity, parse_length_unit, parse_list, parse_pressure, parse_temperature,
};
use propbet_settings::{
    Rotation, AIR, ALPHA, ENGINE, NCRIT, NCRIT_EFFECT, NEURALFOIL_SIZE, POLES, RHO, RPM_SOURCE, TRIP, UNITS,
    XFOIL_BUDGET,
};

use crate::atmosphere::AirState;
use crate::measure::RpmSource;
use crate::units::rpm_to_omega;

/// Numbers as a caller gives them: a list (Python's lists and arrays) or the text a flag
/// takes (`4000,5000`, `start:stop:step`, `start:stop/N`).
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// The numbers themselves.
    Numbers(Vec<f64>),
    /// A list or a range as the command line writes it.
    Text(String),
}

/// A flag's text, as it is (read into numbers by [`Values::numbers`]).
impl std::str::FromStr for Values {
    type Err = std::convert::Infallible;

    fn from_str(text: &str) -> std::result::Result<Self, Self::Err> {
        Ok(Values::Text(text.to_string()))
    }
}

impl Values {
    /// The numbers, each finite; `name` is the caller's name of the value (`rpm`): an error
    /// says `rpm[2] = nan` of a list and `--rpm '1,,2'` of a text.
    pub fn numbers(&self, name: &str) -> Result<Vec<f64>> {
        match self {
            Values::Text(t) => Ok(parse_list(&format!("--{name}"), t)?),
            Values::Numbers(v) if v.is_empty() => Err(Error::Nothing(format!("{name}: an empty list"))),
            Values::Numbers(v) => match v.iter().position(|x| !x.is_finite()) {
                None => Ok(v.clone()),
                Some(i) => {
                    let x = v[i];
                    let text = if x.is_nan() {
                        "nan"
                    } else if x > 0.0 {
                        "inf"
                    } else {
                        "-inf"
                    };
                    let at = if v.len() == 1 {
                        name.to_string()
                    } else {
                        format!("{name}[{i}]")
                    };
                    Err(Error::Range(format!("{at} = {text}: not a finite number")))
                }
            },
        }
    }
}

/// The polar engine, XFOIL's executable and the polar cache, as asked (the flags of every
/// command that makes polars, passed on by `run` and `validate` to their `polars` stages).
#[derive(Debug, Clone, Default, PartialEq, clap::Args)]
pub struct ProcessRequest {
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
    /// Total XFOIL time [s].
    #[arg(long = XFOIL_BUDGET.flag, help = XFOIL_BUDGET.help, value_name = "SECONDS")]
    pub budget: Option<f64>,
    /// `xfoil`, `neuralfoil` or `auto` (None: [`ENGINE`]'s default).
    #[arg(
        long = ENGINE.flag,
        help = ENGINE.help,
        value_parser = ENGINE.choices(),
        default_value = ENGINE.default,
    )]
    pub engine: Option<String>,
    /// NeuralFoil's network size (None: [`NEURALFOIL_SIZE`]'s default).
    #[arg(
        long = NEURALFOIL_SIZE.flag,
        help = NEURALFOIL_SIZE.help,
        value_parser = NEURALFOIL_SIZE.choices(),
    )]
    pub neuralfoil_size: Option<String>,
}

impl ProcessRequest {
    /// The spec: the engine's and the network's names checked.
    pub fn spec(&self) -> Result<XfoilProcessSpec> {
        let engine = ENGINE.choose(self.engine.as_deref().unwrap_or(ENGINE.default))?;
        if let Some(size) = &self.neuralfoil_size {
            NEURALFOIL_SIZE.choose(size)?;
        }
        if self.cache.is_some() && self.no_cache {
            return Err(Error::Conflict("cache and no_cache: give one of them".into()));
        }
        Ok(XfoilProcessSpec {
            xfoil: self.xfoil.clone(),
            cache: self.cache.clone(),
            no_cache: self.no_cache,
            quiet: self.quiet,
            budget: self.budget,
            engine: crate::polar::Engine::parse(engine).unwrap_or_default(),
            neuralfoil_size: self.neuralfoil_size.clone(),
        })
    }
}

/// A propeller file and how to read it: every field but the file is optional, and [`spec`]
/// gives each the default that depends on the file (a blade file without coefficients has
/// its polars computed, and rotation and drag factor follow tables' defaults).
///
/// [`spec`]: ModelRequest::spec
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ModelRequest {
    /// QPROP prop file, APC's PE0, a UIUC geometry table or a blade table.
    pub prop: PathBuf,
    /// Collective blade-angle change [deg].
    pub dbeta_deg: f64,
    /// Length unit of the radii and chords (`in`, `mm`, ...), replacing the file's factors.
    pub units: Option<String>,
    /// Read as QPROP 1.22 does.
    pub qprop_compat: bool,
    /// No tip-loss factor.
    pub no_tip_loss: bool,
    /// Tabulated polars as the section model.
    pub polars: Option<PathBuf>,
    /// Rotational augmentation (`off`, `snel`; None: the default for the section model).
    pub rotation: Option<String>,
    /// Every section's drag times this (None: the default for the section model).
    pub drag_factor: Option<f64>,
    /// Effects added to the model (`id:param=value,...`).
    pub effects: Vec<String>,
    /// TOML file of user-defined effects.
    pub user_effects: Option<PathBuf>,
    /// The sections of a blade file without coefficients: one airfoil, or
    /// `E63@0.25,APC12@0.45`.
    pub airfoil: Option<String>,
    /// APC's design file whose sections a table takes.
    pub sections_from: Option<PathBuf>,
    /// Airfoil coordinates looked in before propbet's library.
    pub airfoils: Option<PathBuf>,
    /// How the polars of a blade file without coefficients are made.
    pub process: ProcessRequest,
}

impl ModelRequest {
    /// A propeller file with propbet's default model.
    pub fn file(prop: impl Into<PathBuf>) -> Self {
        ModelRequest {
            prop: prop.into(),
            ..ModelRequest::default()
        }
    }

    /// The model's spec, in SI.
    pub fn spec(&self) -> Result<ModelSpec> {
        let design = self.design()?;
        let tables = self.polars.is_some() || design.is_some();
        let rotation = self.rotation.as_deref().map(Rotation::parse).transpose()?;
        Ok(ModelSpec {
            design,
            prop: self.prop.clone(),
            dbeta: self.dbeta_deg.to_radians(),
            units: self.units.as_deref().map(parse_length_unit).transpose()?,
            qprop_compat: self.qprop_compat,
            no_tip_loss: self.no_tip_loss,
            polars: self.polars.clone(),
            rotation: Rotation::or_default(rotation, tables),
            drag_factor: propbet_settings::drag_factor_or_default(self.drag_factor, tables),
            effects: self.effects.clone(),
            user_effects: self.user_effects.clone(),
        })
    }

    /// The sections of a blade file without coefficients; None for a QPROP prop file (where
    /// the sections' settings are refused).
    fn design(&self) -> Result<Option<DesignSpec>> {
        use propbet_model::design::{format_of_file, BladeFormat};
        if format_of_file(&self.prop) == BladeFormat::Qprop {
            if self.airfoil.is_some() || self.sections_from.is_some() {
                return Err(Error::Conflict(format!(
                    "--airfoil / --sections-from: {} is a QPROP prop file, whose coefficients are its sections",
                    self.prop.display()
                )));
            }
            return Ok(None);
        }
        Ok(Some(DesignSpec {
            airfoil: self.airfoil.clone(),
            sections_from: self.sections_from.clone(),
            airfoils: self.airfoils.clone(),
            process: self.process.spec()?,
        }))
    }
}

/// Operating points: every rotation speed with every advance ratio or airspeed (the flags of
/// `predict` and `polars`).
#[derive(Debug, Clone, Default, PartialEq, clap::Args)]
pub struct SweepRequest {
    /// Rotation speeds [rpm]: a list, `start:stop:step` or `start:stop/N`.
    #[arg(long, allow_hyphen_values = true)]
    pub rpm: Option<Values>,
    /// Advance ratios J = V/(nD), same syntax.
    #[arg(long, conflicts_with = "v", allow_hyphen_values = true)]
    pub j: Option<Values>,
    /// Axial speeds [m/s], same syntax (default: 0, static).
    #[arg(long, allow_hyphen_values = true)]
    pub v: Option<Values>,
}

impl SweepRequest {
    /// Rotation speeds [rad/s] and the second axis.
    pub fn spec(&self) -> Result<(Vec<f64>, SweepAxis)> {
        let Some(rpm) = &self.rpm else {
            return Err(Error::Nothing(
                "--rpm: give the rotation speeds (or a --motor with --volts, --amps or --thrust)".into(),
            ));
        };
        let omegas = rpm.numbers("rpm")?.into_iter().map(rpm_to_omega).collect();
        Ok((omegas, self.axis()?))
    }

    /// The airspeeds alone [m/s] (static without them), where the rotation speed is not known
    /// before the solve (a motor's operating points): advance ratios are refused.
    pub fn airspeeds(&self) -> Result<Vec<f64>> {
        if self.j.is_some() {
            return Err(Error::Conflict(
                "--j: with --motor the RPM is not known before the solve; give airspeeds with --v".into(),
            ));
        }
        match self.axis()? {
            SweepAxis::V(v) => Ok(v),
            SweepAxis::J(_) => Err(Error::Conflict("--j: advance ratios need a rotation speed".into())),
        }
    }

    /// The second axis alone (static without J or V).
    pub fn axis(&self) -> Result<SweepAxis> {
        Ok(match (&self.j, &self.v) {
            (Some(_), Some(_)) => {
                return Err(Error::Conflict(
                    "j and v: give one of them (advance ratios or airspeeds)".into(),
                ))
            }
            (Some(j), None) => SweepAxis::J(j.numbers("j")?),
            (None, Some(v)) => SweepAxis::V(v.numbers("v")?),
            (None, None) => SweepAxis::V(vec![0.0]),
        })
    }
}

/// The air: density, viscosity and speed of sound (QPROP's defaults where not given), or
/// temperature, pressure and humidity through the atmosphere model.
#[derive(Debug, Clone, Default, PartialEq, clap::Args)]
pub struct AirRequest {
    /// Density [kg/m^3].
    #[arg(long = RHO.flag, help = RHO.help, allow_negative_numbers = true)]
    pub rho: Option<f64>,
    /// Dynamic viscosity [Pa s] (default 1.78e-5, QPROP's).
    #[arg(long, allow_negative_numbers = true)]
    pub mu: Option<f64>,
    /// Speed of sound [m/s] (default 340, QPROP's).
    #[arg(long, allow_negative_numbers = true)]
    pub a: Option<f64>,
    /// Air temperature with unit (20C, 293.15K, 68F); sets rho, mu and a.
    #[arg(long, requires = "pressure")]
    pub temp: Option<String>,
    /// Air pressure (Pa unless suffixed: hPa, mbar, kPa, inHg, psi).
    #[arg(long, requires = "temp")]
    pub pressure: Option<String>,
    /// Relative humidity in percent (with --temp and --pressure).
    #[arg(long, requires = "temp")]
    pub humidity: Option<String>,
}

impl AirRequest {
    /// The air's spec, in SI.
    pub fn spec(&self) -> Result<AirSpec> {
        let state = match (&self.temp, &self.pressure) {
            (Some(t), Some(p)) => {
                let rh = self.humidity.as_deref().map(parse_humidity).transpose()?.unwrap_or(0.0);
                let state = AirState::new(parse_temperature(t)?, parse_pressure(p)?, rh);
                Some(state.map_err(|e| Error::value("--temp", t, e))?)
            }
            (None, None) if self.humidity.is_none() => None,
            _ => return Err(Error::Conflict(
                "--temp, --pressure, --humidity: the air's state takes a temperature and a pressure (and a humidity)"
                    .into(),
            )),
        };
        Ok(AirSpec {
            rho: self.rho,
            mu: self.mu,
            a: self.a,
            state,
        })
    }
}

/// Measured files and how to read them (the flags of `compare`, `diagnose` and `motor fit`).
#[derive(Debug, Clone, Default, PartialEq, clap::Args)]
pub struct MeasuredRequest {
    /// Measured files: RCbenchmark/Tyto CSV, UIUC .txt, or generic CSV.
    #[arg(id = "measured", long = "measured", value_name = "MEASURED", required = true, num_args = 1..)]
    pub files: Vec<PathBuf>,
    /// Motor poles, for logs whose RPM is the ESC's electrical speed.
    #[arg(long = POLES.flag, help = POLES.help)]
    pub poles: Option<u32>,
    /// Which of a log's speeds to use (`optical`, `electrical`).
    #[arg(long = RPM_SOURCE.flag, help = RPM_SOURCE.help, value_parser = rpm_sources())]
    pub rpm_source: Option<String>,
    /// The air in the room as `T,P,RH`.
    #[arg(long = AIR.flag, help = AIR.help)]
    pub atmosphere: Option<String>,
    /// The air's density [kg/m^3].
    #[arg(long = RHO.flag, help = RHO.help, allow_negative_numbers = true)]
    pub rho: Option<f64>,
    /// Column map (TOML) for generic CSV files.
    #[arg(long)]
    pub columns: Option<PathBuf>,
}

/// The RPM columns a log may be read by, each with what it is (`--rpm-source`'s values).
pub fn rpm_sources() -> clap::builder::PossibleValuesParser {
    use clap::builder::PossibleValue;
    clap::builder::PossibleValuesParser::new([
        PossibleValue::new("optical").help("The optical (once-per-revolution) sensor"),
        PossibleValue::new("electrical").help("The ESC's electrical speed"),
    ])
}

impl MeasuredRequest {
    /// The measurements' spec, in SI.
    pub fn spec(&self) -> Result<MeasuredSpec> {
        if self.files.is_empty() {
            return Err(Error::Nothing("--measured: no measured file".into()));
        }
        let rpm_source = match self.rpm_source.as_deref() {
            None => None,
            Some("optical") => Some(RpmSource::Optical),
            Some("electrical") => Some(RpmSource::Electrical),
            Some(other) => return Err(Error::value("--rpm-source", other, "expected optical or electrical")),
        };
        Ok(MeasuredSpec {
            files: self.files.clone(),
            poles: self.poles,
            rpm_source,
            atmosphere: self.atmosphere.as_deref().map(parse_atmosphere).transpose()?,
            rho: self.rho,
            columns: self.columns.clone(),
        })
    }
}

/// What sets a motor's operating point: one of voltages, currents, thrusts, rotation speeds,
/// or throttles (with a battery).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DriveRequest {
    /// Terminal voltages [V].
    pub volts: Option<Values>,
    /// Motor currents [A].
    pub amps: Option<Values>,
    /// Thrusts [N] (hover).
    pub thrust: Option<Values>,
    /// Rotation speeds [rpm].
    pub rpm: Option<Values>,
    /// Throttles, 0 to 1 (with a battery).
    pub throttle: Option<Values>,
}

impl DriveRequest {
    /// The drivers, one per value.
    pub fn drives(&self, supply: Option<&Supply>) -> Result<Vec<Drive>> {
        let given = [&self.volts, &self.amps, &self.thrust, &self.rpm, &self.throttle]
            .iter()
            .filter(|v| v.is_some())
            .count();
        if given > 1 {
            return Err(Error::Conflict(
                "--volts, --amps, --thrust, --rpm, --throttle: give one of them (what sets the operating point)".into(),
            ));
        }
        use crate::motor::{DriveRule, Driver};
        let (driver, name, values) = match (&self.volts, &self.amps, &self.thrust, &self.rpm, &self.throttle) {
            (Some(v), ..) => (Driver::Volts, "volts", v),
            (_, Some(a), ..) => (Driver::Amps, "amps", a),
            (_, _, Some(t), ..) => (Driver::Thrust, "thrust", t),
            (_, _, _, Some(r), _) => (Driver::Rpm, "rpm", r),
            (.., Some(t)) => (Driver::Throttle, "throttle", t),
            _ => {
                return Err(Error::Nothing(
                    "--motor: give --volts, --amps, --thrust, --rpm or --throttle (what sets the operating point)"
                        .into(),
                ))
            }
        };
        let no_battery = || Error::Conflict("--throttle: needs a battery (--battery)".into());
        // Said before the values are read, as the flags' other checks are.
        if driver == Driver::Throttle && supply.is_none() {
            return Err(no_battery());
        }
        crate::motor::drives(driver, values.numbers(name)?, supply).map_err(|rule| match rule {
            DriveRule::ThrottleWithoutBattery => no_battery(),
            DriveRule::ThrottleOutside(bad) => Error::Range(format!("--throttle {bad}: a throttle is between 0 and 1")),
        })
    }
}

/// The battery of `spec` (`3S,2200mAh,R=5mOhm`) through an ESC of `esc_ohms` [ohm].
pub fn supply(spec: &str, esc_ohms: f64) -> Result<Supply> {
    let battery = Battery::parse(spec).map_err(|e| Error::value("--battery", spec, e))?;
    if !(0.0..10.0).contains(&esc_ohms) {
        return Err(Error::Range(format!(
            "--esc-ohms {esc_ohms}: a resistance from 0 to 10 ohm"
        )));
    }
    Ok(Supply { battery, esc_ohms })
}

/// What `diagnose` is asked beyond the model and the measurements: every field optional, its
/// default the setting's.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DiagnoseRequest {
    /// Candidate effects (`all`, or ids; None: all).
    pub effects: Option<Vec<String>>,
    /// Folds of the k-fold cross-validation.
    pub folds: Option<usize>,
    /// Most effects the ladder adds.
    pub max_steps: Option<usize>,
    /// Scored window, as a fraction of the zero-thrust J.
    pub window: Option<f64>,
}

impl DiagnoseRequest {
    /// The stage's spec, of a model and measurements, writing into `out`.
    pub fn spec(&self, model: ModelSpec, measured: MeasuredSpec, out: PathBuf) -> Result<DiagnoseSpec> {
        use propbet_settings::{FOLDS, MAX_STEPS, WINDOW};
        let effects = match &self.effects {
            None => vec!["all".to_string()],
            Some(e) if e.is_empty() => return Err(Error::Nothing("effects: an empty list".into())),
            Some(e) => e.iter().map(|s| s.trim().to_string()).collect(),
        };
        Ok(DiagnoseSpec {
            model,
            measured,
            effects,
            folds: self.folds.unwrap_or(FOLDS.default),
            max_steps: self.max_steps.unwrap_or(MAX_STEPS.default),
            window: self.window.unwrap_or(WINDOW.default),
            out,
        })
    }
}

/// How XFOIL (or NeuralFoil) is asked for a section's polars: the engine and its process, the
/// transition (Ncrit, trip), the angles, the panels and iterations; every field optional, its
/// default the setting's.
#[derive(Debug, Clone, Default, PartialEq, clap::Args)]
pub struct SectionRequest {
    /// The engine, XFOIL's executable, the cache.
    #[command(flatten)]
    pub process: ProcessRequest,
    /// Transition amplification ratio.
    #[arg(long = NCRIT.flag, help = NCRIT.help)]
    pub ncrit: Option<f64>,
    /// Forced transition x/c on both surfaces, or `free`.
    #[arg(long = TRIP.flag, help = TRIP.help, value_name = "X/C|free")]
    pub trip: Option<String>,
    /// Angles of attack [deg].
    #[arg(long = ALPHA.flag, help = ALPHA.help, default_value = ALPHA.default, allow_hyphen_values = true)]
    pub alpha: Option<Values>,
    /// XFOIL panel nodes (default: XFOIL's 160 for `polar`, 120 for `polars`).
    #[arg(long)]
    pub panels: Option<u32>,
    /// XFOIL's viscous iteration limit per angle (None: [`DEFAULT_MAX_ITER`](crate::xfoil::DEFAULT_MAX_ITER)).
    #[arg(long, help = format!("XFOIL's viscous iteration limit per angle [default: {}]", crate::xfoil::DEFAULT_MAX_ITER))]
    pub iter: Option<u32>,
}

impl SectionRequest {
    /// The spec; `default_ncrit` and `default_trip` where Ncrit and the trip are not given.
    pub fn spec(&self, default_ncrit: f64, default_trip: Option<f64>) -> Result<XfoilSpec> {
        let mut alphas = match &self.alpha {
            Some(a) => a.numbers("alpha")?,
            None => parse_list("--alpha", ALPHA.default)?,
        };
        alphas.sort_by(f64::total_cmp);
        alphas.dedup();
        let spec = XfoilSpec {
            process: self.process.spec()?,
            section: crate::xfoil::SectionSettings {
                ncrit: self.ncrit.unwrap_or(default_ncrit),
                trip: match &self.trip {
                    None => default_trip,
                    Some(t) => propbet_settings::values::parse_trip(t)?,
                },
                alphas_deg: alphas,
                panels: self.panels,
                max_iter: self.iter.unwrap_or(crate::xfoil::DEFAULT_MAX_ITER),
            },
        };
        spec.check()?;
        Ok(spec)
    }
}

/// `propbet polars`: every station's polars over the operating points, written as a prop
/// file with fitted coefficients and (optionally) the tables. Its flags.
#[derive(Debug, Clone, Default, PartialEq, clap::Args)]
pub struct PolarsRequest {
    /// Blade geometry: a QPROP prop file (its radii, chords and twists are used; its
    /// coefficients only for the first estimate of each station's inflow), APC's design file
    /// (PE0: its blade and sections), a UIUC geometry table or a blade table (CSV).
    #[arg(long)]
    pub geometry: PathBuf,
    /// Length unit of its radii and chords.
    #[arg(long = UNITS.flag, help = UNITS.help)]
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
    /// APC's design file (PE0) whose sections a UIUC geometry table or blade table takes:
    /// APC's airfoils blended across its transition and scaled to its thickness at each
    /// station, as `propbet validate` models APC's propellers.
    #[arg(long, value_name = "PE0")]
    pub sections_from: Option<PathBuf>,
    /// A directory of airfoil coordinates (`e63.dat`, ...) looked in before propbet's own.
    #[arg(long, value_name = "DIR")]
    pub airfoils: Option<PathBuf>,
    /// The operating points whose Reynolds numbers the polars cover (give the sweep's, or the
    /// measured range).
    #[command(flatten)]
    pub sweep: SweepRequest,
    /// The air.
    #[command(flatten)]
    pub air: AirRequest,
    /// How the polars are made.
    #[command(flatten)]
    pub section: SectionRequest,
    /// More Ncrit values to compute the same polars at.
    #[arg(long = NCRIT_EFFECT.flag, help = NCRIT_EFFECT.help, value_delimiter = ',')]
    pub ncrit_effect: Vec<f64>,
    /// QPROP prop file with the fitted per-station coefficients.
    #[arg(long)]
    pub out_prop: PathBuf,
    /// Every station's polars and fit (JSON), for `propbet predict --polars`.
    #[arg(long)]
    pub out_polars: Option<PathBuf>,
}

impl PolarsRequest {
    /// The stage's spec, in SI.
    pub fn spec(&self) -> Result<PolarsSpec> {
        use propbet_settings::default_trip;
        let (omegas, axis) = self.sweep.spec()?;
        Ok(PolarsSpec {
            geometry: self.geometry.clone(),
            units: self.units.as_deref().map(parse_length_unit).transpose()?,
            airfoil: self.airfoil.clone(),
            thickness: self
                .thickness
                .as_deref()
                .map(propbet_settings::values::parse_fraction)
                .transpose()?,
            station_airfoils: self.station_airfoils.clone(),
            sections_from: self.sections_from.clone(),
            airfoils: self.airfoils.clone(),
            omegas,
            axis,
            air: self.air.spec()?,
            xfoil: self.section.spec(NCRIT.default, default_trip())?,
            ncrit_effect: self.ncrit_effect.clone(),
            out_prop: self.out_prop.clone(),
            out_polars: self.out_polars.clone(),
        })
    }
}
