//! Effects applied together: a [`Stack`] solves one operating point with every hook.

use std::sync::{Arc, Mutex};

use propbet_bemt::{Fluid, OperatingPoint, PointResult, Psi, Rotor, Solver, SolverOptions};

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
        self.predict_psi(rotor, opts, fluid, diameter, op, Psi::Cold)
    }

    /// [`Stack::predict`] with each station's Newton iteration started as `psi` says
    /// ([`propbet_bemt::Psi`]: the wake angles of a nearby solve, or recorded for one).
    pub fn predict_psi(
        &self,
        rotor: &Rotor,
        opts: &SolverOptions,
        fluid: &Fluid,
        diameter: f64,
        op: OperatingPoint,
        psi: Psi<'_>,
    ) -> Result<Prediction, EffectError> {
        let mut point = PointState {
            omega: op.omega,
            v: op.v,
            fluid: *fluid,
            tip_radius: rotor.tip_radius,
            blades: rotor.blades,
            diameter,
        };
        let mut moved = Vec::new();
        for a in self.with(Hook::Measurement) {
            a.effect.measurement(&a.values, &mut point);
            moved.push(a.effect.id().to_string());
        }
        if !moved.is_empty() {
            check_point(&moved, &point)?;
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
                if !(g.chord.is_finite() && g.beta.is_finite()) {
                    let ids: Vec<&str> = geometry.iter().map(|a| a.effect.id()).collect();
                    return Err(EffectError::Formula(format!(
                        "the effects {} give the station at r = {:.4} m a chord of {} m and a twist of {} rad: \
                         not a blade (a formula that is not defined there?)",
                        ids.join(" + "),
                        st.r,
                        g.chord,
                        g.beta
                    )));
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
        let result = Solver::new(solve_rotor, &point.fluid, &o).solve_psi(
            OperatingPoint {
                v: point.v,
                omega: point.omega,
            },
            psi,
        );
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

/// Refuses an operating point the measurement hooks of `ids` moved beyond any propeller test
/// (the ranges the command line and the readers hold points to).
fn check_point(ids: &[String], p: &PointState) -> Result<(), EffectError> {
    use propbet_units::{air, operating, show};
    let bad = if !(p.omega.is_finite() && (0.0..=operating::OMEGA_MAX).contains(&p.omega)) {
        Some(format!("{} rpm", show(propbet_units::omega_to_rpm(p.omega))))
    } else if !(p.v.is_finite() && p.v.abs() <= operating::AIRSPEED_MAX) {
        Some(format!("an airspeed of {} m/s", show(p.v)))
    } else if !air::DENSITY.contains(&p.fluid.rho) {
        Some(format!("an air density of {} kg/m^3", show(p.fluid.rho)))
    } else if !air::VISCOSITY.contains(&p.fluid.mu) || !air::SOUND_SPEED.contains(&p.fluid.a) {
        Some(format!(
            "air of viscosity {} Pa s and speed of sound {} m/s",
            show(p.fluid.mu),
            show(p.fluid.a)
        ))
    } else {
        None
    };
    match bad {
        None => Ok(()),
        Some(what) => Err(EffectError::Formula(format!(
            "the effects {} move the operating point to {what}: beyond any propeller test",
            ids.join(" + ")
        ))),
    }
}
