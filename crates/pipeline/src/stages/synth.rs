//! The synth stage (`propbet synth`): measurements the model makes with its effects hidden in
//! them and noise, in the generic, UIUC or RCbenchmark format, with the answer key.

use std::collections::BTreeMap;

use propbet_atmosphere::AirState;
use propbet_diagnose::synth::{self, Plan};
use propbet_effects::Stack;
use serde::Serialize;

use crate::{out_of_range, Error, Result};
use propbet_model::Model;

/// The format of synthetic measurements.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SynthFormat {
    /// One CSV with self-describing columns (rpm, airspeed, thrust, torque, air).
    Generic,
    /// UIUC `J CT CP eta` files, one per RPM.
    Uiuc,
    /// An RCbenchmark step log of the static points.
    Rcbenchmark,
}

impl SynthFormat {
    /// Its name on the command line and in the answer key.
    pub fn name(self) -> &'static str {
        match self {
            Self::Generic => "generic",
            Self::Uiuc => "uiuc",
            Self::Rcbenchmark => "rcbenchmark",
        }
    }
}

/// What the synth stage is asked (the model's own effects are the hidden ones).
#[derive(Debug, Clone, PartialEq)]
pub struct SynthSpec {
    /// Relative noise on thrust and torque (one standard deviation).
    pub noise: f64,
    /// The files' format.
    pub format: SynthFormat,
    /// RPMs (None: four up to a 150 m/s tip speed).
    pub rpms: Option<Vec<f64>>,
    /// Advance ratios (None: nine from 0 to 80 % of the zero-thrust J; RCbenchmark: 0 only).
    pub js: Option<Vec<f64>>,
    /// Random seed.
    pub seed: u64,
    /// The prop file, as the answer key names it.
    pub prop: String,
    /// The name stem of UIUC files.
    pub stem: String,
}

/// Parses `--noise`: `1%` or `0.01`, below 50 %.
pub fn parse_noise(s: &str) -> Result<f64> {
    let t = s.trim();
    let v = match t.strip_suffix('%') {
        Some(p) => p.trim().parse::<f64>().map(|x| x / 100.0),
        None => t.parse::<f64>(),
    };
    let Ok(v) = v else {
        return Err(Error::value("--noise", s, "not a number (write 1% or 0.01)"));
    };
    if !(0.0..0.5).contains(&v) {
        return Err(Error::value("--noise", s, "must be between 0 and 50 %"));
    }
    Ok(v)
}

/// The answer key of synthetic measurements (its fields in the order JSON objects sort them).
#[derive(Debug, Clone, Serialize)]
pub struct AnswerKey {
    /// Each hidden effect's parameters, by effect id ("none": no effect).
    pub effects: BTreeMap<String, BTreeMap<String, f64>>,
    /// The files' format.
    pub format: &'static str,
    /// Always "propbet synth".
    pub made_by: &'static str,
    /// Relative noise on thrust and torque.
    pub noise: f64,
    /// The prop file.
    pub prop: String,
    /// The air density the loads were made in [kg/m^3].
    pub rho_true: f64,
    /// Random seed.
    pub seed: u64,
}

/// The text of synthetic measurements: one file (generic, RCbenchmark) or one per RPM, named
/// (UIUC).
#[derive(Debug)]
pub enum SynthFiles {
    /// The one file's text.
    One(String),
    /// (file name, text) of each.
    Named(Vec<(String, String)>),
}

/// Synthetic measurements: the files, the answer key, and the plan they were made on.
#[derive(Debug)]
pub struct Synthesized {
    /// The files' text.
    pub files: SynthFiles,
    /// What is hidden in them.
    pub answer: AnswerKey,
    /// The operating points' plan.
    pub plan: Plan,
    /// How many points.
    pub points: usize,
    /// The hidden effects in words.
    pub effects: String,
}

/// Makes `m`'s measurements with its effects hidden, as `spec` asks, in standard air.
pub fn synth(spec: &SynthSpec, m: &Model) -> Result<Synthesized> {
    let state = AirState::ISA;
    let fluid = state.fluid();
    // The model without the hidden effects decides the default plan.
    let base = propbet_diagnose::Model {
        rotor: &m.rotor,
        opts: m.opts,
        diameter: m.diameter,
        fixed: Stack::baseline(),
    };
    let rpms = spec.rpms.clone().unwrap_or_else(|| synth::default_rpms(m.diameter));
    if let Some(bad) = rpms.iter().find(|&&r| r.is_nan() || r <= 0.0) {
        out_of_range!("--rpm: rotation speeds must be positive, found {bad}");
    }
    let js = match (&spec.js, spec.format) {
        (Some(j), _) => j.clone(),
        (None, SynthFormat::Rcbenchmark) => vec![0.0],
        (None, _) => synth::default_js(&base, &fluid, rpms[rpms.len() / 2]),
    };
    if let Some(bad) = js.iter().find(|&&j| j < 0.0) {
        out_of_range!("--j: advance ratios must not be negative, found {bad}");
    }
    let plan = Plan {
        rpms,
        js,
        noise: spec.noise,
        seed: spec.seed,
        fluid,
        logged: (state.temperature - 273.15, state.pressure),
    };
    let points = synth::generate(&base, &m.effects, &plan)?;
    let mut effects: BTreeMap<String, BTreeMap<String, f64>> = m
        .effects
        .active
        .iter()
        .map(|a| {
            let params = a
                .effect
                .params()
                .iter()
                .zip(&a.values)
                .map(|(p, v)| (p.name.clone(), *v));
            (a.effect.id().to_string(), params.collect())
        })
        .collect();
    if effects.is_empty() {
        effects.insert("none".into(), BTreeMap::new());
    }
    let files = match spec.format {
        SynthFormat::Generic => SynthFiles::One(synth::write_generic(&points, &plan)),
        SynthFormat::Rcbenchmark => SynthFiles::One(synth::write_rcbenchmark(&points, &plan)),
        SynthFormat::Uiuc => SynthFiles::Named(synth::write_uiuc(&points, &plan, m.diameter, &spec.stem)),
    };
    Ok(Synthesized {
        files,
        answer: AnswerKey {
            effects,
            format: spec.format.name(),
            made_by: "propbet synth",
            noise: spec.noise,
            prop: spec.prop.clone(),
            rho_true: fluid.rho,
            seed: spec.seed,
        },
        points: points.len(),
        plan,
        effects: m.effects.describe(),
    })
}
