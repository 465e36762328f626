//! QPROP 1.22 file formats.
//!
//! - [`propfile`]: prop files (read with every feature of the format, write so that QPROP
//!   reads them back), and their conversion to the solver's SI [`propbet_bemt::QpropBlade`].
//! - [`apc`]: APC's PE0 design files (stations, thickness, airfoils) and UIUC names.
//! - [`output`]: QPROP's printed output (summary rows and the radial block), with the printed
//!   precision of every number, so tests can compare to it digit for digit.
//!
//! Parsers take `&str` and return values; the CLI owns files.
#![deny(missing_docs)]

pub mod apc;
pub mod command;
pub mod export;
pub mod output;
pub mod propfile;

pub use command::qprop_sequence;
pub use output::{parse_output, ParseOutputError, Printed, QpropOutput};
pub use propfile::{
    parse_prop, write_prop, GeometryAccuracy, ParsePropError, PropFile, PropRow, RadiusReading, Warning,
};

use propbet_bemt::QpropCoefficients;

/// The one set of generic low-Reynolds-number coefficients propbet writes where a station's
/// own are not known yet (a scan before its polars, a validation geometry, a station whose
/// polars could not be fitted): the coefficients of QPROP 1.22's example prop file for a small
/// model propeller (`../shared/reference/qprop/cam6x3`, lines 6-10, copied in
/// `props/cam6x3/cam6x3.qprop`). CL0 0.5 is a cambered section's; where the camber is known it
/// is replaced by thin-airfoil theory's (`propbet_polar::airfoil::naca4_cl0`).
pub const GENERIC: QpropCoefficients = QpropCoefficients {
    cl0: 0.5,
    cl_a: 5.8,
    cl_min: -0.3,
    cl_max: 1.2,
    cd0: 0.028,
    cd2u: 0.05,
    cd2l: 0.05,
    clcd0: 0.5,
    re_ref: 70000.0,
    re_exp: -0.7,
};
