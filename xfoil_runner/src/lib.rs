//! The only crate in propbet that starts a process: it drives XFOIL 6.99.
//!
//! * [`find_xfoil`] locates the executable (with an install hint when it is missing).
//! * [`Xfoil`] runs viscous alpha sweeps: each run in its own temporary directory, coordinates
//!   written by us, a command script built only from numbers and fixed keywords (see
//!   [`script`]), a private X display (see [`display`] for why), a watchdog that kills a run
//!   that stops printing or overruns, and restarts beyond the angle where XFOIL crashed.
//!
//! Sweeps go from the grid angle nearest zero outward in both directions, so that the boundary
//! layer converges by continuation; each direction is its own XFOIL process.
#![deny(missing_docs)]

pub mod display;
pub mod fake;
mod find;
pub mod interrupt;
mod output;
mod run;
pub mod script;

pub use find::{find_xfoil, FindXfoilError};
pub use output::{parse_polar_file, XfoilPoint};
pub use run::{
    Branches, DisplayChoice, Fault, FaultKind, SectionSettings, SweepOutcome, SweepRequest, Xfoil, XfoilConfig,
    DEFAULT_MAX_ITER, DEFAULT_PANELS, DISPLAY_ATTEMPTS,
};

use thiserror::Error;

/// Everything that can go wrong driving XFOIL. Errors that come from an XFOIL run carry the end
/// of what XFOIL printed.
#[derive(Debug, Error)]
pub enum XfoilError {
    /// The executable is missing.
    #[error(transparent)]
    NotFound(#[from] FindXfoilError),
    /// The private X display could not be started.
    #[error("{0} (install it with `apt-get install xvfb xfonts-base`)")]
    Display(String),
    /// The request itself is invalid (checked before any process starts).
    #[error("invalid XFOIL request: {0}")]
    BadRequest(String),
    /// A file or process operation failed.
    #[error("{context}: {source}")]
    Io {
        /// What was being done.
        context: String,
        /// The underlying error.
        source: std::io::Error,
    },
    /// XFOIL wrote something we cannot read.
    #[error("XFOIL produced unreadable output: {detail}\n--- end of XFOIL's output ---\n{output_tail}")]
    Garbage {
        /// What was wrong.
        detail: String,
        /// The last lines XFOIL printed.
        output_tail: String,
    },
    /// XFOIL died or hung before its first angle (loading or paneling the airfoil).
    #[error("XFOIL failed before the first angle ({status}), while loading or paneling the airfoil\n--- end of XFOIL's output ---\n{output_tail}")]
    Startup {
        /// How it ended.
        status: String,
        /// The last lines XFOIL printed.
        output_tail: String,
    },
    /// Every run crashed or hung before converging a single point.
    #[error("XFOIL converged no point: {summary}\n--- end of XFOIL's output ---\n{output_tail}")]
    NoPoints {
        /// The faults, one per line.
        summary: String,
        /// The last lines XFOIL printed in the last run.
        output_tail: String,
    },
}

impl XfoilError {
    pub(crate) fn io(context: impl Into<String>, source: std::io::Error) -> Self {
        XfoilError::Io {
            context: context.into(),
            source,
        }
    }
}
