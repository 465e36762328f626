//! Measured points against the solver: each point is reduced to J, CT, CP, CQ and efficiency
//! with uncertainties, predicted at its own RPM, airspeed and air state, and scored
//! ([`metrics`]); [`curves`] gives the model's curves beside them (pages: `propbet-report`).
#![deny(missing_docs)]

pub mod band;
pub mod curves;
pub mod electric;
pub mod expected;
pub mod metrics;
pub mod plausible;

use propbet_atmosphere::AirState;
use propbet_bemt::{Fluid, OperatingPoint, PointResult, Rotor, SolverOptions};
use propbet_effects::{EffectError, Stack};
use propbet_measure::{Loads, MeasuredPoint, MeasuredSet, Speed};
use rayon::prelude::*;
use serde::Serialize;

pub use metrics::{Metric, MetricGroup, Metrics};

/// The air a comparison assumes where the files say nothing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AirChoice {
    /// Given temperature, pressure and humidity (override what is logged).
    pub given: Option<AirState>,
    /// Given density [kg/m^3] (overrides the density from any state; viscosity and speed of
    /// sound still follow the state).
    pub rho: Option<f64>,
}

/// Where a point's air came from.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PointAir {
    /// The fluid used for the prediction and the coefficients.
    pub fluid: Fluid,
    /// "logged T, p; standard RH" and the like.
    pub source: String,
    /// True when nothing was known and standard air was assumed.
    pub standard: bool,
}

/// Standard air (QPROP's defaults), assumed: a point's air before anything says otherwise.
impl Default for PointAir {
    fn default() -> Self {
        Self {
            fluid: Fluid::QPROP_DEFAULT,
            source: String::new(),
            standard: true,
        }
    }
}

/// The air of one point: given values first, then logged ones, then ISA sea level.
pub fn point_air(p: &MeasuredPoint, choice: &AirChoice) -> PointAir {
    let isa = AirState::ISA;
    let pick = |given: Option<f64>, logged: Option<f64>, standard: f64| match (given, logged) {
        (Some(g), _) => (g, "given"),
        (None, Some(l)) => (l, "logged"),
        (None, None) => (standard, "standard"),
    };
    let g = choice.given;
    let (t, ts) = pick(g.map(|s| s.temperature), p.air.temperature, isa.temperature);
    let (pr, ps) = pick(g.map(|s| s.pressure), p.air.pressure, isa.pressure);
    let (rh, hs) = pick(g.map(|s| s.relative_humidity), p.air.humidity, 0.0);
    let state = AirState {
        temperature: t,
        pressure: pr,
        relative_humidity: rh,
    };
    let mut fluid = state.fluid();
    let mut source = format!("T {ts}, p {ps}, RH {hs}");
    let mut standard = ts == "standard" && ps == "standard";
    if let Some(rho) = choice.rho {
        fluid.rho = rho;
        source = format!("rho given ({rho} kg/m^3); mu and a from {source}");
        standard = false;
    }
    PointAir {
        fluid,
        source,
        standard,
    }
}

/// Performance quantities of a point, measured or predicted; `None` where unknown.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Quantities {
    /// Thrust [N].
    pub thrust: Option<f64>,
    /// Torque [N m].
    pub torque: Option<f64>,
    /// Shaft power [W].
    pub power: Option<f64>,
    /// CT = T/(rho n^2 D^4).
    pub ct: Option<f64>,
    /// CP = P/(rho n^3 D^5).
    pub cp: Option<f64>,
    /// CQ = Q/(rho n^2 D^5).
    pub cq: Option<f64>,
    /// Efficiency T V / P (forward flight with positive thrust and power only).
    pub eta: Option<f64>,
}

/// The quantities scored, in report order.
pub const QUANTITIES: [&str; 6] = ["thrust", "torque", "power", "ct", "cp", "eta"];

impl Quantities {
    /// A quantity by its name in [`QUANTITIES`] (or "cq").
    pub fn get(&self, name: &str) -> Option<f64> {
        match name {
            "thrust" => self.thrust,
            "torque" => self.torque,
            "power" => self.power,
            "ct" => self.ct,
            "cp" => self.cp,
            "cq" => self.cq,
            "eta" => self.eta,
            _ => None,
        }
    }

    /// From thrust and torque at rotation `omega` [rad/s], speed `v` [m/s], density `rho` and
    /// diameter `d`.
    pub fn from_forces(thrust: f64, torque: Option<f64>, omega: f64, v: f64, rho: f64, d: f64) -> Self {
        let n = propbet_units::omega_to_rev_per_s(omega);
        let scale = propbet_units::Scales::new(rho, n, d);
        let power = torque.map(|q| q * omega);
        Self {
            thrust: Some(thrust),
            torque,
            power,
            ct: Some(thrust / scale.thrust),
            cp: power.map(|p| p / scale.power),
            cq: torque.map(|q| q / scale.torque),
            eta: power
                .filter(|p| *p > 0.0 && v > 0.0 && thrust > 0.0)
                .map(|p| thrust * v / p),
        }
    }
}

/// One measured point with its prediction (`Default`: a blank point in standard air, for tests
/// and builders to fill).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct ComparedPoint {
    /// Index of the measured file.
    pub file: usize,
    /// The point's label in its file.
    pub label: String,
    /// Lines of the file.
    pub lines: (usize, usize),
    /// Readings that made the point: of RPM, thrust and torque (a sparse log logs the loads on
    /// fewer rows than the RPM; a published table's point is one reading of each).
    pub samples: Samples,
    /// Rotation speed [rpm].
    pub rpm: f64,
    /// Its scatter [rpm].
    pub rpm_sd: Option<f64>,
    /// Nominal RPM of its group (UIUC file RPM) [rpm].
    pub nominal_rpm: Option<f64>,
    /// Airspeed [m/s].
    pub v: f64,
    /// Advance ratio V/(nD).
    pub j: f64,
    /// Air.
    pub air: PointAir,
    /// Measured.
    pub measured: Quantities,
    /// One standard deviation of the measured values (scatter propagated).
    pub measured_sd: Quantities,
    /// Predicted.
    pub predicted: Quantities,
    /// Reynolds number at 0.75 R (predicted flow).
    pub re75: f64,
    /// Helical tip Mach number.
    pub mach_tip: f64,
    /// Stations the solver did not converge.
    pub not_converged: usize,
    /// Stations solved at a Reynolds number beyond their polars' (below the lowest rung or above
    /// the highest: [`propbet_bemt::check::beyond_data`]), and the stations solved.
    pub beyond_polars: (usize, usize),
    /// What is physically wrong with the prediction at this point
    /// ([`propbet_bemt::check`]): reported with the point, never silently scored.
    pub model_flags: Vec<String>,
    /// Reasons not to score the point.
    pub flags: Vec<String>,
    /// Smallest |measured| value given a relative error, per quantity: 5 % of the largest in
    /// the comparison (near zero thrust, at the windmill end of a J sweep, a relative error
    /// says nothing).
    pub rel_floor: Quantities,
}

/// How many readings of each signal made a point.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Samples {
    /// RPM readings.
    pub rpm: usize,
    /// Thrust readings (none for coefficients).
    pub thrust: Option<usize>,
    /// Torque readings (none without a torque cell, or for coefficients).
    pub torque: Option<usize>,
}

impl Samples {
    /// Of a measured point.
    pub fn of(p: &MeasuredPoint) -> Self {
        match p.loads {
            Loads::Forces { thrust, torque } => Samples {
                rpm: p.omega.n,
                thrust: Some(thrust.n),
                torque: torque.map(|q| q.n),
            },
            Loads::Coefficients { .. } => Samples {
                rpm: p.omega.n,
                thrust: None,
                torque: None,
            },
        }
    }
}

/// Fraction of the largest |measured| value below which no relative error is computed.
pub const RELATIVE_FLOOR: f64 = 0.05;

impl ComparedPoint {
    /// Relative error (predicted - measured)/measured of a quantity; `None` where the
    /// measured value is below the floor.
    pub fn relative_error(&self, q: &str) -> Option<f64> {
        let m = self.measured.get(q)?;
        let p = self.predicted.get(q)?;
        let floor = self.rel_floor.get(q).unwrap_or(0.0).max(1e-12);
        (m.abs() > floor).then(|| (p - m) / m)
    }

    /// True when the point is scored.
    pub fn scored(&self) -> bool {
        self.flags.is_empty()
    }

    /// True for a static (J ~ 0) point.
    pub fn is_static(&self) -> bool {
        self.j < 0.01
    }
}

/// What the comparison is run with.
pub struct Setup<'a> {
    /// The rotor as the solver sees it.
    pub rotor: &'a Rotor,
    /// Propeller diameter for the coefficients and J [m] (the blade's, even when the rotor's
    /// tip-loss radius is QPROP's unscaled line-2 value).
    pub diameter: f64,
    /// Solver options.
    pub opts: SolverOptions,
    /// Air.
    pub air: AirChoice,
    /// Effects added to the model (`--effect`); empty for the baseline.
    pub effects: Stack,
}

fn hypot_rel(parts: &[Option<f64>]) -> f64 {
    parts.iter().flatten().map(|x| x * x).sum::<f64>().sqrt()
}

/// Reynolds number at 0.75 R by linear interpolation of the station results.
pub fn re_at(result: &PointResult, r: f64) -> f64 {
    let s = &result.stations;
    if s.is_empty() {
        return f64::NAN;
    }
    let i = s
        .iter()
        .position(|x| x.r >= r)
        .unwrap_or(s.len() - 1)
        .max(1)
        .min(s.len() - 1);
    let (a, b) = (&s[i - 1], &s[i]);
    let t = ((r - a.r) / (b.r - a.r)).clamp(0.0, 1.0);
    a.re + t * (b.re - a.re)
}

/// Predicts one operating point (with the setup's effects) and derives the coefficients with
/// the setup's diameter, the logged `omega` and the assumed density, as the measured ones are.
pub fn predict(setup: &Setup, omega: f64, v: f64, fluid: &Fluid) -> Result<(Quantities, PointResult), EffectError> {
    let mut opts = setup.opts;
    opts.keep_stations = true;
    let p = setup
        .effects
        .predict(setup.rotor, &opts, fluid, setup.diameter, OperatingPoint { v, omega })?;
    let q = Quantities::from_forces(
        p.loads.thrust,
        Some(p.loads.torque),
        omega,
        v,
        fluid.rho,
        setup.diameter,
    );
    Ok((q, p.result))
}

fn compare_point(setup: &Setup, file: usize, p: &MeasuredPoint) -> Result<ComparedPoint, EffectError> {
    let air = point_air(p, &setup.air);
    let rho = air.fluid.rho;
    let d = setup.diameter;
    let omega = p.omega.mean;
    let n = propbet_units::omega_to_rev_per_s(omega);
    let rel_n = p.omega.relative_sd();
    let (v, v_sd) = match p.speed {
        Speed::Airspeed(v) => (v.mean, v.sd),
        Speed::AdvanceRatio(j) => (j * n * d, None),
    };
    let (measured, measured_sd) = match p.loads {
        Loads::Forces { thrust, torque } => {
            let m = Quantities::from_forces(thrust.mean, torque.map(|q| q.mean), omega, v, rho, d);
            let rt = Some(thrust.relative_sd());
            let rq = torque.map(|q| q.relative_sd());
            let rv = v_sd.filter(|_| v > 0.0).map(|s| s / v);
            let sd = |val: Option<f64>, parts: &[Option<f64>]| val.map(|x| x.abs() * hypot_rel(parts));
            let sds = Quantities {
                thrust: thrust.sd,
                torque: torque.and_then(|q| q.sd),
                power: sd(m.power, &[rq, Some(rel_n)]),
                ct: sd(m.ct, &[rt, Some(2.0 * rel_n)]),
                cp: sd(m.cp, &[rq, Some(2.0 * rel_n)]),
                cq: sd(m.cq, &[rq, Some(2.0 * rel_n)]),
                eta: sd(m.eta, &[rt, rq, rv, Some(rel_n)]),
            };
            (m, sds)
        }
        Loads::Coefficients { ct, cp } => {
            let scale = propbet_units::Scales::new(rho, n, d);
            let thrust = ct * scale.thrust;
            let power = cp * scale.power;
            let m = Quantities {
                thrust: Some(thrust),
                torque: Some(power / omega),
                power: Some(power),
                ct: Some(ct),
                cp: Some(cp),
                cq: Some(propbet_units::cq_of_cp(cp)),
                eta: (v > 0.0 && cp > 0.0 && ct > 0.0).then(|| thrust * v / power),
            };
            (m, Quantities::default())
        }
    };
    let (predicted, result) = predict(setup, omega, v, &air.fluid)?;
    let mut model_flags = propbet_bemt::check::implausible(&result, air.fluid.rho, setup.rotor.tip_radius);
    let outside = propbet_bemt::check::outside_data(setup.rotor, &result);
    if outside > 0 {
        model_flags.push(format!(
            "{outside} stations solved at a Reynolds number far outside their polars"
        ));
    }
    let tip = 0.5 * d;
    Ok(ComparedPoint {
        file,
        label: p.label.clone(),
        lines: p.lines,
        samples: Samples::of(p),
        rpm: p.rpm(),
        rpm_sd: p.omega.sd.map(propbet_units::omega_to_rpm),
        nominal_rpm: p.nominal_omega.map(propbet_units::omega_to_rpm),
        v,
        j: v / (n * d),
        measured,
        measured_sd,
        predicted,
        re75: re_at(&result, 0.75 * tip),
        mach_tip: (omega * tip).hypot(v) / air.fluid.a,
        not_converged: result.not_converged,
        beyond_polars: (
            propbet_bemt::check::beyond_data(setup.rotor, &result),
            result.stations.len(),
        ),
        model_flags,
        flags: p.flags.clone(),
        rel_floor: Quantities::default(),
        air,
    })
}

/// Predicts every point of every set (in parallel) and pairs it with its measurement; fails
/// only when an effect's formula fails.
pub fn compare(setup: &Setup, sets: &[MeasuredSet]) -> Result<Vec<ComparedPoint>, EffectError> {
    let jobs: Vec<(usize, &MeasuredPoint)> = sets
        .iter()
        .enumerate()
        .flat_map(|(i, s)| s.points.iter().map(move |p| (i, p)))
        .collect();
    let mut points: Vec<ComparedPoint> = jobs
        .par_iter()
        .map(|(i, p)| compare_point(setup, *i, p))
        .collect::<Result<_, _>>()?;
    let floor = |q: &str| {
        let max = points
            .iter()
            .filter_map(|p| p.measured.get(q))
            .fold(0.0f64, |a, v| a.max(v.abs()));
        (max > 0.0).then_some(RELATIVE_FLOOR * max)
    };
    let rel_floor = Quantities {
        thrust: floor("thrust"),
        torque: floor("torque"),
        power: floor("power"),
        ct: floor("ct"),
        cp: floor("cp"),
        cq: floor("cq"),
        eta: floor("eta"),
    };
    for p in &mut points {
        p.rel_floor = rel_floor;
    }
    Ok(points)
}
