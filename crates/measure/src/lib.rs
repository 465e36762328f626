//! Measured propeller data reduced to steady operating points.
//!
//! [`text`] turns a file's bytes into text (UTF-8 or Windows-1252, CR / LF / CRLF).
//!
//! Readers (all take text and return values; files and messages naming them live in the CLI):
//! - [`stand`]: thrust-stand logs read by column name: RCbenchmark and Tyto's older app (Series
//!   1520, 1580, 1585 and 1780, trimmed or with script columns), Tyto's Flight Stand software
//!   (one series per powertrain) and Tyto's test database; sparse rows (each sensor at its own
//!   rate) take each sensor's latest reading;
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
pub mod plausible;
pub mod reduce;
pub mod rest;
mod set;
pub mod stand;
pub mod table;
pub mod text;
pub mod uiuc;
pub mod units;
pub mod write;

pub use options::ReadOptions;
pub use reduce::{ReduceOptions, Reduction};
pub use set::*;
pub use units::Quantity;

/// Reads a file's bytes ([`text::decode`]: UTF-8 or Windows-1252, any line ends), every series
/// of it: one set per propulsion unit of a thrust-stand log that holds several, else one.
pub fn read_file(bytes: &[u8], opts: &ReadOptions) -> Result<Vec<MeasuredSet>, ReadError> {
    let (text, note) = text::decode(bytes)?;
    let mut sets = read_all(&text, opts)?;
    if let Some(note) = note {
        for s in &mut sets {
            s.notes.insert(0, note.clone());
        }
    }
    Ok(sets)
}

/// Reads any supported format, detected from the content: the file's first series.
pub fn read(text: &str, opts: &ReadOptions) -> Result<MeasuredSet, ReadError> {
    Ok(read_all(text, opts)?.remove(0))
}

/// Reads any supported format, detected from the content: every series.
pub fn read_all(text: &str, opts: &ReadOptions) -> Result<Vec<MeasuredSet>, ReadError> {
    let text = text::lf(text.strip_prefix('\u{feff}').unwrap_or(text));
    let text = text.as_str();
    let first = text.lines().find(|l| !l.trim().is_empty()).unwrap_or("");
    if opts.column_map.is_some() {
        return generic::read(text, opts).map(|s| vec![s]);
    }
    let sets = if table::delimiter(first) == b',' && !first.contains(',') {
        vec![uiuc::read(text, opts.name.as_deref())?]
    } else if stand::looks_like(&table::header_cells(first)) {
        stand::read(text, opts)?
    } else {
        vec![generic::read(text, opts)?]
    };
    // A file of zeros (a sweep of CT = CP = 0, a log whose load cells were unplugged) gives
    // no relative error anywhere and nothing to fit.
    let thrust = |p: &MeasuredPoint| match p.loads {
        Loads::Forces { thrust, .. } => thrust.mean,
        Loads::Coefficients { ct, .. } => ct,
    };
    for set in &sets {
        if set.points.iter().all(|p| thrust(p) == 0.0) {
            return Err(ReadError::NoUsableRows(format!(
                "the thrust (or CT) of every one of its {} points is 0: a file of zeros, nothing to compare",
                set.points.len()
            )));
        }
    }
    Ok(sets)
}
