//! Rotor definition: blade count, tip radius and the computational stations the solver
//! integrates over, plus QPROP's discretisation of a blade table into those stations.
//!
//! Frame: stations are at radius `r` from the rotation axis; `beta` is the blade angle between
//! the chord line and the rotation plane, positive nose towards the oncoming axial flow (the
//! angle that grows with pitch). Thrust is positive along the direction the air is pushed away
//! from, i.e. opposite to the induced slipstream.

use std::sync::Arc;

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::aero::{QpropAirfoil, QpropCoefficients, SectionAero};
use crate::spline::DrelaSpline;

/// One computational blade station (midpoint-rule strip).
#[derive(Debug, Clone)]
pub struct Station {
    /// Radius of the strip's midpoint [m].
    pub r: f64,
    /// Radial width of the strip [m].
    pub dr: f64,
    /// Local chord [m].
    pub chord: f64,
    /// Blade angle to the rotation plane [rad].
    pub beta: f64,
    /// Section aerodynamics.
    pub aero: Arc<dyn SectionAero>,
}

/// A rotor ready for the solver.
#[derive(Debug, Clone)]
pub struct Rotor {
    /// Number of blades (real, as in QPROP) [-].
    pub blades: f64,
    /// Tip radius used by the tip-loss factor and the coefficients [m].
    pub tip_radius: f64,
    /// Computational stations, radius increasing.
    pub stations: Vec<Station>,
}

/// What is wrong with a rotor or blade table.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum RotorError {
    /// Fewer stations than needed.
    #[error("a blade needs at least {needed} radial stations, found {found}")]
    TooFewStations {
        /// Minimum number of stations.
        needed: usize,
        /// Stations given.
        found: usize,
    },
    /// A value is NaN or infinite.
    #[error("{what} at station {index} (r = {r} m) is not a finite number")]
    NotFinite {
        /// The quantity.
        what: &'static str,
        /// Zero-based station index.
        index: usize,
        /// Station radius [m] (may itself be the bad value).
        r: f64,
    },
    /// Radii must increase strictly.
    #[error("radii must increase: station {index} has r = {r} m after r = {prev} m")]
    NonIncreasingRadius {
        /// Zero-based station index.
        index: usize,
        /// Its radius [m].
        r: f64,
        /// The previous radius [m].
        prev: f64,
    },
    /// A negative radius.
    #[error("radius must not be negative: station {index} has r = {r} m")]
    NegativeRadius {
        /// Zero-based station index.
        index: usize,
        /// Its radius [m].
        r: f64,
    },
    /// The spline through the given stations swings far outside their values (two stations
    /// very close together make it oscillate): QPROP would solve that blade, not the file's.
    #[error(
        "the spline through the stations swings to a {what} of {value:.4} at r = {r:.5} m, while the rows give \
         {lo:.4} to {hi:.4}: the stations at r = {close_a:.5} and {close_b:.5} m lie {gap:.3} % of the span apart and make \
         it oscillate; remove one of them or space the stations out"
    )]
    Overshoot {
        /// "chord [m]" or "twist [deg]".
        what: &'static str,
        /// The interpolated value.
        value: f64,
        /// At radius [m].
        r: f64,
        /// Smallest and largest given value.
        lo: f64,
        /// Largest given value.
        hi: f64,
        /// The closest pair of given radii [m].
        close_a: f64,
        /// Its second radius [m].
        close_b: f64,
        /// Their distance in per cent of the span.
        gap: f64,
    },
    /// A negative chord.
    #[error("chord must not be negative: station {index} (r = {r} m) has chord {chord} m")]
    NegativeChord {
        /// Zero-based station index.
        index: usize,
        /// Its radius [m].
        r: f64,
        /// The chord [m].
        chord: f64,
    },
    /// Blade count not positive.
    #[error("blade count must be positive, found {0}")]
    BadBladeCount(f64),
    /// Tip radius inside the blade.
    #[error("tip radius R = {tip} m must not be less than the last station radius r = {last} m")]
    TipInsideBlade {
        /// Tip radius [m].
        tip: f64,
        /// Last station radius [m].
        last: f64,
    },
    /// A coefficient that must be positive is not.
    #[error("{what} must be positive at station {index} (r = {r} m), found {value}")]
    NotPositive {
        /// The coefficient.
        what: &'static str,
        /// Zero-based station index.
        index: usize,
        /// Station radius [m].
        r: f64,
        /// The value.
        value: f64,
    },
}

impl Rotor {
    /// Gives every station Snel's rotational augmentation with coefficient `a`
    /// ([`crate::aero::snel_fraction`] of its chord and radius, at most
    /// [`crate::aero::SNEL_MAX_FRACTION`]); `a = 0` leaves the rotor as it is.
    pub fn with_rotational_augmentation(mut self, a: f64) -> Rotor {
        if a > 0.0 {
            for s in &mut self.stations {
                let k = crate::aero::snel_fraction(a, s.chord, s.r).min(crate::aero::SNEL_MAX_FRACTION);
                s.aero = Arc::new(crate::aero::Rotational {
                    inner: s.aero.clone(),
                    k,
                });
            }
        }
        self
    }

    /// Multiplies every station's drag by `factor` (1: unchanged); lift is untouched.
    pub fn with_drag_factor(mut self, factor: f64) -> Rotor {
        if factor != 1.0 {
            for s in &mut self.stations {
                s.aero = Arc::new(crate::aero::ScaledDrag {
                    inner: s.aero.clone(),
                    factor,
                });
            }
        }
        self
    }

    /// Checks the invariants the solver relies on.
    pub fn validate(&self) -> Result<(), RotorError> {
        check_blades_and_tip(self.blades, self.tip_radius)?;
        if self.stations.is_empty() {
            return Err(RotorError::TooFewStations { needed: 1, found: 0 });
        }
        let mut prev = f64::NEG_INFINITY;
        for (i, s) in self.stations.iter().enumerate() {
            for (what, v) in [
                ("radius", s.r),
                ("strip width", s.dr),
                ("chord", s.chord),
                ("blade angle", s.beta),
            ] {
                if !v.is_finite() {
                    return Err(RotorError::NotFinite { what, index: i, r: s.r });
                }
            }
            if s.r < 0.0 {
                return Err(RotorError::NegativeRadius { index: i, r: s.r });
            }
            if s.r <= prev {
                return Err(RotorError::NonIncreasingRadius { index: i, r: s.r, prev });
            }
            if s.chord < 0.0 {
                return Err(RotorError::NegativeChord {
                    index: i,
                    r: s.r,
                    chord: s.chord,
                });
            }
            prev = s.r;
        }
        if self.tip_radius < prev && !propbet_units::same_radius(self.tip_radius, prev) {
            return Err(RotorError::TipInsideBlade {
                tip: self.tip_radius,
                last: prev,
            });
        }
        Ok(())
    }
}

fn check_blades_and_tip(blades: f64, tip: f64) -> Result<(), RotorError> {
    if !(blades.is_finite() && blades > 0.0) {
        return Err(RotorError::BadBladeCount(blades));
    }
    if !(tip.is_finite() && tip > 0.0) {
        return Err(RotorError::NotPositive {
            what: "tip radius",
            index: 0,
            r: tip,
            value: tip,
        });
    }
    Ok(())
}

/// A blade as a QPROP prop file describes it, in SI units: input stations with chord, blade
/// angle and the ten coefficients at each.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QpropBlade {
    /// Number of blades [-].
    pub blades: f64,
    /// Tip radius [m].
    pub tip_radius: f64,
    /// Input station radii [m], strictly increasing.
    pub r: Vec<f64>,
    /// Chord at each input station [m].
    pub chord: Vec<f64>,
    /// Blade angle at each input station [rad].
    pub beta: Vec<f64>,
    /// Coefficients at each input station.
    pub coeffs: Vec<QpropCoefficients>,
}

/// How to turn a [`QpropBlade`] into computational stations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Discretization {
    /// Number of equal strips between the first and last input radius (QPROP: 25).
    pub stations: usize,
    /// Use the REref interpolated at the first station for every station, as QPROP 1.22 does
    /// (its `TQCALC` passes the array, i.e. element 1, to the drag law).
    pub qprop_reref_quirk: bool,
}

impl Default for Discretization {
    fn default() -> Self {
        Self {
            stations: 25,
            qprop_reref_quirk: false,
        }
    }
}

impl QpropBlade {
    /// Checks the table: at least two stations, finite values, radii increasing and
    /// non-negative, chords non-negative, REref positive, R not inside the blade.
    pub fn validate(&self) -> Result<(), RotorError> {
        check_blades_and_tip(self.blades, self.tip_radius)?;
        let n = self.r.len();
        if n < 2 {
            return Err(RotorError::TooFewStations { needed: 2, found: n });
        }
        assert!(
            self.chord.len() == n && self.beta.len() == n && self.coeffs.len() == n,
            "blade table columns differ in length"
        );
        for i in 0..n {
            let r = self.r[i];
            let mut values = vec![("radius", r), ("chord", self.chord[i]), ("blade angle", self.beta[i])];
            values.extend(
                QpropCoefficients::NAMES
                    .iter()
                    .zip(self.coeffs[i].to_array())
                    .map(|(name, v)| (*name, v)),
            );
            for (what, v) in values {
                if !v.is_finite() {
                    return Err(RotorError::NotFinite { what, index: i, r });
                }
            }
            if r < 0.0 {
                return Err(RotorError::NegativeRadius { index: i, r });
            }
            if i > 0 && r <= self.r[i - 1] {
                return Err(RotorError::NonIncreasingRadius {
                    index: i,
                    r,
                    prev: self.r[i - 1],
                });
            }
            if self.chord[i] < 0.0 {
                return Err(RotorError::NegativeChord {
                    index: i,
                    r,
                    chord: self.chord[i],
                });
            }
            for (what, v) in [("REref", self.coeffs[i].re_ref), ("CL_a", self.coeffs[i].cl_a)] {
                if v <= 0.0 {
                    return Err(RotorError::NotPositive {
                        what,
                        index: i,
                        r,
                        value: v,
                    });
                }
            }
        }
        if self.tip_radius < self.r[n - 1] && !propbet_units::same_radius(self.tip_radius, self.r[n - 1]) {
            return Err(RotorError::TipInsideBlade {
                tip: self.tip_radius,
                last: self.r[n - 1],
            });
        }
        Ok(())
    }

    /// Refuses an interpolated `value` (of `given`, shown times `show`) more than half the
    /// given range beyond it: a spline that swings, not a blade.
    fn overshoot(&self, what: &'static str, given: &[f64], value: f64, r: f64, show: f64) -> Result<(), RotorError> {
        let lo = given.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = given.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let margin = 0.5 * (hi - lo).max(0.1 * hi.abs().max(lo.abs()));
        if value >= lo - margin && value <= hi + margin {
            return Ok(());
        }
        let (k, gap) = self
            .r
            .windows(2)
            .enumerate()
            .map(|(k, w)| (k, w[1] - w[0]))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((0, 0.0));
        let span = self.r[self.r.len() - 1] - self.r[0];
        Err(RotorError::Overshoot {
            what,
            value: value * show,
            r,
            lo: lo * show,
            hi: hi * show,
            close_a: self.r[k],
            close_b: self.r[(k + 1).min(self.r.len() - 1)],
            gap: 100.0 * gap / span,
        })
    }

    /// QPROP's discretisation: `n` stations at the midpoints of `n` equal intervals between the
    /// first and last input radius, chord, angle and every coefficient interpolated with
    /// [`DrelaSpline`]; no hub model and no extension to the tip radius.
    /// A spline that swings far outside the given chords or twists (stations very close
    /// together) is refused ([`RotorError::Overshoot`]).
    pub fn to_rotor(&self, disc: Discretization) -> Result<Rotor, RotorError> {
        self.validate()?;
        let n = disc.stations.max(1);
        let r0 = self.r[0];
        let r1 = self.r[self.r.len() - 1];
        let dr = (r1 - r0) / n as f64;
        let column = |f: &dyn Fn(usize) -> f64| -> DrelaSpline {
            let x: Vec<f64> = (0..self.r.len()).map(f).collect();
            DrelaSpline::new(&self.r, &x)
        };
        let chord = column(&|i| self.chord[i]);
        let beta = column(&|i| self.beta[i]);
        let coeff_splines: Vec<DrelaSpline> = (0..10).map(|k| column(&|i| self.coeffs[i].to_array()[k])).collect();
        let radii: Vec<f64> = (0..n)
            .map(|i| {
                let frac = (i as f64 + 0.5) / n as f64;
                r0 * (1.0 - frac) + r1 * frac
            })
            .collect();
        let reref_first = coeff_splines[8].eval(radii[0]);
        let mut stations = Vec::with_capacity(n);
        for (i, &r) in radii.iter().enumerate() {
            let mut k = [0.0; 10];
            for (slot, sp) in k.iter_mut().zip(&coeff_splines) {
                *slot = sp.eval(r);
            }
            if disc.qprop_reref_quirk {
                k[8] = reref_first;
            }
            let c = chord.eval(r);
            let b = beta.eval(r);
            self.overshoot("chord [m]", &self.chord, c, r, 1.0)?;
            self.overshoot("twist [deg]", &self.beta, b, r, 180.0 / std::f64::consts::PI)?;
            if c < 0.0 {
                return Err(RotorError::NegativeChord { index: i, r, chord: c });
            }
            if k[8] <= 0.0 {
                return Err(RotorError::NotPositive {
                    what: "interpolated REref",
                    index: i,
                    r,
                    value: k[8],
                });
            }
            stations.push(Station {
                r,
                dr,
                chord: c,
                beta: b,
                aero: Arc::new(QpropAirfoil::new(QpropCoefficients::from_array(k))),
            });
        }
        // A tip at the last row's radius but for rounding is that radius (r / R never above 1).
        let last = self.r.last().copied().unwrap_or(self.tip_radius);
        let rotor = Rotor {
            blades: self.blades,
            tip_radius: if propbet_units::same_radius(self.tip_radius, last) {
                self.tip_radius.max(last)
            } else {
                self.tip_radius
            },
            stations,
        };
        rotor.validate()?;
        Ok(rotor)
    }
}

#[cfg(test)]
mod augmentation_tests {
    use super::*;
    use crate::aero::{DragInput, LiftEval, SNEL_A, SNEL_MAX_FRACTION};

    /// A section stuck at cl 0.5: whatever rotation adds shows directly.
    #[derive(Debug)]
    struct Flat;

    impl SectionAero for Flat {
        fn lift(&self, _alpha: f64, _re: f64, _msq: f64) -> LiftEval {
            LiftEval {
                cl: 0.5,
                dcl_dalpha: 0.0,
                dcl_dmsq: 0.0,
                dcl_dre: 0.0,
                stalled: false,
            }
        }
        fn drag(&self, _input: &DragInput) -> f64 {
            0.02
        }
        fn alpha_zero_lift(&self) -> f64 {
            0.0
        }
    }

    #[test]
    fn the_base_models_augmentation_restores_at_most_half_the_deficit() {
        let station = |r: f64, chord: f64| Station {
            r,
            dr: 0.01,
            chord,
            beta: 0.3,
            aero: Arc::new(Flat),
        };
        // c/r 0.8 (Snel's 3 (c/r)^2 = 1.92: capped) and 0.1 (0.03).
        let rotor = Rotor {
            blades: 2.0,
            tip_radius: 0.2,
            stations: vec![station(0.05, 0.04), station(0.1, 0.01)],
        }
        .with_rotational_augmentation(SNEL_A);
        let alpha = 0.3;
        let deficit = 2.0 * std::f64::consts::PI * alpha - 0.5;
        let k = |s: &Station| (s.aero.lift(alpha, 5e4, 0.0).cl - 0.5) / deficit;
        assert!((k(&rotor.stations[0]) - SNEL_MAX_FRACTION).abs() < 1e-12);
        assert!((k(&rotor.stations[1]) - 0.03).abs() < 1e-12);
    }

    #[test]
    fn the_drag_factor_scales_drag_and_leaves_lift() {
        let rotor = Rotor {
            blades: 2.0,
            tip_radius: 0.2,
            stations: vec![Station {
                r: 0.1,
                dr: 0.01,
                chord: 0.02,
                beta: 0.3,
                aero: Arc::new(Flat),
            }],
        };
        let input = DragInput {
            alpha: 0.1,
            cl: 0.5,
            stalled: false,
            re: 5e4,
            mach: 0.1,
        };
        let same = rotor.clone().with_drag_factor(1.0);
        assert_eq!(same.stations[0].aero.drag(&input), 0.02);
        let scaled = rotor.with_drag_factor(1.25);
        assert!((scaled.stations[0].aero.drag(&input) - 0.025).abs() < 1e-15);
        assert_eq!(scaled.stations[0].aero.lift(0.1, 5e4, 0.0).cl, 0.5);
    }
}
