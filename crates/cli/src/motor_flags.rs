//! The motor's flags of `propbet predict` (`--motor`, `--volts`, `--amps`, `--thrust`) and the
//! drivers they give.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use propbet_api::motor::{Drive, Supply};
use propbet_api::{DriveRequest, Values};

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
    pub volts: Option<Values>,
    /// Motor currents [A], with --motor.
    #[arg(long, requires = "motor", conflicts_with_all = ["volts", "thrust", "rpm"])]
    pub amps: Option<Values>,
    /// Thrusts [N] (hover: the weight carried by this propeller), with --motor.
    #[arg(long, requires = "motor", conflicts_with_all = ["volts", "amps", "rpm"])]
    pub thrust: Option<Values>,
    /// The battery, with --motor: `3S` (cells in series), then any of `2200mAh`, `R=5mOhm`
    /// (per cell), `V=3.7` (open-circuit volts per cell), `cutoff=3.3`, `usable=80%`, separated
    /// by commas (LiPo defaults: 3.7 V, 5 mOhm, cutoff 3.3 V, 80 % usable). Adds the throttle,
    /// the battery's current, voltage and power, and minutes of flight to every point.
    #[arg(long, requires = "motor", value_name = "SPEC")]
    pub battery: Option<String>,
    /// The ESC's resistance in the motor's current path [ohm], with --battery.
    #[arg(long, requires = "battery", default_value_t = propbet_api::motor::ESC_OHMS, value_name = "OHMS")]
    pub esc_ohms: f64,
    /// Throttles (0 to 1, list or range syntax), with --battery: the battery through the ESC
    /// drives the motor.
    #[arg(long, requires = "battery", conflicts_with_all = ["volts", "amps", "thrust", "rpm"])]
    pub throttle: Option<Values>,
}

impl MotorArgs {
    /// The drivers the flags give (`rpm` the sweep's --rpm).
    pub fn drives(&self, rpm: Option<&Values>, supply: Option<&Supply>) -> Result<Vec<Drive>> {
        let request = DriveRequest {
            volts: self.volts.clone(),
            amps: self.amps.clone(),
            thrust: self.thrust.clone(),
            rpm: rpm.cloned(),
            throttle: self.throttle.clone(),
        };
        Ok(request.drives(supply)?)
    }

    /// The battery and ESC the flags give.
    pub fn supply(&self) -> Result<Option<Supply>> {
        Ok(self
            .battery
            .as_deref()
            .map(|b| propbet_api::supply(b, self.esc_ohms))
            .transpose()?)
    }
}
