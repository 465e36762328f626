//! `propbet predict`: performance of a QPROP prop file over RPM x (J or V).

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, ValueEnum};
use propbet_api::spec::{ModelSpec, PredictSpec, TableFormat};
use propbet_api::{AirRequest, ModelRequest, SweepRequest};

/// Output format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// One row per operating point.
    Csv,
    /// All results, with the inputs, as one JSON document.
    Json,
}

/// Arguments of `propbet predict`.
#[derive(Debug, Args)]
pub struct PredictArgs {
    /// The propeller model.
    #[command(flatten)]
    pub model: ModelArgs,
    /// The operating points.
    #[command(flatten)]
    pub points: SweepRequest,
    /// The motor (optional).
    #[command(flatten)]
    pub motor: crate::motor_flags::MotorArgs,
    /// Air properties.
    #[command(flatten)]
    pub air: AirRequest,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Csv)]
    pub format: Format,
    /// Output file (default: standard output).
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Also write the per-station table (CSV) to this file; with --format json the stations
    /// are included in the JSON as well. (`--stations` is a scan's stations as r/R; this flag
    /// was once called that and still answers to it.)
    #[arg(long = "out-stations", alias = "stations", value_name = "FILE")]
    pub stations: Option<PathBuf>,
    #[arg(long, help = band_help())]
    pub band: bool,
}

/// `--band`'s help.
fn band_help() -> String {
    format!(
        "Also give the uncertainty band of CT, CP and efficiency at each point (columns `ct_lo`, `ct_hi`, \
         `cp_lo`, `cp_hi`, `eta_lo`, `eta_hi`; `band` in JSON): {} (`--polars`), each solved at both \
         ends, their root-sum-square (docs/studies/uncertainty-band.md). Solves every point seven (nine) \
         times.",
        propbet_api::BAND_SOURCES
    )
}

/// The propeller model: a prop file, how to read it, and what to change in it.
#[derive(Debug, Args)]
pub struct ModelArgs {
    /// The blade: a QPROP prop file, APC's design file (PE0: blade and sections), a UIUC
    /// geometry table or a blade table (CSV of r, chord, beta; optionally t/c and airfoil). The
    /// last three have no section coefficients: their polars are computed first (`--engine`).
    #[arg(long)]
    pub prop: PathBuf,
    /// How to read it, and what to change in it.
    #[command(flatten)]
    pub flags: ModelFlags,
}

/// How a blade file is read and what is changed in it: the flags of a model beside its
/// `--prop` (each needs one: `export` takes measurements without it).
#[derive(Debug, Args)]
pub struct ModelFlags {
    /// The sections of a blade file without coefficients.
    #[command(flatten)]
    pub blade: BladeArgs,
    /// Collective blade-angle change [deg].
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true, requires = "prop")]
    pub dbeta: f64,
    #[arg(long = propbet_api::settings::UNITS.flag, help = propbet_api::settings::UNITS.help, requires = "prop")]
    pub units: Option<String>,
    /// Reproduce QPROP 1.22 exactly: R on line 2 unscaled, REref of the first station everywhere.
    #[arg(long, requires = "prop")]
    pub qprop_compat: bool,
    /// Switch the tip-loss factor off.
    #[arg(long, requires = "prop")]
    pub no_tip_loss: bool,
    /// Use the tabulated XFOIL polars of this file (from `propbet polars --out-polars`) as the
    /// section model, instead of the prop file's QPROP coefficients.
    #[arg(long, requires = "prop")]
    pub polars: Option<PathBuf>,
    #[arg(long = propbet_api::settings::ROTATION.flag, help = propbet_api::settings::ROTATION.help, value_name = "off|snel", requires = "prop")]
    pub rotation: Option<String>,
    #[arg(long = propbet_api::settings::DRAG_FACTOR.flag, help = propbet_api::settings::DRAG_FACTOR.help, value_name = "K", requires = "prop")]
    pub drag_factor: Option<f64>,
    /// Add a physical effect to the model: `id` or `id:param=value[,param=value]`, for
    /// example `pitch-offset:deg=1.2` or `torque-tare:q0=0.002,q1=2e-6` (repeatable; see
    /// `propbet effects` for the list). Parameters not given take their neutral value.
    #[arg(long = "effect", value_name = "SPEC", requires = "prop")]
    pub effect: Vec<String>,
    /// TOML file of user-defined effects (formulas on a hook), usable by `--effect`.
    #[arg(long, requires = "prop")]
    pub user_effects: Option<PathBuf>,
}

/// The sections of a blade file without coefficients (APC's PE0, UIUC's table, a blade table)
/// and how its polars are made.
#[derive(Debug, Args)]
pub struct BladeArgs {
    /// The section of every station of a UIUC table or blade table (or replacing a PE0 file's):
    /// a coordinate file, a NACA 4-digit name, APC12, a name of propbet's library (e63, clarky,
    /// sd7037, e387, s1223), or airfoils blended along the blade (`E63@0.25,APC12@0.45`).
    #[arg(long)]
    pub airfoil: Option<String>,
    /// Where APC's sections come from, and the airfoils' directory.
    #[command(flatten)]
    pub design: crate::engine::DesignArgs,
    /// The polar engine, XFOIL and its cache.
    #[command(flatten)]
    pub process: propbet_api::ProcessRequest,
}

impl ModelArgs {
    /// What the flags ask for.
    pub fn request(&self) -> Result<ModelRequest> {
        Ok(self.flags.request(&self.prop))
    }

    /// The model's spec (flags in SI).
    pub fn spec(&self) -> Result<ModelSpec> {
        Ok(self.request()?.spec()?)
    }
}

impl ModelFlags {
    /// What the flags ask for of the blade file `prop`.
    pub fn request(&self, prop: &std::path::Path) -> ModelRequest {
        ModelRequest {
            dbeta_deg: self.dbeta,
            units: self.units.clone(),
            qprop_compat: self.qprop_compat,
            no_tip_loss: self.no_tip_loss,
            polars: self.polars.clone(),
            rotation: self.rotation.clone(),
            drag_factor: self.drag_factor,
            effects: self.effect.clone(),
            user_effects: self.user_effects.clone(),
            ..self.blade.request(prop)
        }
    }
}

impl BladeArgs {
    /// The default model of `prop` with these sections.
    pub fn request(&self, prop: &std::path::Path) -> ModelRequest {
        ModelRequest {
            airfoil: self.airfoil.clone(),
            sections_from: self.design.sections_from.clone(),
            airfoils: self.design.airfoils.clone(),
            process: self.process.clone(),
            ..ModelRequest::file(prop)
        }
    }
}

impl PredictArgs {
    /// The stage's spec (flags in SI).
    pub fn spec(&self) -> Result<PredictSpec> {
        let (omegas, axis) = self.points.spec()?;
        Ok(PredictSpec {
            model: self.model.spec()?,
            omegas,
            axis,
            air: self.air.spec()?,
            format: match self.format {
                Format::Csv => TableFormat::Csv,
                Format::Json => TableFormat::Json,
            },
            out: self.out.clone(),
            stations: self.stations.clone(),
            band: self.band,
        })
    }
}

/// Runs `propbet predict`; returns whether every station of every point converged.
pub fn run(args: &PredictArgs) -> Result<bool> {
    let term = crate::output::Terminal::default();
    Ok(match args.motor.motor {
        Some(_) => propbet_api::commands::predict::powered(&args.powered_spec()?, &term)?,
        None => propbet_api::commands::predict::predict(&args.spec()?, &term)?,
    })
}
