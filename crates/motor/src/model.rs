//! QPROP 1.22's DC motor models (`MOTORQ` and `VOLTM` in `motor.f`), in SI.
//!
//! Type 1 (brushed or brushless DC, first order): $I = (V - \Omega/K_v)/R$,
//! $Q = (I - I_0)/K_q$ with $K_q = K_v$ (both in rad/s per volt).
//!
//! Type 2 (second order): the back EMF grows with speed, $V_m = (1 + \tau\Omega)\Omega/K_v$;
//! the winding's resistance with current, $V = I (R_0 + R_2 I^2) + V_m$; the no-load current
//! with speed, $I_0 = I_{00} + I_{01}\Omega + I_{02}\Omega^2$; and $Q = (I - I_0)/K_q$ with
//! $K_q$ its own constant ($K_q = 0$ in the file means $K_q = K_v$, as QPROP reads it).
//! Type 1 is type 2 with $\tau = I_{01} = I_{02} = R_2 = 0$ and $K_q = K_v$, and is computed
//! so.
//!
//! QPROP solves the type 2 current by 10 Newton steps to a residual of 1e-6 V; propbet solves
//! the same cubic to rounding, which differs from QPROP's by less than its printed digits.

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// QPROP's motor model index (the second line of a motor file).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MotorKind {
    /// Type 1: R, Io, Kv.
    Dc1,
    /// Type 2: R0, Io0, Kv, Kq, tau, Io1, Io2, R2.
    Dc2,
}

impl MotorKind {
    /// QPROP's index of the model.
    pub fn index(self) -> i64 {
        match self {
            MotorKind::Dc1 => 1,
            MotorKind::Dc2 => 2,
        }
    }

    /// Names and units of the model's parameters, in the file's order (what QPROP's example
    /// files write after their `!`).
    pub fn labels(self) -> &'static [&'static str] {
        match self {
            MotorKind::Dc1 => &["Rmotor (Ohms)", "Io     (Amps)", "Kv     (rpm/Volt)"],
            MotorKind::Dc2 => &[
                "R0     (Ohms)",
                "Io0    (Amps)",
                "Kv     (rpm/Volt)",
                "Kq     (rpm/Volt)",
                "tau    (s)",
                "Io1    (Amp-s)",
                "Io2    (Amp-s^2)",
                "R2     (Ohms/Amps^2)",
            ],
        }
    }
}

/// A DC motor (and gearbox: QPROP's constants are at the output shaft).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Motor {
    /// The model.
    pub kind: MotorKind,
    /// Winding resistance R (R0 of type 2) [ohm].
    pub r0: f64,
    /// No-load current Io (Io0 of type 2) [A].
    pub io0: f64,
    /// Speed constant Kv [rpm/V].
    pub kv_rpm: f64,
    /// Torque constant Kq [rpm/V] as QPROP writes it ((A/N m) 30/pi); Kv for type 1.
    pub kq_rpm: f64,
    /// Back-EMF growth with speed tau [s] (type 2).
    pub tau: f64,
    /// No-load current growth with speed Io1 [A s] (type 2).
    pub io1: f64,
    /// No-load current growth with speed squared Io2 [A s^2] (type 2).
    pub io2: f64,
    /// Resistance growth with current squared R2 [ohm/A^2] (type 2).
    pub r2: f64,
}

/// A motor whose constants cannot describe a motor.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MotorError {
    /// The model index is neither 1 nor 2.
    #[error("motor type {0}: QPROP 1.22 knows types 1 (R, Io, Kv) and 2 (R0, Io0, Kv, Kq, tau, Io1, Io2, R2)")]
    UnknownType(i64),
    /// Fewer parameters than the model needs.
    #[error("motor type {kind} needs at least 3 parameters (R, Io, Kv); the file has {found}")]
    TooFewParameters {
        /// The model index.
        kind: i64,
        /// Parameters found.
        found: usize,
    },
    /// A parameter outside its physical range.
    #[error("{name} = {value}: {why}")]
    Parameter {
        /// The parameter's position in the file's list (0 = the first).
        index: usize,
        /// Its name.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        why: &'static str,
    },
}

/// The motor's torque and current at a speed and a terminal voltage.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotorPoint {
    /// Shaft torque [N m].
    pub torque: f64,
    /// Current [A].
    pub amps: f64,
}

impl Motor {
    /// A type 1 motor: winding resistance [ohm], no-load current [A], Kv [rpm/V].
    pub fn dc1(r: f64, io: f64, kv_rpm: f64) -> Result<Motor, MotorError> {
        Motor::from_params(1, &[r, io, kv_rpm])
    }

    /// The motor of QPROP's model `kind` with the parameters in the file's order (missing
    /// ones 0, as QPROP clears them; those past the model's own are ignored, as QPROP does).
    pub fn from_params(kind: i64, params: &[f64]) -> Result<Motor, MotorError> {
        let kind = match kind {
            1 => MotorKind::Dc1,
            2 => MotorKind::Dc2,
            k => return Err(MotorError::UnknownType(k)),
        };
        if params.len() < 3 {
            return Err(MotorError::TooFewParameters {
                kind: kind.index(),
                found: params.len(),
            });
        }
        let p = |i: usize| params.get(i).copied().unwrap_or(0.0);
        let names = ["R", "Io", "Kv", "Kq", "tau", "Io1", "Io2", "R2"];
        let used = match kind {
            MotorKind::Dc1 => 3,
            MotorKind::Dc2 => 8,
        };
        for (i, name) in names.iter().enumerate().take(used) {
            let value = p(i);
            let why = if !value.is_finite() {
                Some("must be a finite number")
            } else {
                match i {
                    0 if value <= 0.0 => Some("the winding resistance must be positive"),
                    2 if value <= 0.0 => Some("Kv must be positive (rpm per volt)"),
                    _ if value < 0.0 => Some("must not be negative"),
                    _ => None,
                }
            };
            if let Some(why) = why {
                return Err(MotorError::Parameter {
                    index: i,
                    name,
                    value,
                    why,
                });
            }
        }
        let motor = match kind {
            MotorKind::Dc1 => Motor {
                kind,
                r0: p(0),
                io0: p(1),
                kv_rpm: p(2),
                kq_rpm: p(2),
                tau: 0.0,
                io1: 0.0,
                io2: 0.0,
                r2: 0.0,
            },
            MotorKind::Dc2 => Motor {
                kind,
                r0: p(0),
                io0: p(1),
                kv_rpm: p(2),
                kq_rpm: if p(3) == 0.0 { p(2) } else { p(3) },
                tau: p(4),
                io1: p(5),
                io2: p(6),
                r2: p(7),
            },
        };
        Ok(motor)
    }

    /// Kv in rad/s per volt.
    pub fn kv(&self) -> f64 {
        propbet_units::rpm_to_omega(self.kv_rpm)
    }

    /// Kq in rad/s per volt (torque = current / Kq).
    pub fn kq(&self) -> f64 {
        propbet_units::rpm_to_omega(self.kq_rpm)
    }

    /// Back EMF at `omega` [rad/s] [V].
    pub fn back_emf(&self, omega: f64) -> f64 {
        (1.0 + self.tau * omega) * omega / self.kv()
    }

    /// No-load current at `omega` [rad/s] [A].
    pub fn no_load_current(&self, omega: f64) -> f64 {
        self.io0 + self.io1 * omega + self.io2 * omega * omega
    }

    /// The winding's voltage drop at `amps` [V]: I (R0 + R2 I^2).
    pub fn drop(&self, amps: f64) -> f64 {
        amps * (self.r0 + self.r2 * amps * amps)
    }

    /// The current whose winding drop is `v` [V] (the inverse of [`Motor::drop`], which is
    /// strictly increasing).
    fn current_of_drop(&self, v: f64) -> f64 {
        let mut i = v / self.r0;
        if self.r2 == 0.0 {
            return i;
        }
        for _ in 0..100 {
            let res = self.drop(i) - v;
            let step = res / (self.r0 + 3.0 * self.r2 * i * i);
            i -= step;
            if step.abs() <= 1e-15 * i.abs().max(1e-12) {
                break;
            }
        }
        i
    }

    /// Torque and current at `omega` [rad/s] and terminal voltage `volts` (QPROP `MOTORQ`).
    pub fn at(&self, omega: f64, volts: f64) -> MotorPoint {
        let amps = self.current_of_drop(volts - self.back_emf(omega));
        MotorPoint {
            torque: (amps - self.no_load_current(omega)) / self.kq(),
            amps,
        }
    }

    /// The terminal voltage and current that give `torque` [N m] at `omega` [rad/s] (QPROP
    /// `VOLTM`, which inverts `MOTORQ` by Newton; here in closed form).
    pub fn volts_for(&self, omega: f64, torque: f64) -> (f64, f64) {
        let amps = torque * self.kq() + self.no_load_current(omega);
        (self.drop(amps) + self.back_emf(omega), amps)
    }

    /// The speed at which the motor gives no torque at `volts` (its no-load speed) [rad/s], or
    /// `None` when the voltage cannot even carry the no-load current at rest.
    pub fn free_speed(&self, volts: f64) -> Option<f64> {
        let needed = |w: f64| self.volts_for(w, 0.0).0;
        if volts.is_nan() || volts <= needed(0.0) {
            return None;
        }
        // needed(w) grows with w: bracket and bisect (the type 1 answer is Kv (V - Io R)).
        let mut hi = self.kv() * volts;
        while needed(hi) < volts {
            hi *= 2.0;
        }
        let mut lo = 0.0;
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if needed(mid) < volts {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo <= 1e-14 * hi {
                break;
            }
        }
        let w = 0.5 * (lo + hi);
        w.is_finite().then_some(w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s400() -> Motor {
        Motor::dc1(0.31, 0.77, 2760.0).unwrap()
    }

    #[test]
    fn type_1_is_motorq() {
        let m = s400();
        let kv = propbet_units::rpm_to_omega(2760.0);
        let (w, v) = (1100.0, 6.0);
        let p = m.at(w, v);
        let i = (v - w / kv) / 0.31;
        assert!((p.amps - i).abs() < 1e-12);
        assert!((p.torque - (i - 0.77) / kv).abs() < 1e-12);
        // VOLTM inverts it.
        let (vv, ii) = m.volts_for(w, p.torque);
        assert!((vv - v).abs() < 1e-12 && (ii - i).abs() < 1e-12);
        // The free speed is Kv (V - Io R).
        let free = m.free_speed(v).unwrap();
        assert!((free - kv * (v - 0.77 * 0.31)).abs() < 1e-9 * free, "{free}");
        assert!(m.at(free, v).torque.abs() < 1e-9);
    }

    #[test]
    fn type_2_inverts_itself_and_reduces_to_type_1() {
        // Drela's Speed-280 (`runs/s280-6v-dd`).
        let m = Motor::from_params(2, &[0.70, 0.160, 3800.0, 3800.0, 1.0e-5, 5.7e-5, 4.0e-8, 0.012]).unwrap();
        for (w, v) in [(500.0, 4.0), (1500.0, 6.0), (2000.0, 7.5)] {
            let p = m.at(w, v);
            assert!((m.drop(p.amps) + m.back_emf(w) - v).abs() < 1e-12);
            let (vv, ii) = m.volts_for(w, p.torque);
            assert!((vv - v).abs() < 1e-10 && (ii - p.amps).abs() < 1e-10, "{vv} {ii}");
        }
        let same = Motor::from_params(2, &[0.31, 0.77, 2760.0]).unwrap();
        let p1 = s400().at(1000.0, 6.0);
        let p2 = same.at(1000.0, 6.0);
        assert!((p1.torque - p2.torque).abs() < 1e-15 && (p1.amps - p2.amps).abs() < 1e-15);
    }

    #[test]
    fn constants_that_cannot_be_a_motor_are_named() {
        let e = Motor::from_params(3, &[0.1, 1.0, 1000.0]).unwrap_err();
        assert!(e.to_string().contains("motor type 3"), "{e}");
        let e = Motor::dc1(-0.1, 1.0, 1000.0).unwrap_err();
        assert!(e.to_string().starts_with("R = -0.1"), "{e}");
        let e = Motor::dc1(0.1, 1.0, 0.0).unwrap_err();
        assert!(e.to_string().starts_with("Kv = 0"), "{e}");
        let e = Motor::from_params(1, &[0.1, 1.0]).unwrap_err();
        assert!(matches!(e, MotorError::TooFewParameters { found: 2, .. }), "{e}");
        let e = Motor::dc1(0.1, f64::NAN, 1000.0).unwrap_err();
        assert!(e.to_string().contains("finite"), "{e}");
        assert!(s400().free_speed(0.2).is_none(), "0.2 V cannot carry Io through R");
    }
}
