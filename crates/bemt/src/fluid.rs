//! The fluid the rotor works in: density, dynamic viscosity and speed of sound.

use serde::{Deserialize, Serialize};

/// Fluid properties, SI.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Fluid {
    /// Density [kg/m^3].
    pub rho: f64,
    /// Dynamic viscosity [Pa s].
    pub mu: f64,
    /// Speed of sound [m/s].
    pub a: f64,
}

impl Fluid {
    /// QPROP's defaults without a `qcon.def` (qprop.f `QDEF.INC`): 1.225, 1.78e-5, 340.
    pub const QPROP_DEFAULT: Fluid = Fluid {
        rho: 1.225,
        mu: 1.78e-5,
        a: 340.0,
    };

    /// Checks that every property is finite and positive.
    pub fn validate(&self) -> Result<(), String> {
        for (name, v) in [
            ("density", self.rho),
            ("viscosity", self.mu),
            ("speed of sound", self.a),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!("{name} must be a positive number, found {v}"));
            }
        }
        Ok(())
    }
}

impl Default for Fluid {
    fn default() -> Self {
        Self::QPROP_DEFAULT
    }
}
