//! The motor's flags of `propbet predict` (`--motor`, `--volts`, `--amps`, `--thrust`) and the
//! drivers they give.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::Args;
use propbet_pipeline::motor::Drive;
use propbet_pipeline::units::rpm_to_omega;
use propbet_pipeline::values::parse_list;

/// The motor that turns the propeller, and what sets its operating point.
#[derive(Debug, Args)]
pub struct MotorArgs {
    /// A QPROP motor file (type 1: R, Io, Kv; type 2: R0, Io0, Kv, Kq, tau, Io1, Io2, R2): the
    /// RPM becomes the speed where motor and propeller torques meet, at --volts, --amps or
    /// --thrust (with --rpm: the voltage and current at those speeds).
    #[arg(long, value_name = "FILE")]
    pub motor: Option<PathBuf>,
    /// Terminal voltages [V] (list or range syntax, as --rpm), with --motor.
    #[arg(long, requires = "motor", conflicts_with_all = ["amps", "thrust", "rpm"])]
    pub volts: Option<String>,
    /// Motor currents [A], with --motor.
    #[arg(long, requires = "motor", conflicts_with_all = ["volts", "thrust", "rpm"])]
    pub amps: Option<String>,
    /// Thrusts [N] (hover: the weight carried by this propeller), with --motor.
    #[arg(long, requires = "motor", conflicts_with_all = ["volts", "amps", "rpm"])]
    pub thrust: Option<String>,
}

impl MotorArgs {
    /// The drivers the flags give (`rpm` the sweep's --rpm).
    pub fn drives(&self, rpm: Option<&str>) -> Result<Vec<Drive>> {
        Ok(match (&self.volts, &self.amps, &self.thrust, rpm) {
            (Some(v), ..) => parse_list("--volts", v)?.into_iter().map(Drive::Volts).collect(),
            (_, Some(a), ..) => parse_list("--amps", a)?.into_iter().map(Drive::Amps).collect(),
            (_, _, Some(t), _) => parse_list("--thrust", t)?.into_iter().map(Drive::Thrust).collect(),
            (_, _, _, Some(r)) => parse_list("--rpm", r)?
                .into_iter()
                .map(|r| Drive::Omega(rpm_to_omega(r)))
                .collect(),
            _ => bail!("--motor: give --volts, --amps, --thrust or --rpm (what sets the operating point)"),
        })
    }
}
