//! The log's zero: what the sensors read while the propeller stands still.
//!
//! A stand log often begins (or ends) with the motor stopped. There the current the supply
//! meter reads is its offset and the ESC's own draw, and the torque cell reads its zero: none
//! of it is the motor's. A current sensor of a Series 1780 reads -1.24 A at rest in one of the
//! shared logs, enough to make a motor fit's no-load current negative. The motor fit takes the
//! torque's zero off every step, and the current's where it is below zero (a meter's offset
//! for certain; above zero it may be the ESC's own draw, which the supply gives while the
//! motor runs too).

use propbet_units::stats::median;

use crate::set::limits::ZERO_THRUST;
pub use crate::set::AtRest;
use crate::table::Sample;

/// Fewest rows at rest that make a zero.
pub const MIN_ROWS: usize = 5;

/// The zero of a log's samples (as read, before any row is left out): the rows that read no
/// rotation while the loads read what a stopped propeller's do (thrust and torque within
/// [`ZERO_THRUST`] of the highest the log reads; a row that reads no rotation under load is a
/// speed sensor that lost its signal, not rest). None with fewer than [`MIN_ROWS`] such rows.
pub fn at_rest(samples: &[Sample]) -> Option<AtRest> {
    let top = |pick: &dyn Fn(&Sample) -> Option<f64>| samples.iter().filter_map(pick).map(f64::abs).fold(0.0, f64::max);
    let thrust_top = top(&|s| Some(s.thrust));
    let torque_top = top(&|s| s.torque);
    let rest: Vec<&Sample> = samples
        .iter()
        .filter(|s| s.omega == 0.0)
        .filter(|s| s.thrust.abs() <= ZERO_THRUST * thrust_top)
        .filter(|s| s.torque.is_none_or(|q| q.abs() <= ZERO_THRUST * torque_top))
        .collect();
    if rest.len() < MIN_ROWS {
        return None;
    }
    let med = |pick: &dyn Fn(&Sample) -> Option<f64>| {
        let v: Vec<f64> = rest.iter().filter_map(|s| pick(s)).collect();
        (v.len() >= MIN_ROWS).then(|| median(v))
    };
    // The torque in the sign the points will carry (made positive where the propeller pulls).
    let spinning: Vec<Sample> = samples.iter().filter(|s| s.omega > 0.0).copied().collect();
    let sign = crate::reduce::pull_sign(&spinning, |s| s.torque);
    Some(AtRest {
        rows: rest.len(),
        amps: med(&|s| s.amps),
        torque: med(&|s| s.torque).map(|q| q * sign),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::Fresh;

    fn row(line: usize, rpm: f64, thrust: f64, torque: f64, amps: f64) -> Sample {
        Sample {
            line,
            time: Some(line as f64),
            esc: Some(1000.0),
            omega: propbet_units::rpm_to_omega(rpm),
            omega_other: None,
            thrust,
            torque: Some(torque),
            airspeed: 0.0,
            temperature: None,
            pressure: None,
            humidity: None,
            volts: Some(16.0),
            amps: Some(amps),
            fresh: Fresh::ALL,
        }
    }

    #[test]
    fn the_zero_is_read_where_nothing_turns_or_pulls() {
        // Torque logged negative when the propeller pulls: the zero in the points' sign.
        let mut log: Vec<Sample> = (0..6).map(|i| row(i, 0.0, 0.01, -0.001, -1.2)).collect();
        // No rotation read under load: a lost speed signal, not rest.
        log.extend((6..12).map(|i| row(i, 0.0, 8.0, -0.1, 20.0)));
        log.extend((12..30).map(|i| row(i, 5000.0, 10.0, -0.12, 25.0)));
        let z = at_rest(&log).unwrap();
        assert_eq!(z.rows, 6);
        assert_eq!(z.amps, Some(-1.2));
        assert_eq!(z.torque, Some(0.001));
        // Fewer than MIN_ROWS at rest: no zero.
        assert_eq!(at_rest(&log[3..]), None);
    }
}
