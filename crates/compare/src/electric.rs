//! The electrical columns of a stand log against a motor: at each compared point that logged
//! the supply's voltage and current, the current and electrical power the motor model draws
//! to give the propeller's torque at the measured speed.
//!
//! The log's voltage and current are the supply's, upstream of the ESC; the ESC is taken as
//! lossless, so the supply gives the motor's electrical power: predicted supply current =
//! V_m I_m / V_b, with (V_m, I_m) the motor's voltage and current for the torque at the speed
//! (QPROP's `VOLTM`). Twice: with the predicted torque (the whole chain, propeller and motor)
//! and with the measured torque (the motor model alone, where the log has torque).

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
}

/// The electrical comparison of `points` (of `sets`) on `motor`; None where no point logged
/// the supply's voltage and current.
pub fn score(points: &[ComparedPoint], sets: &[MeasuredSet], motor: &Motor, name: &str) -> Option<Electric> {
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
        points: out,
    })
}
