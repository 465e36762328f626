//! The settings a user gives, each declared once: its command-line flag, its case-file key,
//! its default, what it may be, and its help. The binary's flags take their help and default
//! from here (`#[arg(long = settings::NCRIT.flag, help = settings::NCRIT.help, ...)]`), a case
//! file's keys and `validate`'s options are checked by the same [`Setting::check`], and the
//! binary's tests hold every command's flag and every case key to these declarations.
//!
//! [`scan`] holds a scan's settings as a user writes them; [`values`] reads what users write (lists and ranges, quantities with units, the air) into SI.
#![deny(missing_docs)]

pub mod scan;
pub mod spec;
pub mod values;

/// A value as written does not read, or a declared setting's value is outside what it allows.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A value as written does not read (a list, a unit, a quantity): `FLAG 'TEXT': PROBLEM`.
    #[error("{flag} '{text}': {problem}")]
    Value {
        /// The flag or key.
        flag: String,
        /// The value as given.
        text: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A declared setting's value is outside what it allows.
    #[error(transparent)]
    Setting(#[from] BadSetting),
    /// Settings that cannot go together, or a setting missing that another needs.
    #[error("{0}")]
    Conflict(String),
    /// A value outside what propbet can compute with (an angle XFOIL cannot be asked for, a
    /// density no air has).
    #[error("{0}")]
    Range(String),
}

impl Error {
    /// A value that does not read: `FLAG 'TEXT': PROBLEM`.
    pub fn value(flag: &str, text: &str, problem: impl std::fmt::Display) -> Self {
        Error::Value {
            flag: flag.to_string(),
            text: text.to_string(),
            problem: problem.to_string(),
        }
    }
}

/// The settings' result.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// One setting.
#[derive(Debug, Clone, Copy)]
pub struct Setting<T: 'static> {
    /// The long flag, without its dashes (`ncrit`).
    pub flag: &'static str,
    /// The case-file key as `[section] key` (empty: no key; a case cannot set it).
    pub key: &'static str,
    /// The value when none is given.
    pub default: T,
    /// What the value may be.
    pub allowed: Allowed<T>,
    /// The help the command line prints.
    pub help: &'static str,
}

/// What a setting's value may be.
#[derive(Debug, Clone, Copy)]
pub enum Allowed<T: 'static> {
    /// Between `low` (excluded when `low_open`) and `high` (included); `meaning` is the text
    /// after the value in the error (`XFOIL's transition amplification ratio, ...`).
    Between {
        /// The lowest value.
        low: T,
        /// `low` itself is refused.
        low_open: bool,
        /// The highest value.
        high: T,
        /// What the setting is and may be, in words.
        meaning: &'static str,
    },
    /// One of these names.
    OneOf(&'static [&'static str]),
    /// A text its own parser reads (a list, a range, a file).
    Text,
}

/// A wrong value of a setting.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("--{flag} {value}: {meaning}")]
pub struct BadSetting {
    /// The flag.
    pub flag: &'static str,
    /// The value as given.
    pub value: String,
    /// What it may be.
    pub meaning: String,
}

impl<T: PartialOrd + Copy + std::fmt::Display> Setting<T> {
    /// `x` if the setting allows it; else the error naming the flag, the value and the range.
    pub fn check(&self, x: T) -> Result<T, BadSetting> {
        match self.allowed {
            Allowed::Between {
                low,
                low_open,
                high,
                meaning,
            } => {
                // A NaN compares false both ways: refused.
                let above = if low_open { x > low } else { x >= low };
                if above && x <= high {
                    Ok(x)
                } else {
                    Err(self.bad(short(&x), meaning.to_string()))
                }
            }
            Allowed::OneOf(_) | Allowed::Text => Ok(x),
        }
    }
}

/// A value as a message quotes it: a number of more than 12 characters in scientific notation
/// (`1e300`, not its 301 digits).
fn short<T: std::fmt::Display>(x: &T) -> String {
    let s = x.to_string();
    match s.parse::<f64>() {
        Ok(v) if s.len() > 12 => propbet_units::show(v),
        _ => s,
    }
}

impl<T> Setting<T> {
    /// The error of a wrong value.
    pub fn bad(&self, value: String, meaning: String) -> BadSetting {
        BadSetting {
            flag: self.flag,
            value,
            meaning,
        }
    }

    /// What a number may be, in words (empty for a choice or a text).
    pub(crate) fn allowed_meaning(&self) -> &'static str {
        match self.allowed {
            Allowed::Between { meaning, .. } => meaning,
            _ => "",
        }
    }

    /// The names a choice takes (empty for a number or a text).
    pub fn names(&self) -> &'static [&'static str] {
        match self.allowed {
            Allowed::OneOf(n) => n,
            _ => &[],
        }
    }

    /// The names a choice takes, as its flag's parser (`value_parser = ENGINE.choices()`).
    pub fn choices(&self) -> clap::builder::PossibleValuesParser {
        clap::builder::PossibleValuesParser::new(self.names().iter().copied())
    }
}

impl<T> Setting<T> {
    /// The name as given, if it is one of the choice's.
    pub fn choose<'a>(&self, name: &'a str) -> Result<&'a str, BadSetting> {
        let names = self.names();
        if names.is_empty() || names.contains(&name) {
            return Ok(name);
        }
        Err(self.bad(
            format!("`{}`", propbet_bemt::units::excerpt(name)),
            format!("expected {}", names.join(" or ")),
        ))
    }
}

/// A setting as the tests and the book see it: flag, key, default as the command line
/// prints it, help.
#[derive(Debug, Clone, PartialEq)]
pub struct About {
    /// The long flag.
    pub flag: &'static str,
    /// The case key (`[section] key`; empty: none).
    pub key: &'static str,
    /// The default, written as the flag takes it.
    pub default: String,
    /// The names a choice takes.
    pub names: &'static [&'static str],
    /// What a number may be, in words (empty for a choice or a text).
    pub range: &'static str,
    /// The help.
    pub help: &'static str,
}

impl<T: std::fmt::Display> Setting<T> {
    /// The setting's description.
    pub fn about(&self) -> About {
        About {
            flag: self.flag,
            key: self.key,
            default: self.default.to_string(),
            names: self.names(),
            range: self.allowed_meaning(),
            help: self.help,
        }
    }
}

/// Transition amplification ratio of a propeller's blade polars.
///
/// 5, chosen on the six shared UIUC props (docs/studies/ncrit-tables.md: validate for Ncrit
/// 1-9): the median errors fall from 30 % (CT) at XFOIL's wind-tunnel 9 to 16 % at 5 and change
/// little below (14-17 %), while static CT's measured rise with RPM (Reynolds number) is
/// followed less and less below 5; published BEMT work on small propellers finds 5-7 best.
pub const NCRIT: Setting<f64> = Setting {
    flag: "ncrit",
    key: "[polars] ncrit",
    default: 5.0,
    allowed: Allowed::Between {
        low: 0.1,
        low_open: false,
        high: 20.0,
        meaning: "XFOIL's transition amplification ratio, from 0.1 to 20 (9: a quiet wind tunnel)",
    },
    help: "Transition amplification ratio Ncrit (default: 5 for a propeller's blades, \
           docs/studies/ncrit-tables.md; 9, XFOIL's average wind tunnel, for `polar`'s one airfoil)",
};

/// Ncrit of a single airfoil's polars (`propbet polar`): XFOIL's 9, an average wind tunnel.
pub const AIRFOIL_NCRIT: Setting<f64> = Setting {
    default: 9.0,
    key: "",
    ..NCRIT
};

/// More Ncrit values to compute every polar at, for the `transition` effect.
pub const NCRIT_EFFECT: Setting<&str> = Setting {
    flag: "ncrit-effect",
    key: "[polars] ncrit_effect",
    default: "",
    allowed: Allowed::Text,
    help: "Also compute every polar at these Ncrit values (comma-separated, e.g. `3,9`), for the \
           `transition` effect: `diagnose` fits Ncrit between the lowest and highest, `predict \
           --effect transition:ncrit=N` applies it. Each value costs as much XFOIL time again",
};

/// Forced transition of a blade's polars: the chord fraction where transition is forced on both
/// surfaces at the latest (free transition ahead of it still happens), or 1 (the trailing edge):
/// free transition by Ncrit alone, the default for a blade as for `propbet polar`'s one airfoil.
/// Free transition was chosen by cross-validation over the 35 shared APC props
/// (`docs/studies/default-by-cross-validation.md`); what a trip does:
/// `docs/studies/transition-trip.md`.
pub const TRIP: Setting<f64> = Setting {
    flag: "trip",
    key: "[polars] trip",
    default: 1.0,
    allowed: Allowed::Between {
        low: 0.0,
        low_open: true,
        high: 1.0,
        meaning:
            "`free`, or the chord fraction where transition is forced, in (0, 1] (0.05: just behind the leading edge)",
    },
    help: "Force transition at this chord fraction on both surfaces, at the latest (XFOIL's XTR), \
           or `free` (by Ncrit alone; the default, chosen by cross-validation over the shared \
           props: docs/studies/default-by-cross-validation.md)",
};

/// A trip as `--trip` takes it: `free` or the chord fraction (`values::parse_trip` reads it back).
pub fn trip_text(trip: Option<f64>) -> String {
    trip.map_or_else(|| "free".to_string(), |x| format!("{x}"))
}

/// The trip of a blade's polars when none is given: [`TRIP`]'s default as the polar stage
/// takes it (`None`: free transition).
pub fn default_trip() -> Option<f64> {
    Some(TRIP.default).filter(|x| *x < 1.0)
}

/// Angles of attack of the polar commands [deg].
pub const ALPHA: Setting<&str> = Setting {
    flag: "alpha",
    key: "[polars] alpha",
    default: "-8:16:1",
    allowed: Allowed::Text,
    help: "Angles of attack [deg]: `start:stop:step`, `start:stop/N` or a list",
};

/// Rotational augmentation of the section lift (`docs/studies/rotational-augmentation.md` has
/// the shared data with each): snel with the tabulated section model, off with QPROP's law.
pub const ROTATION: Setting<Rotation> = Setting {
    flag: "rotation",
    key: "[polars] rotation",
    default: Rotation::Snel,
    allowed: Allowed::OneOf(&["off", "snel"]),
    help: "Rotational augmentation of the section lift: `off` or `snel` (Snel's 3 (c/r)^2 of the \
           lift lost below the attached-flow line). Default: snel with tabulated polars, off with \
           QPROP's law (a prop file's coefficients, or `--section-model qprop`)",
};

/// The drag multiplier of the tabulated section model: XFOIL's 2-D polar of the smooth
/// nominal section, times this. The shared props' static figure of merit, the one error all
/// six share, comes out 11-19 % high with 1 (too little power for the thrust); 1.25 halves
/// that on every prop and takes the median CP error from 10.0 % to 7.6 %
/// (`docs/studies/drag-factor.md`, with 1, 1.1, 1.25, 1.35 and 1.5). QPROP's law is always as
/// QPROP has it (1), unless asked.
pub const DRAG_FACTOR: Setting<f64> = Setting {
    flag: "drag-factor",
    key: "[polars] drag_factor",
    default: 1.25,
    allowed: Allowed::Between {
        low: 0.0,
        low_open: true,
        high: f64::MAX,
        meaning: "the sections' drag multiplier, a positive number (1: the polars' own drag)",
    },
    help: "Every section's drag times this. Default: 1.25 with tabulated polars \
           (docs/studies/drag-factor.md), 1 with QPROP's law (a prop file's coefficients, or \
           `--section-model qprop`)",
};

/// The section model of the sweeps, comparison and diagnosis.
pub const SECTION_MODEL: Setting<&str> = Setting {
    flag: "section-model",
    key: "[polars] model",
    default: "tables",
    allowed: Allowed::OneOf(&["tables", "qprop"]),
    help: "Section model: `tables` (XFOIL's polars interpolated in alpha and Re) or `qprop` \
           (QPROP's law fitted to them, as the exported prop file holds it)",
};

/// Folds of the diagnosis's cross-validation.
pub const FOLDS: Setting<usize> = Setting {
    flag: "folds",
    key: "[measured] folds",
    default: 5,
    allowed: Allowed::Between {
        low: 2,
        low_open: false,
        high: usize::MAX,
        meaning: "at least 2",
    },
    help: "Folds of the k-fold cross-validation",
};

/// Most effects a diagnosis's ladder adds.
pub const MAX_STEPS: Setting<usize> = Setting {
    flag: "max-steps",
    key: "[measured] max_steps",
    default: 3,
    allowed: Allowed::Between {
        low: 0,
        low_open: false,
        high: usize::MAX,
        meaning: "a count of effects",
    },
    help: "Most effects the ladder adds",
};

/// The scored window of the diagnosis and validate: points below this fraction of their
/// file's measured zero-thrust J.
pub const WINDOW: Setting<f64> = Setting {
    flag: "window",
    key: "",
    default: propbet_compare::metrics::VALIDATION_J_WINDOW,
    allowed: Allowed::Between {
        low: 0.0,
        low_open: true,
        high: 2.0,
        meaning: "a fraction of the zero-thrust J in (0, 2]",
    },
    help: "Scored window: only points below this fraction of their file's measured zero-thrust J \
           are fitted and scored (near zero thrust a relative error says nothing); the same window \
           as `validate` and the report's headline",
};

/// Length unit of a scan or prop file.
pub const UNITS: Setting<&str> = Setting {
    flag: "units",
    key: "[geometry] units",
    default: "mm",
    allowed: Allowed::OneOf(&["m", "cm", "mm", "in"]),
    help: "Length unit of the file: m, cm, mm, in (default: mm for a scan, assumed, and a point \
           cloud then says so in every output; a prop file's own Rfac and Cfac)",
};

/// Stations of a scan, as r/R.
pub const STATIONS: Setting<&str> = Setting {
    flag: "stations",
    key: "[geometry] stations",
    default: "0.15:0.97/25",
    allowed: Allowed::Text,
    help: "Stations as r/R: a list, start:stop:step or start:stop/N",
};

/// Where a thrust-stand log's RPM comes from.
pub const RPM_SOURCE: Setting<&str> = Setting {
    flag: "rpm-source",
    key: "[measured] rpm_source",
    default: "",
    allowed: Allowed::OneOf(&["optical", "electrical"]),
    help: "The RPM column of thrust-stand logs: `optical` (a sensor on the prop) or `electrical` \
           (the ESC's commutation, divided by the pole pairs). Default: optical where it reads, \
           else electrical",
};

/// Rotational augmentation of the section lift (`docs/studies/rotational-augmentation.md` has
/// the shared data with each).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rotation {
    /// The 2-D sections as they are.
    Off,
    /// Snel, Houwink & Bosschers (1994): `cl + 3 (c/r)^2 (cl_attached - cl)` where a section
    /// lifts less than its attached-flow line (`propbet_bemt::aero::augment_lift`).
    Snel,
}

impl Rotation {
    /// The setting a model gets: `asked`, else [`ROTATION`]'s default with
    /// tabulated polars and
    /// off with QPROP's law.
    pub fn or_default(asked: Option<Rotation>, tables: bool) -> Rotation {
        asked.unwrap_or(if tables { ROTATION.default } else { Rotation::Off })
    }

    /// Every setting, as the command line names it.
    pub const ALL: [Rotation; 2] = [Rotation::Off, Rotation::Snel];

    /// The name the command line and a case use.
    pub fn name(self) -> &'static str {
        match self {
            Rotation::Off => "off",
            Rotation::Snel => "snel",
        }
    }

    /// The setting a name gives.
    pub fn parse(name: &str) -> Result<Rotation, BadSetting> {
        let name = ROTATION.choose(name)?;
        Ok(Rotation::ALL
            .into_iter()
            .find(|r| r.name() == name)
            .unwrap_or(Rotation::Off))
    }

    /// Snel's coefficient `a` (0: off).
    pub fn coefficient(self) -> f64 {
        match self {
            Rotation::Off => 0.0,
            Rotation::Snel => propbet_bemt::aero::SNEL_A,
        }
    }
}

impl std::fmt::Display for Rotation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The air of the measurements, overriding what their files log.
pub const AIR: Setting<&str> = Setting {
    flag: "atmosphere",
    key: "[atmosphere] air",
    default: "",
    allowed: Allowed::Text,
    help: "Air state T,P,RH of the measurements, overriding what the files log: temperature (°C unless \
           suffixed K or F), pressure (Pa unless suffixed hPa, mbar, kPa, inHg, psi), relative humidity (%). \
           Example: 22,1009hPa,40",
};

/// Air density, overriding every other source.
pub const RHO: Setting<&str> = Setting {
    flag: "rho",
    key: "[atmosphere] rho",
    default: "",
    allowed: Allowed::Text,
    help: "Air density [kg/m^3], overriding every other source: QPROP's 1.225 where no air is given, the \
           density of an air state (--temp, --atmosphere) or of the files' logged air (to reproduce a study)",
};

/// Motor poles of thrust-stand logs whose RPM is electrical.
pub const POLES: Setting<&str> = Setting {
    flag: "poles",
    key: "[measured] poles",
    default: "",
    allowed: Allowed::Text,
    help: "Motor poles of the thrust-stand logs: electrical RPM readings are multiplied by 2/N (an even \
           number, at least 2)",
};

/// The XFOIL time of one command (of one prop in `validate`) [s]: a prop's polars take a few
/// minutes; an XFOIL that never finishes a polar (each stops at 120 s) cannot hold a command
/// for longer than this.
pub const XFOIL_BUDGET: Setting<f64> = Setting {
    flag: "xfoil-budget",
    key: "",
    default: 3600.0,
    allowed: Allowed::Between {
        low: 0.0,
        low_open: true,
        high: f64::MAX,
        meaning: "a positive number of seconds",
    },
    help: "Total XFOIL time of the command (of each prop in `validate`) [s]: polars not started by then are \
           errors, a running one gives up its remaining angles (each polar has 120 s of its own at most). \
           Default 3600",
};

/// Which program makes the section polars.
pub const ENGINE: Setting<&str> = Setting {
    flag: "engine",
    key: "[polars] engine",
    default: "xfoil",
    allowed: Allowed::OneOf(&["xfoil", "neuralfoil", "auto"]),
    help: "Polar engine: `xfoil` (the XFOIL program), `neuralfoil` (NeuralFoil's networks, evaluated in \
           propbet: milliseconds a polar, no XFOIL needed) or `auto` (XFOIL, with the angles it does not \
           converge and the polars it cannot make from NeuralFoil); every point says which engine made it \
           and NeuralFoil's its confidence (polars.json, the polar table, a run's summary.json and report)",
};

/// NeuralFoil's network size.
pub const NEURALFOIL_SIZE: Setting<&str> = Setting {
    flag: "neuralfoil-size",
    key: "[polars] neuralfoil_size",
    default: propbet_neuralfoil::DEFAULT_SIZE,
    allowed: Allowed::OneOf(&propbet_neuralfoil::SIZES),
    help: "NeuralFoil's network size (with --engine neuralfoil or auto): larger is closer to XFOIL and \
           slower",
};

/// Every declared setting, for the tests that hold the flags and keys to them.
pub fn all() -> Vec<About> {
    vec![
        NCRIT.about(),
        NCRIT_EFFECT.about(),
        About {
            default: trip_text(default_trip()),
            ..TRIP.about()
        },
        ALPHA.about(),
        ROTATION.about(),
        DRAG_FACTOR.about(),
        SECTION_MODEL.about(),
        FOLDS.about(),
        MAX_STEPS.about(),
        WINDOW.about(),
        UNITS.about(),
        STATIONS.about(),
        RPM_SOURCE.about(),
        AIR.about(),
        RHO.about(),
        POLES.about(),
        XFOIL_BUDGET.about(),
        ENGINE.about(),
        NEURALFOIL_SIZE.about(),
    ]
}

/// The drag factor a model gets: `asked`, else [`DRAG_FACTOR`]'s default with tabulated polars
/// and 1 with QPROP's law.
pub fn drag_factor_or_default(asked: Option<f64>, tables: bool) -> f64 {
    asked.unwrap_or(if tables { crate::DRAG_FACTOR.default } else { 1.0 })
}

/// Checks `--ncrit-effect`'s values against the polars' own Ncrit: each an Ncrit XFOIL takes,
/// none equal to `ncrit`; returns them ascending.
pub fn check_ncrit_effect(values: &[f64], ncrit: f64) -> Result<Vec<f64>> {
    let mut v = values.to_vec();
    let each = Setting {
        flag: NCRIT_EFFECT.flag,
        ..NCRIT
    };
    for x in &v {
        each.check(*x)?;
    }
    if v.contains(&ncrit) {
        return Err(Error::Conflict(format!(
            "--ncrit-effect {ncrit}: the polars' own Ncrit; give the other values the effect may move to"
        )));
    }
    v.sort_by(f64::total_cmp);
    v.dedup();
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_outside_the_range_names_the_flag_and_the_range() {
        assert_eq!(NCRIT.check(5.0).unwrap(), 5.0);
        let e = NCRIT.check(25.0).unwrap_err().to_string();
        assert_eq!(
            e,
            "--ncrit 25: XFOIL's transition amplification ratio, from 0.1 to 20 (9: a quiet wind tunnel)"
        );
        assert!(NCRIT.check(0.0).is_err() && NCRIT.check(1e-300).is_err() && NCRIT.check(0.1).is_ok());
        let e = NCRIT.check(1e300).unwrap_err().to_string();
        assert!(e.starts_with("--ncrit 1e300: "), "a number printed short: {e}");
        assert!(NCRIT.check(f64::NAN).is_err());
        assert!(DRAG_FACTOR.check(f64::INFINITY).is_err());
        assert!(
            FOLDS.check(1).is_err() && FOLDS.check(2).is_ok(),
            "the low end is closed"
        );
        let e = SECTION_MODEL.choose("fast").unwrap_err().to_string();
        assert_eq!(e, "--section-model `fast`: expected tables or qprop");
        assert_eq!(SECTION_MODEL.choose("qprop").unwrap(), "qprop");
    }

    #[test]
    fn every_default_is_allowed_and_every_flag_and_key_is_declared_once() {
        for s in [NCRIT, AIRFOIL_NCRIT, DRAG_FACTOR, WINDOW, XFOIL_BUDGET] {
            s.check(s.default).unwrap();
        }
        for s in [FOLDS, MAX_STEPS] {
            s.check(s.default).unwrap();
        }
        for s in [SECTION_MODEL, UNITS, ENGINE, NEURALFOIL_SIZE] {
            assert!(s.names().contains(&s.default), "{}", s.flag);
        }
        assert!(ROTATION.names().contains(&ROTATION.default.name()));
        let engines: Vec<&str> = propbet_polar::Engine::ALL.iter().map(|e| e.name()).collect();
        assert_eq!(ENGINE.names(), engines.as_slice(), "the polar engines, by their names");
        assert_eq!(ENGINE.default, propbet_polar::Engine::default().name());
        TRIP.check(TRIP.default).unwrap();
        let all = all();
        for a in &all {
            assert_eq!(all.iter().filter(|b| b.flag == a.flag).count(), 1, "{}", a.flag);
            assert!(
                a.key.is_empty() || all.iter().filter(|b| b.key == a.key).count() == 1,
                "{}",
                a.key
            );
            assert!(!a.help.ends_with('.'), "clap's help reads as a phrase: {}", a.flag);
        }
    }
}
