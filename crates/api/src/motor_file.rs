//! Motors: read from QPROP's files, made from their constants, written back.

use std::path::Path;

use crate::motor::{write_motor, Motor, MotorFile};
use propbet_model::{Error, Result};

/// A QPROP motor file, read as QPROP 1.22 reads it.
pub fn read_motor(path: &Path) -> Result<MotorFile> {
    propbet_pipeline::stages::read_motor(path)
}

/// A motor of QPROP's type `kind` (1 or 2) with its parameters in a motor file's order.
pub fn motor(name: &str, kind: i64, params: &[f64]) -> Result<MotorFile> {
    let motor = Motor::from_params(kind, params).map_err(|e| Error::Range(e.to_string()))?;
    Ok(MotorFile {
        name: name.to_string(),
        motor,
        params: params.to_vec(),
        labels: Vec::new(),
    })
}

/// The motor as a QPROP motor file's text.
pub fn motor_text(file: &MotorFile) -> String {
    write_motor(file, &[])
}
