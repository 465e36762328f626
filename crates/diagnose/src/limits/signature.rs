//! Each candidate's signature: the change of the residual rows per unit of each parameter, on
//! the baseline (what the data can tell before any answer, and the verdict's rivals).

use std::sync::Arc;

use propbet_effects::{Effect, Stack};

use crate::fit::stack_at;
use crate::{Data, Model};

/// One candidate's signature: a column per parameter (change of the residual rows per unit of
/// the parameter), with its reference values and bounds.
#[derive(Debug, Clone)]
pub struct Signature {
    /// The effect.
    pub effect: Arc<dyn Effect>,
    /// The parameters' reference values.
    pub reference: Vec<f64>,
    /// Columns, one per parameter (None where the data do not respond or it cannot be solved).
    pub columns: Vec<Option<Vec<f64>>>,
}

/// The signatures of `candidates` on top of `base` (the baseline, or a stack), whose residual
/// rows are `r_base`.
pub fn signatures(
    model: &Model,
    data: &Data,
    base: &Stack,
    r_base: &[f64],
    candidates: &[Arc<dyn Effect>],
) -> Vec<Signature> {
    let all: Vec<usize> = (0..data.obs.len()).collect();
    let base_effects: Vec<Arc<dyn Effect>> = base.active.iter().map(|a| a.effect.clone()).collect();
    let base_p: Vec<f64> = base.active.iter().flat_map(|a| a.values.clone()).collect();
    candidates
        .iter()
        .filter(|c| !base.active.iter().any(|a| a.effect.id() == c.id()))
        .map(|c| {
            let params = c.params();
            let reference: Vec<f64> = params.iter().map(|p| p.neutral.unwrap_or(p.start)).collect();
            let columns = params
                .iter()
                .enumerate()
                .map(|(k, p)| {
                    let h = if reference[k] + p.scale <= p.upper {
                        p.scale
                    } else {
                        -p.scale
                    };
                    let mut v = reference.clone();
                    v[k] += h;
                    let mut effects = base_effects.clone();
                    effects.push(c.clone());
                    let mut pv = base_p.clone();
                    pv.extend(v);
                    let r = model.residuals(data, &stack_at(&effects, &pv), &all).ok()?;
                    let col: Vec<f64> = r.iter().zip(r_base).map(|(a, b)| (a - b) / h).collect();
                    col.iter().all(|x| x.is_finite()).then_some(col)
                })
                .collect();
            Signature {
                effect: c.clone(),
                reference,
                columns,
            }
        })
        .collect()
}
