//! Synthetic measurements: the model with hidden effects, plus noise, written as a generic
//! CSV, UIUC files or an RCbenchmark log, with an answer key. For tests, and for users
//! learning what each effect looks like.

use propbet_bemt::{Fluid, OperatingPoint};
use propbet_effects::{EffectError, Stack};
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};
use serde::Serialize;

use crate::Model;

/// What to measure.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Rotation speeds [rpm] (logged).
    pub rpms: Vec<f64>,
    /// Advance ratios per RPM (J = 0: static).
    pub js: Vec<f64>,
    /// Relative noise (one standard deviation) on thrust and torque.
    pub noise: f64,
    /// Random seed.
    pub seed: u64,
    /// The true air (as logged).
    pub fluid: Fluid,
    /// Logged air temperature [degC] and pressure [Pa] written with the generic format.
    pub logged: (f64, f64),
}

/// One synthetic measured point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Point {
    /// Logged RPM.
    pub rpm: f64,
    /// Airspeed [m/s].
    pub v: f64,
    /// Advance ratio with the logged RPM.
    pub j: f64,
    /// Thrust [N].
    pub thrust: f64,
    /// Torque [N m].
    pub torque: f64,
}

/// The default RPMs: four from 40 % to 100 % of the RPM that gives a 150 m/s tip speed.
pub fn default_rpms(diameter: f64) -> Vec<f64> {
    // A tip speed of 150 m/s: omega = 150 / R.
    let top = propbet_units::omega_to_rpm(150.0 / (0.5 * diameter));
    [0.4, 0.6, 0.8, 1.0]
        .iter()
        .map(|f| (f * top / 100.0).round() * 100.0)
        .collect()
}

/// The advance ratio where the baseline's thrust reaches zero at `rpm` (searched to J = 3).
pub fn zero_thrust_j(model: &Model, fluid: &Fluid, rpm: f64) -> Option<f64> {
    let omega = propbet_units::rpm_to_omega(rpm);
    let nd = propbet_units::omega_to_rev_per_s(omega) * model.diameter;
    let mut j = 0.0;
    while j < 3.0 {
        j += 0.02;
        let p = model
            .fixed
            .predict(
                model.rotor,
                &model.opts,
                fluid,
                model.diameter,
                OperatingPoint { v: j * nd, omega },
            )
            .ok()?;
        if p.loads.thrust <= 0.0 {
            return Some(j);
        }
    }
    None
}

/// Nine advance ratios from 0 to 80 % of the zero-thrust J at `rpm`.
pub fn default_js(model: &Model, fluid: &Fluid, rpm: f64) -> Vec<f64> {
    let j0 = zero_thrust_j(model, fluid, rpm).unwrap_or(0.8);
    (0..9)
        .map(|k| (0.8 * j0 * k as f64 / 8.0 * 1000.0).round() / 1000.0)
        .collect()
}

/// Zero-mean normal noise of standard deviation `sd` (none for a negative or non-finite `sd`).
fn normal(sd: f64) -> Normal<f64> {
    let sd = if sd.is_finite() { sd.max(0.0) } else { 0.0 };
    Normal::new(0.0, sd).expect("a finite, non-negative standard deviation")
}

/// Measures the plan on the model with `stack` (the hidden effects) and adds the noise.
pub fn generate(model: &Model, stack: &Stack, plan: &Plan) -> Result<Vec<Point>, EffectError> {
    let mut rng = rand::rngs::StdRng::seed_from_u64(plan.seed);
    let normal = normal(plan.noise);
    let mut out = Vec::new();
    for &rpm in &plan.rpms {
        let omega = propbet_units::rpm_to_omega(rpm);
        let nd = propbet_units::omega_to_rev_per_s(omega) * model.diameter;
        for &j in &plan.js {
            let v = j * nd;
            let p = stack.predict(
                model.rotor,
                &model.opts,
                &plan.fluid,
                model.diameter,
                OperatingPoint { v, omega },
            )?;
            let thrust = p.loads.thrust * (1.0 + normal.sample(&mut rng));
            let torque = p.loads.torque * (1.0 + normal.sample(&mut rng));
            out.push(Point {
                rpm,
                v,
                j,
                thrust,
                torque,
            });
        }
    }
    Ok(out)
}

fn to_write(points: &[Point]) -> Vec<propbet_measure::write::Point> {
    points
        .iter()
        .map(|p| propbet_measure::write::Point {
            omega: propbet_units::rpm_to_omega(p.rpm),
            v: p.v,
            j: p.j,
            thrust: p.thrust,
            torque: p.torque,
        })
        .collect()
}

/// Generic CSV (`propbet_measure::write::generic`) with the plan's logged air.
pub fn write_generic(points: &[Point], plan: &Plan) -> String {
    propbet_measure::write::generic(&to_write(points), (plan.logged.0 + 273.15, plan.logged.1))
}

/// UIUC files, one sweep per RPM of the plan (`propbet_measure::write::uiuc`), coefficients
/// with the plan's density.
pub fn write_uiuc(points: &[Point], plan: &Plan, diameter: f64, stem: &str) -> Vec<(String, String)> {
    let omegas: Vec<f64> = plan.rpms.iter().map(|&r| propbet_units::rpm_to_omega(r)).collect();
    propbet_measure::write::uiuc(&to_write(points), &omegas, plan.fluid.rho, diameter, stem)
}

/// An RCbenchmark step log of the static points: one ESC step per RPM, eight samples 0.5 s
/// apart, each with its own noise (RPM scatter 0.2 %).
pub fn write_rcbenchmark(points: &[Point], plan: &Plan) -> String {
    let mut rng = rand::rngs::StdRng::seed_from_u64(plan.seed ^ 0x5eed);
    let rel = normal(plan.noise);
    let rpm_noise = normal(0.002);
    let mut samples = Vec::new();
    let mut t = 0.0;
    for (k, p) in points.iter().filter(|p| p.v == 0.0).enumerate() {
        let esc = 1100 + 100 * k as u32;
        for _ in 0..8 {
            let rpm = p.rpm * (1.0 + rpm_noise.sample(&mut rng));
            let torque = p.torque * (1.0 + rel.sample(&mut rng));
            let thrust = p.thrust * (1.0 + rel.sample(&mut rng));
            samples.push(propbet_measure::write::LogSample {
                time: t,
                esc,
                omega: propbet_units::rpm_to_omega(rpm),
                thrust,
                torque,
            });
            t += 0.5;
        }
    }
    propbet_measure::write::rcbenchmark(&samples)
}
