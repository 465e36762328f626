//! `propbet export`: a prediction or measurements as flight-simulator files (Gazebo, PX4 SIH,
//! JSBSim) and a plain map; the work is `propbet_simexport`'s.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use propbet_api::settings::RPM_SOURCE;

use propbet_api::{AirRequest, SweepRequest, Values};

/// Arguments of `propbet export`.
#[derive(Debug, Args)]
pub struct ExportArgs {
    /// What to write, comma-separated or repeated: gazebo, px4-sih, jsbsim, map, or all.
    #[arg(long, required = true, value_delimiter = ',', num_args = 1..)]
    pub to: Vec<String>,
    /// Output folder (created; files in it of the same names are replaced).
    #[arg(long, short)]
    pub out: PathBuf,
    /// The propeller to predict (with --rpm), or, with --measured, where the diameter, blade
    /// count and inertia come from: a QPROP prop file, APC's design file (PE0), a UIUC geometry
    /// table or a blade table, as `predict --prop` takes it.
    #[arg(long, required_unless_present = "measured")]
    pub prop: Option<PathBuf>,
    /// How the prop file is read and what is changed in it (as `predict` takes them).
    #[command(flatten)]
    pub model: crate::predict::ModelFlags,
    /// Rotation speeds of the prediction [rpm]: a list, `start:stop:step` or `start:stop/N`.
    #[arg(
        long,
        allow_hyphen_values = true,
        conflicts_with = "measured",
        required_unless_present = "measured"
    )]
    pub rpm: Option<Values>,
    /// Advance ratios of the prediction, same syntax (default: static only).
    #[arg(long, conflicts_with_all = ["v", "measured"], allow_hyphen_values = true)]
    pub j: Option<Values>,
    /// Axial speeds of the prediction [m/s], same syntax.
    #[arg(long, conflicts_with = "measured", allow_hyphen_values = true)]
    pub v: Option<Values>,
    /// Air of the prediction; --rho also overrides the measured files' density.
    #[command(flatten)]
    pub air: AirRequest,
    /// Measured files instead of a prediction: RCbenchmark/Tyto CSV, UIUC .txt, generic CSV.
    #[arg(long, num_args = 1..)]
    pub measured: Vec<PathBuf>,
    #[arg(long = propbet_api::settings::POLES.flag, help = propbet_api::settings::POLES.help, requires = "measured")]
    pub poles: Option<u32>,
    #[arg(long = RPM_SOURCE.flag, help = RPM_SOURCE.help, value_parser = propbet_api::rpm_sources(), requires = "measured")]
    pub rpm_source: Option<String>,
    #[arg(long = propbet_api::settings::AIR.flag, help = propbet_api::settings::AIR.help, requires = "measured")]
    pub atmosphere: Option<String>,
    /// Column map (TOML) for generic CSV files.
    #[arg(long, requires = "measured")]
    pub columns: Option<PathBuf>,
    /// Propeller diameter of the measurements, with its unit (10in, 254mm, 0.254m) when no
    /// --prop gives it.
    #[arg(long, conflicts_with = "prop")]
    pub diameter: Option<String>,
    /// Number of blades when no --prop gives it (default 2).
    #[arg(long, conflicts_with = "prop")]
    pub blades: Option<f64>,
    /// Moment of inertia about the shaft [kg m^2] for JSBSim (default: estimated from the
    /// prop file's chords).
    #[arg(long)]
    pub ixx: Option<f64>,
    /// Gazebo: fit the constants over this RPM range only, `LO:HI` (default: every static point).
    #[arg(long, value_name = "LO:HI")]
    pub rpm_range: Option<String>,
    /// The propeller's name in the files (default: the prop file's, or the first measured file's).
    #[arg(long)]
    pub name: Option<String>,
}

impl ExportArgs {
    /// What the flags ask for.
    pub fn request(&self) -> propbet_api::commands::export::ExportRequest {
        propbet_api::commands::export::ExportRequest {
            to: self.to.clone(),
            model: self.prop.as_deref().map(|p| self.model.request(p)),
            sweep: SweepRequest {
                rpm: self.rpm.clone(),
                j: self.j.clone(),
                v: self.v.clone(),
            },
            air: self.air.clone(),
            measured: propbet_api::MeasuredRequest {
                files: self.measured.clone(),
                poles: self.poles,
                rpm_source: self.rpm_source.clone(),
                atmosphere: self.atmosphere.clone(),
                rho: self.air.rho,
                columns: self.columns.clone(),
            },
            diameter: self.diameter.clone(),
            blades: self.blades,
            ixx: self.ixx,
            rpm_range: self.rpm_range.clone(),
            name: self.name.clone(),
        }
    }
}

/// Runs `propbet export`.
pub fn run(args: &ExportArgs) -> Result<bool> {
    let request = args.request();
    let term = crate::output::Terminal::default();
    Ok(propbet_api::commands::export::export(
        &request.spec()?,
        &args.out,
        &request.inputs(),
        &term,
    )?)
}
