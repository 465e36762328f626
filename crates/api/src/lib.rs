//! propbet's typed API: what a user asks for, in the words and units a user gives it, made
//! into the stages' specs here and only here, where every default and every check on a value
//! is applied once. The command line's argument parser fills these requests from its flags
//! and the Python package from its keyword arguments; neither builds or reads a command line
//! to reach the other.
//!
//! - [`ModelRequest`]: a propeller file and how to read it ([`ModelSpec`]);
//! - [`SweepRequest`]: rotation speeds with advance ratios or airspeeds;
//! - [`AirRequest`]: the air, as densities or as temperature, pressure and humidity;
//! - [`MeasuredRequest`]: measured files and how to read them ([`MeasuredSpec`]);
//! - [`DriveRequest`] and [`supply`]: what sets a motor's operating point, and the battery.
//!
//! The types these hand out, from the crates below, are in its modules [`bemt`], [`qprop`],
//! [`motor`](types::motor), [`measure`], [`compare`], ... (the binary's one door to them).
//!
//! What the commands do with them, in memory: [`model`] reads a propeller (a blade file's
//! polars computed), [`case`] checks a run before it starts, [`outputs`] makes each command's
//! files and tables, and [`files`] writes them, the separate and explicit step. Errors are
//! [`CommandError`]s. [`commands`] runs each command whole, telling a [`console::Console`]
//! what a person is told of it.
//!
//! Values come as numbers ([`Values::Numbers`]) or as the text a flag takes
//! ([`Values::Text`]: `4000:8000:1000`), and are named in every error by the name the caller
//! used.

pub mod case;
mod command_error;
pub mod commands;
pub mod console;
pub mod files;
pub mod model;
mod motor_file;
pub mod outputs;
mod request;
mod types;
pub mod workbench;

pub use command_error::{with_causes, CommandError, CommandResult};
pub use motor_file::{motor, motor_text, read_motor};
pub use types::motor::{Battery, Drive, KvSource, Motor, MotorFile, Supply};
pub use types::{
    atmosphere, bemt, compare, diagnose, effects, geometry, measure, motor, polar, qprop, settings, units, xfoil,
};

pub use request::{
    rpm_sources, supply, AirRequest, DiagnoseRequest, DriveRequest, MeasuredRequest, ModelRequest, PolarsRequest,
    ProcessRequest, SectionRequest, SweepRequest, Values,
};

/// The sources of the uncertainty band, in words (`--band`'s help).
pub use propbet_model::band::SOURCES_TEXT as BAND_SOURCES;
pub use propbet_model::{Error, Result};
pub use propbet_settings::scan::ScanSettings;
pub use propbet_settings::spec;
pub use propbet_settings::spec::{
    AirSpec, CompareSpec, DiagnoseSpec, MeasuredSpec, ModelSpec, PoweredSpec, PredictSpec, ScanSpec, SweepAxis,
    TableFormat,
};
