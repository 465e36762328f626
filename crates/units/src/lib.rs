//! Unit conventions written once, for every crate: rotation speed in revolutions per minute
//! (how people and files state it) against the angular rate [rad/s] used inside, and the
//! denominators of the propeller coefficients CT = T/(ρn²D⁴), CP = P/(ρn³D⁵),
//! CQ = Q/(ρn²D⁵) (n in rev/s, D the diameter).
#![deny(missing_docs)]

use std::f64::consts::PI;

/// Angular rate [rad/s] of `rpm` revolutions per minute.
pub fn rpm_to_omega(rpm: f64) -> f64 {
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

/// Revolutions per minute, printed without the round-off of a conversion: the shortest decimal
/// that converts back to exactly `omega` (so 5000 rpm prints as `5000`, not `5000.000000000001`).
pub fn rpm_text(omega: f64) -> String {
    let rpm = omega_to_rpm(omega);
    for digits in 6..=17 {
        let text = format!("{:.*e}", digits - 1, rpm);
        if let Ok(v) = text.parse::<f64>() {
            if rpm_to_omega(v) == omega {
                return format!("{v}");
            }
        }
    }
    format!("{rpm}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_round_trip() {
        for rpm in [0.0, 2400.0, 5000.0, 6512.0, 12345.678] {
            let w = rpm_to_omega(rpm);
            assert_eq!(rpm_text(w).parse::<f64>().map(rpm_to_omega), Ok(w));
        }
        assert_eq!(rpm_text(rpm_to_omega(5000.0)), "5000");
        assert!((omega_to_rev_per_s(2.0 * PI) - 1.0).abs() < 1e-15);
        assert!((omega_to_rpm(PI) - 30.0).abs() < 1e-12);
        // CQ = CP / (2 pi) by the definitions.
        let s = Scales::new(1.2, 100.0, 0.25);
        assert!((s.power / s.torque - 100.0).abs() < 1e-12);
        assert_eq!(rpm_to_rev_per_s(6000.0), 100.0);
    }
}
