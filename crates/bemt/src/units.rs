//! Unit conversions that the boundaries need, written once: rotation speed in revolutions per
//! minute (how people and files state it) against the solver's angular rate [rad/s].

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
    }
}
