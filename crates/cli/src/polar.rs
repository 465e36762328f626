//! `propbet polar` (polars of one section) and `propbet polars` (polars of every station of a
//! blade at its operating Reynolds and Mach numbers, reduced to a QPROP prop file).

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use propbet_api::spec::{PolarsSpec, XfoilSpec};

pub use crate::engine::{DesignArgs, XfoilProcess};
use crate::predict::FluidArgs;

/// How XFOIL runs, and the cache.
#[derive(Debug, Args)]
pub struct XfoilArgs {
    /// Executable, cache, progress.
    #[command(flatten)]
    pub process: XfoilProcess,
    #[arg(long = propbet_api::settings::NCRIT.flag, help = propbet_api::settings::NCRIT.help)]
    pub ncrit: Option<f64>,
    #[arg(long = propbet_api::settings::TRIP.flag, help = propbet_api::settings::TRIP.help, value_name = "X/C|free")]
    pub trip: Option<String>,
    #[arg(long = propbet_api::settings::ALPHA.flag, help = propbet_api::settings::ALPHA.help, default_value = propbet_api::settings::ALPHA.default, allow_hyphen_values = true)]
    pub alpha: String,
    /// XFOIL panel nodes (default: XFOIL's 160 for `polar`, 120 for `polars`).
    #[arg(long)]
    pub panels: Option<u32>,
    /// XFOIL's viscous iteration limit per angle.
    #[arg(long, default_value_t = propbet_api::xfoil::DEFAULT_MAX_ITER)]
    pub iter: u32,
}

impl XfoilArgs {
    /// The spec (flags in SI); `default_ncrit` and `default_trip` when `--ncrit` and `--trip`
    /// are not given.
    pub fn spec(&self, default_ncrit: f64, default_trip: Option<f64>) -> Result<XfoilSpec> {
        Ok(self.request().spec(default_ncrit, default_trip)?)
    }

    /// What the flags ask for.
    pub fn request(&self) -> propbet_api::SectionRequest {
        propbet_api::SectionRequest {
            process: self.process.request(),
            ncrit: self.ncrit,
            trip: self.trip.clone(),
            alpha: Some(propbet_api::Values::Text(self.alpha.clone())),
            panels: self.panels,
            iter: Some(self.iter),
        }
    }
}

/// The section to analyse.
#[derive(Debug, Args)]
pub struct AirfoilArgs {
    /// Coordinate file (Selig or Lednicer), or a NACA 4-digit name such as `naca4412`.
    #[arg(long)]
    pub airfoil: String,
    /// Scale the section to this thickness ratio t/c (0.06 or 6%), keeping its camber line.
    #[arg(long)]
    pub thickness: Option<String>,
}

/// Arguments of `propbet polar`.
#[derive(Debug, Args)]
pub struct PolarArgs {
    /// The section.
    #[command(flatten)]
    pub section: AirfoilArgs,
    /// Reynolds numbers: a list (5e4,1e5) or a range.
    #[arg(long)]
    pub re: String,
    /// Mach number.
    #[arg(long, default_value_t = 0.0)]
    pub mach: f64,
    /// XFOIL settings.
    #[command(flatten)]
    pub xfoil: XfoilArgs,
    /// Polar table (CSV; default: standard output).
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Figure of the polars and the QPROP fit (.svg or .png).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// The QPROP fit at each Re, with residuals, as JSON.
    #[arg(long)]
    pub fit_out: Option<PathBuf>,
}

/// Runs `propbet polar`; false when some polar failed (the others are written).
pub fn run_polar(a: &PolarArgs) -> Result<bool> {
    let command = propbet_api::commands::polar::PolarCommand {
        airfoil: a.section.airfoil.clone(),
        thickness: a.section.thickness.clone(),
        re: a.re.clone(),
        mach: a.mach,
        xfoil: a.xfoil.request(),
        out: a.out.clone(),
        plot: a.plot.clone(),
        fit_out: a.fit_out.clone(),
    };
    Ok(propbet_api::commands::polar::polar(
        &command,
        &crate::output::Terminal::default(),
    )?)
}

/// Arguments of `propbet polars`.
#[derive(Debug, Args)]
pub struct PolarsArgs {
    /// Blade geometry: a QPROP prop file (its radii, chords and twists are used; its
    /// coefficients only for the first estimate of each station's inflow), APC's design file
    /// (PE0: its blade and sections), a UIUC geometry table or a blade table (CSV).
    #[arg(long)]
    pub geometry: PathBuf,
    #[arg(long = propbet_api::settings::UNITS.flag, help = propbet_api::settings::UNITS.help)]
    pub units: Option<String>,
    /// The section used at every station (with --station-airfoils, at the stations without
    /// their own): a coordinate file (Selig or Lednicer), a NACA 4-digit name, APC12 or a name
    /// of propbet's library (e63, clarky, sd7037, ...), or airfoils blended along the blade
    /// (`E63@0.25,APC12@0.45`). Not needed for a PE0 file or a table naming its sections.
    #[arg(long)]
    pub airfoil: Option<String>,
    /// Scale the --airfoil section to this thickness ratio t/c (0.06 or 6%), keeping its
    /// camber line.
    #[arg(long, requires = "airfoil")]
    pub thickness: Option<String>,
    /// Per-station sections: a directory of `station_NN.dat` (NN = 00, 01, ... in the
    /// geometry's station order, as `propbet scan` writes them); a station without its file
    /// uses `--airfoil`, or without it the nearest station's section.
    #[arg(long)]
    pub station_airfoils: Option<PathBuf>,
    #[command(flatten)]
    pub design: DesignArgs,
    /// The operating points whose Reynolds numbers the polars cover (give the sweep's, or the
    /// measured range).
    #[command(flatten)]
    pub points: crate::predict::SweepArgs,
    /// Air properties.
    #[command(flatten)]
    pub air: FluidArgs,
    /// XFOIL settings.
    #[command(flatten)]
    pub xfoil: XfoilArgs,
    #[arg(long = propbet_api::settings::NCRIT_EFFECT.flag, help = propbet_api::settings::NCRIT_EFFECT.help, value_delimiter = ',')]
    pub ncrit_effect: Vec<f64>,
    /// QPROP prop file with the fitted per-station coefficients.
    #[arg(long)]
    pub out_prop: PathBuf,
    /// Every station's polars and fit (JSON), for `propbet predict --polars`.
    #[arg(long)]
    pub out_polars: Option<PathBuf>,
}

impl PolarsArgs {
    /// The stage's spec (flags in SI).
    pub fn spec(&self) -> Result<PolarsSpec> {
        let request = propbet_api::PolarsRequest {
            geometry: self.geometry.clone(),
            units: self.units.clone(),
            airfoil: self.airfoil.clone(),
            thickness: self.thickness.clone(),
            station_airfoils: self.station_airfoils.clone(),
            sections_from: self.design.sections_from.clone(),
            airfoils: self.design.airfoils.clone(),
            sweep: self.points.request(),
            air: self.air.request(),
            section: self.xfoil.request(),
            ncrit_effect: self.ncrit_effect.clone(),
            out_prop: self.out_prop.clone(),
            out_polars: self.out_polars.clone(),
        };
        Ok(request.spec()?)
    }
}

/// Runs `propbet polars`; false when a station has no fit (its coefficients are kept from the
/// geometry file, and it is reported).
pub fn run_polars(args: &PolarsArgs) -> Result<bool> {
    Ok(propbet_api::commands::polar::polars(
        &args.spec()?,
        &crate::output::Terminal::default(),
    )?)
}
