//! propbet's tables, whole: numbers as every table prints them ([`Num`], [`push_num`]), rows as
//! CSV, the same rows as typed columns for Python ([`columns`]), and a prediction's tables
//! ([`sweep`]). The binary writes the bytes these make.

pub mod columns;
mod number;
pub mod sweep;

pub use number::{csv_rows, push_num, written, Num};
