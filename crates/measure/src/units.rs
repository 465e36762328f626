//! Units written in column headers and mapping files, converted once to SI.
//!
//! Conversion factors: 1 gf = 9.80665e-3 N (standard gravity, CGPM 1901); 1 lbf = 4.4482216152605 N
//! and 1 ozf = lbf/16 (international avoirdupois pound, 1959); 1 inHg = 3386.389 Pa (at 0 °C);
//! 1 psi = 6894.757 Pa; 1 mmHg = 133.322 Pa; 1 knot = 1852/3600 m/s; 1 mph = 0.44704 m/s
//! (NIST SP 811, appendix B).

use serde::Serialize;

/// What a column measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Time [s].
    Time,
    /// ESC command [µs] (kept as written: a label, not a physical quantity).
    Esc,
    /// Thrust [N].
    Thrust,
    /// Torque [N m].
    Torque,
    /// Rotation rate [rad/s].
    Rotation,
    /// Axial airspeed [m/s].
    Airspeed,
    /// Air temperature [K].
    Temperature,
    /// Air pressure [Pa].
    Pressure,
    /// Relative humidity [0..1].
    Humidity,
    /// The supply's voltage [V] (a thrust stand's power meter, upstream of the ESC).
    Voltage,
    /// The supply's current [A].
    Current,
}

impl Quantity {
    /// Name used in messages and mapping files.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Time => "time",
            Quantity::Esc => "esc",
            Quantity::Thrust => "thrust",
            Quantity::Torque => "torque",
            Quantity::Rotation => "rpm",
            Quantity::Airspeed => "airspeed",
            Quantity::Temperature => "temperature",
            Quantity::Pressure => "pressure",
            Quantity::Humidity => "humidity",
            Quantity::Voltage => "voltage",
            Quantity::Current => "current",
        }
    }

    /// The units this quantity may be written in (for error messages).
    pub fn known_units(self) -> &'static str {
        match self {
            Quantity::Time => "s, ms, min",
            Quantity::Esc => "µs, us",
            Quantity::Thrust => "N, mN, gf, kgf, lbf, ozf",
            Quantity::Torque => "N·m, N·mm, mN·m, N·cm, kgf·cm, gf·cm, ozf·in, lbf·in, lbf·ft",
            Quantity::Rotation => "rpm, rad/s, Hz",
            Quantity::Airspeed => "m/s, km/h, mph, kt, ft/s",
            Quantity::Temperature => "°C, K, °F",
            Quantity::Pressure => "Pa, hPa, mbar, kPa, bar, inHg, mmHg, psi",
            Quantity::Humidity => "%, fraction",
            Quantity::Voltage => "V, mV",
            Quantity::Current => "A, mA",
        }
    }

    /// Unit assumed when a header gives none.
    pub fn default_unit(self) -> &'static str {
        match self {
            Quantity::Time => "s",
            Quantity::Esc => "us",
            Quantity::Thrust => "N",
            Quantity::Torque => "Nm",
            Quantity::Rotation => "rpm",
            Quantity::Airspeed => "m/s",
            Quantity::Temperature => "C",
            Quantity::Pressure => "Pa",
            Quantity::Humidity => "%",
            Quantity::Voltage => "V",
            Quantity::Current => "A",
        }
    }
}

/// An affine conversion to SI: `si = value * scale + offset`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Conversion {
    /// Multiplier.
    pub scale: f64,
    /// Offset added after scaling (temperatures).
    pub offset: f64,
}

impl Conversion {
    const fn mul(scale: f64) -> Self {
        Self { scale, offset: 0.0 }
    }

    /// The SI value of `v`.
    pub fn apply(&self, v: f64) -> f64 {
        v * self.scale + self.offset
    }
}

/// Lower case, without the separators people put inside units (`N·m`, `N.m`, `N*m`, `N m`,
/// `ºC`, `°C`, `m_s`).
pub fn normalise_unit(unit: &str) -> String {
    unit.trim()
        .chars()
        .filter(|c| !matches!(c, '·' | '.' | '*' | ' ' | '-' | '_' | '°' | 'º' | '⋅' | '×'))
        .flat_map(char::to_lowercase)
        .map(|c| if c == 'µ' || c == 'μ' { 'u' } else { c })
        .collect()
}

/// The conversion of `unit` for `q`, or `None` when the unit is not one propbet knows.
pub fn conversion(q: Quantity, unit: &str) -> Option<Conversion> {
    const G0: f64 = propbet_units::STANDARD_GRAVITY;
    const LBF: f64 = 4.448_221_615_260_5;
    const INCH: f64 = 0.0254;
    let u = normalise_unit(unit);
    let u = u.as_str();
    let c = match q {
        Quantity::Time => match u {
            "s" | "sec" | "" => Conversion::mul(1.0),
            "ms" => Conversion::mul(1e-3),
            "min" => Conversion::mul(60.0),
            _ => return None,
        },
        Quantity::Esc => match u {
            "us" | "" | "µs" => Conversion::mul(1.0),
            _ => return None,
        },
        Quantity::Thrust => match u {
            "n" => Conversion::mul(1.0),
            "mn" => Conversion::mul(1e-3),
            "gf" | "g" => Conversion::mul(G0 * 1e-3),
            "kgf" | "kg" => Conversion::mul(G0),
            "lbf" | "lb" => Conversion::mul(LBF),
            "ozf" | "oz" => Conversion::mul(LBF / 16.0),
            _ => return None,
        },
        Quantity::Torque => match u {
            "nm" => Conversion::mul(1.0),
            "nmm" | "mnm" => Conversion::mul(1e-3),
            "ncm" => Conversion::mul(1e-2),
            "kgfcm" => Conversion::mul(G0 * 1e-2),
            "gfcm" => Conversion::mul(G0 * 1e-5),
            "ozfin" | "ozin" => Conversion::mul(LBF / 16.0 * INCH),
            "lbfin" | "lbin" => Conversion::mul(LBF * INCH),
            "lbfft" | "lbft" => Conversion::mul(LBF * 12.0 * INCH),
            _ => return None,
        },
        Quantity::Rotation => match u {
            "rpm" | "1/min" | "revmin" | "revs/min" => Conversion::mul(propbet_units::rpm_to_omega(1.0)),
            "rad/s" | "rads" => Conversion::mul(1.0),
            "hz" | "rps" | "rev/s" | "revs" => Conversion::mul(propbet_units::rpm_to_omega(60.0)),
            _ => return None,
        },
        Quantity::Airspeed => match u {
            "m/s" | "ms" | "mps" => Conversion::mul(1.0),
            "km/h" | "kmh" | "kph" => Conversion::mul(1.0 / 3.6),
            "mph" => Conversion::mul(0.44704),
            "kt" | "kts" | "kn" | "knots" => Conversion::mul(1852.0 / 3600.0),
            "ft/s" | "fps" | "fts" => Conversion::mul(0.3048),
            _ => return None,
        },
        Quantity::Temperature => match u {
            "c" | "degc" | "celsius" => Conversion {
                scale: 1.0,
                offset: 273.15,
            },
            "k" | "kelvin" => Conversion::mul(1.0),
            "f" | "degf" | "fahrenheit" => Conversion {
                scale: 5.0 / 9.0,
                offset: 273.15 - 32.0 * 5.0 / 9.0,
            },
            _ => return None,
        },
        Quantity::Pressure => match u {
            "pa" => Conversion::mul(1.0),
            "hpa" | "mbar" => Conversion::mul(100.0),
            "kpa" => Conversion::mul(1000.0),
            "bar" => Conversion::mul(1e5),
            "inhg" => Conversion::mul(3386.389),
            "mmhg" | "torr" => Conversion::mul(133.322),
            "psi" => Conversion::mul(6894.757),
            _ => return None,
        },
        Quantity::Humidity => match u {
            "%" | "pct" | "percent" | "rh" | "%rh" => Conversion::mul(0.01),
            "fraction" | "" | "1" => Conversion::mul(1.0),
            _ => return None,
        },
        Quantity::Voltage => match u {
            "v" => Conversion::mul(1.0),
            "mv" => Conversion::mul(1e-3),
            _ => return None,
        },
        Quantity::Current => match u {
            "a" => Conversion::mul(1.0),
            "ma" => Conversion::mul(1e-3),
            _ => return None,
        },
    };
    Some(c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn header_spellings() {
        assert_eq!(conversion(Quantity::Torque, "N·m"), conversion(Quantity::Torque, "Nm"));
        assert_eq!(conversion(Quantity::Torque, "N.m"), conversion(Quantity::Torque, "N*m"));
        assert_relative_eq!(conversion(Quantity::Thrust, "gf").unwrap().apply(1000.0), 9.80665);
        assert_relative_eq!(conversion(Quantity::Thrust, "kgf").unwrap().apply(1.0), 9.80665);
        assert_relative_eq!(conversion(Quantity::Temperature, "ºC").unwrap().apply(15.0), 288.15);
        assert_relative_eq!(
            conversion(Quantity::Temperature, "°F").unwrap().apply(59.0),
            288.15,
            epsilon = 1e-9
        );
        assert_relative_eq!(conversion(Quantity::Airspeed, "m_s").unwrap().apply(3.0), 3.0);
        assert_relative_eq!(
            conversion(Quantity::Torque, "ozf·in").unwrap().apply(1.0),
            7.061552e-3,
            epsilon = 1e-8
        );
        assert_eq!(conversion(Quantity::Esc, "µs"), Some(Conversion::mul(1.0)));
        assert!(conversion(Quantity::Thrust, "furlong").is_none());
    }
}
