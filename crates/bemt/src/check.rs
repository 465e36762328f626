//! Physical sense of a solved point: what no real propeller does, flagged so that such a
//! prediction is never scored or plotted without a word.
//!
//! - Thrust with negative torque: the propeller would deliver thrust while driving the shaft.
//! - Static thrust beyond momentum theory: the figure of merit T^1.5 / (P sqrt(2 rho A)) is at
//!   most 1 for any rotor (actuator disc, no losses).
//! - Forward flight above the ideal efficiency: momentum theory caps eta at
//!   2 / (1 + sqrt(1 + T / (rho/2 V^2 A))).
//! - Stations far outside their section data: a tabulated polar solved at a Reynolds number
//!   below half its lowest polar or above twice its highest runs on extrapolation.

use crate::{PointResult, Rotor};

/// Sentences saying what is physically wrong with `p` (empty: nothing). `tip_radius` [m] gives
/// the disc area, `rho` [kg/m^3] the air density.
pub fn implausible(p: &PointResult, rho: f64, tip_radius: f64) -> Vec<String> {
    let mut said = Vec::new();
    let area = std::f64::consts::PI * tip_radius * tip_radius;
    let (t, q, power, v) = (p.thrust, p.torque, p.power, p.v);
    if !(t.is_finite() && q.is_finite()) {
        said.push("thrust or torque is not a number".into());
        return said;
    }
    if t > 0.0 && q < 0.0 {
        said.push(format!("thrust {t:.3} N with negative torque {q:.4} N m"));
    }
    if t > 0.0 && power > 0.0 {
        if v.abs() < 1e-9 {
            let fm = figure_of_merit(t, power, rho, area);
            if fm > 1.0 {
                said.push(format!(
                    "static thrust beyond momentum theory (figure of merit {fm:.2} > 1)"
                ));
            }
        } else if v > 0.0 {
            let ideal = 2.0 / (1.0 + (1.0 + t / (0.5 * rho * v * v * area)).sqrt());
            let eta = t * v / power;
            if eta > ideal {
                said.push(format!("efficiency {eta:.2} above the ideal (momentum) {ideal:.2}"));
            }
        }
    }
    said
}

/// The figure of merit T^1.5 / (P sqrt(2 rho A)): the ideal (actuator-disc) power of the
/// thrust `t` [N] over the power `power` [W], with air density `rho` [kg/m^3] and disc area
/// `area` [m^2]; at most 1 for any rotor.
pub fn figure_of_merit(t: f64, power: f64, rho: f64, area: f64) -> f64 {
    t.powf(1.5) / (power * (2.0 * rho * area).sqrt())
}

/// Stations of `p` (solved with `keep_stations`) whose Reynolds number lies below half the
/// lowest or above twice the highest of their section data's ([`crate::SectionAero::reynolds_range`]).
pub fn outside_data(rotor: &Rotor, p: &PointResult) -> usize {
    outside(rotor, p, 2.0)
}

/// Stations of `p` (solved with `keep_stations`) whose Reynolds number lies beyond their
/// section data's at all (below the lowest polar or above the highest): solved on the end
/// polar's extrapolation in Re, however near.
pub fn beyond_data(rotor: &Rotor, p: &PointResult) -> usize {
    outside(rotor, p, 1.0)
}

/// Stations below `1 / factor` of their data's lowest Reynolds number or above `factor` times
/// its highest.
fn outside(rotor: &Rotor, p: &PointResult, factor: f64) -> usize {
    p.stations
        .iter()
        .zip(&rotor.stations)
        .filter(|(s, st)| {
            st.aero
                .reynolds_range()
                .is_some_and(|(lo, hi)| s.re < lo / factor || s.re > hi * factor)
        })
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(thrust: f64, torque: f64, v: f64, omega: f64) -> PointResult {
        PointResult {
            v,
            omega,
            rpm: crate::units::omega_to_rpm(omega),
            thrust,
            torque,
            power: torque * omega,
            j: None,
            ct: None,
            cp: None,
            cq: None,
            eta: 0.0,
            adv_qprop: None,
            ct_qprop: None,
            cp_qprop: None,
            dv: 0.0,
            cl_avg: 0.0,
            cd_avg: 0.0,
            not_converged: 0,
            stations: Vec::new(),
        }
    }

    #[test]
    fn what_no_propeller_does_is_named() {
        let (rho, r) = (1.225, 0.127);
        // A 10-inch prop at 5000 rpm: 4 N for 0.06 N m is ordinary (FM about 0.6).
        assert!(implausible(&point(4.0, 0.06, 0.0, 523.6), rho, r).is_empty());
        assert!(implausible(&point(4.0, -0.01, 0.0, 523.6), rho, r)[0].contains("negative torque"));
        // 4 N for 5 W: FM = 8 / (5 sqrt(2 1.225 0.0507)) = 4.5.
        let s = implausible(&point(4.0, 5.0 / 523.6, 0.0, 523.6), rho, r);
        assert!(s.len() == 1 && s[0].contains("figure of merit"), "{s:?}");
        // At 10 m/s, 4 N for 30 W gives eta 1.33.
        let s = implausible(&point(4.0, 30.0 / 523.6, 10.0, 523.6), rho, r);
        assert!(s.len() == 1 && s[0].contains("ideal"), "{s:?}");
        assert!(implausible(&point(f64::NAN, 0.0, 0.0, 1.0), rho, r)[0].contains("not a number"));
    }
}
