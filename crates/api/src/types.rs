//! The types and file formats of the crates below that propbet's functions hand out or take:
//! the API's vocabulary, as the binary and the Python package reach it (through this crate,
//! one door). Each module names the crate it comes from and holds only what its callers use.

/// The solver's results ([`propbet_bemt`]).
pub mod bemt {
    pub use propbet_bemt::{check, Convergence, Fluid, OperatingPoint, PointResult};
}

/// QPROP's files ([`propbet_qprop`]): the prop file writer, QPROP's output, APC's files.
pub mod qprop {
    pub use propbet_qprop::{apc, export, output, write_prop, RadiusReading};
}

/// The motor ([`propbet_motor`]): its files and the operating point's drivers.
pub mod motor {
    pub use propbet_motor::fit::KvSource;
    pub use propbet_motor::power::ESC_OHMS;
    pub use propbet_motor::FitKind;
    pub use propbet_motor::{
        drives, write_motor, Battery, Drive, DriveRule, Driver, Motor, MotorFile, Powered, Supply, SupplyPoint,
    };
}

/// The air ([`propbet_atmosphere`]).
pub mod atmosphere {
    pub use propbet_atmosphere::AirState;
}

/// Sections and their polars ([`propbet_polar`]).
pub mod polar {
    pub use propbet_polar::{Airfoil, Engine, Makers, Polar, QpropFit};
}

/// XFOIL's runner ([`xfoil_runner`]): its limits, and the signal handler that stops every XFOIL.
pub mod xfoil {
    pub use xfoil_runner::{interrupt, SectionSettings, DEFAULT_MAX_ITER};
}

/// Measured data ([`propbet_measure`]).
pub mod measure {
    pub use propbet_measure::{
        summarise_dropped, uiuc, DropReason, Format, Loads, MeasuredSet, Refused, RpmSource, Speed,
    };
}

/// The comparison ([`propbet_compare`]).
pub mod compare {
    pub use propbet_compare::{band, curves, electric, expected, metrics, point_air, ComparedPoint, Quantities};
}

/// Effects ([`propbet_effects`]).
pub mod effects {
    pub use propbet_effects::fmt_value;
}

/// The diagnosis ([`propbet_diagnose`]).
pub mod diagnose {
    pub use propbet_diagnose::discover::Diagnosis;
    pub use propbet_diagnose::inject;
}

/// Scans ([`propbet_geometry`]) and the vectors their options are given in.
pub mod geometry {
    pub use nalgebra::Vector3;
    pub use propbet_geometry::{cloud, scan};
}

/// Unit conversions ([`propbet_units`]).
pub mod units {
    pub use propbet_units::{
        omega_to_rev_per_s, omega_to_rpm, rpm_to_omega, rpm_to_rev_per_s, seconds_to_minutes, STANDARD_GRAVITY,
    };
}

/// The settings a user gives, each declared once, and the values as users write them
/// ([`propbet_settings`]).
pub mod settings {
    pub use propbet_settings::*;
}
