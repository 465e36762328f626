//! `propbet prop`: inspect a QPROP prop file and optionally write it back normalised.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use propbet_api::qprop::write_prop;

use crate::output::emit;
use propbet_pipeline::spec::ModelSpec;

use crate::predict::load_model;

/// Arguments of `propbet prop`.
#[derive(Debug, Args)]
pub struct PropArgs {
    /// The blade file: a QPROP prop file, APC's design file (PE0), a UIUC geometry table or a
    /// blade table (CSV).
    pub file: PathBuf,
    #[arg(long = propbet_api::settings::UNITS.flag, help = propbet_api::settings::UNITS.help)]
    pub units: Option<String>,
    /// Read as QPROP 1.22 does (R on line 2 unscaled, REref of the first station).
    #[arg(long)]
    pub qprop_compat: bool,
    /// Write the prop file back to this path as QPROP 1.22 reads what propbet reads: metres and
    /// degrees, R on line 2, every row's drag law on one REref.
    #[arg(long)]
    pub write: Option<PathBuf>,
}

impl PropArgs {
    /// The file as a model's spec reads it (its units, QPROP's reading).
    pub fn model_spec(&self) -> Result<ModelSpec> {
        Ok(ModelSpec {
            units: self
                .units
                .as_deref()
                .map(propbet_api::settings::values::parse_length_unit)
                .transpose()?,
            qprop_compat: self.qprop_compat,
            ..ModelSpec::prop(self.file.clone())
        })
    }
}

/// The blade file's model as `prop` shows it: a QPROP file as it is; APC's PE0, a UIUC table
/// or a blade table as its stations with QPROP's generic coefficients (the polars of
/// `predict` replace them).
pub fn load(args: &PropArgs) -> Result<propbet_pipeline::model::Model> {
    load_spec(&args.model_spec()?)
}

/// The blade file's model as `prop` shows it, of a model's spec (its file, units and reading).
pub fn load_spec(spec: &ModelSpec) -> Result<propbet_pipeline::model::Model> {
    let spec = ModelSpec {
        units: spec.units,
        qprop_compat: spec.qprop_compat,
        ..ModelSpec::prop(spec.prop.clone())
    };
    let opts = propbet_pipeline::design::DesignOptions {
        units: spec.units,
        ..Default::default()
    };
    match propbet_pipeline::design::read_design(&spec.prop, &opts)? {
        Some(d) => Ok(propbet_pipeline::model::Model::from_loaded(
            &ModelSpec { units: None, ..spec },
            d.geometry,
            false,
        )?),
        None => load_model(&spec, false),
    }
}

/// Runs `propbet prop`.
pub fn run(args: &PropArgs) -> Result<bool> {
    let model = load(args)?;
    let (loaded, rotor) = (&model.loaded, &model.rotor);
    println!("name: {}", loaded.file.name);
    println!("blades: {}", rotor.blades);
    println!("tip radius: {:.6} m", rotor.tip_radius);
    println!("input rows: {}", loaded.file.rows.len());
    println!("# computational stations (QPROP discretisation)");
    println!("r_m,dr_m,chord_m,beta_deg");
    for s in &rotor.stations {
        println!("{:.6},{:.6},{:.6},{:.4}", s.r, s.dr, s.chord, s.beta.to_degrees());
    }
    if let Some(out) = &args.write {
        emit(
            Some(out),
            &[write_prop(&loaded.file.as_qprop_reads())],
            &[args.file.as_path()],
        )?;
    }
    Ok(true)
}
