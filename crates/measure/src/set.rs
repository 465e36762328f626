//! What a measured file becomes: points (mean ± scatter), dropped rows with their reasons, and
//! the errors of reading.

use serde::Serialize;
use thiserror::Error;

/// How rows became points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Reduction {
    /// ESC steps: transient dropped, steady part averaged.
    Steps,
    /// One already-averaged row per step (the RCbenchmark app's step-test summary).
    AveragedSteps,
    /// Continuous variation: binned by RPM (and airspeed).
    Ramp,
    /// Each row is a point.
    Rows,
    /// Published table (UIUC).
    Table,
}

/// A measured mean with its scatter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Value {
    /// Mean of the samples (SI).
    pub mean: f64,
    /// Sample standard deviation (SI); `None` when the file holds one value (already averaged).
    pub sd: Option<f64>,
    /// Number of samples averaged.
    pub n: usize,
}

impl Value {
    /// A single value without known scatter.
    pub fn single(v: f64) -> Self {
        Self {
            mean: v,
            sd: None,
            n: 1,
        }
    }

    /// Mean and sample standard deviation of `xs` (not empty).
    pub fn of(xs: &[f64]) -> Self {
        let n = xs.len();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let sd = (n > 1).then(|| (xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt());
        Self { mean, sd, n }
    }

    /// Relative scatter sd/|mean| (0 when unknown).
    pub fn relative_sd(&self) -> f64 {
        match self.sd {
            Some(sd) if self.mean != 0.0 => sd / self.mean.abs(),
            _ => 0.0,
        }
    }
}

/// How fast the propeller moves through the air.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Speed {
    /// Axial airspeed [m/s] (0 on a static stand).
    Airspeed(Value),
    /// Advance ratio J = V/(nD) as published (UIUC), the diameter being the propeller's.
    AdvanceRatio(f64),
}

/// What was measured at a point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Loads {
    /// Forces: thrust [N] and, when the stand has a torque cell, torque [N m].
    Forces {
        /// Thrust [N], positive pulling upstream.
        thrust: Value,
        /// Shaft torque absorbed by the propeller [N m], positive.
        torque: Option<Value>,
    },
    /// Published coefficients (UIUC): CT = T/(rho n^2 D^4), CP = P/(rho n^3 D^5).
    Coefficients {
        /// Thrust coefficient.
        ct: f64,
        /// Power coefficient.
        cp: f64,
    },
}

/// Air state logged with a point (each part only when the file has it).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct LoggedAir {
    /// Air temperature [K].
    pub temperature: Option<f64>,
    /// Static pressure [Pa].
    pub pressure: Option<f64>,
    /// Relative humidity [0..1].
    pub humidity: Option<f64>,
}

/// One steady operating point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeasuredPoint {
    /// Where it came from: "step at ESC 1425 µs", "rpm bin 5000", "row".
    pub label: String,
    /// First and last line of the file that went into it (1-based).
    pub lines: (usize, usize),
    /// Rotation rate [rad/s].
    pub omega: Value,
    /// Airspeed or advance ratio.
    pub speed: Speed,
    /// Forces or coefficients.
    pub loads: Loads,
    /// Air state, when logged.
    pub air: LoggedAir,
    /// Samples dropped as the transient at the start of the step.
    pub transient: usize,
    /// Nominal group for per-RPM metrics (e.g. the RPM in a UIUC file name) [rad/s].
    pub nominal_omega: Option<f64>,
    /// Reasons not to trust the point (unsteady RPM, ...); flagged points are reported, not scored.
    pub flags: Vec<String>,
    /// The supply's voltage and current, when logged.
    pub electric: Option<Electric>,
}

/// What a thrust stand's power meter logged at a point: the supply side of the ESC.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Electric {
    /// Voltage [V].
    pub volts: Value,
    /// Current [A].
    pub amps: Value,
    /// The ESC command [µs] (mean), when logged.
    pub esc: Option<f64>,
}

impl MeasuredPoint {
    /// Rotation speed [rpm] (a label for people).
    pub fn rpm(&self) -> f64 {
        propbet_units::omega_to_rpm(self.omega.mean)
    }
}

/// Why a row was not used.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DropReason {
    /// RPM is zero: the propeller was not turning (idle steps; expected, not a fault).
    NotSpinning,
    /// The motor idling, starting or stopping: below [`limits::IDLE`] of the log's highest
    /// RPM, or a thrust at the load cell's zero on the wrong side (expected, not a fault).
    Idle,
    /// A sparse log's row before one of the needed sensors logged its first reading (expected,
    /// not a fault).
    BeforeFirstReading,
    /// A needed cell is empty.
    Missing,
    /// A needed cell is not a finite number.
    NotANumber,
    /// Negative RPM reading.
    NegativeRpm,
    /// Thrust against the propeller's direction (after orienting the column) with no airspeed.
    NegativeThrust,
    /// Negative thrust in a stream: past the zero-thrust J, the propeller windmills (expected
    /// at the end of a J sweep, not a fault; outside what the model scores).
    Windmilling,
    /// Same time stamp as the row before.
    DuplicateTime,
    /// Time stamp out of order (a stray row).
    TimeOutOfOrder,
    /// A value no small propeller can have (see [`limits`]): a file error, not a measurement.
    Implausible,
    /// The RPM sensor read 0 in a step that spins, and the row's thrust was too far from the
    /// step's steady thrust to take the step's steady RPM.
    RpmDropout,
}

/// Magnitudes beyond which a measured value is not a small propeller's: a row holding one is
/// dropped as [`DropReason::Implausible`] (a corrupt or mistyped file; the largest real values
/// in the shared data are about 30,000 rpm, 60 N, 2 N m, CT 0.2, J 1.2).
pub mod limits {
    /// Rotation rate [rad/s] (500,000 rpm).
    pub const OMEGA: f64 = propbet_units::operating::OMEGA_MAX;
    /// Thrust [N].
    pub const THRUST: f64 = 1.0e5;
    /// Torque [N m].
    pub const TORQUE: f64 = 1.0e4;
    /// Airspeed [m/s].
    pub const AIRSPEED: f64 = propbet_units::operating::AIRSPEED_MAX;
    /// |CT|, |CP|.
    pub const COEFFICIENT: f64 = 10.0;
    /// Advance ratio.
    pub const ADVANCE_RATIO: f64 = 20.0;

    /// Rows below this fraction of their log's highest RPM are the motor idling, starting or
    /// stopping ([`DropReason::Idle`]): a propeller there makes 0.25 % of its top thrust,
    /// below a load cell's zero drift.
    pub const IDLE: f64 = 0.05;

    /// A thrust within this fraction of the log's largest |thrust| on the side opposite the
    /// pull, with no airspeed, is the load cell's zero, not windmilling.
    pub const ZERO_THRUST: f64 = 0.02;

    /// Slowest rotation a measured point can have [rad/s] (1 rpm): below it the coefficients
    /// divide by almost nothing (a row of 1e-300 rpm is a corrupt cell, not a test).
    pub const OMEGA_MIN: f64 = propbet_units::rpm_to_omega(1.0);

    /// The first value of `checks` (name, value, limit) beyond its limit, as a drop's detail.
    pub fn beyond(checks: &[(&str, f64, f64)]) -> Option<String> {
        checks
            .iter()
            .find(|(_, v, lim)| v.abs() > *lim)
            .map(|(n, v, lim)| format!("{n} = {v:.4e} is beyond {lim:.0e}"))
    }

    /// A rotation [rad/s] that turns but slower than [`OMEGA_MIN`], as a drop's detail.
    pub fn too_slow(omega: f64) -> Option<String> {
        (omega > 0.0 && omega < OMEGA_MIN).then(|| {
            format!(
                "RPM = {} is below 1 rpm: no test point",
                propbet_units::show(propbet_units::omega_to_rpm(omega))
            )
        })
    }

    /// Logged air outside what any test site has and the air formulas are meant for
    /// ([`propbet_units::air`], the ranges `--atmosphere` is checked against), as a drop's
    /// detail: temperature [K], pressure [Pa], relative humidity [0..1].
    pub fn air(temperature: Option<f64>, pressure: Option<f64>, humidity: Option<f64>) -> Option<String> {
        use propbet_units::{air, show};
        if let Some(t) = temperature.filter(|t| !air::TEMPERATURE.contains(t)) {
            return Some(format!(
                "air temperature {} °C is outside {} to {} °C",
                show(t - 273.15),
                air::TEMPERATURE.start() - 273.15,
                air::TEMPERATURE.end() - 273.15
            ));
        }
        if let Some(p) = pressure.filter(|p| !air::PRESSURE.contains(p)) {
            return Some(format!(
                "air pressure {} Pa is outside {}-{} Pa (hPa or kPa logged as Pa?)",
                show(p),
                air::PRESSURE.start(),
                air::PRESSURE.end()
            ));
        }
        if let Some(h) = humidity.filter(|h| !air::HUMIDITY.contains(h)) {
            return Some(format!("relative humidity {} % is outside 0-100 %", show(100.0 * h)));
        }
        None
    }
}

impl DropReason {
    /// True for rows that are wrong, as opposed to rows that are expected not to count.
    pub fn is_fault(self) -> bool {
        !matches!(
            self,
            DropReason::NotSpinning | DropReason::Windmilling | DropReason::Idle | DropReason::BeforeFirstReading
        )
    }

    /// Short text.
    pub fn text(self) -> &'static str {
        match self {
            DropReason::NotSpinning => "not spinning (RPM 0)",
            DropReason::Idle => "idle (motor starting, stopping or below 5 % of the top RPM; thrust at zero)",
            DropReason::BeforeFirstReading => "before a sensor's first reading (sparse log)",
            DropReason::Missing => "empty cell",
            DropReason::NotANumber => "not a number",
            DropReason::NegativeRpm => "negative RPM",
            DropReason::NegativeThrust => "negative thrust",
            DropReason::Windmilling => "negative thrust in a stream (windmilling, past zero thrust)",
            DropReason::DuplicateTime => "duplicate time",
            DropReason::TimeOutOfOrder => "time out of order",
            DropReason::Implausible => "beyond any small propeller's values",
            DropReason::RpmDropout => "RPM sensor dropout (read 0 while its step spins; thrust not steady)",
        }
    }
}

/// A row that was not used.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Dropped {
    /// Line in the file (1-based).
    pub line: usize,
    /// Why.
    pub reason: DropReason,
    /// The value or column concerned.
    pub detail: String,
}

/// Which file format a set came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Format {
    /// RCbenchmark / Tyto Robotics CSV export (the older app).
    RcBenchmark,
    /// Tyto Robotics' Flight Stand software's CSV export (`Powertrain 1 - ...` columns).
    FlightStand,
    /// Tyto Robotics' online test database's table (`Rotation speed (rpm)`, `Thrust (kgf)`).
    TytoDatabase,
    /// UIUC static file (RPM CT CP).
    UiucStatic,
    /// UIUC advance-ratio sweep (J CT CP eta).
    UiucSweep,
    /// CSV with a column map.
    Generic,
}

/// Where the RPM came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RpmSource {
    /// Optical (or other once-per-revolution) sensor.
    Optical,
    /// The ESC's electrical speed (commutation frequency over pole pairs).
    Electrical,
}

/// A file's points, with what was dropped and what was assumed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeasuredSet {
    /// The format detected.
    pub format: Format,
    /// How rows became points.
    pub reduction: Reduction,
    /// The points, in file order.
    pub points: Vec<MeasuredPoint>,
    /// Rows not used, in file order.
    pub dropped: Vec<Dropped>,
    /// Data rows read.
    pub rows: usize,
    /// True when the file has a torque (or power) measurement.
    pub has_torque: bool,
    /// Where the RPM came from (thrust stands).
    pub rpm_source: Option<RpmSource>,
    /// What was detected or assumed, for the report.
    pub notes: Vec<String>,
    /// Which propulsion unit of a file of several (`Powertrain 2`, the Series 1780's `B`).
    pub series: Option<String>,
    /// Why the data may not be a propeller's (thrust not rising with RPM, torque against
    /// thrust): said on the terminal and in the reports, exit 1.
    pub warnings: Vec<String>,
    /// What the sensors read with the propeller at rest, where the log has such rows (a time
    /// log's; `rest::at_rest`).
    pub at_rest: Option<AtRest>,
}

/// The sensors' readings with the propeller at rest (medians over the rows).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AtRest {
    /// Rows at rest.
    pub rows: usize,
    /// The supply current at rest [A] (the meter's offset and the ESC's own draw).
    pub amps: Option<f64>,
    /// The torque at rest [N m], in the sign the points carry (the cell's zero).
    pub torque: Option<f64>,
}

/// A file of a batch that could not be read: the others are read, this one named with why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Refused {
    /// The file as given.
    pub file: String,
    /// Why it was not read.
    pub reason: String,
}

impl MeasuredSet {
    /// Dropped rows that are faults (not idle rows).
    pub fn faults(&self) -> usize {
        self.dropped.iter().filter(|d| d.reason.is_fault()).count()
    }
}

/// A file that cannot be read as measured data.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ReadError {
    /// No header or no data rows.
    #[error("no data: {0}")]
    Empty(String),
    /// A needed column is absent.
    #[error("no {what} column (columns: {columns})")]
    MissingColumn {
        /// The quantity.
        what: &'static str,
        /// The headers found.
        columns: String,
    },
    /// A column's unit is not known.
    #[error("column '{column}': unknown unit '{unit}' for {quantity} (known: {known})")]
    UnknownUnit {
        /// Header as written.
        column: String,
        /// Unit as written.
        unit: String,
        /// The quantity.
        quantity: &'static str,
        /// Known units.
        known: &'static str,
    },
    /// The CSV structure is broken at a line.
    #[error("line {line}: {message}")]
    Line {
        /// Line (1-based).
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The column map is wrong.
    #[error("column map: {0}")]
    Map(String),
    /// Every row was dropped.
    #[error("no usable rows: {0}")]
    NoUsableRows(String),
    /// A choice made by the user does not fit the file.
    #[error("{0}")]
    Option(String),
}

/// "12 rows: 10 not spinning (RPM 0), 2 not a number (first at line 7)".
/// The error of a file that gave no point: what was dropped, and when nothing was, why the
/// rows left made no point (the reduction's last note) or that there were none.
pub fn no_points(dropped: &[Dropped], rows: usize, notes: &[String]) -> ReadError {
    if let Some(first) = dropped.iter().min_by_key(|d| d.line) {
        return ReadError::NoUsableRows(format!(
            "{}; line {}: {}",
            summarise_dropped(dropped),
            first.line,
            first.detail
        ));
    }
    if rows == 0 {
        return ReadError::Empty("a header and no data rows".into());
    }
    ReadError::NoUsableRows(format!(
        "no row was dropped, but {rows} rows made no point: {}",
        notes.last().map_or("no reduction applied", String::as_str)
    ))
}

/// "N rows dropped: ..." by reason, with the first line of each.
pub fn summarise_dropped(dropped: &[Dropped]) -> String {
    let mut by: std::collections::BTreeMap<DropReason, (usize, usize)> = Default::default();
    for d in dropped {
        let e = by.entry(d.reason).or_insert((0, d.line));
        e.0 += 1;
    }
    if by.is_empty() {
        return "no row was dropped".into();
    }
    let parts: Vec<String> = by
        .iter()
        .map(|(r, (n, first))| format!("{n} {} (first at line {first})", r.text()))
        .collect();
    format!("{} rows dropped: {}", dropped.len(), parts.join(", "))
}
