//! QPROP 1.22 file formats.
//!
//! - [`propfile`]: prop files (read with every feature of the format, write so that QPROP
//!   reads them back), and their conversion to the solver's SI [`propbet_bemt::QpropBlade`].
//! - [`output`]: QPROP's printed output (summary rows and the radial block), with the printed
//!   precision of every number, so tests can compare to it digit for digit.
//!
//! Parsers take `&str` and return values; the CLI owns files.
#![deny(missing_docs)]

pub mod command;
pub mod output;
pub mod propfile;

pub use command::qprop_sequence;
pub use output::{parse_output, ParseOutputError, Printed, QpropOutput};
pub use propfile::{parse_prop, write_prop, ParsePropError, PropFile, PropRow, RadiusReading, Warning};
