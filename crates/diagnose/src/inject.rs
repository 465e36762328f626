//! Known effects added to real measurements, and whether the diagnosis finds them: the test of
//! the diagnosis on top of a model's own error.
//!
//! Each effect is added to the measured points as propbet's own effect defines it (the
//! `effects` crate's built-ins), its size the relative change it makes to the static loads:
//!
//! | effect | measured point becomes | parameter injected at size `s` |
//! |---|---|---|
//! | `thrust-tare` | T − k ½ρ(V + Δv)² πR², Δv = √(V² + 2T/(ρπR²)) − V of the measured T | k = s (static: s T) |
//! | `torque-tare` | Q + q0 | q0 = s × the measured static torque at the lowest RPM |
//! | `rpm-scale` | logged Ω = true Ω / f, J = V/(nD) of the logged n | f = √(1 + s) (loads f² against the logged RPM) |
//! | `density` | assumed ρ = true ρ / r (measured loads kept) | r = 1 + s |
//!
//! An injected effect is *found* when the ladder on the injected points holds it and the rise
//! of its parameter over its clean value (the same stack refitted to the clean points) is the
//! injected value within the two fits' 95 % intervals ([`score`]).

use std::f64::consts::PI;

use serde::Serialize;

use propbet_effects::{builtin, Param};

use crate::discover::Diagnosis;
use crate::fit::{fit, FittedParam};
use crate::{Data, DiagnoseError, Model, Observation};

/// An effect that can be injected: a built-in of the same id.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Injected {
    /// `thrust-tare`.
    ThrustTare,
    /// `torque-tare`.
    TorqueTare,
    /// `rpm-scale`.
    RpmScale,
    /// `density`.
    Density,
}

/// Every effect that can be injected.
pub const INJECTABLE: [Injected; 4] = [
    Injected::ThrustTare,
    Injected::TorqueTare,
    Injected::RpmScale,
    Injected::Density,
];

impl Injected {
    /// The built-in effect's id.
    pub fn id(self) -> &'static str {
        match self {
            Self::ThrustTare => "thrust-tare",
            Self::TorqueTare => "torque-tare",
            Self::RpmScale => "rpm-scale",
            Self::Density => "density",
        }
    }

    /// The built-in effect's parameter the injection sets (its first: k, q0, factor, ratio).
    fn param(self) -> &'static Param {
        let effect = builtin::all()
            .iter()
            .find(|e| e.id() == self.id())
            .expect("every injectable effect is a built-in");
        &effect.params()[0]
    }
}

/// One known effect of a given size.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Injection {
    /// The effect.
    pub effect: Injected,
    /// Relative change of the static loads (0.05: 5 %).
    pub size: f64,
}

/// Lowest J of a static point.
const STATIC_J: f64 = 0.02;

impl Injection {
    /// An injection of the built-in effect `id` (one of [`INJECTABLE`]) at `size`.
    pub fn new(id: &str, size: f64) -> Result<Self, String> {
        let Some(effect) = INJECTABLE.into_iter().find(|e| e.id() == id) else {
            let ids: Vec<&str> = INJECTABLE.iter().map(|e| e.id()).collect();
            return Err(format!("`{id}` cannot be injected: one of {}", ids.join(", ")));
        };
        if !size.is_finite() || size <= -0.5 || size == 0.0 || size > 1.0 {
            return Err(format!(
                "injected size {size}: a relative change of the loads, not zero, above -0.5 and at most 1"
            ));
        }
        Ok(Self { effect, size })
    }

    /// The effect's parameter this injection sets on `data`: k, q0 [N m], the RPM factor or
    /// the density ratio; None for a torque tare on data without a torque.
    pub fn value(&self, data: &Data) -> Option<f64> {
        let s = self.size;
        match self.effect {
            Injected::ThrustTare => Some(s),
            Injected::TorqueTare => static_torque(data).map(|q| s * q),
            Injected::RpmScale => Some((1.0 + s).sqrt()),
            Injected::Density => Some(1.0 + s),
        }
    }

    /// The parameter's name in the effect (as its fit reports it).
    pub fn param(&self) -> &'static str {
        &self.effect.param().name
    }

    /// The parameter's value that changes nothing.
    pub fn neutral(&self) -> f64 {
        self.effect.param().neutral.unwrap_or_default()
    }

    /// The parameter's value expected with the injection on top of `clean`: a tare (neutral 0)
    /// adds, a scale (neutral 1) multiplies.
    fn expected(&self, clean: f64, injected: f64) -> f64 {
        if self.neutral() == 0.0 {
            clean + injected
        } else {
            clean * injected
        }
    }

    /// The parameter's value ([`Injection::value`]) and `data` of a propeller of `diameter` [m]
    /// with the effect added to every measured point; None where it cannot be added (a torque
    /// tare without a measured torque).
    pub fn apply(&self, data: &Data, diameter: f64) -> Option<(f64, Data)> {
        let value = self.value(data)?;
        let mut out = data.clone();
        for o in &mut out.obs {
            self.apply_to(o, value, diameter);
        }
        Some((value, out))
    }

    fn apply_to(&self, o: &mut Observation, value: f64, diameter: f64) {
        match self.effect {
            Injected::ThrustTare => {
                let area = PI * 0.25 * diameter * diameter;
                let rho = o.fluid.rho;
                let vs = (o.v * o.v + 2.0 * o.thrust.max(0.0) / (rho * area)).sqrt();
                o.thrust -= value * 0.5 * rho * vs * vs * area;
            }
            Injected::TorqueTare => o.torque = o.torque.map(|q| q + value),
            Injected::RpmScale => {
                o.omega /= value;
                o.j *= value;
                o.mach_tip /= value;
            }
            Injected::Density => o.fluid.rho /= value,
        }
    }
}

/// The measured static torque at the lowest RPM (the mean of the static points in that RPM
/// group); without static points, the torque of the lowest-J point of the lowest RPM group.
pub fn static_torque(data: &Data) -> Option<f64> {
    let with_q: Vec<&Observation> = data.obs.iter().filter(|o| o.torque.is_some()).collect();
    let statics: Vec<&&Observation> = with_q.iter().filter(|o| o.j < STATIC_J).collect();
    if !statics.is_empty() {
        let low = statics.iter().map(|o| o.omega).fold(f64::INFINITY, f64::min);
        let near: Vec<f64> = statics
            .iter()
            .filter(|o| o.omega < 1.05 * low)
            .filter_map(|o| o.torque)
            .collect();
        return Some(near.iter().sum::<f64>() / near.len() as f64);
    }
    let low = with_q.iter().map(|o| o.omega).fold(f64::INFINITY, f64::min);
    with_q
        .iter()
        .filter(|o| o.omega < 1.05 * low)
        .min_by(|a, b| a.j.total_cmp(&b.j))
        .and_then(|o| o.torque)
}

/// Whether an injected effect was found, and with what size.
#[derive(Debug, Clone, Serialize)]
pub struct Finding {
    /// The injection.
    pub injection: Injection,
    /// The parameter's injected value (k, q0 [N m], factor, ratio).
    pub injected: f64,
    /// Its clean value: the injected ladder refitted to the clean points (the clean ladder's value, or
    /// its neutral one, where the injected ladder does not hold it).
    pub clean: f64,
    /// Its value in the injected ladder (None: the ladder does not hold it).
    pub fitted: Option<f64>,
    /// Half-width of the 95 % interval of the rise (the two fits' intervals combined).
    pub ci95: Option<f64>,
    /// The ladder holds the effect and its rise over the clean value is the injected change
    /// within `ci95`.
    pub found: bool,
    /// Not found, but answered as one of a group the data cannot tell apart (the verdict's
    /// [`crate::limits::AnswerKind::Group`], alike candidates included), or among a calibration
    /// factor's physical stand-ins.
    pub tied: bool,
    /// The smallest change of the injected parameter these data detect, from the injected
    /// diagnosis' limits (None: none within its bounds).
    pub limit: Option<f64>,
    /// Effects the injected verdict names as found physics that were neither injected nor in
    /// the clean ladder: wrong answers.
    pub wrong: Vec<String>,
    /// How the injection was answered.
    pub outcome: Outcome,
    /// The injected verdict's answers, one per effect of its ladder ("drag-scale: one of
    /// drag-scale, torque-tare; re-lift: below limit").
    pub answers: String,
    /// The clean ladder, as `--effect` arguments.
    pub clean_ladder: String,
    /// The injected ladder.
    pub ladder: String,
    /// In words, when not found: what the ladder answered instead.
    pub note: String,
}

/// How an injection was answered.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Outcome {
    /// Named alone with its size.
    Found,
    /// Answered as one of a group that contains it.
    Group,
    /// Said to be below the detection limit the diagnosis states, and nothing else named.
    BelowLimit,
    /// Not found, nothing wrong named.
    Missed,
    /// Another effect named as physics: neither injected nor in the clean ladder.
    Wrong,
}

impl Outcome {
    /// Its name in the tables.
    pub fn name(self) -> &'static str {
        match self {
            Self::Found => "found",
            Self::Group => "group",
            Self::BelowLimit => "below limit",
            Self::Missed => "missed",
            Self::Wrong => "wrong",
        }
    }
}

/// The value of `param` of `effect` in a fit's parameters, with its 95 % half-width.
fn value_of(params: &[FittedParam], effect: &str, param: &str) -> Option<(f64, Option<f64>)> {
    find(params, effect, param).map(|p| (p.value, p.ci95))
}

fn find<'a>(params: &'a [FittedParam], effect: &str, param: &str) -> Option<&'a FittedParam> {
    params.iter().find(|p| p.effect == effect && p.name == param)
}

/// How the injected diagnosis' verdict answers the injected `effect`: named alone (found
/// physics or a calibration factor), in a group (or among a calibration factor's physical
/// stand-ins), and the effects it names as found physics that were neither injected nor in
/// the `clean` ladder (wrong answers).
fn answered(clean: &Diagnosis, injected: &Diagnosis, effect: &str) -> (bool, bool, Vec<String>) {
    use crate::limits::AnswerKind;
    let answer = injected.verdict.answers.iter().find(|a| a.id == effect);
    let alone = answer.is_some_and(|a| matches!(a.kind, AnswerKind::Found | AnswerKind::Calibration));
    let group = injected.verdict.answers.iter().any(|a| {
        matches!(a.kind, AnswerKind::Group | AnswerKind::Calibration)
            && a.group
                .iter()
                .any(|g| g.split(crate::limits::PAIR).any(|e| e == effect))
    });
    let clean_ids: Vec<&str> = clean.final_stack.active.iter().map(|a| a.effect.id()).collect();
    let wrong = injected
        .verdict
        .physics()
        .into_iter()
        .filter(|id| *id != effect && !clean_ids.contains(id))
        .map(str::to_string)
        .collect();
    (alone, group, wrong)
}

/// Scores an injection: `clean` is the diagnosis of `data` (the measurements), `injected` that
/// of the same measurements with the effect added (`injected_value` its parameter). The clean
/// value of the parameter is the injected ladder's stack refitted to the clean measurements
/// (from the injected fit's values): the rise is then the effect's alone, whatever the other
/// effects of the stack take from the model's own error.
pub fn score(
    model: &Model,
    data: &Data,
    injection: &Injection,
    injected_value: f64,
    clean: &Diagnosis,
    injected: &Diagnosis,
) -> Result<Finding, DiagnoseError> {
    let (effect, param) = (injection.effect.id(), injection.param());
    let neutral = injection.neutral();
    let after = injected.ladder.last().and_then(|r| value_of(&r.params, effect, param));
    // Whether the clean refit's value sits on a physical bound: the rise is then not measured.
    let mut clean_on_bound = false;
    let before = match after {
        Some(_) => {
            let stack = &injected.final_stack;
            let effects: Vec<_> = stack.active.iter().map(|a| a.effect.clone()).collect();
            let start: Vec<f64> = stack.active.iter().flat_map(|a| a.values.clone()).collect();
            let params = fit(model, data, &effects, &start)?.params();
            clean_on_bound = find(&params, effect, param).is_some_and(|p| p.at_bound);
            value_of(&params, effect, param)
        }
        None => clean.ladder.last().and_then(|r| value_of(&r.params, effect, param)),
    };
    // The clean value, and the injected one on top of it.
    let clean_value = before.map_or(neutral, |b| b.0);
    let expected = injection.expected(clean_value, injected_value);
    // The fits' intervals assume independent rows; neighbouring points of a sweep leave alike
    // errors, which widens them by sqrt((1 + rho) / (1 - rho)) (rho: the injected diagnosis'
    // residual correlation between neighbours, of the load that correlates more).
    let rho = injected
        .separability
        .noise
        .neighbour_correlation
        .iter()
        .fold(0.0f64, |a, b| a.max(*b));
    let widen = ((1.0 + rho) / (1.0 - rho)).sqrt();
    let ci95 = after.and_then(|a| {
        let ci_b = before.map_or(Some(0.0), |b| b.1)?;
        Some(widen * (a.1? * a.1? + ci_b * ci_b).sqrt())
    });
    // A parameter whose interval the data cannot set is held to 10 % of the injected change.
    let tolerance = ci95.unwrap_or(0.1 * (expected - clean_value).abs());
    let found = !clean_on_bound && after.is_some_and(|a| (a.0 - expected).abs() <= tolerance.max(1e-12));
    let ladder = injected.final_effects().join(" + ");
    let note = match after {
        _ if found => String::new(),
        None => format!(
            "not in the ladder ({})",
            if ladder.is_empty() { "nothing found" } else { &ladder }
        ),
        Some(_) if clean_on_bound => {
            format!("its clean value {clean_value:.4} is on a physical bound: no rise to measure")
        }
        Some((v, _)) => format!("{param} {v:.4} where {expected:.4} ± {tolerance:.4} was injected"),
    };
    use crate::limits::AnswerKind;
    let (alone, group, wrong) = answered(clean, injected, effect);
    let found = found && alone;
    let limit = injected
        .separability
        .limits
        .iter()
        .find(|l| l.effect == effect && l.param == param)
        .and_then(|l| l.limit);
    let below = limit.is_none_or(|l| (injected_value - neutral).abs() < l);
    let outcome = if !wrong.is_empty() {
        Outcome::Wrong
    } else if found {
        Outcome::Found
    } else if group {
        Outcome::Group
    } else if below {
        Outcome::BelowLimit
    } else {
        Outcome::Missed
    };
    Ok(Finding {
        injection: injection.clone(),
        injected: injected_value,
        clean: clean_value,
        fitted: after.map(|a| a.0),
        ci95,
        found,
        tied: !found && group,
        limit,
        wrong,
        outcome,
        answers: injected
            .verdict
            .answers
            .iter()
            .map(|a| match a.kind {
                AnswerKind::Group => format!("{}: one of {}", a.id, a.group.join(", ")),
                AnswerKind::Found => format!("{}: found", a.id),
                AnswerKind::Calibration if a.group.len() > 1 => {
                    format!("{}: calibration, or one of {}", a.id, a.group[1..].join(", "))
                }
                AnswerKind::Calibration => format!("{}: calibration", a.id),
                AnswerKind::BelowLimit => format!("{}: below limit", a.id),
            })
            .collect::<Vec<_>>()
            .join("; "),
        clean_ladder: clean.final_effects().join(" + "),
        ladder,
        note,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points of a 0.25 m propeller: (rpm, V [m/s], thrust [N], torque [N m]).
    fn data(points: &[(f64, f64, f64, f64)]) -> Data {
        let obs = points
            .iter()
            .enumerate()
            .map(|(index, &(rpm, v, thrust, torque))| Observation {
                index,
                file: 0,
                label: format!("line {index}"),
                omega: propbet_units::rpm_to_omega(rpm),
                v,
                j: v / (rpm / 60.0 * 0.25),
                fluid: propbet_bemt::Fluid::QPROP_DEFAULT,
                thrust,
                torque: Some(torque),
                rpm_group: rpm as i64,
                rpm_name: format!("{rpm} rpm"),
                mach_tip: 0.2,
            })
            .collect();
        Data {
            obs,
            thrust_floor: 0.1,
            torque_floor: 0.001,
        }
    }

    #[test]
    fn each_effect_changes_the_measured_points_as_its_definition_says() {
        let d = data(&[
            (4000.0, 0.0, 4.0, 0.05),
            (6000.0, 0.0, 9.0, 0.11),
            (6000.0, 10.0, 5.0, 0.08),
        ]);
        let tare = Injection::new("thrust-tare", 0.05).unwrap().apply(&d, 0.25).unwrap().1;
        // Static: the slipstream's dynamic pressure over the disc is T / A, the tare k T.
        assert!((tare.obs[0].thrust - 0.95 * 4.0).abs() < 1e-12);
        assert!((tare.obs[1].thrust - 0.95 * 9.0).abs() < 1e-12);
        // In forward flight the slipstream's q is above T / A: more than k T.
        assert!(tare.obs[2].thrust < 0.95 * 5.0);
        assert_eq!(tare.obs[2].torque, Some(0.08), "a thrust tare leaves the torque");

        // The torque tare: 5 % of the static torque at the lowest RPM, at every point.
        let q = Injection::new("torque-tare", 0.05).unwrap();
        assert!((q.value(&d).unwrap() - 0.05 * 0.05).abs() < 1e-15);
        let t = q.apply(&d, 0.25).unwrap().1;
        for (a, b) in t.obs.iter().zip(&d.obs) {
            assert!((a.torque.unwrap() - b.torque.unwrap() - 0.0025).abs() < 1e-15);
            assert_eq!(a.thrust, b.thrust);
        }

        // The RPM scale: the loads at the true RPM, the logged one lower by f; J higher by f.
        let r = Injection::new("rpm-scale", 0.05).unwrap();
        let f = r.value(&d).unwrap();
        assert!((f * f - 1.05).abs() < 1e-12);
        let s = r.apply(&d, 0.25).unwrap().1;
        assert!((s.obs[2].omega * f - d.obs[2].omega).abs() < 1e-9);
        assert!((s.obs[2].j / f - d.obs[2].j).abs() < 1e-12);
        assert_eq!(s.obs[2].thrust, d.obs[2].thrust);

        // The density: the air assumed lighter by r, the measured loads kept.
        let rho = Injection::new("density", 0.05).unwrap().apply(&d, 0.25).unwrap().1;
        assert!((rho.obs[0].fluid.rho * 1.05 - d.obs[0].fluid.rho).abs() < 1e-12);
        assert_eq!(rho.obs[0].thrust, d.obs[0].thrust);
    }

    #[test]
    fn the_static_torque_is_that_of_the_lowest_rpm_or_the_lowest_j_without_static_points() {
        let d = data(&[
            (6000.0, 0.0, 9.0, 0.11),
            (4000.0, 0.0, 4.0, 0.05),
            (4010.0, 0.0, 4.1, 0.052),
        ]);
        assert!((static_torque(&d).unwrap() - 0.051).abs() < 1e-12);
        let sweep = data(&[
            (5000.0, 8.0, 3.0, 0.06),
            (5000.0, 4.0, 4.0, 0.07),
            (7000.0, 4.0, 8.0, 0.12),
        ]);
        assert_eq!(static_torque(&sweep), Some(0.07));
        let mut none = sweep.clone();
        none.obs.iter_mut().for_each(|o| o.torque = None);
        assert!(Injection::new("torque-tare", 0.05)
            .unwrap()
            .apply(&none, 0.25)
            .is_none());
    }

    #[test]
    fn unknown_effects_and_sizes_that_change_nothing_are_refused() {
        assert!(Injection::new("pitch-offset", 0.05)
            .unwrap_err()
            .contains("cannot be injected"));
        assert!(Injection::new("density", 0.0).is_err());
        assert!(Injection::new("density", f64::NAN).is_err());
        assert!(Injection::new("density", -0.6).is_err());
        assert!(Injection::new("density", -0.05).is_ok());
        // The parameter and its neutral value are the built-in effect's own.
        let names: Vec<(&str, f64)> = INJECTABLE
            .iter()
            .map(|&e| {
                let i = Injection { effect: e, size: 0.05 };
                (i.param(), i.neutral())
            })
            .collect();
        assert_eq!(names, [("k", 0.0), ("q0", 0.0), ("factor", 1.0), ("ratio", 1.0)]);
    }
}
