//! The electrical columns of a stand log against a motor: at each compared point that logged
//! the supply's voltage and current, the current and electrical power the motor model draws
//! to give the propeller's torque at the measured speed.
//!
//! The log's voltage and current are the supply's, upstream of the ESC; the ESC is taken as
//! lossless, so the supply gives the motor's electrical power: predicted supply current =
//! V_m I_m / V_b, with (V_m, I_m) the motor's voltage and current for the torque at the speed
//! (QPROP's `VOLTM`). Twice: with the predicted torque (the whole chain, propeller and motor)
//! and with the measured torque (the motor model alone, where the log has torque).
//!
//! And the speed the chain gives at the log's throttle: where the ESC command is logged at half
//! throttle and above, the motor at the voltage the ESC gives it (its duty, read as a linear
//! ESC calibrated to 1000-2000 µs, times the supply's voltage) turning the predicted
//! propeller, against the measured speed; and the motor's efficiency, shaft power over
//! electrical, measured (with the log's torque) and predicted.

use propbet_measure::MeasuredSet;
use propbet_motor::Motor;
use serde::Serialize;

use crate::ComparedPoint;

/// One point's electrical numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ElectricPoint {
    /// The point's label.
    pub label: String,
    /// Rotation speed [rpm].
    pub rpm: f64,
    /// Supply voltage measured [V].
    pub volts: f64,
    /// Supply current measured [A].
    pub amps: f64,
    /// Supply current the motor draws for the predicted torque [A].
    pub amps_predicted: f64,
    /// Supply current the motor draws for the measured torque [A] (the motor model alone).
    pub amps_motor_only: Option<f64>,
    /// Electrical power measured, V I [W].
    pub power: f64,
    /// Electrical power predicted [W].
    pub power_predicted: f64,
    /// Thrust per electrical power measured [g/W].
    pub g_per_w: Option<f64>,
    /// Thrust per electrical power predicted [g/W].
    pub g_per_w_predicted: Option<f64>,
    /// The motor's efficiency measured, Q Omega / (V I) (where the log has torque).
    pub eta_motor: Option<f64>,
    /// The motor's efficiency predicted, for the predicted torque.
    pub eta_motor_predicted: f64,
    /// The speed [rpm] the motor gives the predicted propeller at the ESC's voltage (at half
    /// throttle and above, with the ESC command logged).
    pub rpm_at_volts: Option<f64>,
}

/// The electrical comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Electric {
    /// The motor's name.
    pub motor: String,
    /// Every point with the supply's voltage and current.
    pub points: Vec<ElectricPoint>,
    /// Median relative error of the current (predicted torque).
    pub current_median: f64,
    /// Median |relative error| of the current (predicted torque).
    pub current_median_abs: f64,
    /// Median relative error of the electrical power.
    pub power_median: f64,
    /// Median |relative error| of the current with the measured torque (the motor alone).
    pub motor_only_median_abs: Option<f64>,
    /// Median relative error of the speed at the ESC's voltage.
    pub rpm_median: Option<f64>,
}

/// The propeller's thrust and torque [N, N m] at a point's airspeed and air, at a speed [rad/s].
pub type Loads<'a> = dyn Fn(&ComparedPoint, f64) -> Option<(f64, f64)> + 'a;

/// The speed [rad/s] where `motor` at `volts` turns the propeller of `loads` at `p`'s airspeed
/// (searched up to three times the measured speed).
fn speed_at(motor: &Motor, volts: f64, p: &ComparedPoint, loads: &Loads) -> Option<f64> {
    let ceiling = 3.0 * propbet_units::rpm_to_omega(p.rpm);
    let mut at = |w: f64| -> Result<propbet_motor::PropLoads, ()> {
        let (thrust, torque) = loads(p, w).ok_or(())?;
        Ok(propbet_motor::PropLoads { thrust, torque })
    };
    propbet_motor::operate(motor, propbet_motor::Drive::Volts(volts), ceiling, &mut at)
        .ok()
        .map(|s| s.omega)
}

/// The electrical comparison of `points` (of `sets`) on `motor`, the propeller's loads at
/// other speeds from `loads`; None where no point logged the supply's voltage and current.
pub fn score(
    points: &[ComparedPoint],
    sets: &[MeasuredSet],
    motor: &Motor,
    name: &str,
    loads: &Loads,
) -> Option<Electric> {
    let g = propbet_units::STANDARD_GRAVITY;
    let out: Vec<ElectricPoint> = points
        .iter()
        .filter_map(|p| {
            let m = sets.get(p.file)?.points.iter().find(|m| m.lines == p.lines)?;
            let e = m.electric?;
            let omega = propbet_units::rpm_to_omega(p.rpm);
            let draw = |q: f64| {
                let (v, i) = motor.volts_for(omega, q);
                v * i
            };
            let power_predicted = draw(p.predicted.torque?);
            let (volts, amps) = (e.volts.mean, e.amps.mean);
            if !(volts > 0.0 && amps > 0.0) {
                return None;
            }
            let per_watt = |t: Option<f64>, w: f64| t.filter(|_| w > 0.0).map(|t| t / g * 1000.0 / w);
            let duty = e.esc.map(|c| (c - 1000.0) / 1000.0).filter(|d| (0.5..=1.0).contains(d));
            let rpm_at_volts = duty
                .and_then(|d| speed_at(motor, d * volts, p, loads))
                .map(propbet_units::omega_to_rpm);
            Some(ElectricPoint {
                label: p.label.clone(),
                rpm: p.rpm,
                volts,
                amps,
                amps_predicted: power_predicted / volts,
                amps_motor_only: p.measured.torque.map(|q| draw(q) / volts),
                power: volts * amps,
                power_predicted,
                g_per_w: per_watt(p.measured.thrust, volts * amps),
                g_per_w_predicted: per_watt(p.predicted.thrust, power_predicted),
                eta_motor: p.measured.torque.map(|q| q * omega / (volts * amps)),
                eta_motor_predicted: p.predicted.torque.map_or(f64::NAN, |q| q * omega / power_predicted),
                rpm_at_volts,
            })
        })
        .collect();
    if out.is_empty() {
        return None;
    }
    let median = |f: &dyn Fn(&ElectricPoint) -> Option<f64>| {
        let v: Vec<f64> = out.iter().filter_map(f).collect();
        (!v.is_empty()).then(|| propbet_units::stats::median(v))
    };
    Some(Electric {
        motor: name.to_string(),
        current_median: median(&|p| Some(p.amps_predicted / p.amps - 1.0))?,
        current_median_abs: median(&|p| Some((p.amps_predicted / p.amps - 1.0).abs()))?,
        power_median: median(&|p| Some(p.power_predicted / p.power - 1.0))?,
        motor_only_median_abs: median(&|p| p.amps_motor_only.map(|a| (a / p.amps - 1.0).abs())),
        rpm_median: median(&|p| p.rpm_at_volts.map(|r| r / p.rpm - 1.0)),
        points: out,
    })
}
