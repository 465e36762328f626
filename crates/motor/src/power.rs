//! The battery and the ESC in front of the motor, as simple models (stated so, with their
//! sources), so that an operating point can be asked for at a throttle, and a hover point
//! says its throttle and how long the battery lasts there.
//!
//! - Battery: `cells` in series, each an open-circuit voltage behind an internal resistance
//!   (the Thevenin cell of battery modelling, e.g. Tremblay & Dessaint 2009 without the
//!   charge-dependent terms): terminal voltage $V_b = n (V_{oc} - I_b R_{cell})$. The
//!   open-circuit voltage is one number, not a discharge curve: 3.7 V per cell by default
//!   (a lithium-polymer cell's rated nominal voltage, its mean over a discharge).
//! - ESC: an ideal PWM switch with a resistance in the motor's current path (MOSFETs and
//!   wiring): the motor sees the average $V_m = \tau V_b - I_m R_{esc}$ at throttle $\tau$
//!   and the battery gives $I_b = \tau I_m$ (power through the switch conserved). Timing,
//!   switching losses and the ESC's own current are not modelled.
//!
//! Together they are a source of $E = \tau n V_{oc}$ behind $R_s = \tau^2 n R_{cell} + R_{esc}$
//! for the motor ([`Supply::source`]).

use thiserror::Error;

/// A battery of cells in series.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Battery {
    /// Cells in series.
    pub cells: u32,
    /// Open-circuit voltage of a cell [V].
    pub cell_volts: f64,
    /// Internal resistance of a cell [ohm].
    pub cell_ohms: f64,
    /// Capacity [A h] (0: not given).
    pub capacity_ah: f64,
    /// The lowest loaded cell voltage allowed [V].
    pub cutoff_volts: f64,
    /// The fraction of the capacity used before landing [-].
    pub usable: f64,
}

/// Defaults of a lithium-polymer cell: nominal 3.7 V, 5 mOhm (a 2,200 mAh 25C cell measures
/// 3 to 8), cut off at 3.3 V under load, 80 % of the capacity used (the hobby's rule of thumb
/// for cell life).
pub const LIPO: Battery = Battery {
    cells: 1,
    cell_volts: 3.7,
    cell_ohms: 0.005,
    capacity_ah: 0.0,
    cutoff_volts: 3.3,
    usable: 0.8,
};

/// The ESC's resistance where none is given [ohm]: MOSFETs and wiring of a hobby ESC of
/// 20-40 A (its MOSFETs' on-resistance, a few mOhm, and the leads).
pub const ESC_OHMS: f64 = 0.005;

/// A battery or ESC setting that cannot be.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("{what}: {why}")]
pub struct PowerError {
    /// The piece of the spec.
    pub what: String,
    /// What is wrong.
    pub why: String,
}

fn bad(what: &str, why: impl Into<String>) -> PowerError {
    PowerError {
        what: what.to_string(),
        why: why.into(),
    }
}

/// A number with an optional unit suffix from `units` (each with its factor to SI).
fn number(piece: &str, text: &str, units: &[(&str, f64)]) -> Result<f64, PowerError> {
    let t = text.trim();
    let lower = t.to_ascii_lowercase();
    let (num, factor) = units
        .iter()
        .find(|(u, _)| lower.ends_with(&u.to_ascii_lowercase()))
        .map_or((t, 1.0), |(u, f)| (&t[..t.len() - u.len()], *f));
    num.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .map(|v| v * factor)
        .ok_or_else(|| bad(piece, "not a number"))
}

impl Battery {
    /// Reads a battery spec: `3S` (cells, required), then any of `2200mAh` (or `2.2Ah`),
    /// `R=5mOhm` (per cell; ohms without a unit), `V=3.85` (open-circuit volts per cell),
    /// `cutoff=3.3`, `usable=80%`, separated by commas; LiPo defaults ([`LIPO`]) for the rest.
    pub fn parse(spec: &str) -> Result<Battery, PowerError> {
        let mut b = LIPO;
        let mut cells = None;
        for piece in spec.split(',').map(str::trim).filter(|p| !p.is_empty()) {
            let lower = piece.to_ascii_lowercase();
            if let Some(n) = lower
                .strip_suffix('s')
                .filter(|n| n.chars().all(|c| c.is_ascii_digit()))
            {
                let n: u32 = n.parse().map_err(|_| bad(piece, "not a cell count"))?;
                cells = Some(n);
            } else if lower.ends_with("mah") || lower.ends_with("ah") {
                b.capacity_ah = number(piece, piece, &[("mAh", 1e-3), ("Ah", 1.0)])?;
            } else if let Some((key, value)) = piece.split_once('=') {
                match key.trim().to_ascii_lowercase().as_str() {
                    "r" => b.cell_ohms = number(piece, value, &[("mOhm", 1e-3), ("Ohm", 1.0)])?,
                    "v" => b.cell_volts = number(piece, value, &[("V", 1.0)])?,
                    "cutoff" => b.cutoff_volts = number(piece, value, &[("V", 1.0)])?,
                    "usable" => b.usable = number(piece, value, &[("%", 0.01)])?,
                    _ => return Err(bad(piece, "unknown; give 3S, 2200mAh, R=, V=, cutoff=, usable=")),
                }
            } else {
                return Err(bad(piece, "unknown; give 3S, 2200mAh, R=, V=, cutoff=, usable="));
            }
        }
        b.cells = cells.ok_or_else(|| bad(spec, "no cell count (3S for three cells in series)"))?;
        b.check().map(|_| b)
    }

    /// The spec [`Battery::parse`] reads back to this battery: every value written, in ohms,
    /// volts and ampere-hours (`3S,2.2Ah,R=0.005,V=3.7,cutoff=3.3,usable=0.8`).
    pub fn text(&self) -> String {
        let capacity = if self.capacity_ah > 0.0 {
            format!(",{}Ah", self.capacity_ah)
        } else {
            String::new()
        };
        format!(
            "{}S{capacity},R={},V={},cutoff={},usable={}",
            self.cells, self.cell_ohms, self.cell_volts, self.cutoff_volts, self.usable
        )
    }

    /// The battery's values are a battery's.
    pub fn check(&self) -> Result<(), PowerError> {
        if self.cells == 0 || self.cells > 100 {
            return Err(bad(&format!("{}S", self.cells), "between 1 and 100 cells"));
        }
        if !(self.cell_volts > 0.0 && self.cell_volts < 10.0) {
            return Err(bad(
                &format!("V={}", self.cell_volts),
                "a cell's open-circuit voltage, above 0 and below 10 V",
            ));
        }
        if !(self.cell_ohms >= 0.0 && self.cell_ohms < 10.0) {
            return Err(bad(
                &format!("R={}", self.cell_ohms),
                "a cell's resistance, 0 to 10 ohm",
            ));
        }
        if !(self.capacity_ah >= 0.0 && self.capacity_ah < 1e4) {
            return Err(bad(&format!("{} Ah", self.capacity_ah), "a capacity, not negative"));
        }
        if !(self.usable > 0.0 && self.usable <= 1.0) {
            return Err(bad(
                &format!("usable={}", self.usable),
                "a fraction above 0 and at most 100 %",
            ));
        }
        if !(self.cutoff_volts >= 0.0 && self.cutoff_volts < self.cell_volts) {
            return Err(bad(
                &format!("cutoff={}", self.cutoff_volts),
                format!(
                    "the battery is at or below its cutoff: {} V per cell open-circuit, cutoff {} V",
                    self.cell_volts, self.cutoff_volts
                ),
            ));
        }
        Ok(())
    }
}

/// The battery and the ESC.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Supply {
    /// The battery.
    pub battery: Battery,
    /// The ESC's resistance in the motor's current path [ohm].
    pub esc_ohms: f64,
}

/// What the battery and the ESC do at an operating point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SupplyPoint {
    /// Throttle [0, 1].
    pub throttle: f64,
    /// Battery current [A].
    pub battery_amps: f64,
    /// Battery terminal voltage [V].
    pub battery_volts: f64,
    /// Power drawn from the battery [W].
    pub battery_power: f64,
    /// How long the usable capacity lasts at this current [s] (None without a capacity).
    pub endurance: Option<f64>,
}

impl Supply {
    /// The motor's source at `throttle`: open-circuit voltage and series resistance.
    pub fn source(&self, throttle: f64) -> (f64, f64) {
        let b = &self.battery;
        let n = b.cells as f64;
        (
            throttle * n * b.cell_volts,
            throttle * throttle * n * b.cell_ohms + self.esc_ohms,
        )
    }

    /// The driver of an operating point at `throttle`.
    pub fn drive(&self, throttle: f64) -> crate::Drive {
        let (volts, ohms) = self.source(throttle);
        crate::Drive::Throttle { throttle, volts, ohms }
    }

    /// The battery's side of a motor point (`motor_volts`, `motor_amps`): the throttle that
    /// gives it, or why the battery cannot (more than full throttle; loaded below its cutoff).
    pub fn at(&self, motor_volts: f64, motor_amps: f64) -> Result<SupplyPoint, String> {
        let b = &self.battery;
        let n = b.cells as f64;
        let (voc, rb) = (n * b.cell_volts, n * b.cell_ohms);
        // V_m = t (Voc - t I_m Rb) - I_m Resc: rb I t^2 - Voc t + (V_m + I Resc) = 0.
        let c = motor_volts + motor_amps * self.esc_ohms;
        let a = rb * motor_amps;
        let throttle = if a.abs() < 1e-12 {
            c / voc
        } else {
            let disc = voc * voc - 4.0 * a * c;
            if disc < 0.0 {
                return Err(format!(
                    "the battery cannot give {motor_volts:.2} V at {motor_amps:.1} A (its resistance)"
                ));
            }
            (voc - disc.sqrt()) / (2.0 * a)
        };
        if throttle > 1.0 + 1e-9 {
            return Err(format!(
                "needs {:.0} % throttle: {motor_volts:.2} V at the motor is more than this battery gives",
                100.0 * throttle
            ));
        }
        let battery_amps = throttle * motor_amps;
        let battery_volts = voc - battery_amps * rb;
        if battery_volts < n * b.cutoff_volts {
            return Err(format!(
                "the battery sags to {:.2} V per cell at {battery_amps:.1} A, below its cutoff of {} V",
                battery_volts / n,
                b.cutoff_volts
            ));
        }
        Ok(SupplyPoint {
            throttle: throttle.max(0.0),
            battery_amps,
            battery_volts,
            battery_power: battery_amps * battery_volts,
            endurance: (b.capacity_ah > 0.0 && battery_amps > 0.0)
                .then(|| b.capacity_ah * b.usable * 3600.0 / battery_amps),
        })
    }
}

/// The kind of value that sets a table of operating points: a flag of `predict --motor` and a
/// key of a case's `[motor]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Driver {
    /// Terminal voltages [V].
    Volts,
    /// Motor currents [A].
    Amps,
    /// Thrusts [N].
    Thrust,
    /// Rotation speeds [rpm].
    Rpm,
    /// Throttles on the battery [0, 1].
    Throttle,
}

/// Why values cannot set operating points (each door says it in its own words).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DriveRule {
    /// A throttle without the battery it opens.
    ThrottleWithoutBattery,
    /// A throttle outside 0-1.
    ThrottleOutside(f64),
}

/// One driver per value of `driver`'s kind (in its unit): the one rule of the command line and
/// the case file, where a throttle needs the battery (`supply`) and lies in 0-1.
pub fn drives(driver: Driver, values: Vec<f64>, supply: Option<&Supply>) -> Result<Vec<crate::Drive>, DriveRule> {
    Ok(match driver {
        Driver::Volts => values.into_iter().map(crate::Drive::Volts).collect(),
        Driver::Amps => values.into_iter().map(crate::Drive::Amps).collect(),
        Driver::Thrust => values.into_iter().map(crate::Drive::Thrust).collect(),
        Driver::Rpm => values
            .into_iter()
            .map(|r| crate::Drive::Omega(propbet_units::rpm_to_omega(r)))
            .collect(),
        Driver::Throttle => {
            let s = supply.ok_or(DriveRule::ThrottleWithoutBattery)?;
            if let Some(&bad) = values.iter().find(|t| !(0.0..=1.0).contains(*t)) {
                return Err(DriveRule::ThrottleOutside(bad));
            }
            values.into_iter().map(|t| s.drive(t)).collect()
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The one rule of both doors: each value its driver, a throttle on the battery in 0-1.
    #[test]
    fn values_become_drivers_and_a_throttle_needs_the_battery() {
        let supply = Supply {
            battery: Battery { cells: 3, ..LIPO },
            esc_ohms: 0.005,
        };
        assert_eq!(
            drives(Driver::Volts, vec![6.0, 8.0], None),
            Ok(vec![crate::Drive::Volts(6.0), crate::Drive::Volts(8.0)])
        );
        let w = drives(Driver::Rpm, vec![6000.0], None).unwrap();
        assert!(matches!(w[..], [crate::Drive::Omega(x)] if (x - 6000.0 * std::f64::consts::PI / 30.0).abs() < 1e-9));
        assert_eq!(
            drives(Driver::Throttle, vec![0.5], None),
            Err(DriveRule::ThrottleWithoutBattery)
        );
        assert_eq!(
            drives(Driver::Throttle, vec![0.5, 1.2], Some(&supply)),
            Err(DriveRule::ThrottleOutside(1.2))
        );
        let t = drives(Driver::Throttle, vec![0.0, 1.0], Some(&supply)).unwrap();
        assert_eq!(t, vec![supply.drive(0.0), supply.drive(1.0)]);
    }

    #[test]
    fn a_batterys_text_reads_back_to_the_same_battery() {
        for spec in [
            "3S",
            "3S,2200mAh",
            "6S,5.2Ah,R=2.5mOhm,V=3.85,cutoff=3.4,usable=75%",
            "1S,0.3Ah,R=0",
        ] {
            let b = Battery::parse(spec).unwrap();
            assert_eq!(Battery::parse(&b.text()).unwrap(), b, "{spec} -> {}", b.text());
        }
        assert_eq!(
            Battery::parse("3S,2200mAh").unwrap().text(),
            "3S,2.2Ah,R=0.005,V=3.7,cutoff=3.3,usable=0.8"
        );
    }

    #[test]
    fn battery_specs_read_with_units_and_defaults() {
        let b = Battery::parse("3S, 2200mAh, R=6mOhm, usable=75%").unwrap();
        assert_eq!((b.cells, b.cell_volts, b.cutoff_volts), (3, 3.7, 3.3));
        assert!((b.capacity_ah - 2.2).abs() < 1e-12 && (b.cell_ohms - 0.006).abs() < 1e-12);
        assert!((b.usable - 0.75).abs() < 1e-12);
        assert_eq!(Battery::parse("4s,5Ah,V=3.85").unwrap().capacity_ah, 5.0);
        for (spec, words) in [
            ("2200mAh", "no cell count"),
            ("3S,V=3.2", "at or below its cutoff"),
            ("3S,capacity", "unknown"),
            ("3S,R=fast", "not a number"),
            ("0S", "between 1 and 100"),
        ] {
            let e = Battery::parse(spec).unwrap_err().to_string();
            assert!(e.contains(words), "{spec}: {e}");
        }
    }

    #[test]
    fn the_throttle_is_the_one_that_gives_the_motor_its_point() {
        let s = Supply {
            battery: Battery::parse("3S,2200mAh,R=5mOhm").unwrap(),
            esc_ohms: 0.01,
        };
        for t in [0.3, 0.7, 1.0] {
            let (e, rs) = s.source(t);
            let im = 8.0;
            let vm = e - im * rs;
            let p = s.at(vm, im).unwrap();
            assert!((p.throttle - t).abs() < 1e-12, "{} {t}", p.throttle);
            // Power: what the battery gives is what the motor takes plus the losses.
            let losses = p.battery_amps.powi(2) * 3.0 * 0.005 + im * im * 0.01;
            let balance = p.battery_amps * 3.0 * 3.7 - (vm * im + losses);
            assert!(balance.abs() < 1e-9, "{balance}");
        }
        // More than the battery has, and a sag below the cutoff, are said.
        assert!(s.at(12.0, 5.0).unwrap_err().contains("throttle"));
        let weak = Supply {
            battery: Battery::parse("3S,R=0.1").unwrap(),
            esc_ohms: 0.0,
        };
        assert!(
            weak.at(8.0, 10.0).unwrap_err().contains("cutoff"),
            "{:?}",
            weak.at(8.0, 10.0)
        );
    }
}
