//! Effects applied together: a [`Stack`] solves one operating point with every hook.

use std::sync::{Arc, Mutex};

use propbet_bemt::{Fluid, OperatingPoint, PointResult, Rotor, Solver, SolverOptions};

use crate::effect::*;
use crate::section;

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
