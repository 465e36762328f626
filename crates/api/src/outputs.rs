//! What each command makes, in memory: its pages, tables and figures as the files it writes
//! ([`Outputs`](crate::files::Outputs)), and what a caller reads back as data. Computed here
//! from the stages' results; the binary prints its summary and writes the files, the Python
//! package returns them.

pub mod compare;
pub mod diagnose;
pub mod measured;
pub mod motor;
pub mod predict;
pub mod props;
pub mod scan;
