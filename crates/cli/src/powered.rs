//! `propbet predict --motor`: the propeller on a QPROP motor, at a voltage, a current, a
//! thrust or an RPM, one row per (driver, airspeed) point with QPROP's electrical columns.

use anyhow::Result;
use propbet_api::motor::MotorFile;
use propbet_pipeline::spec::{PoweredSpec, SweepAxis, TableFormat};
use propbet_pipeline::stages::polar_omegas;
use propbet_report::table::powered::PoweredRun;

use crate::output::emit;
use crate::predict::PredictArgs;

/// `spec`'s model on `motor` (the file `spec.motor` names, read, or a motor made in memory)
/// at each driver value and airspeed, each point's stations kept when `keep_stations`; a blade
/// file's polars computed over the speeds the motor can reach.
pub fn solve(spec: &PoweredSpec, motor: &MotorFile, keep_stations: bool) -> Result<PoweredRun> {
    let supply = spec.supply.as_ref();
    let model = crate::predict::load_model_at(
        &spec.model,
        || {
            let battery = supply.map(|s| s.source(1.0).0);
            Ok((
                polar_omegas(&motor.motor, &spec.drives, battery),
                SweepAxis::V(spec.speeds.clone()),
            ))
        },
        keep_stations,
    )?;
    let fluid = spec.air.fluid()?;
    let table = propbet_pipeline::stages::powered_table(
        &model,
        &fluid.0,
        motor.clone(),
        supply,
        &spec.drives,
        &spec.speeds,
        spec.band,
    )?;
    Ok(PoweredRun::new(table, &model, &fluid, supply.is_some()))
}

impl PredictArgs {
    /// The powered stage's spec (with `--motor`).
    pub fn powered_spec(&self) -> Result<propbet_pipeline::spec::PoweredSpec> {
        let Some(motor) = &self.motor.motor else {
            anyhow::bail!("--motor: no motor file");
        };
        let supply = self.motor.supply()?;
        Ok(propbet_pipeline::spec::PoweredSpec {
            model: self.model.spec()?,
            motor: motor.clone(),
            drives: self.motor.drives(self.points.rpm.as_deref(), supply.as_ref())?,
            supply,
            speeds: self.points.request().airspeeds()?,
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

/// Runs `propbet predict --motor`; returns whether every point has its operating point and
/// every station converged.
pub fn run(args: &PredictArgs) -> Result<bool> {
    let spec = args.powered_spec()?;
    let file = propbet_pipeline::stages::read_motor(&spec.motor)?;
    let run = solve(&spec, &file, spec.stations.is_some())?;
    let mut inputs = spec.model.inputs();
    inputs.push(spec.motor.as_path());
    emit(spec.out.as_deref(), &[run.body(spec.format)?], &inputs)?;
    if let Some(path) = &spec.stations {
        propbet_api::files::write_atomic(
            path,
            &[propbet_report::table::sweep::stations_csv(&run.solved())?],
            &inputs,
        )?;
    }
    for line in run.warnings() {
        eprintln!("propbet: {line}");
    }
    if let Some(out) = &spec.out {
        eprintln!(
            "propbet predict: {} operating points on {} ({}) -> {}{}",
            run.table.points.len(),
            file.name,
            spec.motor.display(),
            out.display(),
            spec.stations
                .as_ref()
                .map_or(String::new(), |s| format!(", stations -> {}", s.display()))
        );
    }
    Ok(run.table.clean())
}
