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
//! built-in effects (one file each), [`transition`] the one built from polar tables at several Ncrit
//! values when the polars have them, [`user`] the effects users write as TOML formulas. A
//! [`Stack`] is a list of effects with parameter values; [`Stack::predict`] solves one
//! operating point with all of them applied.
#![deny(missing_docs)]

pub mod builtin;
mod effect;
mod section;
pub mod spec;
mod stack;
pub mod transition;
pub mod user;

pub use effect::*;
pub use spec::{parse_spec, EffectSpec};
pub use stack::{Prediction, Stack};
