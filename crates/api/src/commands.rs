//! Each command run whole below the binary: its inputs read, its results computed, its
//! files written (the explicit step, through [`crate::files`]) and what a person is told of
//! it said to the door's [`Console`](crate::console::Console), line by line. The binary
//! parses its arguments into these functions' specs and prints; the Python package calls the
//! same functions with its own console.

pub mod compare;
pub mod diagnose;
pub mod export;
pub mod motor;
pub mod polar;
pub mod predict;
pub mod prop;
pub mod run;
pub mod scan;
pub mod synth;
pub mod validate;
