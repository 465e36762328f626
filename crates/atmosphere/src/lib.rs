//! Air properties from a measured state: density of moist air, viscosity (Sutherland) and
//! speed of sound, as the solver's [`Fluid`].
//!
//! Sources: ideal-gas mixture of dry air and water vapour (R_d = 287.058, R_v = 461.495
//! J/(kg K), ICAO Doc 7488 / CIPM-2007 simplified); saturation vapour pressure by Buck (1996),
//! $e_s = 611.21\exp[(18.678 - T_c/234.5)\,T_c/(257.14 + T_c)]$ Pa; Sutherland's law with
//! mu_ref = 1.716e-5 Pa s at 273.15 K and S = 110.4 K (White, Viscous Fluid Flow, eq. 1-36);
//! a = sqrt(1.4 R_d T) (humidity changes a by < 0.3 %, neglected).
#![deny(missing_docs)]

use propbet_bemt::Fluid;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Gas constant of dry air [J/(kg K)].
pub const R_DRY: f64 = 287.058;
/// Gas constant of water vapour [J/(kg K)].
pub const R_VAPOUR: f64 = 461.495;
/// ISA sea-level temperature [K].
pub const ISA_T: f64 = 288.15;
/// ISA sea-level pressure [Pa].
pub const ISA_P: f64 = 101_325.0;

/// A measured or assumed air state.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AirState {
    /// Static temperature [K].
    pub temperature: f64,
    /// Static pressure [Pa].
    pub pressure: f64,
    /// Relative humidity, 0..1 [-].
    pub relative_humidity: f64,
}

/// An air state outside what the formulas are meant for.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum AirStateError {
    /// Temperature outside 150..400 K.
    #[error("temperature {0} K is outside 150..400 K (is it in degrees Celsius?)")]
    Temperature(f64),
    /// Pressure outside 10..200 kPa.
    #[error("pressure {0} Pa is outside 10,000..200,000 Pa (is it in hPa or kPa?)")]
    Pressure(f64),
    /// Humidity outside 0..1.
    #[error("relative humidity {0} is outside 0..1 (is it in percent?)")]
    Humidity(f64),
}

impl AirState {
    /// ISA sea level, dry.
    pub const ISA: AirState = AirState {
        temperature: ISA_T,
        pressure: ISA_P,
        relative_humidity: 0.0,
    };

    /// A checked state.
    pub fn new(temperature: f64, pressure: f64, relative_humidity: f64) -> Result<Self, AirStateError> {
        if !propbet_units::air::TEMPERATURE.contains(&temperature) {
            return Err(AirStateError::Temperature(temperature));
        }
        if !propbet_units::air::PRESSURE.contains(&pressure) {
            return Err(AirStateError::Pressure(pressure));
        }
        if !propbet_units::air::HUMIDITY.contains(&relative_humidity) {
            return Err(AirStateError::Humidity(relative_humidity));
        }
        Ok(Self {
            temperature,
            pressure,
            relative_humidity,
        })
    }

    /// Saturation vapour pressure over water (Buck 1996) [Pa].
    pub fn saturation_pressure(&self) -> f64 {
        let tc = self.temperature - 273.15;
        611.21 * ((18.678 - tc / 234.5) * (tc / (257.14 + tc))).exp()
    }

    /// Density of moist air [kg/m^3].
    pub fn density(&self) -> f64 {
        let pv = self.relative_humidity * self.saturation_pressure();
        (self.pressure - pv) / (R_DRY * self.temperature) + pv / (R_VAPOUR * self.temperature)
    }

    /// Dynamic viscosity by Sutherland's law [Pa s].
    pub fn viscosity(&self) -> f64 {
        const MU_REF: f64 = 1.716e-5;
        const T_REF: f64 = 273.15;
        const S: f64 = 110.4;
        let t = self.temperature;
        MU_REF * (t / T_REF).powf(1.5) * (T_REF + S) / (t + S)
    }

    /// Speed of sound of dry air [m/s].
    pub fn speed_of_sound(&self) -> f64 {
        (1.4 * R_DRY * self.temperature).sqrt()
    }

    /// The solver's fluid.
    pub fn fluid(&self) -> Fluid {
        Fluid {
            rho: self.density(),
            mu: self.viscosity(),
            a: self.speed_of_sound(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn isa_sea_level() {
        // ISA sea level: rho = 1.2250 kg/m^3, a = 340.29 m/s, mu = 1.7894e-5 Pa s (ICAO 7488).
        let f = AirState::ISA.fluid();
        assert_relative_eq!(f.rho, 1.2250, epsilon = 2e-4);
        assert_relative_eq!(f.a, 340.29, epsilon = 0.01);
        assert_relative_eq!(f.mu, 1.7894e-5, max_relative = 2e-3);
    }

    #[test]
    fn humidity_lowers_density() {
        // Buck: e_s(20 C) = 2338.8 Pa (tabulated 2339 Pa).
        let s = AirState::new(293.15, 101_325.0, 1.0).unwrap();
        assert_relative_eq!(s.saturation_pressure(), 2339.0, max_relative = 1e-3);
        let dry = AirState::new(293.15, 101_325.0, 0.0).unwrap().density();
        assert!(s.density() < dry);
        // Saturated air at 20 C is about 0.9 % lighter than dry air.
        assert_relative_eq!(s.density() / dry, 0.9914, epsilon = 1e-3);
    }

    #[test]
    fn rejects_wrong_units() {
        assert_eq!(
            AirState::new(20.0, 101_325.0, 0.5),
            Err(AirStateError::Temperature(20.0))
        );
        assert_eq!(
            AirState::new(293.0, 1013.25, 0.5),
            Err(AirStateError::Pressure(1013.25))
        );
        assert_eq!(
            AirState::new(293.0, 101_325.0, 50.0),
            Err(AirStateError::Humidity(50.0))
        );
    }
}
