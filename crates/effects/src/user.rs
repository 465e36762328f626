//! User-defined effects: a TOML file of formulas (evalexpr) on a hook, with parameters and
//! bounds, fitted and ranked like the built-ins without recompiling.
//!
//! ```toml
//! [[effect]]
//! id = "motor-windage"
//! hook = "torque"                  # beta | chord | cl | cd | thrust | torque | rpm | rho | v
//! formula = "torque + c * omega^2" # the new value of the hooked quantity
//! explanation = "Motor windage grows with the square of the speed."
//!
//! [[effect.param]]
//! name = "c"
//! unit = "N m s^2"
//! neutral = 0.0                    # optional: where the effect does nothing
//! start = 0.0                      # optional, default neutral (or the middle of the bounds)
//! lower = -1e-7
//! upper = 1e-7
//! scale = 1e-9                     # optional: typical size of a change
//! ```
//!
//! Variables (SI, angles in degrees): everywhere `rpm omega v rho mu a R D B J`; on `beta`,
//! `chord`, `cl` and `cd` also `r x chord beta` (x = r/R); on `cl` and `cd` also
//! `alpha re mach cl`, on `cd` also `cd`; on `thrust` and `torque` also `thrust torque dv`.
//! Functions: evalexpr's built-ins (`math::sin`, `math::exp`, `math::sqrt`, `min`, `max`, ...).

use std::sync::Arc;

use evalexpr::{
    build_operator_tree, error::EvalexprResultValue, Context, DefaultNumericTypes, EvalexprError, EvalexprResult, Node,
    Value,
};
use propbet_bemt::{DragInput, LiftEval, PointResult, SectionAero};
use serde::Deserialize;

use crate::{Effect, EffectError, Hook, Loads, Param, PointState, SectionCtx, StationGeom};

/// The quantity a user formula replaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Target {
    /// Blade angle [deg].
    Beta,
    /// Chord [m].
    Chord,
    /// Lift coefficient.
    Cl,
    /// Drag coefficient.
    Cd,
    /// Thrust [N].
    Thrust,
    /// Torque [N m].
    Torque,
    /// Rotation speed [rpm] (true from logged).
    Rpm,
    /// Density [kg/m^3].
    Rho,
    /// Axial speed [m/s] (true from logged: a wind tunnel's or a stand's airspeed reading).
    V,
}

impl Target {
    fn hook(self) -> Hook {
        match self {
            Target::Beta | Target::Chord => Hook::Geometry,
            Target::Cl | Target::Cd => Hook::Section,
            Target::Thrust | Target::Torque => Hook::Loads,
            Target::Rpm | Target::Rho | Target::V => Hook::Measurement,
        }
    }

    fn variables(self) -> Vec<&'static str> {
        let mut v = vec!["rpm", "omega", "v", "rho", "mu", "a", "R", "D", "B", "J"];
        match self {
            Target::Beta | Target::Chord => v.extend(["r", "x", "chord", "beta"]),
            Target::Cl => v.extend(["r", "x", "chord", "beta", "alpha", "re", "mach", "cl"]),
            Target::Cd => v.extend(["r", "x", "chord", "beta", "alpha", "re", "mach", "cl", "cd"]),
            Target::Thrust | Target::Torque => v.extend(["thrust", "torque", "dv"]),
            Target::Rpm | Target::Rho | Target::V => {}
        }
        v
    }

    fn name(self) -> &'static str {
        match self {
            Target::Beta => "beta",
            Target::Chord => "chord",
            Target::Cl => "cl",
            Target::Cd => "cd",
            Target::Thrust => "thrust",
            Target::Torque => "torque",
            Target::Rpm => "rpm",
            Target::Rho => "rho",
            Target::V => "v",
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileDef {
    effect: Vec<EffectDef>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct EffectDef {
    id: String,
    hook: Target,
    formula: String,
    #[serde(default)]
    explanation: String,
    #[serde(default)]
    param: Vec<ParamDef>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ParamDef {
    name: String,
    #[serde(default)]
    unit: String,
    neutral: Option<f64>,
    start: Option<f64>,
    lower: f64,
    upper: f64,
    scale: Option<f64>,
    #[serde(default)]
    doc: String,
    /// The physically expected range, `[lower, upper]` inside the bounds.
    expected: Option<[f64; 2]>,
}

/// A user effect: one formula on one hook.
#[derive(Debug)]
pub struct UserEffect {
    id: String,
    /// The file that defines it (errors name it).
    path: String,
    target: Target,
    formula: String,
    tree: Node<DefaultNumericTypes>,
    names: Vec<String>,
    params: Vec<Param>,
    hooks: [Hook; 1],
    explanation: String,
}

/// Variables of one evaluation, looked up by name.
struct Vars<'a> {
    names: &'a [String],
    values: Vec<Value<DefaultNumericTypes>>,
}

impl Context for Vars<'_> {
    type NumericTypes = DefaultNumericTypes;
    fn get_value(&self, identifier: &str) -> Option<&Value<DefaultNumericTypes>> {
        self.names.iter().position(|n| n == identifier).map(|i| &self.values[i])
    }
    fn call_function(&self, identifier: &str, _argument: &Value<DefaultNumericTypes>) -> EvalexprResultValue {
        Err(EvalexprError::FunctionIdentifierNotFound(identifier.to_string()))
    }
    fn are_builtin_functions_disabled(&self) -> bool {
        false
    }
    fn set_builtin_functions_disabled(&mut self, _disabled: bool) -> EvalexprResult<()> {
        Err(EvalexprError::BuiltinFunctionsCannotBeDisabled)
    }
}

/// Reads a user effects file (`path` only names it in messages).
pub fn parse(text: &str, path: &str) -> Result<Vec<Arc<dyn Effect>>, EffectError> {
    let file: FileDef = toml::from_str(text).map_err(|e| {
        let at = e
            .span()
            .map_or_else(String::new, |s| format!("{}: ", propbet_units::place(text, s.start)));
        EffectError::UserFile(format!("{path}: {at}{}", propbet_units::excerpt(e.message())))
    })?;
    let mut out: Vec<Arc<dyn Effect>> = Vec::new();
    for def in file.effect {
        let e = UserEffect::new(def, path)?;
        if out.iter().any(|o| o.id() == e.id) {
            return Err(EffectError::UserFile(format!(
                "{path}: effect `{}` is defined twice",
                e.id
            )));
        }
        out.push(Arc::new(e));
    }
    if out.is_empty() {
        return Err(EffectError::UserFile(format!("{path}: no [[effect]] defined")));
    }
    Ok(out)
}

impl UserEffect {
    fn new(def: EffectDef, path: &str) -> Result<Self, EffectError> {
        let at = format!("{path}: effect `{}`", def.id);
        let bad = |msg: String| EffectError::UserFile(format!("{at}: {msg}"));
        if def.id.is_empty() || def.id.contains([':', ',', ' ']) {
            return Err(bad("the id must be a non-empty word without ':' ',' or spaces".into()));
        }
        check_formula_size(&def.formula).map_err(bad)?;
        let tree = build_operator_tree::<DefaultNumericTypes>(&def.formula)
            .map_err(|e| bad(format!("formula `{}` does not parse: {e}", def.formula)))?;
        let mut names: Vec<String> = def.hook.variables().iter().map(|s| s.to_string()).collect();
        let mut params = Vec::new();
        for p in &def.param {
            if names.contains(&p.name) {
                return Err(bad(format!(
                    "parameter `{}` hides a variable or another parameter",
                    p.name
                )));
            }
            if !(p.lower.is_finite() && p.upper.is_finite() && p.lower < p.upper) {
                return Err(bad(format!(
                    "parameter `{}`: bounds [{}, {}] must be finite with lower < upper",
                    p.name, p.lower, p.upper
                )));
            }
            let start = p.start.or(p.neutral).unwrap_or(0.5 * (p.lower + p.upper));
            for (what, v) in [("start", Some(start)), ("neutral", p.neutral)] {
                if let Some(v) = v {
                    if !(p.lower..=p.upper).contains(&v) {
                        return Err(bad(format!(
                            "parameter `{}`: {what} {v} is outside [{}, {}]",
                            p.name, p.lower, p.upper
                        )));
                    }
                }
            }
            if let Some([a, b]) = p.expected {
                if !(p.lower <= a && a < b && b <= p.upper) {
                    return Err(bad(format!(
                        "parameter `{}`: expected range [{a}, {b}] must lie inside the bounds [{}, {}] with lower < upper",
                        p.name, p.lower, p.upper
                    )));
                }
            }
            if let Some(sc) = p.scale {
                // The fit's step: positive, and no larger than the span it steps in.
                if !(sc.is_finite() && sc > 0.0 && sc <= p.upper - p.lower) {
                    return Err(bad(format!(
                        "parameter `{}`: scale {} must be positive and at most the width of the bounds ({})",
                        p.name,
                        propbet_units::show(sc),
                        propbet_units::show(p.upper - p.lower)
                    )));
                }
            }
            names.push(p.name.clone());
            params.push(Param {
                name: p.name.clone(),
                unit: p.unit.clone(),
                neutral: p.neutral,
                start,
                lower: p.lower,
                upper: p.upper,
                scale: p.scale.unwrap_or(0.1 * (p.upper - p.lower)),
                doc: p.doc.clone(),
                expected: p.expected.map(|[a, b]| (a, b)),
                known: None,
            });
        }
        for id in tree.iter_read_variable_identifiers() {
            if !names.iter().any(|n| n == id) {
                return Err(bad(format!(
                    "formula `{}` uses `{id}`, which is neither a variable of the `{}` hook nor a parameter; \
                     available: {}",
                    def.formula,
                    def.hook.name(),
                    names.join(" ")
                )));
            }
        }
        if tree.iter_variable_identifiers().count() > tree.iter_read_variable_identifiers().count() {
            return Err(bad(format!("formula `{}` assigns to a variable", def.formula)));
        }
        let e = Self {
            explanation: if def.explanation.is_empty() {
                format!("user-defined: {} = {}", def.hook.name(), def.formula)
            } else {
                def.explanation
            },
            id: def.id,
            path: path.to_string(),
            target: def.hook,
            formula: def.formula,
            tree,
            names,
            params,
            hooks: [def.hook.hook()],
        };
        e.dry_run().map_err(|msg| bad(msg.to_string()))?;
        Ok(e)
    }

    /// Evaluates the formula at typical values with the parameters at their start and at both
    /// bounds: a formula that fails or divides by zero there is rejected when the file is read.
    fn dry_run(&self) -> Result<(), EffectError> {
        let typical = |name: &str| match name {
            "rpm" => 8000.0,
            "omega" => propbet_units::rpm_to_omega(8000.0),
            "v" => 5.0,
            "rho" => 1.225,
            "mu" => 1.81e-5,
            "a" => 340.0,
            "R" => 0.1,
            "D" => 0.2,
            "B" => 2.0,
            "J" => 0.2,
            "r" => 0.07,
            "x" => 0.7,
            "chord" => 0.02,
            "beta" => 15.0,
            "alpha" => 5.0,
            "re" => 6e4,
            "mach" => 0.2,
            "cl" => 0.6,
            "cd" => 0.03,
            "thrust" => 5.0,
            "torque" => 0.08,
            "dv" => 10.0,
            _ => 0.0,
        };
        let nv = self.target.variables().len();
        let base: Vec<f64> = self.names[..nv].iter().map(|n| typical(n)).collect();
        let mut sets = vec![self.params.iter().map(|p| p.start).collect::<Vec<_>>()];
        sets.push(self.params.iter().map(|p| p.lower).collect());
        sets.push(self.params.iter().map(|p| p.upper).collect());
        for ps in sets {
            let mut vals = base.clone();
            vals.extend(&ps);
            self.eval_values(&vals)?;
        }
        Ok(())
    }

    fn eval_values(&self, vals: &[f64]) -> Result<f64, EffectError> {
        let vars = Vars {
            names: &self.names,
            values: vals.iter().map(|&v| Value::Float(v)).collect(),
        };
        let shown = || {
            self.names
                .iter()
                .zip(vals)
                .map(|(n, v)| format!("{n}={}", crate::fmt_value(*v)))
                .collect::<Vec<_>>()
                .join(" ")
        };
        let out = self.tree.eval_number_with_context(&vars).map_err(|e| {
            EffectError::Formula(format!(
                "{}: user effect `{}`: formula `{}` fails ({e}) at {}",
                self.path,
                self.id,
                self.formula,
                shown()
            ))
        })?;
        if !out.is_finite() {
            return Err(EffectError::Formula(format!(
                "{}: user effect `{}`: formula `{}` gives {out} (a division by zero?) at {}",
                self.path,
                self.id,
                self.formula,
                shown()
            )));
        }
        Ok(out)
    }

    fn common(point: &PointState) -> [f64; 10] {
        [
            point.rpm(),
            point.omega,
            point.v,
            point.fluid.rho,
            point.fluid.mu,
            point.fluid.a,
            0.5 * point.diameter,
            point.diameter,
            point.blades,
            point.advance_ratio(),
        ]
    }

    fn eval(&self, p: &[f64], vars: &[f64]) -> Result<f64, EffectError> {
        let mut all = Vec::with_capacity(vars.len() + p.len());
        all.extend_from_slice(vars);
        all.extend_from_slice(p);
        self.eval_values(&all)
    }

    fn section_vars(ctx: &SectionCtx, alpha: f64, re: f64, mach: f64, cl: f64) -> Vec<f64> {
        let mut v = Self::common(&ctx.point).to_vec();
        let g = ctx.geom;
        v.extend([g.r, g.x, g.chord, g.beta.to_degrees(), alpha.to_degrees(), re, mach, cl]);
        v
    }
}

impl Effect for UserEffect {
    fn id(&self) -> &str {
        &self.id
    }
    fn params(&self) -> &[Param] {
        &self.params
    }
    fn hooks(&self) -> &[Hook] {
        &self.hooks
    }
    fn explanation(&self) -> &str {
        &self.explanation
    }

    fn measurement(&self, p: &[f64], point: &mut PointState) {
        // Errors surface in the loads check: a non-finite value poisons the prediction.
        let v = Self::common(point);
        let out = self.eval(p, &v).unwrap_or(f64::NAN);
        match self.target {
            Target::Rpm => point.omega = propbet_units::rpm_to_omega(out),
            Target::Rho => point.fluid.rho = out,
            Target::V => point.v = out,
            _ => {}
        }
    }

    fn geometry(&self, p: &[f64], point: &PointState, g: &mut StationGeom) {
        let mut v = Self::common(point).to_vec();
        v.extend([g.r, g.x, g.chord, g.beta.to_degrees()]);
        let out = self.eval(p, &v).unwrap_or(f64::NAN);
        match self.target {
            Target::Beta => g.beta = out.to_radians(),
            Target::Chord => g.chord = out,
            _ => {}
        }
    }

    fn lift(
        &self,
        p: &[f64],
        ctx: &SectionCtx,
        _inner: &dyn SectionAero,
        (alpha, re, msq): (f64, f64, f64),
        base: LiftEval,
    ) -> Result<LiftEval, EffectError> {
        if self.target != Target::Cl {
            return Ok(base);
        }
        let mach = msq.sqrt();
        let f = |a: f64, cl: f64| self.eval(p, &Self::section_vars(ctx, a, re, mach, cl));
        let cl = f(alpha, base.cl)?;
        let h = 1e-5;
        let dcl_dalpha =
            (f(alpha + h, base.cl + base.dcl_dalpha * h)? - f(alpha - h, base.cl - base.dcl_dalpha * h)?) / (2.0 * h);
        let dc = 1e-5 * base.cl.abs().max(1e-3);
        let f_cl = (f(alpha, base.cl + dc)? - f(alpha, base.cl - dc)?) / (2.0 * dc);
        Ok(LiftEval {
            cl,
            dcl_dalpha,
            dcl_dmsq: f_cl * base.dcl_dmsq,
            dcl_dre: f_cl * base.dcl_dre,
            stalled: base.stalled,
        })
    }

    fn drag(
        &self,
        p: &[f64],
        ctx: &SectionCtx,
        _inner: &dyn SectionAero,
        d: &DragInput,
        cd: f64,
    ) -> Result<f64, EffectError> {
        if self.target != Target::Cd {
            return Ok(cd);
        }
        let mut v = Self::section_vars(ctx, d.alpha, d.re, d.mach, d.cl);
        v.push(cd);
        self.eval(p, &v)
    }

    fn loads(&self, p: &[f64], point: &PointState, result: &PointResult, l: &mut Loads) -> Result<(), EffectError> {
        let mut v = Self::common(point).to_vec();
        v.extend([l.thrust, l.torque, result.dv]);
        let out = self.eval(p, &v)?;
        match self.target {
            Target::Thrust => l.thrust = out,
            Target::Torque => l.torque = out,
            _ => {}
        }
        Ok(())
    }
}

/// Longest formula accepted [characters]: a physical correction is a line, not a program.
pub const MAX_FORMULA_CHARS: usize = 2000;
/// Deepest nesting accepted (brackets, and runs of unary signs, which the parser also nests).
pub const MAX_FORMULA_DEPTH: usize = 64;

/// Refuses formulas whose size would take the expression parser (recursive) down a deep stack
/// or through a long parse before it says anything: too long, too deeply bracketed, too many
/// signs in a row.
fn check_formula_size(formula: &str) -> Result<(), String> {
    let n = formula.chars().count();
    if n > MAX_FORMULA_CHARS {
        return Err(format!(
            "formula of {n} characters: at most {MAX_FORMULA_CHARS} (a formula is one expression)"
        ));
    }
    let (mut depth, mut deepest, mut signs, mut most_signs) = (0usize, 0usize, 0usize, 0usize);
    for c in formula.chars() {
        match c {
            '(' => {
                depth += 1;
                deepest = deepest.max(depth);
            }
            ')' => depth = depth.saturating_sub(1),
            _ => {}
        }
        if c == '-' || c == '+' || c == '!' {
            signs += 1;
            most_signs = most_signs.max(signs);
        } else if !c.is_whitespace() {
            signs = 0;
        }
    }
    if deepest > MAX_FORMULA_DEPTH || most_signs > MAX_FORMULA_DEPTH {
        return Err(format!(
            "formula nested {} deep: at most {MAX_FORMULA_DEPTH} brackets or signs in a row",
            deepest.max(most_signs)
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formulas_too_long_or_too_deep_are_refused_before_parsing() {
        let deep = format!("{}x{}", "(".repeat(50_000), ")".repeat(50_000));
        let e = check_formula_size(&deep).unwrap_err();
        assert!(e.contains("at most 2000"), "{e}");
        let deep = format!("{}x{}", "(".repeat(100), ")".repeat(100));
        assert!(check_formula_size(&deep).unwrap_err().contains("nested 100 deep"));
        assert!(check_formula_size(&format!("{}x", "-".repeat(500)))
            .unwrap_err()
            .contains("nested 500 deep"));
        assert!(check_formula_size("beta + k * (1 - x) ^ 2 - -1").is_ok());
    }

    const GOOD: &str = r#"
[[effect]]
id = "motor-windage"
hook = "torque"
formula = "torque + c * omega^2"
[[effect.param]]
name = "c"
neutral = 0.0
lower = -1e-6
upper = 1e-6
"#;

    #[test]
    fn an_airspeed_formula_moves_the_point_and_leaves_static_alone() {
        // A wind tunnel reading its speed 1 m/s high: the true speed is the logged one minus 1,
        // a static point stays static.
        let toml = GOOD
            .replace("hook = \"torque\"", "hook = \"v\"")
            .replace("torque + c * omega^2", "if(v > 0.0, v + c, 0.0)")
            .replace("lower = -1e-6", "lower = -2.0")
            .replace("upper = 1e-6", "upper = 2.0");
        let e = parse(&toml, "u.toml").unwrap();
        assert_eq!(e[0].hooks(), &[Hook::Measurement]);
        let mut point = PointState {
            omega: 500.0,
            v: 10.0,
            fluid: propbet_bemt::Fluid::QPROP_DEFAULT,
            tip_radius: 0.125,
            blades: 2.0,
            diameter: 0.25,
        };
        e[0].measurement(&[-1.0], &mut point);
        assert_eq!((point.v, point.omega), (9.0, 500.0));
        point.v = 0.0;
        e[0].measurement(&[-1.0], &mut point);
        assert_eq!(point.v, 0.0);
    }

    #[test]
    fn reads_and_rejects() {
        let e = parse(GOOD, "u.toml").unwrap();
        assert_eq!(e[0].id(), "motor-windage");
        assert_eq!(e[0].hooks(), &[Hook::Loads]);
        let err = |t: &str| parse(t, "u.toml").unwrap_err().to_string();
        let m = err(&GOOD.replace("torque + c * omega^2", "torque + * c"));
        assert!(
            m.contains("u.toml: effect `motor-windage`") && m.contains("formula `torque + * c` fails"),
            "{m}"
        );
        let m = err(&GOOD.replace("torque + c * omega^2", "torque + c / (rpm - rpm)"));
        assert!(m.contains("division by zero"), "{m}");
        let m = err(&GOOD.replace("torque + c * omega^2", "torque + c * alpha"));
        assert!(
            m.contains("uses `alpha`, which is neither a variable of the `torque` hook"),
            "{m}"
        );
        let m = err(&GOOD.replace("hook = \"torque\"", "hook = \"lift\""));
        assert!(m.contains("u.toml"), "{m}");
        let m = err(&GOOD.replace("upper = 1e-6", "upper = -1e-6"));
        assert!(m.contains("lower < upper"), "{m}");
        let m = err(&GOOD.replace("torque + c * omega^2", "torque + c * 1/0"));
        assert!(m.contains("fails") || m.contains("division"), "{m}");
    }
}
