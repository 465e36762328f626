//! Measured propeller data reduced to steady operating points.
//!
//! Readers (all take text and return values; files and messages naming them live in the CLI):
//! - [`rcbenchmark`]: RCbenchmark / Tyto Robotics thrust-stand exports, every header variant of
//!   Series 1520, 1580, 1585 and 1780 (BOM, trailing comma, `µs`, `N·m`, `ºC`, gf / kgf / N,
//!   electrical or optical RPM, script columns, rows longer than the header);
//! - [`uiuc`]: UIUC Propeller Data Site files (static `RPM CT CP`, sweeps `J CT CP eta`);
//! - [`generic`]: any CSV with a column map (TOML) or self-describing headers (`thrust_N`).
//!
//! [`reduce`] turns a log of samples into points: ESC steps are detected, their transient
//! dropped and their steady part averaged with its scatter kept as the uncertainty; ramps are
//! binned by RPM (and airspeed). Rows that cannot be used are never silently lost: each is a
//! [`Dropped`] with its line and reason.
#![deny(missing_docs)]

pub mod generic;
mod options;
pub mod rcbenchmark;
pub mod reduce;
mod set;
pub mod table;
pub mod uiuc;
pub mod units;
pub mod write;

pub use options::ReadOptions;
pub use reduce::{ReduceOptions, Reduction};
pub use set::*;
pub use units::Quantity;

/// Reads any supported format, detected from the content.
pub fn read(text: &str, opts: &ReadOptions) -> Result<MeasuredSet, ReadError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let first = text.lines().find(|l| !l.trim().is_empty()).unwrap_or("");
    if opts.column_map.is_some() {
        return generic::read(text, opts);
    }
    let set = if table::delimiter(first) == b',' && !first.contains(',') {
        uiuc::read(text, opts.name.as_deref())?
    } else if rcbenchmark::looks_like(first) {
        rcbenchmark::read(text, opts)?
    } else {
        generic::read(text, opts)?
    };
    // A file of zeros (a sweep of CT = CP = 0, a log whose load cells were unplugged) gives
    // no relative error anywhere and nothing to fit.
    let thrust = |p: &MeasuredPoint| match p.loads {
        Loads::Forces { thrust, .. } => thrust.mean,
        Loads::Coefficients { ct, .. } => ct,
    };
    if set.points.iter().all(|p| thrust(p) == 0.0) {
        return Err(ReadError::NoUsableRows(format!(
            "the thrust (or CT) of every one of its {} points is 0: a file of zeros, nothing to compare",
            set.points.len()
        )));
    }
    Ok(set)
}
