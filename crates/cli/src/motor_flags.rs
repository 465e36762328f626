//! The motor's flags of `propbet predict` (`--motor`, `--volts`, `--amps`, `--thrust`) and the
//! drivers they give.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::Args;
use propbet_pipeline::motor::{Battery, Drive, Supply};
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
    /// The battery, with --motor: `3S` (cells in series), then any of `2200mAh`, `R=5mOhm`
    /// (per cell), `V=3.7` (open-circuit volts per cell), `cutoff=3.3`, `usable=80%`, separated
    /// by commas (LiPo defaults: 3.7 V, 5 mOhm, cutoff 3.3 V, 80 % usable). Adds the throttle,
    /// the battery's current, voltage and power, and minutes of flight to every point.
    #[arg(long, requires = "motor", value_name = "SPEC")]
    pub battery: Option<String>,
    /// The ESC's resistance in the motor's current path [ohm], with --battery.
    #[arg(long, requires = "battery", default_value_t = 0.005, value_name = "OHMS")]
    pub esc_ohms: f64,
    /// Throttles (0 to 1, list or range syntax), with --battery: the battery through the ESC
    /// drives the motor.
    #[arg(long, requires = "battery", conflicts_with_all = ["volts", "amps", "thrust", "rpm"])]
    pub throttle: Option<String>,
}

impl MotorArgs {
    /// The drivers the flags give (`rpm` the sweep's --rpm).
    pub fn drives(&self, rpm: Option<&str>, supply: Option<&Supply>) -> Result<Vec<Drive>> {
        if let (Some(t), Some(s)) = (&self.throttle, supply) {
            let list = parse_list("--throttle", t)?;
            if let Some(bad) = list.iter().find(|t| !(0.0..=1.0).contains(*t)) {
                bail!("--throttle {bad}: a throttle is between 0 and 1");
            }
            return Ok(list.into_iter().map(|t| s.drive(t)).collect());
        }
        Ok(match (&self.volts, &self.amps, &self.thrust, rpm) {
            (Some(v), ..) => parse_list("--volts", v)?.into_iter().map(Drive::Volts).collect(),
            (_, Some(a), ..) => parse_list("--amps", a)?.into_iter().map(Drive::Amps).collect(),
            (_, _, Some(t), _) => parse_list("--thrust", t)?.into_iter().map(Drive::Thrust).collect(),
            (_, _, _, Some(r)) => parse_list("--rpm", r)?
                .into_iter()
                .map(|r| Drive::Omega(rpm_to_omega(r)))
                .collect(),
            _ => bail!("--motor: give --volts, --amps, --thrust, --rpm or --throttle (what sets the operating point)"),
        })
    }

    /// The battery and ESC the flags give.
    pub fn supply(&self) -> Result<Option<Supply>> {
        self.battery.as_deref().map(|b| supply(b, self.esc_ohms)).transpose()
    }
}

/// The battery and ESC of `--battery SPEC` and `--esc-ohms`.
pub fn supply(spec: &str, esc_ohms: f64) -> Result<Supply> {
    let battery = Battery::parse(spec).map_err(|e| anyhow::anyhow!("--battery '{spec}': {e}"))?;
    if !(0.0..10.0).contains(&esc_ohms) {
        bail!("--esc-ohms {esc_ohms}: a resistance from 0 to 10 ohm");
    }
    Ok(Supply { battery, esc_ohms })
}
