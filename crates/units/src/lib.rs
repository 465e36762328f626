//! Unit conventions written once, for every crate: rotation speed in revolutions per minute
//! (how people and files state it) against the angular rate [rad/s] used inside, and the
//! denominators of the propeller coefficients CT = T/(ρn²D⁴), CP = P/(ρn³D⁵),
//! CQ = Q/(ρn²D⁵) (n in rev/s, D the diameter).
//!
//! Also how a piece of a user's file is quoted in a message ([`excerpt`]): every parser uses it.
#![deny(missing_docs)]

use std::f64::consts::PI;

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
