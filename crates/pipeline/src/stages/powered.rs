//! The propeller on its motor: each (driver, airspeed) point solved where the motor's torque
//! meets the model's (QPROP's `qprop PROP MOTOR V RPM Volt ...` drivers), with the model's
//! effects, in QPROP's order (the driver outer, the airspeed inner).

use std::path::Path;

use propbet_bemt::{Fluid, OperatingPoint, PointResult};
use propbet_motor::{operate, Drive, MotorFile, OperateError, Powered, PropLoads, Supply, SupplyPoint};
use rayon::prelude::*;

use crate::{read_text, Error, Result};
use propbet_model::Model;

/// Reads a QPROP motor file (its constants checked: a bad one names its line and value).
pub fn read_motor(path: &Path) -> Result<MotorFile> {
    let text = read_text(path)?;
    propbet_motor::parse_motor(&text).map_err(|e| Error::input(path, e.to_string()))
}

/// One point of a powered sweep: its driver and airspeed, and the operating point or why
/// there is none.
#[derive(Debug, Clone)]
pub struct PoweredPoint {
    /// What set the point.
    pub drive: Drive,
    /// Airspeed [m/s].
    pub v: f64,
    /// The motor's side and the propeller's full result, or why the motor and the propeller
    /// have no common operating point.
    pub outcome: std::result::Result<(Powered, PointResult), String>,
    /// With a battery and ESC: what they do at the point, or why they cannot give it.
    pub supply: Option<std::result::Result<SupplyPoint, String>>,
}

impl PoweredPoint {
    /// Why the point has no answer: no common operating point of motor and propeller, or a
    /// battery that cannot give it.
    pub fn problem(&self) -> Option<&str> {
        match (&self.outcome, &self.supply) {
            (Err(why), _) | (Ok(_), Some(Err(why))) => Some(why),
            _ => None,
        }
    }
}

/// The fastest a propeller is searched at: a tip speed of 1.5 times the speed of sound.
pub(crate) fn omega_ceiling(model: &Model, fluid: &Fluid) -> f64 {
    (1.5 * fluid.a / model.rotor.tip_radius).min(propbet_units::operating::OMEGA_MAX)
}

/// The model's full result at one airspeed [m/s] and speed [rad/s].
pub(crate) fn solve_at(model: &Model, fluid: &Fluid, v: f64, omega: f64) -> Result<PointResult> {
    let mut r = crate::stages::solve(model, fluid, &[OperatingPoint { v, omega }])?;
    r.pop()
        .ok_or_else(|| Error::Nothing("the solver returned no point".into()))
}

/// Every driver at every airspeed (the driver outer), on `motor` (and `supply`, the battery
/// and ESC, when given), in parallel.
pub fn powered(
    model: &Model,
    fluid: &Fluid,
    motor: &propbet_motor::Motor,
    supply: Option<&Supply>,
    drives: &[Drive],
    speeds: &[f64],
) -> Result<Vec<PoweredPoint>> {
    let ceiling = omega_ceiling(model, fluid);
    let pairs: Vec<(Drive, f64)> = drives
        .iter()
        .flat_map(|&d| speeds.iter().map(move |&v| (d, v)))
        .collect();
    if pairs.is_empty() {
        crate::nothing!("no operating point: give at least one driver value and one airspeed");
    }
    pairs
        .par_iter()
        .map(|&(drive, v)| {
            let at = |omega: f64| solve_at(model, fluid, v, omega);
            let mut loads = |omega: f64| {
                at(omega).map(|p| PropLoads {
                    thrust: p.thrust,
                    torque: p.torque,
                })
            };
            let outcome = match operate(motor, drive, ceiling, &mut loads) {
                Ok(p) => Ok((p, at(p.omega)?)),
                Err(OperateError::Prop(e)) => return Err(e),
                Err(e @ OperateError::NoSolution { .. }) => Err(e.to_string()),
            };
            let supply = match (&outcome, supply) {
                (Ok((p, _)), Some(s)) => Some(s.at(p.volts, p.amps)),
                _ => None,
            };
            Ok(PoweredPoint {
                drive,
                v,
                outcome,
                supply,
            })
        })
        .collect()
}

/// A powered prediction: the motor, each point, and the propeller's band at each point with
/// an operating point (where asked for).
#[derive(Debug, Clone)]
pub struct PoweredTable {
    /// The motor file read.
    pub motor: MotorFile,
    /// The points, one per driver value and airspeed.
    pub points: Vec<PoweredPoint>,
    /// The propeller's uncertainty band at each point (None where it has no operating point).
    pub band: Option<Vec<Option<propbet_compare::band::PointBand>>>,
}

impl PoweredTable {
    /// Every point has its operating point and every station converged.
    pub fn clean(&self) -> bool {
        self.points
            .iter()
            .all(|p| p.problem().is_none() && p.outcome.as_ref().is_ok_and(|(_, r)| r.not_converged == 0))
    }
}

/// `model` in `fluid` on `motor` (with `supply`, the battery and ESC) at each driver and
/// airspeed [m/s], with the propeller's band at each operating point when `band`.
pub fn powered_table(
    model: &Model,
    fluid: &Fluid,
    motor: MotorFile,
    supply: Option<&Supply>,
    drives: &[Drive],
    speeds: &[f64],
    band: bool,
) -> Result<PoweredTable> {
    let points = powered(model, fluid, &motor.motor, supply, drives, speeds)?;
    let band = band.then(|| powered_band(model, fluid, &points)).transpose()?;
    Ok(PoweredTable { motor, points, band })
}

/// The powered table a spec asks for, with `model` (loaded from `spec.model`) in `fluid`.
pub(crate) fn powered_stage(
    model: &Model,
    fluid: &Fluid,
    spec: &propbet_settings::spec::PoweredSpec,
) -> Result<PoweredTable> {
    let motor = read_motor(&spec.motor)?;
    powered_table(
        model,
        fluid,
        motor,
        spec.supply.as_ref(),
        &spec.drives,
        &spec.speeds,
        spec.band,
    )
}

/// The propeller's uncertainty band (`predict --band`'s) at each operating point found: its CT,
/// CP and efficiency at that speed and airspeed, the motor's point held.
pub(crate) fn powered_band(
    model: &Model,
    fluid: &Fluid,
    points: &[PoweredPoint],
) -> Result<Vec<Option<propbet_compare::band::PointBand>>> {
    let solved: Vec<(usize, OperatingPoint, PointResult)> = points
        .iter()
        .enumerate()
        .filter_map(|(i, p)| {
            let (s, r) = p.outcome.as_ref().ok()?;
            Some((i, OperatingPoint { v: p.v, omega: s.omega }, r.clone()))
        })
        .collect();
    let ops: Vec<OperatingPoint> = solved.iter().map(|x| x.1).collect();
    let base: Vec<PointResult> = solved.iter().map(|x| x.2.clone()).collect();
    let bands = propbet_model::band::BandSpec::for_model(model).at_points(model, fluid, &ops, &base)?;
    let mut out = vec![None; points.len()];
    for ((i, ..), b) in solved.iter().zip(bands) {
        out[*i] = Some(b);
    }
    Ok(out)
}

/// A motor fitted to stand logs, and how well it predicts each step's current when that step
/// is left out of the fit.
#[derive(Debug, Clone)]
pub struct FittedMotor {
    /// The fit.
    pub fit: propbet_motor::MotorFit,
    /// Each fitted point: (its set's name and step label, the point, the current predicted
    /// with its own step left out).
    pub points: Vec<(String, propbet_motor::FitPoint, Option<f64>)>,
    /// The median |predicted / measured - 1| of the held-out currents.
    pub held_out_median: Option<f64>,
    /// What was assumed or left out, in words.
    pub notes: Vec<String>,
    /// Where the model misses, in words: the held-out current error's trend over speed when it
    /// is significant (none where it is not).
    pub misses: Option<String>,
}

/// Fits a motor of `kind` to the steps of the measured files that log speed, torque, voltage
/// and current (`kv_rpm` the maker's Kv when given), each step also predicted with itself
/// left out.
pub fn fit_motor(
    spec: &propbet_settings::spec::MeasuredSpec,
    kv_rpm: Option<f64>,
    kind: propbet_motor::FitKind,
) -> Result<FittedMotor> {
    let batch = crate::stages::load_batch(spec)?;
    if let Some(r) = batch.refused.first() {
        return Err(Error::input(Path::new(&r.file), r.reason.clone()));
    }
    let (points, names, mut notes) = fit_points(&batch);
    let fit = propbet_motor::fit_motor(&points, kv_rpm, kind).map_err(|e| {
        let hint = match e {
            propbet_motor::FitError::Unphysical(_) => {
                " (an RPM column that is the motor's electrical speed needs --poles; a log of a varying \
                 throttle rather than held steps gives few steady points)"
            }
            _ => "",
        };
        Error::Nothing(format!("{e}{hint}"))
    })?;
    const DUTY: &str = "the ESC's duty read as (command - 1000 µs) / 1000 µs (a linear ESC calibrated to \
                        1000-2000 µs)";
    match (kind, fit.kv_source) {
        (propbet_motor::FitKind::Type1, propbet_motor::fit::KvSource::EscDuty(n)) => notes.push(format!(
            "Kv from the voltage the motor sees at {n} steps of half throttle and above, {DUTY}; give the maker's \
             Kv (--kv) where the ESC is not"
        )),
        (propbet_motor::FitKind::Type2, source) => {
            notes.push(format!(
                "Kq and Io from the motor's own current (the supply's over the duty) at the steps of half throttle \
                 and above, {DUTY}; R {} from the supply power",
                if source == propbet_motor::fit::KvSource::Given {
                    "(Kv given)"
                } else {
                    "and Kv"
                }
            ));
            if source != propbet_motor::fit::KvSource::Given {
                notes.push(
                    "on a propeller's load the current and the speed rise together, so R and Kv trade against each \
                     other: their intervals are wide; the maker's Kv (--kv) makes R's narrow"
                        .into(),
                );
            }
        }
        _ => {}
    }
    notes.extend(
        fit.sides
            .as_ref()
            .map(|s| both_sides(s, fit.kv_source != propbet_motor::fit::KvSource::Given)),
    );
    notes.push(
        match kind {
            propbet_motor::FitKind::Type1 => {
                "the ESC taken as lossless: its losses are in R, and Io holds the motor's and the ESC's no-load draw"
            }
            propbet_motor::FitKind::Type2 => {
                "the ESC taken as lossless: its losses, and the motor's that grow with its power, are in Kq above Kv, \
             in R and in Io"
            }
        }
        .into(),
    );
    let step: Vec<usize> = (0..points.len()).collect();
    let held = propbet_motor::held_out_amps(&points, &step, kv_rpm, kind);
    let errors: Vec<f64> = points
        .iter()
        .zip(&held)
        .filter_map(|(p, h)| h.map(|h| (h / p.amps - 1.0).abs()))
        .collect();
    let held_out_median = (!errors.is_empty()).then(|| propbet_units::stats::median(errors));
    let misses = speed_trend(&points, &held);
    Ok(FittedMotor {
        misses,
        fit,
        points: names
            .into_iter()
            .zip(points)
            .zip(held)
            .map(|((n, p), h)| (n, p, h))
            .collect(),
        held_out_median,
        notes,
    })
}

/// The steps of `batch` a motor fit takes (speed, torque, voltage and current, unflagged), each
/// log's zero at rest taken off, with their names and what was taken off or left out.
fn fit_points(batch: &crate::stages::Batch) -> (Vec<propbet_motor::FitPoint>, Vec<String>, Vec<String>) {
    use propbet_measure::Loads;
    let mut points = Vec::new();
    let mut names = Vec::new();
    let mut notes = Vec::new();
    let mut without = 0;
    for (set, name) in batch.sets.iter().zip(&batch.names) {
        // The log's zero, taken off every step: at rest the torque is the cell's zero, and a
        // current below zero the meter's offset. A current above zero at rest may be the ESC's
        // own draw, which the supply gives while the motor runs too: kept (in Io).
        let zero = set.at_rest.filter(|_| set.points.iter().any(|p| p.electric.is_some()));
        let (amps0, torque0) = zero.map_or((0.0, 0.0), |z| {
            (z.amps.unwrap_or(0.0).min(0.0), z.torque.unwrap_or(0.0))
        });
        if let Some(z) = zero {
            notes.push(format!(
                "{name}: at rest ({} rows) the torque read {torque0:.4} N m{}: taken off every step (the torque \
                 cell's zero{}: not the motor's)",
                z.rows,
                if amps0 < 0.0 {
                    format!(" and the current {amps0:.3} A")
                } else {
                    String::new()
                },
                if amps0 < 0.0 {
                    ", the current meter's offset"
                } else {
                    ""
                },
            ));
        }
        for p in &set.points {
            let torque = match &p.loads {
                Loads::Forces { torque: Some(q), .. } => q.mean - torque0,
                _ => f64::NAN,
            };
            match &p.electric {
                Some(e)
                    if torque.is_finite() && e.volts.mean > 0.0 && e.amps.mean - amps0 > 0.0 && p.flags.is_empty() =>
                {
                    points.push(propbet_motor::FitPoint {
                        omega: p.omega.mean,
                        torque,
                        volts: e.volts.mean,
                        amps: e.amps.mean - amps0,
                        esc: e.esc,
                    });
                    names.push(format!("{name}: {}", p.label));
                }
                _ => without += 1,
            }
        }
    }
    if without > 0 {
        notes.push(format!(
            "{without} steps without torque, voltage or current (or flagged: unsteady, windmilling) left out"
        ));
    }
    (points, names, notes)
}

/// Kv from both sides of the motor, in words: the agreement, a disagreement above 10 % with
/// what may cause it, and the steps left out.
fn both_sides(s: &propbet_motor::Sides, io_from_torque: bool) -> String {
    let apart = s.disagreement();
    let mut text = format!(
        "both sides of the motor at {} steps: Kv = {:.0} ± {:.0} rpm/V from its voltage, {:.0} ± {:.0} rpm/V from \
         its torque constant (1/Kt, Kt = {:.4} N m/A): {:.1} % apart",
        s.steps,
        s.kv_rpm.value,
        s.kv_rpm.plus_minus,
        s.torque_kv_rpm.value,
        s.torque_kv_rpm.plus_minus,
        propbet_units::omega_to_rpm(1.0) / s.torque_kv_rpm.value,
        100.0 * apart
    );
    if apart.abs() > propbet_motor::fit::sides::DISAGREE {
        text.push_str(
            "; they disagree: the logged speed (an electrical speed needs --poles), the torque's scale or the ESC's \
             duty map is not what it seems, and the fitted motor holds the supply's current only",
        );
    } else if io_from_torque {
        text.push_str("; Io is the torque side's (the motor's current at zero torque)");
    }
    if !s.left_out.is_empty() {
        let us: Vec<String> = s.left_out.iter().map(|u| format!("{u:.0} µs")).collect();
        text.push_str(&format!(
            "; left out: the steps at {} (off the line the motor's voltage makes at the others: an ESC at full \
             duty before its command, or a supply at its current limit)",
            us.join(", ")
        ));
    }
    text
}

/// The held-out current error's straight-line trend over speed, in words, when it exceeds
/// twice its standard error and 3 % over the steps' range: what type 1's constant Io misses.
fn speed_trend(points: &[propbet_motor::FitPoint], held: &[Option<f64>]) -> Option<String> {
    let xy: Vec<(f64, f64)> = points
        .iter()
        .zip(held)
        .filter_map(|(p, h)| h.map(|h| (p.omega, h / p.amps - 1.0)))
        .collect();
    if xy.len() < 4 {
        return None;
    }
    let n = xy.len() as f64;
    let (mx, my) = (
        xy.iter().map(|p| p.0).sum::<f64>() / n,
        xy.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxx: f64 = xy.iter().map(|p| (p.0 - mx).powi(2)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let slope = xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>() / sxx;
    let ss: f64 = xy.iter().map(|p| (p.1 - my - slope * (p.0 - mx)).powi(2)).sum();
    let se = (ss / (n - 2.0) / sxx).sqrt();
    let (lo, hi) = xy
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let change = slope * (hi - lo);
    (slope.abs() > 2.0 * se && change.abs() > 0.03).then(|| {
        format!(
            "the predicted current drifts {:+.1} % from the slowest step to the fastest: {}",
            100.0 * change,
            if change < 0.0 {
                "the motor draws more than R and a constant Io allow as it speeds up: no-load losses rising \
                 with speed (bearings, iron; QPROP type 2's Io1, Io2) or the ESC's timing"
            } else {
                "the motor draws less at speed than at low speed: a resistance falling with load, or heating \
                 during the slow steps (R rises with temperature)"
            }
        )
    })
}

/// The comparison's electrical columns against the motor file at `motor` (None where no
/// point logged the supply's voltage and current), the speed at the ESC's voltage with
/// `model` (the comparison's, its effects included).
pub fn electric(
    c: &crate::stages::Compared,
    model: &Model,
    motor: &Path,
) -> Result<Option<propbet_compare::electric::Electric>> {
    let file = read_motor(motor)?;
    let setup = crate::stages::setup(model, c.air, model.effects.clone());
    let loads = |p: &propbet_compare::ComparedPoint, omega: f64| {
        let (q, _) = propbet_compare::predict(&setup, omega, p.v, &p.air.fluid).ok()?;
        Some((q.thrust?, q.torque?))
    };
    Ok(propbet_compare::electric::score(
        &c.points,
        &c.sets,
        &file.motor,
        &file.name,
        &loads,
    ))
}

/// Rotation rates the polars of a blade file are computed over: up to the motor's no-load
/// speed at the highest voltage given or the battery's (12 V, a 3-cell battery, where none
/// is).
pub fn polar_omegas(
    motor: &propbet_motor::Motor,
    drives: &[propbet_motor::Drive],
    battery_volts: Option<f64>,
) -> Vec<f64> {
    use propbet_motor::Drive;
    let volts = drives
        .iter()
        .filter_map(|d| match d {
            Drive::Volts(v) | Drive::Throttle { volts: v, .. } => Some(*v),
            _ => None,
        })
        .chain(battery_volts)
        .fold(None, |m: Option<f64>, v| Some(m.map_or(v, |m| m.max(v))))
        .unwrap_or(12.0);
    let top = motor.free_speed(volts).unwrap_or(motor.kv() * volts);
    let mut omegas: Vec<f64> = (1..=8).map(|k| top * k as f64 / 8.0).collect();
    omegas.extend(drives.iter().filter_map(|d| match d {
        Drive::Omega(w) => Some(*w),
        _ => None,
    }));
    omegas
}
