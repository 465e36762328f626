//! propbet's stages as typed functions, under the `propbet` command.
//!
//! * what each stage is asked, in SI: `propbet_settings::spec`.
//! * [`case`]: case files (`case.toml`) and the plan of stages they ask for.
//! * [`stages`]: scan, polars, predict, compare, diagnose as functions returning artifacts.
//! * [`run`]: a case's plan run in memory ([`run::run_case`]).
//!
//! The model the stages solve (its blade files, solves and band, and the error) is
//! `propbet_model`'s.
//!
//! The settings a user gives and the values as written are `propbet_settings`'.
//!
//! Inputs are read here; outputs are written by the caller. Progress goes through callbacks.
#![deny(missing_docs)]

pub mod case;
pub mod run;
pub mod stages;

pub(crate) use propbet_model::{conflict, nothing, out_of_range, read_bytes, read_text, Error, Result};
