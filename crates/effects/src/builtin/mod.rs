//! The built-in effects: each a type in its own file (its id, parameters, hooks, explanation
//! and the hooks' code), listed once in [`all`]. The book's page of them
//! (`docs/builtin-effects.md`) is generated from [`all`] and checked by `tests/docs.rs`; adding
//! an effect is its file, its line in [`all`], and that page regenerated.

use std::f64::consts::PI;
use std::sync::{Arc, OnceLock};

use propbet_bemt::aero::{attached_lift, augment_lift, snel_fraction};
use propbet_bemt::{DragInput, LiftEval, PointResult, QpropAirfoil, Rotor, SectionAero, SolverOptions};

use crate::{Effect, EffectError, Evidence, Hook, Loads, Param, PointState, SectionCtx, StationGeom};

/// Reference Reynolds number of `re-scaling` for sections that are not QPROP's model, and of
/// `re-lift`.
const RE_SCALING_REF: f64 = 1e5;

/// Bounds of the RPM scale when every file's RPM is optical (the wide bounds hold the
/// pole-count ratios of an electrical reading, 12/14 and 14/12). An optical tachometer times
/// pulses against a quartz clock: a handheld one is specified to ±0.02 % of the reading ± 1
/// count (Ono Sokki HT-5500's data sheet), so ±1 % is fifty times that and still not a
/// miscount, which would be a factor of 2 (two reflections a turn). The bounds were once ±3 %
/// with no source; validate's held-out columns with each are in `README.md` (Validation on
/// real propellers).
pub const OPTICAL_RPM_SCALE: (f64, f64) = (0.99, 1.01);

/// Bounds of the density ratio when every file gives coefficients (UIUC's CT and CP): the lab
/// reduced its loads with the density it measured, so the ratio is only that measurement's
/// error. Density from a barometer and a thermometer (ideal gas) is good to a few tenths of a
/// percent (1 hPa is 0.1 %, 1 K 0.35 %); humidity left out makes dry-air density up to about
/// 1 % high at 30 C and 60 % RH (moist air's gas constant): ±2 % holds both with room. The
/// wide bounds (0.75-1.2) are those of a stand log whose air nobody wrote down.
pub const LAB_DENSITY_RATIO: (f64, f64) = (0.98, 1.02);

mod chord_scale;
mod compressibility;
mod density;
mod drag_scale;
mod elastic_twist;
mod hub_loss;
mod pitch_offset;
mod post_stall;
mod re_lift;
mod re_scaling;
mod rpm_scale;
mod stall_delay;
mod thrust_tare;
mod tip_loss;
mod torque_tare;

/// What a built-in effect says about itself (the [`Effect`] methods [`about!`] answers).
#[derive(Debug)]
struct About {
    id: &'static str,
    params: Vec<Param>,
    hooks: &'static [Hook],
    explanation: &'static str,
}

/// The [`Effect`] methods that read a built-in's [`About`] (its field `.0`).
macro_rules! about {
    () => {
        fn id(&self) -> &str {
            self.0.id
        }

        fn params(&self) -> &[Param] {
            &self.0.params
        }

        fn hooks(&self) -> &[Hook] {
            self.0.hooks
        }

        fn explanation(&self) -> &str {
            self.0.explanation
        }
    };
}
use about;

/// Every built-in effect, in the documented order (the diagnosis tries them in it).
pub fn all() -> &'static [Arc<dyn Effect>] {
    static ALL: OnceLock<Vec<Arc<dyn Effect>>> = OnceLock::new();
    ALL.get_or_init(|| {
        vec![
            Arc::new(tip_loss::TipLoss::new()),
            Arc::new(hub_loss::HubLoss::new()),
            Arc::new(re_scaling::ReScaling::new()),
            Arc::new(drag_scale::DragScale::new()),
            Arc::new(re_lift::ReLift::new()),
            Arc::new(compressibility::Compressibility::new()),
            Arc::new(stall_delay::StallDelay::new()),
            Arc::new(post_stall::PostStall::new()),
            Arc::new(elastic_twist::ElasticTwist::new()),
            Arc::new(pitch_offset::PitchOffset::new()),
            Arc::new(chord_scale::ChordScale::new()),
            Arc::new(density::Density::new()),
            Arc::new(rpm_scale::RpmScale::new()),
            Arc::new(thrust_tare::ThrustTare::new()),
            Arc::new(torque_tare::TorqueTare::new()),
        ]
    })
}

/// The ids of the built-in effects.
pub fn ids() -> Vec<&'static str> {
    all().iter().map(|e| e.id()).collect()
}

/// A built-in effect by id.
pub fn get(id: &str) -> Option<Arc<dyn Effect>> {
    all().iter().find(|e| e.id() == id).cloned()
}
