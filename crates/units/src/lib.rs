//! Unit conventions written once, for every crate: rotation speed in revolutions per minute
//! (how people and files state it) against the angular rate [rad/s] used inside, and the
//! denominators of the propeller coefficients CT = T/(ρn²D⁴), CP = P/(ρn³D⁵),
//! CQ = Q/(ρn²D⁵) (n in rev/s, D the diameter).
//!
//! Also how a piece of a user's file is quoted in a message ([`excerpt`]): every parser uses it.
#![deny(missing_docs)]

pub mod stats;

use std::f64::consts::PI;

/// Standard gravity [m/s^2] (CGPM 1901): one gram-force is 9.80665e-3 N.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Angular rate [rad/s] of `rpm` revolutions per minute.
pub const fn rpm_to_omega(rpm: f64) -> f64 {
    rpm * PI / 30.0
}

/// Revolutions per minute of the angular rate `omega` [rad/s].
pub fn omega_to_rpm(omega: f64) -> f64 {
    omega * 30.0 / PI
}

/// Revolutions per second [1/s] of the angular rate `omega` [rad/s] (the n of J = V/(nD)).
pub fn omega_to_rev_per_s(omega: f64) -> f64 {
    omega / (2.0 * PI)
}

/// The torque coefficient of a power coefficient: P = 2π n Q, so CQ = CP / (2π).
pub fn cq_of_cp(cp: f64) -> f64 {
    cp / (2.0 * PI)
}

/// Minutes of `seconds` (a battery's endurance as people state it).
pub fn seconds_to_minutes(seconds: f64) -> f64 {
    seconds / 60.0
}

/// Revolutions per second [1/s] of `rpm` revolutions per minute.
pub fn rpm_to_rev_per_s(rpm: f64) -> f64 {
    rpm / 60.0
}

/// The denominators of the coefficients at `n` [rev/s], density `rho` [kg/m^3] and diameter
/// `d` [m]: CT = T / [`Scales::thrust`], CP = P / [`Scales::power`], CQ = Q / [`Scales::torque`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// ρ n² D⁴ [N].
    pub thrust: f64,
    /// ρ n³ D⁵ [W].
    pub power: f64,
    /// ρ n² D⁵ [N m].
    pub torque: f64,
}

impl Scales {
    /// The denominators at `n` [rev/s], `rho` [kg/m^3], `d` [m].
    pub fn new(rho: f64, n: f64, d: f64) -> Self {
        Scales {
            thrust: rho * n * n * d.powi(4),
            power: rho * n.powi(3) * d.powi(5),
            torque: rho * n * n * d.powi(5),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_round_trip() {
        for rpm in [0.0, 2400.0, 5000.0, 6512.0, 12345.678] {
            assert!((omega_to_rpm(rpm_to_omega(rpm)) - rpm).abs() <= 1e-12 * rpm);
        }
        assert!((omega_to_rev_per_s(2.0 * PI) - 1.0).abs() < 1e-15);
        assert!((omega_to_rpm(PI) - 30.0).abs() < 1e-12);
        // CQ = CP / (2 pi) by the definitions.
        let s = Scales::new(1.2, 100.0, 0.25);
        assert!((s.power / s.torque - 100.0).abs() < 1e-12);
        assert_eq!(rpm_to_rev_per_s(6000.0), 100.0);
    }
}

/// A name from a user's file (a prop title, a case name) as propbet shows it: control
/// characters (terminal escapes, bells, newlines) replaced by `?`, blanks trimmed. A file must
/// not be able to drive the terminal or break a line of an output.
pub fn printable(text: &str) -> String {
    text.trim()
        .chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect()
}

/// An error and its causes in one line, "error: cause: cause" (as the binary prints errors):
/// how a message that goes on as text (a prop not validated, an error to Python) keeps them.
pub fn with_causes(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        text.push_str(": ");
        text.push_str(&c.to_string());
        cause = c.source();
    }
    text
}

/// Where in `text` the byte `offset` lies, as "line L, column C" (1-based): how a parser's
/// error names its place without echoing the line (a 10 KB line would be 10 KB of message).
pub fn place(text: &str, offset: usize) -> String {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    format!("line {line}, column {column}")
}

/// Longest excerpt of a user's file that a message quotes [characters].
pub const EXCERPT_CHARS: usize = 60;

/// A piece of a user's file, safe and short enough to quote in a message: surrounding blanks
/// trimmed, control characters (escape sequences, bells, carriage returns) shown as `?`, and
/// at most [`EXCERPT_CHARS`] characters, the rest replaced by `…` and the full length. A file
/// that is not what the command expected (a case may name any file) is never echoed whole.
pub fn excerpt(text: &str) -> String {
    let text = text.trim();
    let n = text.chars().count();
    let mut out: String = text
        .chars()
        .take(EXCERPT_CHARS)
        .map(|c| if c.is_control() { '?' } else { c })
        .collect();
    if n > EXCERPT_CHARS {
        out.push_str(&format!("… ({n} characters)"));
    }
    out
}

#[cfg(test)]
mod excerpt_tests {
    use super::*;

    #[test]
    fn excerpts_are_short_and_carry_no_control_characters() {
        assert_eq!(excerpt("  0.5 0.1  "), "0.5 0.1");
        let long = format!("\x1b[31m{}", "x".repeat(500));
        let e = excerpt(&long);
        assert!(e.starts_with("?[31mxxx"), "{e}");
        assert!(e.ends_with("… (505 characters)"), "{e}");
        assert!(!e.chars().any(char::is_control));
        assert!(e.chars().count() < EXCERPT_CHARS + 20);
    }
}

/// A number as a message quotes it: as written when short (`0.1524`, `5000`), else with
/// six significant digits and an exponent where large or small (`1e308`, not 309 digits;
/// `1.23457e-300`). Never a value the reader cannot read in one glance.
pub fn show(x: f64) -> String {
    let plain = format!("{x}");
    if plain.len() <= 12 {
        return plain;
    }
    let a = x.abs();
    if a != 0.0 && !(1e-4..1e9).contains(&a) {
        let e = format!("{x:.5e}");
        // Trailing zeros of the mantissa say nothing: 1.00000e308 -> 1e308.
        match e.split_once('e') {
            Some((m, exp)) if m.contains('.') => {
                format!("{}e{exp}", m.trim_end_matches('0').trim_end_matches('.'))
            }
            _ => e,
        }
    } else {
        let s = format!("{x:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    }
}

/// The operating range of any small propeller test: a measured row beyond it is a corrupt
/// file, a sweep beyond it a typing error, an effect that moves a point beyond it a broken
/// formula.
pub mod operating {
    /// Fastest rotation [rad/s] (500,000 rpm).
    pub const OMEGA_MAX: f64 = crate::rpm_to_omega(500_000.0);
    /// Fastest airspeed [m/s].
    pub const AIRSPEED_MAX: f64 = 500.0;
}

/// The air a measurement can have been taken in, and the range the air formulas are meant
/// for: one definition for a given air state (`--atmosphere`) and a logged one.
pub mod air {
    /// Static temperature [K].
    pub const TEMPERATURE: std::ops::RangeInclusive<f64> = 150.0..=400.0;
    /// Static pressure [Pa].
    pub const PRESSURE: std::ops::RangeInclusive<f64> = 10_000.0..=200_000.0;
    /// Relative humidity [0..1].
    pub const HUMIDITY: std::ops::RangeInclusive<f64> = 0.0..=1.0;
    /// Density a given `--rho` may have [kg/m^3] (air at 10 kPa and 400 K is 0.087; 20 is
    /// far above any air).
    pub const DENSITY: std::ops::RangeInclusive<f64> = 0.01..=20.0;
    /// Dynamic viscosity a given `--mu` may have [Pa s] (air: 1.5e-5 to 2.5e-5).
    pub const VISCOSITY: std::ops::RangeInclusive<f64> = 1e-6..=1e-3;
    /// Speed of sound a given `--a` may have [m/s] (air: 250 to 400).
    pub const SOUND_SPEED: std::ops::RangeInclusive<f64> = 100.0..=2000.0;

    /// `Err` with a message naming `flag` when `value` lies outside `range`.
    pub fn check(flag: &str, value: f64, range: &std::ops::RangeInclusive<f64>, unit: &str) -> Result<(), String> {
        if range.contains(&value) {
            Ok(())
        } else {
            Err(format!(
                "{flag} {}: not a plausible value for air ({}-{} {unit})",
                crate::show(value),
                crate::show(*range.start()),
                crate::show(*range.end())
            ))
        }
    }
}

#[cfg(test)]
mod show_tests {
    use super::*;

    #[test]
    fn numbers_in_messages_are_short() {
        assert_eq!(show(0.1524), "0.1524");
        assert_eq!(show(5000.0), "5000");
        assert_eq!(show(1e308), "1e308");
        assert_eq!(show(-1.2345678e-300), "-1.23457e-300");
        assert_eq!(show(0.15239999999999998), "0.1524");
        assert_eq!(show(f64::INFINITY), "inf");
        assert!(show(f64::MAX).len() < 14, "{}", show(f64::MAX));
    }
}

/// Whether two radii are the same but for floating-point rounding (within 1e-9 of the larger):
/// a radius read back from numbers computed from it (a tip at r/R = 1.00 times R, a last row
/// placed half a station beyond the last station's midpoint) is compared with this, never
/// exactly. Every reader and writer of radii uses it.
pub fn same_radius(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs())
}

/// `r`, or `tip` where `r` is the tip radius but for rounding ([`same_radius`]): a radius that
/// must not lie beyond the tip, snapped to it.
pub fn at_most_tip(r: f64, tip: f64) -> f64 {
    if r > tip && same_radius(r, tip) {
        tip
    } else {
        r
    }
}

#[cfg(test)]
mod radius_tests {
    use super::*;

    #[test]
    fn radii_equal_but_for_rounding_are_the_same() {
        let tip = 5.5 * 0.0254;
        let read_back = 1.0 * tip + 1e-17 + 2.0 * f64::EPSILON * tip;
        assert!(same_radius(tip, read_back) && read_back > tip);
        assert_eq!(at_most_tip(read_back, tip), tip);
        assert!(!same_radius(tip, tip * 1.001));
        assert_eq!(at_most_tip(tip * 1.001, tip), tip * 1.001);
        assert_eq!(at_most_tip(0.5 * tip, tip), 0.5 * tip);
    }
}
