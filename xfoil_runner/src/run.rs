//! Running XFOIL sweeps: processes, watchdog, restarts.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use serde::{Deserialize, Serialize};

use crate::display::PrivateDisplay;
use crate::output::{parse_polar_file, XfoilPoint};
use crate::script::{self, RunSettings, Step};
use crate::XfoilError;

/// Which X display XFOIL gets.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum DisplayChoice {
    /// A private Xvfb server started on first use (the default; Debian's XFOIL needs a display).
    PrivateXvfb {
        /// The Xvfb executable.
        xvfb: PathBuf,
    },
    /// An existing display, for example `:0`.
    Existing(String),
    /// No display: only for an XFOIL built without floating-point traps.
    Headless,
}

/// How XFOIL is run.
#[derive(Debug, Clone, PartialEq)]
pub struct XfoilConfig {
    /// The XFOIL executable.
    pub executable: PathBuf,
    /// Its display.
    pub display: DisplayChoice,
    /// A run that prints nothing for this long is taken as hung and killed.
    pub stall_timeout: Duration,
    /// A run may take at most `startup_timeout + point_timeout * (angles + 1)`.
    pub startup_timeout: Duration,
    /// See `startup_timeout`.
    pub point_timeout: Duration,
    /// Restarts per sweep direction after crashes or hangs before the rest is given up.
    pub max_restarts: usize,
    /// Longest a whole sweep (one polar, every restart and retry) may take; what is left
    /// then is given up (a fault of kind [`FaultKind::OverBudget`]).
    pub sweep_budget: Duration,
}

impl XfoilConfig {
    /// Defaults for `executable`: a private Xvfb (found on `PATH`), 5 s without output is a
    /// hang, 5 s + 2 s per angle at most, 6 restarts per direction.
    pub fn new(executable: PathBuf) -> Self {
        let xvfb = crate::find::find_on_path("Xvfb", std::env::var_os("PATH").as_deref())
            .unwrap_or_else(|| PathBuf::from("Xvfb"));
        XfoilConfig {
            executable,
            display: DisplayChoice::PrivateXvfb { xvfb },
            stall_timeout: Duration::from_secs(5),
            startup_timeout: Duration::from_secs(5),
            point_timeout: Duration::from_secs(2),
            max_restarts: 6,
            sweep_budget: Duration::from_secs(120),
        }
    }
}

/// How a section's polar is asked for, at any Reynolds and Mach number: the transition (Ncrit,
/// a trip), the angles, and XFOIL's panels and iterations. The one carrier of these settings
/// from a blade's polars down to XFOIL's script (NeuralFoil reads the transition from it too).
#[derive(Debug, Clone, PartialEq)]
pub struct SectionSettings {
    /// e^n amplification ratio (9 = average wind tunnel) [-].
    pub ncrit: f64,
    /// Forced transition at this fraction of the chord on both surfaces (XFOIL's XTR), at
    /// the latest: free transition ahead of it still happens. None: free transition only.
    pub trip: Option<f64>,
    /// Angles of attack [deg], ascending, evenly spaced or not.
    pub alphas_deg: Vec<f64>,
    /// Viscous iteration limit per point (XFOIL's ITER).
    pub max_iter: u32,
    /// Panel nodes (XFOIL's PPAR N, at most 490 in XFOIL 6.99; None: the asker's default,
    /// [`DEFAULT_PANELS`] here).
    pub panels: Option<u32>,
}

impl SectionSettings {
    /// Ncrit 9, free transition, [`DEFAULT_PANELS`] and [`DEFAULT_MAX_ITER`], at `alphas_deg`.
    pub fn new(alphas_deg: Vec<f64>) -> Self {
        SectionSettings {
            ncrit: 9.0,
            trip: None,
            alphas_deg,
            max_iter: DEFAULT_MAX_ITER,
            panels: None,
        }
    }

    /// The panel nodes XFOIL is asked for.
    pub fn panel_count(&self) -> u32 {
        self.panels.unwrap_or(DEFAULT_PANELS)
    }
}

/// One viscous alpha sweep to run.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepRequest {
    /// Airfoil contour in Selig order (trailing edge, upper surface, leading edge, lower surface).
    pub coordinates: Vec<[f64; 2]>,
    /// Chord Reynolds number [-].
    pub reynolds: f64,
    /// Mach number [-].
    pub mach: f64,
    /// The transition, the angles, the panels and iterations.
    pub section: SectionSettings,
}

impl SweepRequest {
    /// A request with [`SectionSettings::new`]'s settings.
    pub fn new(coordinates: Vec<[f64; 2]>, reynolds: f64, mach: f64, alphas_deg: Vec<f64>) -> Self {
        SweepRequest {
            coordinates,
            reynolds,
            mach,
            section: SectionSettings::new(alphas_deg),
        }
    }

    fn validate(&self) -> Result<(), XfoilError> {
        use propbet_units::show;
        let bad = |m: String| Err(XfoilError::BadRequest(m));
        if !(self.reynolds.is_finite() && self.reynolds > 0.0 && self.reynolds < 1e9) {
            return bad(format!("Reynolds number {} must be in (0, 1e9)", show(self.reynolds)));
        }
        if !(self.mach.is_finite() && (0.0..0.9).contains(&self.mach)) {
            return bad(format!("Mach number {} must be in [0, 0.9)", show(self.mach)));
        }
        if !(self.section.ncrit.is_finite() && self.section.ncrit > 0.0 && self.section.ncrit <= 20.0) {
            return bad(format!("Ncrit {} must be in (0, 20]", show(self.section.ncrit)));
        }
        if let Some(x) = self.section.trip.filter(|x| !(x.is_finite() && *x > 0.0 && *x <= 1.0)) {
            return bad(format!("forced transition at x/c = {} must be in (0, 1]", show(x)));
        }
        if !(1..=1000).contains(&self.section.max_iter) {
            return bad(format!("iteration limit {} must be in 1..=1000", self.section.max_iter));
        }
        if !(40..=490).contains(&self.section.panel_count()) {
            return bad(format!(
                "panel count {} must be in 40..=490",
                self.section.panel_count()
            ));
        }
        if self.section.alphas_deg.is_empty() || self.section.alphas_deg.len() > 2000 {
            return bad(format!(
                "{} angles requested; give 1 to 2000",
                self.section.alphas_deg.len()
            ));
        }
        if let Some(a) = self
            .section
            .alphas_deg
            .iter()
            .find(|a| !(a.is_finite() && a.abs() <= 90.0))
        {
            return bad(format!("angle of attack {a} deg is outside -90..90"));
        }
        if self.section.alphas_deg.windows(2).any(|w| w[1] <= w[0]) {
            return bad("angles of attack must be strictly ascending".into());
        }
        if self.coordinates.len() < 10 || self.coordinates.len() > 2000 {
            return bad(format!(
                "{} coordinate points; XFOIL needs 10 to 2000",
                self.coordinates.len()
            ));
        }
        if let Some((i, _)) = self
            .coordinates
            .iter()
            .enumerate()
            .find(|(_, p)| !(p[0].is_finite() && p[1].is_finite()))
        {
            return bad(format!("coordinate point {} is not finite", i + 1));
        }
        Ok(())
    }
}

/// How a run failed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum FaultKind {
    /// XFOIL died (a signal such as SIGFPE, or a non-zero exit).
    Crash {
        /// The exit status as the system reported it.
        status: String,
    },
    /// XFOIL stopped printing, or overran its time budget, and was killed.
    Hang {
        /// How long it ran [s].
        seconds: f64,
    },
    /// The polar's (or the command's) time budget ran out: the angles left were given up.
    OverBudget {
        /// The time spent on the polar [s].
        seconds: f64,
    },
}

/// One crash or hang, at the angle XFOIL was working on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Fault {
    /// What happened.
    pub kind: FaultKind,
    /// The angle given up [deg] (the first one after the last converged point).
    pub alpha_deg: f64,
    /// The last lines XFOIL printed.
    pub output_tail: String,
}

impl std::fmt::Display for Fault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.kind {
            FaultKind::Crash { status } => write!(f, "XFOIL crashed ({status}) at alpha {} deg", self.alpha_deg),
            FaultKind::Hang { seconds } => {
                write!(
                    f,
                    "XFOIL hung at alpha {} deg and was killed after {seconds:.1} s",
                    self.alpha_deg
                )
            }
            FaultKind::OverBudget { seconds } => write!(
                f,
                "the time budget ran out after {seconds:.1} s: alpha {} deg and the angles after it were given up",
                self.alpha_deg
            ),
        }
    }
}

/// What a sweep produced.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct SweepOutcome {
    /// Converged points, ascending in alpha.
    pub points: Vec<XfoilPoint>,
    /// Angles XFOIL tried but did not converge, or that were given up after a fault [deg].
    pub unconverged_deg: Vec<f64>,
    /// Crashes and hangs, each followed by a restart beyond the failed angle.
    pub faults: Vec<Fault>,
    /// XFOIL processes started.
    pub runs: usize,
    /// Angles where the sweep's return ([`Xfoil::sweep`]) found another solution than its way
    /// out: a hysteresis loop.
    #[serde(default)]
    pub hysteresis: Vec<Branches>,
    /// Points of the returns, before they are set against the outward ones.
    #[serde(skip)]
    returned: Vec<XfoilPoint>,
}

/// Two converged solutions at one angle, from the two directions of approach; the one kept in
/// the polar is the one with the lower drag (attached flow, which a disturbed stream such as a
/// rotating blade's reattaches to), the other is kept here for the record.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Branches {
    /// The solution in the polar.
    pub kept: XfoilPoint,
    /// The other one.
    pub other: XfoilPoint,
}

/// Lift coefficients further apart than this at one angle are two branches [-] (XFOIL's
/// converged lift repeats to 1e-4 from the same side; loops at low Re differ by 0.05-0.2).
pub const HYSTERESIS_CL: f64 = 0.02;

/// How far the sweep returns over the angles it came through: from the highest requested angle
/// down over this many degrees (stall hysteresis lives within a few degrees past the lift
/// peak), and from the lowest up over [`LOWER_RETURN_DEG`] [deg].
pub const UPPER_RETURN_DEG: f64 = 8.0;
/// See [`UPPER_RETURN_DEG`].
pub const LOWER_RETURN_DEG: f64 = 4.0;

/// Steps of a return over `alphas` (continuing, nothing re-initialised).
fn returning(alphas: impl Iterator<Item = f64>) -> impl Iterator<Item = Step> {
    alphas.map(|alpha_deg| Step {
        alpha_deg,
        init: false,
        returning: true,
    })
}

/// Whether two angles are the same requested angle (XFOIL prints three decimals).
fn same_angle(a: f64, b: f64) -> bool {
    (a - b).abs() < ALPHA_MATCH_DEG
}

/// Whether `points` hold one at angle `x`.
fn has_angle(points: &[XfoilPoint], x: f64) -> bool {
    points.iter().any(|p| same_angle(p.alpha_deg, x))
}

/// An XFOIL installation ready to run sweeps; share it between threads.
#[derive(Debug)]
pub struct Xfoil {
    config: XfoilConfig,
    display: Mutex<Option<Arc<PrivateDisplay>>>,
}

enum Ending {
    Finished,
    Crashed(ExitStatus),
    Hung(Duration),
}

impl Ending {
    /// The fault this ending is, if any.
    fn fault(&self) -> Option<FaultKind> {
        match self {
            Ending::Finished => None,
            Ending::Crashed(status) => Some(FaultKind::Crash {
                status: status.to_string(),
            }),
            Ending::Hung(t) => Some(FaultKind::Hang {
                seconds: t.as_secs_f64(),
            }),
        }
    }
}

struct RunOutput {
    ending: Ending,
    /// XFOIL got as far as the sweep (its log says "Polar accumulation enabled").
    reached_sweep: bool,
    points: Vec<XfoilPoint>,
    output_tail: String,
    /// XFOIL stopped because it could not connect to its X display (Xlib's `XOpenDisplay`).
    display_refused: bool,
}

/// What Debian's XFOIL prints (then exits 1) when it cannot connect to its X display.
const DISPLAY_REFUSED: &[u8] = b"Cannot open display";
/// Runs started in all when XFOIL cannot open its display ([`Xfoil::with_display_retries`]).
pub const DISPLAY_ATTEMPTS: u32 = 4;
/// Pause before the second attempt, doubled before each next one (0.1 + 0.2 + 0.4 s in all).
const DISPLAY_RETRY_PAUSE: Duration = Duration::from_millis(100);

/// Whether `haystack` holds `needle`.
fn contains(haystack: &[u8], needle: &[u8]) -> bool {
    haystack.windows(needle.len()).any(|w| w == needle)
}

const TAIL_BYTES: usize = 3000;
/// Viscous iterations per angle: continuation converges in far fewer, and an angle that fails
/// costs them all.
pub const DEFAULT_MAX_ITER: u32 = 75;
/// Panel nodes: XFOIL's own default.
pub const DEFAULT_PANELS: u32 = 160;
/// Iteration limit of the retry pass (see [`Xfoil::sweep`]).
const RETRY_ITER: u32 = 40;
/// Angles closer than this are the same (XFOIL saves alpha with three decimals).
const ALPHA_MATCH_DEG: f64 = 2e-3;

mod process;

#[cfg(test)]
mod tests {
    use super::process::tail;

    #[test]
    fn output_tails_carry_no_control_bytes() {
        let t = tail(b"\x1b[31mred\x1b[0m\x07 a =  1.0\r\n\tdone\x00\n");
        assert_eq!(t, "[31mred[0m a =  1.0\n\tdone\n");
    }
}
