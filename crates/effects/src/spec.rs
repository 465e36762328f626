//! `--effect id[:name=value,...]` arguments and the registry they are looked up in.

use std::sync::Arc;

use crate::{builtin, Active, Effect, EffectError};

/// A parsed `--effect` argument.
#[derive(Debug, Clone, PartialEq)]
pub struct EffectSpec {
    /// Effect id.
    pub id: String,
    /// Given parameter values.
    pub values: Vec<(String, f64)>,
    /// The argument as written.
    pub text: String,
}

/// Parses `id`, `id:name=value` or `id:name=value,name=value` (also `;` between pairs).
pub fn parse_spec(text: &str) -> Result<EffectSpec, EffectError> {
    let syntax = |reason: String| EffectError::Syntax {
        text: text.to_string(),
        reason,
    };
    let (id, rest) = match text.split_once(':') {
        Some((id, rest)) => (id.trim(), Some(rest)),
        None => (text.trim(), None),
    };
    if id.is_empty() {
        return Err(syntax("no effect id before the parameters".into()));
    }
    let mut values = Vec::new();
    for pair in rest.into_iter().flat_map(|r| r.split([',', ';'])) {
        let pair = pair.trim();
        if pair.is_empty() {
            continue;
        }
        let (name, value) = pair
            .split_once('=')
            .ok_or_else(|| syntax(format!("`{pair}` is not name=value")))?;
        let v: f64 = value
            .trim()
            .parse()
            .map_err(|_| syntax(format!("`{}` is not a number", value.trim())))?;
        if !v.is_finite() {
            return Err(syntax(format!("`{}` is not a finite number", value.trim())));
        }
        values.push((name.trim().to_string(), v));
    }
    Ok(EffectSpec {
        id: id.to_string(),
        values,
        text: text.to_string(),
    })
}

/// The effects known to a run: the built-ins and any user-defined ones.
#[derive(Debug, Clone)]
pub struct Registry {
    /// Every effect, built-ins first.
    pub effects: Vec<Arc<dyn Effect>>,
}

impl Default for Registry {
    fn default() -> Self {
        Self {
            effects: builtin::all().to_vec(),
        }
    }
}

impl Registry {
    /// The built-ins plus `user` (a user effect may not reuse a built-in id).
    pub fn with_user(user: Vec<Arc<dyn Effect>>) -> Result<Self, EffectError> {
        let mut r = Self::default();
        for e in user {
            if r.get(e.id()).is_some() {
                return Err(EffectError::UserFile(format!(
                    "user effect id `{}` is already taken (built-in or defined twice)",
                    e.id()
                )));
            }
            r.effects.push(e);
        }
        Ok(r)
    }

    /// An effect by id.
    pub fn get(&self, id: &str) -> Option<Arc<dyn Effect>> {
        self.effects.iter().find(|e| e.id() == id).cloned()
    }

    /// An effect by id, or an error listing the known ids.
    pub fn require(&self, id: &str) -> Result<Arc<dyn Effect>, EffectError> {
        self.get(id).ok_or_else(|| EffectError::Unknown {
            id: id.to_string(),
            known: self.effects.iter().map(|e| e.id()).collect::<Vec<_>>().join(", "),
        })
    }

    /// The effect of a spec with its values: given ones checked against the bounds, the others
    /// at their neutral value (an error for a parameter without one).
    pub fn resolve(&self, spec: &EffectSpec) -> Result<Active, EffectError> {
        let effect = self.require(&spec.id)?;
        let params = effect.params();
        for (name, _) in &spec.values {
            if !params.iter().any(|p| &p.name == name) {
                return Err(EffectError::UnknownParam {
                    id: spec.id.clone(),
                    name: name.clone(),
                    known: params.iter().map(|p| p.name.as_str()).collect::<Vec<_>>().join(", "),
                });
            }
        }
        let mut values = Vec::with_capacity(params.len());
        for p in params {
            let v = match spec.values.iter().rev().find(|(n, _)| n == &p.name) {
                Some(&(_, v)) => v,
                None => p.neutral.ok_or_else(|| EffectError::Missing {
                    id: spec.id.clone(),
                    name: p.name.clone(),
                })?,
            };
            if v < p.lower || v > p.upper {
                return Err(EffectError::OutOfBounds {
                    id: spec.id.clone(),
                    name: p.name.clone(),
                    value: v,
                    lower: p.lower,
                    upper: p.upper,
                });
            }
            values.push(v);
        }
        Ok(Active { effect, values })
    }

    /// Selects effects by a list of ids (`all` for every one).
    pub fn select(&self, list: &[String]) -> Result<Vec<Arc<dyn Effect>>, EffectError> {
        if list.is_empty() || list.iter().any(|s| s == "all") {
            return Ok(self.effects.clone());
        }
        list.iter().map(|id| self.require(id.trim())).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_parse_and_resolve() {
        let r = Registry::default();
        let s = parse_spec("torque-tare:q0=0.002,q1=2e-6").unwrap();
        let a = r.resolve(&s).unwrap();
        assert_eq!(a.values, vec![0.002, 2e-6]);
        assert_eq!(a.describe(), "torque-tare:q0=0.002,q1=2.000e-6");
        let a = r.resolve(&parse_spec("pitch-offset").unwrap()).unwrap();
        assert_eq!(a.values, vec![0.0]);
        let e = r.resolve(&parse_spec("pitch-ofset:deg=1").unwrap()).unwrap_err();
        assert!(e.to_string().contains("unknown effect `pitch-ofset`"), "{e}");
        let e = r.resolve(&parse_spec("pitch-offset:degs=1").unwrap()).unwrap_err();
        assert!(e.to_string().contains("has no parameter `degs`; it has: deg"), "{e}");
        let e = r.resolve(&parse_spec("pitch-offset:deg=40").unwrap()).unwrap_err();
        assert!(e.to_string().contains("outside its bounds"), "{e}");
        let e = r.resolve(&parse_spec("post-stall").unwrap()).unwrap_err();
        assert!(e.to_string().contains("needs a value for `cd_max`"), "{e}");
        let e = parse_spec("pitch-offset:deg").unwrap_err();
        assert!(e.to_string().contains("not name=value"), "{e}");
        let e = parse_spec("pitch-offset:deg=abc").unwrap_err();
        assert!(e.to_string().contains("`abc` is not a number"), "{e}");
        assert_eq!(builtin::ids().len(), 15);
    }
}
