//! What an effect is: its hooks, parameters, errors and the trait; an effect with values.

use std::sync::Arc;

use propbet_bemt::{DragInput, Fluid, LiftEval, PointResult, Rotor, SolverOptions};
use serde::Serialize;
use thiserror::Error;

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
    /// The range a physical cause would give (narrower than the bounds, which are what the fit
    /// may reach): a fitted value outside it makes the effect a calibration factor, one that
    /// imitates something the model misses, not found physics. None: the bounds are it.
    pub expected: Option<(f64, f64)>,
    /// Narrower bounds that hold when the measurements' provenance shows something (an optical
    /// RPM sensor: no pole count to get wrong); the diagnosis narrows the candidate to them.
    #[serde(skip)]
    pub known: Option<Known>,
}

/// What the measured files' provenance can show about them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Evidence {
    /// Every file's RPM is optical (a wind tunnel's, a thrust stand's optical probe).
    OpticalRpm,
    /// Every file gives coefficients a lab reduced with the air it measured (UIUC's).
    LabAir,
}

/// A parameter's bounds when some evidence holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Known {
    /// The evidence.
    pub given: Evidence,
    /// The bounds it sets.
    pub bounds: (f64, f64),
    /// Why, in words (appended to the parameter's description when narrowed).
    pub why: &'static str,
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
            expected: None,
            known: None,
        }
    }

    /// The same parameter with the bounds `given` sets.
    pub fn known(self, given: Evidence, bounds: (f64, f64), why: &'static str) -> Self {
        Self {
            known: Some(Known { given, bounds, why }),
            ..self
        }
    }

    /// The same parameter with its physically expected range.
    pub fn expecting(self, lower: f64, upper: f64) -> Self {
        Self {
            expected: Some((lower, upper)),
            ..self
        }
    }

    /// The physically expected range: [`Param::expected`], else the bounds.
    pub fn expected_range(&self) -> (f64, f64) {
        self.expected.unwrap_or((self.lower, self.upper))
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
    #[error("{id}:{name} = {} is outside its bounds [{lower}, {upper}]", propbet_units::show(*.value))]
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

/// An effect with narrower bounds on its parameters, the same physics otherwise: what the
/// measurement rules out (an optical RPM sensor has no pole count to get wrong, so an RPM scale
/// beyond its calibration is not on the table).
#[derive(Debug, Clone)]
pub struct Narrowed {
    inner: Arc<dyn Effect>,
    params: Vec<Param>,
}

impl Narrowed {
    /// `inner` with each named parameter's bounds replaced by `(lower, upper, why)`: the
    /// reason is appended to the parameter's description.
    pub fn new(inner: Arc<dyn Effect>, bounds: &[(&str, f64, f64, &str)]) -> Narrowed {
        let params = inner
            .params()
            .iter()
            .map(|p| match bounds.iter().find(|b| b.0 == p.name) {
                Some(&(_, lower, upper, why)) => Param {
                    lower,
                    upper,
                    start: p.start.clamp(lower, upper),
                    doc: format!("{} ({why}: {lower}-{upper})", p.doc),
                    ..p.clone()
                },
                None => p.clone(),
            })
            .collect();
        Narrowed { inner, params }
    }
}

impl Effect for Narrowed {
    fn id(&self) -> &str {
        self.inner.id()
    }
    fn params(&self) -> &[Param] {
        &self.params
    }
    fn hooks(&self) -> &[Hook] {
        self.inner.hooks()
    }
    fn explanation(&self) -> &str {
        self.inner.explanation()
    }
    fn extra_starts(&self) -> Vec<Vec<f64>> {
        self.inner.extra_starts()
    }
    fn measurement(&self, p: &[f64], point: &mut PointState) {
        self.inner.measurement(p, point);
    }
    fn geometry(&self, p: &[f64], point: &PointState, geom: &mut StationGeom) {
        self.inner.geometry(p, point, geom);
    }
    fn inflow(&self, p: &[f64], point: &PointState, rotor: &Rotor, opts: &mut SolverOptions) {
        self.inner.inflow(p, point, rotor, opts);
    }
    fn lift(
        &self,
        p: &[f64],
        ctx: &SectionCtx,
        inner: &dyn propbet_bemt::SectionAero,
        state: (f64, f64, f64),
        base: LiftEval,
    ) -> Result<LiftEval, EffectError> {
        self.inner.lift(p, ctx, inner, state, base)
    }
    fn drag(
        &self,
        p: &[f64],
        ctx: &SectionCtx,
        inner: &dyn propbet_bemt::SectionAero,
        input: &DragInput,
        cd: f64,
    ) -> Result<f64, EffectError> {
        self.inner.drag(p, ctx, inner, input, cd)
    }
    fn loads(&self, p: &[f64], point: &PointState, result: &PointResult, loads: &mut Loads) -> Result<(), EffectError> {
        self.inner.loads(p, point, result, loads)
    }
}
