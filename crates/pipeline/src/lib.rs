//! propbet's stages as typed functions, under the `propbet` command.
//!
//! * what each stage is asked, in SI: `propbet_settings::spec`.
//! * [`case`]: case files (`case.toml`) and the plan of stages they ask for.
//! * [`stages`]: scan, polars, predict, compare, diagnose as functions returning artifacts.
//! * [`run`]: a case's plan run in memory ([`run::run_case`]).
//! * [`model`]: a prop file turned into the model a stage solves.
//! * [`design`]: blade files other than QPROP's (APC's PE0, UIUC tables, blade tables).
//! * [`band`]: a prediction's uncertainty band, from its model.
//!
//! The settings a user gives and the values as written are `propbet_settings`'.
//!
//! Inputs are read here; outputs are written by the caller. Progress goes through callbacks.
#![deny(missing_docs)]

pub mod band;
pub mod case;
pub mod design;
mod error;
pub mod model;
pub mod run;
mod solve;
pub mod stages;

pub(crate) use error::read_bytes;
pub use error::{read_text, Error, Result};
