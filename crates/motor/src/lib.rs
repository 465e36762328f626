//! The motor of the powertrain: QPROP 1.22's DC motor models and the operating point where
//! the motor's torque meets the propeller's.
//!
//! - [`model`]: [`Motor`], QPROP's type 1 (R, Io, Kv) and type 2 (R0, Io0, Kv, Kq, tau, Io1,
//!   Io2, R2) exactly as `MOTORQ` and `VOLTM` in `motor.f` compute them.
//! - [`file`]: QPROP's motor files, read as QPROP 1.22 reads them (a name line, a type line,
//!   one number per parameter line, `#` and `!` comments) and written so that QPROP reads them
//!   back.
//! - [`operate`]: the operating point of a motor on a propeller driven by a voltage, a
//!   current, a thrust or a speed, solved on a bracket so that a point either has its answer
//!   or says there is none.
//! - [`fit`]: R, Io and Kv fitted to a thrust stand's speed, torque, voltage and current.
//! - [`power`]: the battery and the ESC as simple stated models, so that a point can be asked
//!   at a throttle, and a hover point says its throttle and the battery's endurance.
//!
//! The crate reads no file and knows no propeller: a propeller is a function from rotation
//! rate to thrust and torque, which the pipeline builds from its solver.
#![deny(missing_docs)]

pub mod file;
pub mod fit;
pub mod model;
pub mod operate;
pub mod power;

pub use file::{parse_motor, write_motor, MotorFile, ParseMotorError};
pub use fit::{fit_motor, held_out_amps, FitError, FitKind, FitPoint, MotorFit, Sides};
pub use model::{Motor, MotorError, MotorKind};
pub use operate::{operate, Drive, OperateError, Powered, PropLoads};
pub use power::{drives, Battery, DriveRule, Driver, PowerError, Supply, SupplyPoint};
