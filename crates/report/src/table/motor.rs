//! `propbet motor fit`'s steps as a table.

use super::{columns, Error, Num};

/// A fitted step as a row.
#[derive(serde::Serialize)]
struct StepRow<'a> {
    step: &'a str,
    rpm: Num,
    torque_nm: Num,
    volts: Num,
    amps: Num,
    esc_us: Num,
    amps_held_out: Num,
}

/// The fitted steps: speed, torque, voltage, current, ESC command and the current predicted
/// with the step left out.
pub fn steps(f: &propbet_pipeline::stages::FittedMotor) -> Result<columns::Table, Error> {
    let rows = f.points.iter().map(|(step, p, held)| StepRow {
        step,
        rpm: propbet_units::omega_to_rpm(p.omega).into(),
        torque_nm: p.torque.into(),
        volts: p.volts.into(),
        amps: p.amps.into(),
        esc_us: p.esc.into(),
        amps_held_out: (*held).into(),
    });
    Ok(columns::table(rows)?)
}
