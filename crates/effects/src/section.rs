//! A station's section aerodynamics with the section hooks of a [`crate::Stack`] applied.

use std::sync::{Arc, Mutex};

use propbet_bemt::{DragInput, LiftEval, SectionAero};

use crate::effect::{Active, EffectError, SectionCtx};

/// The inner section with effects on top; the first formula error is kept for the caller
/// (the solver's interface has no error path) and the unmodified value used meanwhile.
#[derive(Debug)]
pub(crate) struct Modified {
    pub(crate) inner: Arc<dyn SectionAero>,
    pub(crate) ctx: SectionCtx,
    pub(crate) effects: Arc<Vec<Active>>,
    pub(crate) errors: Arc<Mutex<Option<EffectError>>>,
}

impl Modified {
    fn keep(&self, e: EffectError) {
        if let Ok(mut slot) = self.errors.lock() {
            slot.get_or_insert(e);
        }
    }
}

impl SectionAero for Modified {
    fn lift(&self, alpha: f64, re: f64, msq: f64) -> LiftEval {
        let mut l = self.inner.lift(alpha, re, msq);
        for a in self.effects.iter() {
            match a
                .effect
                .lift(&a.values, &self.ctx, self.inner.as_ref(), (alpha, re, msq), l)
            {
                Ok(x) => l = x,
                Err(e) => self.keep(e),
            }
        }
        l
    }

    fn drag(&self, input: &DragInput) -> f64 {
        let mut cd = self.inner.drag(input);
        for a in self.effects.iter() {
            match a.effect.drag(&a.values, &self.ctx, self.inner.as_ref(), input, cd) {
                Ok(x) => cd = x,
                Err(e) => self.keep(e),
            }
        }
        cd
    }

    fn alpha_zero_lift(&self) -> f64 {
        self.inner.alpha_zero_lift()
    }
}
