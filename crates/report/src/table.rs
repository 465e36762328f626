//! propbet's tables, whole: numbers as every table prints them ([`Num`], [`push_num`]), rows as
//! CSV, the same rows as typed columns for Python ([`columns`]); a prediction's tables
//! ([`sweep`]), a propeller's on its motor ([`powered`]), a comparison's points ([`points`]),
//! propellers side by side ([`props`]). The binary writes the bytes these make.

pub mod columns;
pub mod measured;
pub mod motor;
mod number;
pub mod points;
pub mod powered;
pub mod props;
pub mod stations;
pub mod sweep;
pub mod validation;

pub use number::{bytes, csv_rows, push_num, text, written, Num};

/// A table that could not be made: its CSV, its columns or its JSON.
#[derive(Debug)]
pub enum Error {
    /// Writing CSV.
    Csv(csv::Error),
    /// Gathering typed columns.
    Columns(columns::Error),
    /// Writing JSON.
    Json(serde_json::Error),
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Error::Csv(e) => write!(f, "writing CSV: {e}"),
            Error::Columns(e) => write!(f, "gathering columns: {e}"),
            Error::Json(e) => write!(f, "writing JSON: {e}"),
        }
    }
}

impl std::error::Error for Error {}

impl From<csv::Error> for Error {
    fn from(e: csv::Error) -> Self {
        Error::Csv(e)
    }
}

impl From<columns::Error> for Error {
    fn from(e: columns::Error) -> Self {
        Error::Columns(e)
    }
}

impl From<serde_json::Error> for Error {
    fn from(e: serde_json::Error) -> Self {
        Error::Json(e)
    }
}
