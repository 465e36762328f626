//! `propbet predict --motor`: the propeller on a QPROP motor, at a voltage, a current, a
//! thrust or an RPM, one row per (driver, airspeed) point with QPROP's electrical columns.

use anyhow::Result;
use propbet_api::spec::TableFormat;

use crate::predict::PredictArgs;

impl PredictArgs {
    /// The powered stage's spec (with `--motor`).
    pub fn powered_spec(&self) -> Result<propbet_api::spec::PoweredSpec> {
        let Some(motor) = &self.motor.motor else {
            anyhow::bail!("--motor: no motor file");
        };
        let supply = self.motor.supply()?;
        Ok(propbet_api::spec::PoweredSpec {
            model: self.model.spec()?,
            motor: motor.clone(),
            drives: self.motor.drives(self.points.rpm.as_ref(), supply.as_ref())?,
            supply,
            speeds: self.points.airspeeds()?,
            air: self.air.spec()?,
            format: match self.format {
                crate::predict::Format::Csv => TableFormat::Csv,
                crate::predict::Format::Json => TableFormat::Json,
            },
            out: self.out.clone(),
            stations: self.stations.clone(),
            band: self.band,
        })
    }
}
