//! Physical effects that modify the BEMT model, and the machinery that applies them.
//!
//! An [`Effect`] acts through one or more [`Hook`]s, in this order for every operating point:
//!
//! 1. **measurement** — what the logged point really was (true RPM, true density);
//! 2. **geometry** — each station's chord and blade angle, per operating point;
//! 3. **inflow** — the solver's loss factors;
//! 4. **section** — lift and drag of each station;
//! 5. **loads** — the integrated thrust and torque, as the stand reads them.
//!
//! Each effect has named parameters with a neutral value (where the effect does nothing, when
//! there is one), bounds and a scale, and a physical explanation. [`builtin`] holds the
//! thirteen built-in effects, [`user`] the effects users write as TOML formulas. A
//! [`Stack`] is a list of effects with parameter values; [`Stack::predict`] solves one
//! operating point with all of them applied.
#![deny(missing_docs)]

pub mod builtin;
mod section;
pub mod spec;
pub mod user;

use std::sync::{Arc, Mutex};

use propbet_bemt::{DragInput, Fluid, LiftEval, OperatingPoint, PointResult, Rotor, Solver, SolverOptions};
use serde::Serialize;
use thiserror::Error;

pub use spec::{parse_spec, EffectSpec};

/// Where an effect acts on the model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Hook {
    /// The logged operating point (RPM sensor, air density).
    Measurement,
    /// Station chord and blade angle, per operating point.
    Geometry,
    /// The solver's loss factors.
    Inflow,
    /// Section lift and drag.
    Section,
    /// Integrated thrust and torque.
    Loads,
}

/// One named parameter of an effect.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Param {
    /// Name, as written in `--effect id:name=value`.
    pub name: String,
    /// Unit, for people.
    pub unit: String,
    /// The value at which the effect changes nothing, if there is one.
    pub neutral: Option<f64>,
    /// Value the fit starts from.
    pub start: f64,
    /// Lower bound.
    pub lower: f64,
    /// Upper bound.
    pub upper: f64,
    /// Typical magnitude of a change (the fit's step scale).
    pub scale: f64,
    /// What the parameter means.
    pub doc: String,
}

impl Param {
    /// A parameter with a neutral value that is also the start.
    pub fn new(name: &str, unit: &str, neutral: f64, (lower, upper): (f64, f64), scale: f64, doc: &str) -> Self {
        Self {
            name: name.to_string(),
            unit: unit.to_string(),
            neutral: Some(neutral),
            start: neutral,
            lower,
            upper,
            scale,
            doc: doc.to_string(),
        }
    }
}

/// The operating point as the effects see and change it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointState {
    /// Rotation rate [rad/s] (after the measurement hook: the true one).
    pub omega: f64,
    /// Axial speed [m/s].
    pub v: f64,
    /// The air.
    pub fluid: Fluid,
    /// Tip radius of the rotor [m].
    pub tip_radius: f64,
    /// Blade count.
    pub blades: f64,
    /// Propeller diameter used for coefficients [m].
    pub diameter: f64,
}

impl PointState {
    /// Rotation speed [1/min].
    pub fn rpm(&self) -> f64 {
        propbet_units::omega_to_rpm(self.omega)
    }

    /// Advance ratio V/(nD), 0 without rotation.
    pub fn advance_ratio(&self) -> f64 {
        if self.omega > 0.0 {
            self.v / (self.omega / (2.0 * std::f64::consts::PI) * self.diameter)
        } else {
            0.0
        }
    }
}

/// A station's geometry as the geometry hook changes it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StationGeom {
    /// Radius [m].
    pub r: f64,
    /// r/R [-].
    pub x: f64,
    /// Chord [m].
    pub chord: f64,
    /// Blade angle [rad].
    pub beta: f64,
}

/// What a section hook knows about its station and point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionCtx {
    /// Station geometry (after the geometry hooks).
    pub geom: StationGeom,
    /// The operating point (after the measurement hooks).
    pub point: PointState,
}

/// Integrated loads as the stand reads them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Loads {
    /// Thrust [N].
    pub thrust: f64,
    /// Torque [N m].
    pub torque: f64,
}

/// Something wrong with an effect or its use.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum EffectError {
    /// No effect with that id.
    #[error("unknown effect `{id}`; known: {known}")]
    Unknown {
        /// The id given.
        id: String,
        /// The ids there are.
        known: String,
    },
    /// A parameter name the effect does not have.
    #[error("effect `{id}` has no parameter `{name}`; it has: {known}")]
    UnknownParam {
        /// Effect id.
        id: String,
        /// Name given.
        name: String,
        /// Its parameters.
        known: String,
    },
    /// A parameter outside its bounds.
    #[error("{id}:{name} = {value} is outside its bounds [{lower}, {upper}]")]
    OutOfBounds {
        /// Effect id.
        id: String,
        /// Parameter.
        name: String,
        /// Value given.
        value: f64,
        /// Lower bound.
        lower: f64,
        /// Upper bound.
        upper: f64,
    },
    /// A parameter with no neutral value was not given.
    #[error("effect `{id}` needs a value for `{name}` (it has no neutral value): write {id}:{name}=VALUE")]
    Missing {
        /// Effect id.
        id: String,
        /// Parameter.
        name: String,
    },
    /// An `--effect` argument that does not parse.
    #[error("cannot read effect `{text}`: {reason}")]
    Syntax {
        /// The argument.
        text: String,
        /// Why.
        reason: String,
    },
    /// A user formula failed during a prediction.
    #[error("{0}")]
    Formula(String),
    /// A user effects file is wrong.
    #[error("{0}")]
    UserFile(String),
}

/// A physical effect: parameters, hooks and explanation.
///
/// Hook methods get the parameter values in the order of [`Effect::params`]; the defaults do
/// nothing, so an effect implements only the hooks it lists in [`Effect::hooks`].
pub trait Effect: Send + Sync + std::fmt::Debug {
    /// Identifier (`pitch-offset`).
    fn id(&self) -> &str;
    /// Parameters, in order.
    fn params(&self) -> &[Param];
    /// The hooks it acts through.
    fn hooks(&self) -> &[Hook];
    /// The physics, in a sentence or two.
    fn explanation(&self) -> &str;
    /// More start vectors for the fit beyond the parameters' `start` (effects whose response
    /// is flat at their start, such as a drag-rise Mach number above every local Mach number).
    fn extra_starts(&self) -> Vec<Vec<f64>> {
        Vec::new()
    }
    /// Measurement hook: change the point (true RPM, true air).
    fn measurement(&self, _p: &[f64], _point: &mut PointState) {}
    /// Geometry hook: change one station.
    fn geometry(&self, _p: &[f64], _point: &PointState, _geom: &mut StationGeom) {}
    /// Inflow hook: change the solver's options.
    fn inflow(&self, _p: &[f64], _point: &PointState, _rotor: &Rotor, _opts: &mut SolverOptions) {}
    /// Section hook: change the lift at a state (`inner` is the unmodified section).
    fn lift(
        &self,
        _p: &[f64],
        _ctx: &SectionCtx,
        _inner: &dyn propbet_bemt::SectionAero,
        _state: (f64, f64, f64),
        base: LiftEval,
    ) -> Result<LiftEval, EffectError> {
        Ok(base)
    }
    /// Section hook: change the drag at a converged state.
    fn drag(
        &self,
        _p: &[f64],
        _ctx: &SectionCtx,
        _inner: &dyn propbet_bemt::SectionAero,
        _input: &DragInput,
        cd: f64,
    ) -> Result<f64, EffectError> {
        Ok(cd)
    }
    /// Loads hook: change thrust and torque (`result` is the solver's, before any load hook).
    fn loads(
        &self,
        _p: &[f64],
        _point: &PointState,
        _result: &PointResult,
        _loads: &mut Loads,
    ) -> Result<(), EffectError> {
        Ok(())
    }
    /// Whether it acts through a hook.
    fn has(&self, hook: Hook) -> bool {
        self.hooks().contains(&hook)
    }
}

/// An effect with parameter values.
#[derive(Debug, Clone)]
pub struct Active {
    /// The effect.
    pub effect: Arc<dyn Effect>,
    /// Its parameter values, in the order of [`Effect::params`].
    pub values: Vec<f64>,
}

impl Active {
    /// "pitch-offset:deg=1.2".
    pub fn describe(&self) -> String {
        let params: Vec<String> = self
            .effect
            .params()
            .iter()
            .zip(&self.values)
            .map(|(p, v)| format!("{}={}", p.name, fmt_value(*v)))
            .collect();
        if params.is_empty() {
            self.effect.id().to_string()
        } else {
            format!("{}:{}", self.effect.id(), params.join(","))
        }
    }
}

/// A value with four significant digits.
pub fn fmt_value(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.abs() >= 1e-3 && v.abs() < 1e5 {
        let digits = (3 - v.abs().log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.digits$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        format!("{v:.3e}")
    }
}

/// The model's prediction at one point with effects applied.
#[derive(Debug, Clone)]
pub struct Prediction {
    /// Thrust and torque as the stand reads them.
    pub loads: Loads,
    /// The solver's result (before the load hooks).
    pub result: PointResult,
    /// The point after the measurement hooks.
    pub point: PointState,
}

/// Effects applied together, in order.
#[derive(Debug, Clone, Default)]
pub struct Stack {
    /// The effects.
    pub active: Vec<Active>,
}

impl Stack {
    /// No effect: the baseline model.
    pub fn baseline() -> Self {
        Self::default()
    }

    /// True when there is no effect.
    pub fn is_empty(&self) -> bool {
        self.active.is_empty()
    }

    fn with(&self, hook: Hook) -> impl Iterator<Item = &Active> {
        self.active.iter().filter(move |a| a.effect.has(hook))
    }

    /// Solves one operating point with every effect applied. `op` is the logged point,
    /// `diameter` the propeller diameter the coefficients use.
    pub fn predict(
        &self,
        rotor: &Rotor,
        opts: &SolverOptions,
        fluid: &Fluid,
        diameter: f64,
        op: OperatingPoint,
    ) -> Result<Prediction, EffectError> {
        let mut point = PointState {
            omega: op.omega,
            v: op.v,
            fluid: *fluid,
            tip_radius: rotor.tip_radius,
            blades: rotor.blades,
            diameter,
        };
        for a in self.with(Hook::Measurement) {
            a.effect.measurement(&a.values, &mut point);
        }
        let geometry: Vec<&Active> = self.with(Hook::Geometry).collect();
        let section: Vec<Active> = self.with(Hook::Section).cloned().collect();
        let errors = Arc::new(Mutex::new(None));
        let modified;
        let solve_rotor = if geometry.is_empty() && section.is_empty() {
            rotor
        } else {
            let section = Arc::new(section);
            let mut r = rotor.clone();
            for st in &mut r.stations {
                let mut g = StationGeom {
                    r: st.r,
                    x: st.r / rotor.tip_radius,
                    chord: st.chord,
                    beta: st.beta,
                };
                for a in &geometry {
                    a.effect.geometry(&a.values, &point, &mut g);
                }
                st.chord = g.chord.max(0.0);
                st.beta = g.beta;
                if !section.is_empty() {
                    st.aero = Arc::new(section::Modified {
                        inner: st.aero.clone(),
                        ctx: SectionCtx { geom: g, point },
                        effects: section.clone(),
                        errors: errors.clone(),
                    });
                }
            }
            modified = r;
            &modified
        };
        let mut o = *opts;
        for a in self.with(Hook::Inflow) {
            a.effect.inflow(&a.values, &point, rotor, &mut o);
        }
        let result = Solver::new(solve_rotor, &point.fluid, &o).solve(OperatingPoint {
            v: point.v,
            omega: point.omega,
        });
        if let Some(e) = errors.lock().map(|mut g| g.take()).unwrap_or(None) {
            return Err(e);
        }
        let mut loads = Loads {
            thrust: result.thrust,
            torque: result.torque,
        };
        for a in self.with(Hook::Loads) {
            a.effect.loads(&a.values, &point, &result, &mut loads)?;
        }
        if !(loads.thrust.is_finite() && loads.torque.is_finite()) {
            return Err(EffectError::Formula(format!(
                "the effects {} give a non-finite load at {:.0} rpm, V = {:.2} m/s",
                self.describe(),
                propbet_units::omega_to_rpm(op.omega),
                op.v
            )));
        }
        Ok(Prediction { loads, result, point })
    }

    /// "pitch-offset:deg=1.2 + torque-tare:q0=0.002,q1=2e-6", or "baseline".
    pub fn describe(&self) -> String {
        if self.active.is_empty() {
            "baseline".into()
        } else {
            self.active.iter().map(Active::describe).collect::<Vec<_>>().join(" + ")
        }
    }
}
