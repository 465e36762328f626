//! The operating point of a motor on a propeller: the speed at which the propeller's torque
//! is the motor's, for a given terminal voltage, current, thrust or speed (QPROP's `Volt`,
//! `Amps`, `Thrust` and `RPM` drivers).
//!
//! QPROP finds it by Newton from an 80 %-radius pitch guess and stops after 25 steps
//! whatever the residual; propbet scans the speeds from the motor's no-load speed down (or,
//! for the other drivers, from rest up) for the stable crossing (propeller torque rising
//! through the motor's) and closes it with argmin's Brent root finder to 1e-12 of the speed.
//! Where there is no crossing below the search's ceiling the point has no solution, said in
//! words; it is never NaN.

use argmin::core::{CostFunction, Executor};
use argmin::solver::brent::BrentRoot;
use thiserror::Error;

use crate::model::Motor;

/// A propeller's loads at one rotation rate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PropLoads {
    /// Thrust [N].
    pub thrust: f64,
    /// Torque [N m].
    pub torque: f64,
}

/// What sets the operating point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Drive {
    /// Terminal voltage [V].
    Volts(f64),
    /// Motor current [A].
    Amps(f64),
    /// Propeller thrust [N] (hover: the thrust that carries a weight).
    Thrust(f64),
    /// Rotation rate [rad/s].
    Omega(f64),
    /// A throttle on a battery and ESC ([`crate::power::Supply::drive`]): the motor on a
    /// source of `volts` behind `ohms`.
    Throttle {
        /// Throttle [0, 1].
        throttle: f64,
        /// The source's open-circuit voltage [V].
        volts: f64,
        /// Its series resistance [ohm].
        ohms: f64,
    },
}

impl Drive {
    /// The driver's value with its unit, as a message says it.
    pub fn describe(&self) -> String {
        match self {
            Drive::Volts(v) => format!("{v} V"),
            Drive::Amps(a) => format!("{a} A"),
            Drive::Thrust(t) => format!("{t} N of thrust"),
            Drive::Omega(w) => format!("{:.0} rpm", propbet_units::omega_to_rpm(*w)),
            Drive::Throttle { throttle, .. } => format!("{:.0} % throttle", 100.0 * throttle),
        }
    }
}

/// The solved operating point, the motor's side of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Powered {
    /// Rotation rate [rad/s].
    pub omega: f64,
    /// Terminal voltage [V].
    pub volts: f64,
    /// Current [A].
    pub amps: f64,
    /// The propeller's loads there.
    pub loads: PropLoads,
}

impl Powered {
    /// Shaft power Q Omega [W].
    pub fn shaft_power(&self) -> f64 {
        self.loads.torque * self.omega
    }

    /// Electrical power V I [W].
    pub fn electrical_power(&self) -> f64 {
        self.volts * self.amps
    }

    /// Thrust per electrical power [gram-force per watt] (0 where no electrical power).
    pub fn grams_per_watt(&self) -> f64 {
        let p = self.electrical_power();
        if p != 0.0 {
            self.loads.thrust / propbet_units::STANDARD_GRAVITY * 1000.0 / p
        } else {
            0.0
        }
    }

    /// Motor efficiency, shaft over electrical power (0 where no electrical power, as QPROP).
    pub fn motor_efficiency(&self) -> f64 {
        let p = self.electrical_power();
        if p != 0.0 {
            self.shaft_power() / p
        } else {
            0.0
        }
    }
}

/// Why an operating point could not be found.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum OperateError<E> {
    /// The propeller's loads could not be computed.
    #[error("{0}")]
    Prop(E),
    /// The motor and the propeller have no common operating point.
    #[error("no operating point at {drive}: {why}")]
    NoSolution {
        /// The driver, in words.
        drive: String,
        /// Why, in words.
        why: String,
    },
}

/// Speeds scanned for the crossing.
const SCAN: usize = 40;

/// The operating point of `motor` on the propeller `prop` (loads at a rotation rate) under
/// `drive`, searched below `omega_max` [rad/s].
pub fn operate<E>(
    motor: &Motor,
    drive: Drive,
    omega_max: f64,
    prop: &mut dyn FnMut(f64) -> Result<PropLoads, E>,
) -> Result<Powered, OperateError<E>> {
    let none = |why: String| OperateError::NoSolution {
        drive: drive.describe(),
        why,
    };
    let finish = |omega: f64, loads: PropLoads, volts_amps: (f64, f64)| Powered {
        omega,
        volts: volts_amps.0,
        amps: volts_amps.1,
        loads,
    };
    match drive {
        Drive::Omega(w) => {
            if !(w.is_finite() && w >= 0.0) {
                return Err(none("the speed must be finite and not negative".into()));
            }
            let loads = prop(w).map_err(OperateError::Prop)?;
            Ok(finish(w, loads, motor.volts_for(w, loads.torque)))
        }
        Drive::Throttle { volts, ohms, .. } => {
            // The source's resistance in series with the winding; the motor's terminals see
            // the source's voltage less its drop.
            let behind = Motor {
                r0: motor.r0 + ohms,
                ..*motor
            };
            let p = operate(&behind, Drive::Volts(volts), omega_max, prop).map_err(|e| match e {
                OperateError::NoSolution { why, .. } => none(why),
                e => e,
            })?;
            Ok(Powered {
                volts: volts - p.amps * ohms,
                ..p
            })
        }
        Drive::Volts(v) => {
            let free = motor.free_speed(v).ok_or_else(|| {
                none(format!(
                    "the motor does not turn: {v} V cannot carry its no-load current"
                ))
            })?;
            // Above the no-load speed the motor brakes; a propeller that windmills there is
            // still a crossing, so the scan may go past it up to the ceiling.
            let top = if free < omega_max { free } else { omega_max };
            let residual = |w: f64, l: &PropLoads| l.torque - motor.at(w, v).torque;
            let w = crossing_down(top, omega_max, &residual, prop)?.ok_or_else(|| {
                none(format!(
                    "the propeller's torque never meets the motor's below {:.0} rpm",
                    propbet_units::omega_to_rpm(omega_max)
                ))
            })?;
            let loads = prop(w).map_err(OperateError::Prop)?;
            Ok(finish(w, loads, (v, motor.at(w, v).amps)))
        }
        Drive::Amps(a) => {
            let residual = |w: f64, l: &PropLoads| l.torque - (a - motor.no_load_current(w)) / motor.kq();
            let w = crossing_up(omega_max, &residual, prop)?.ok_or_else(|| {
                none(format!(
                    "the propeller does not absorb the motor's torque at {a} A below {:.0} rpm",
                    propbet_units::omega_to_rpm(omega_max)
                ))
            })?;
            let loads = prop(w).map_err(OperateError::Prop)?;
            Ok(finish(w, loads, motor.volts_for(w, loads.torque)))
        }
        Drive::Thrust(t) => {
            let residual = |_: f64, l: &PropLoads| l.thrust - t;
            let w = crossing_up(omega_max, &residual, prop)?.ok_or_else(|| {
                none(format!(
                    "the propeller does not reach {t} N below {:.0} rpm",
                    propbet_units::omega_to_rpm(omega_max)
                ))
            })?;
            let loads = prop(w).map_err(OperateError::Prop)?;
            Ok(finish(w, loads, motor.volts_for(w, loads.torque)))
        }
    }
}

type Residual<'a> = dyn Fn(f64, &PropLoads) -> f64 + 'a;

/// The highest speed at or below `top` where the residual rises through zero, scanning down
/// (and up from `top` to `ceiling` first when the residual is still negative at `top`).
fn crossing_down<E>(
    top: f64,
    ceiling: f64,
    residual: &Residual<'_>,
    prop: &mut dyn FnMut(f64) -> Result<PropLoads, E>,
) -> Result<Option<f64>, OperateError<E>> {
    let mut f = |w: f64| prop(w).map(|l| residual(w, &l)).map_err(OperateError::Prop);
    let mut hi = top;
    let mut f_hi = f(hi)?;
    // A propeller still driven at the motor's no-load speed: look above it.
    while f_hi < 0.0 && hi < ceiling {
        let next = (2.0 * hi).min(ceiling);
        let f_next = f(next)?;
        if f_next >= 0.0 {
            return close(hi, next, &mut f).map(Some);
        }
        (hi, f_hi) = (next, f_next);
    }
    if f_hi < 0.0 {
        return Ok(None);
    }
    for k in 1..=SCAN {
        let lo = top * (1.0 - k as f64 / SCAN as f64).max(1e-4);
        let f_lo = f(lo)?;
        if f_lo < 0.0 {
            return close(lo, hi, &mut f).map(Some);
        }
        hi = lo;
    }
    Ok(None)
}

/// The lowest speed below `ceiling` where the residual rises through zero, scanning up from
/// rest on a geometric ladder.
fn crossing_up<E>(
    ceiling: f64,
    residual: &Residual<'_>,
    prop: &mut dyn FnMut(f64) -> Result<PropLoads, E>,
) -> Result<Option<f64>, OperateError<E>> {
    let mut f = |w: f64| prop(w).map(|l| residual(w, &l)).map_err(OperateError::Prop);
    let ratio: f64 = 1.25;
    let mut lo = ceiling * 1e-4;
    if f(lo)? >= 0.0 {
        return Ok(None);
    }
    while lo < ceiling {
        let hi = (lo * ratio).min(ceiling);
        if f(hi)? >= 0.0 {
            return close(lo, hi, &mut f).map(Some);
        }
        lo = hi;
    }
    Ok(None)
}

/// The root of `f` between `lo` (f < 0) and `hi` (f >= 0), to 1e-12 of `hi`.
fn close<E>(lo: f64, hi: f64, f: &mut dyn FnMut(f64) -> Result<f64, OperateError<E>>) -> Result<f64, OperateError<E>> {
    struct Problem<'a, E> {
        f: std::cell::RefCell<&'a mut dyn FnMut(f64) -> Result<f64, OperateError<E>>>,
        failed: &'a std::cell::RefCell<Option<OperateError<E>>>,
    }
    impl<E> CostFunction for Problem<'_, E> {
        type Param = f64;
        type Output = f64;
        fn cost(&self, w: &f64) -> Result<f64, argmin::core::Error> {
            match (self.f.borrow_mut())(*w) {
                Ok(r) => Ok(r),
                Err(e) => {
                    self.failed.borrow_mut().get_or_insert(e);
                    Err(argmin::core::Error::msg("the propeller failed"))
                }
            }
        }
    }
    let failed = std::cell::RefCell::new(None);
    let problem = Problem {
        f: std::cell::RefCell::new(f),
        failed: &failed,
    };
    let solver = BrentRoot::new(lo, hi, 1e-12 * hi);
    let run = Executor::new(problem, solver)
        .configure(|s| s.param(0.5 * (lo + hi)).max_iters(200))
        .run();
    if let Some(e) = failed.take() {
        return Err(e);
    }
    Ok(run.ok().and_then(|r| r.state.best_param).unwrap_or(0.5 * (lo + hi)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A propeller of constant CT and CQ: T = kt w^2, Q = kq w^2.
    fn quadratic(kt: f64, kq: f64) -> impl FnMut(f64) -> Result<PropLoads, String> {
        move |w| {
            Ok(PropLoads {
                thrust: kt * w * w,
                torque: kq * w * w,
            })
        }
    }

    #[test]
    fn every_driver_meets_the_motor_where_the_torques_are_equal() {
        let m = Motor::dc1(0.31, 0.77, 2760.0).unwrap();
        let (kt, kq) = (1.6e-6, 1.6e-8);
        let mut p = quadratic(kt, kq);
        let at_v = operate(&m, Drive::Volts(6.0), 5000.0, &mut p).unwrap();
        // Closed form: kq w^2 = (V - w/Kv)/(R Kv) - Io/Kv.
        let kv = m.kv();
        let (a, b, c) = (kq, 1.0 / (0.31 * kv * kv), 0.77 / kv - 6.0 / (0.31 * kv));
        let w = (-b + (b * b - 4.0 * a * c).sqrt()) / (2.0 * a);
        assert!((at_v.omega - w).abs() < 1e-9 * w, "{} {w}", at_v.omega);
        assert!((at_v.loads.torque - m.at(w, 6.0).torque).abs() < 1e-12);
        // The current, thrust and speed at that point give the same point back.
        for drive in [
            Drive::Amps(at_v.amps),
            Drive::Thrust(at_v.loads.thrust),
            Drive::Omega(w),
        ] {
            let back = operate(&m, drive, 5000.0, &mut p).unwrap();
            assert!((back.omega - w).abs() < 1e-8 * w, "{drive:?}: {}", back.omega);
            assert!((back.volts - 6.0).abs() < 1e-8, "{drive:?}: {} V", back.volts);
        }
    }

    #[test]
    fn a_throttle_is_the_motor_behind_its_source() {
        let m = Motor::dc1(0.31, 0.77, 2760.0).unwrap();
        let mut p = quadratic(1.6e-6, 1.6e-8);
        let drive = Drive::Throttle {
            throttle: 0.8,
            volts: 8.0,
            ohms: 0.05,
        };
        let at = operate(&m, drive, 5000.0, &mut p).unwrap();
        // The motor's terminals see 8 V less the drop, and there the torques meet.
        assert!((at.volts - (8.0 - 0.05 * at.amps)).abs() < 1e-12);
        let own = m.at(at.omega, at.volts);
        assert!((own.torque - at.loads.torque).abs() < 1e-9 * at.loads.torque.abs());
        assert!((own.amps - at.amps).abs() < 1e-9);
    }

    #[test]
    fn points_without_a_solution_say_why() {
        let m = Motor::dc1(0.31, 0.77, 2760.0).unwrap();
        let mut p = quadratic(1.6e-6, 1.6e-8);
        let e = operate(&m, Drive::Volts(0.1), 5000.0, &mut p).unwrap_err();
        assert!(e.to_string().contains("does not turn"), "{e}");
        let e = operate(&m, Drive::Thrust(1e6), 5000.0, &mut p).unwrap_err();
        assert!(e.to_string().contains("does not reach"), "{e}");
        let mut failing = |_: f64| -> Result<PropLoads, String> { Err("no polar".into()) };
        let e = operate(&m, Drive::Volts(6.0), 5000.0, &mut failing).unwrap_err();
        assert_eq!(e, OperateError::Prop("no polar".to_string()));
    }
}
