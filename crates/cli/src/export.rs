//! `propbet export`: a prediction or measurements as flight-simulator files (Gazebo, PX4 SIH,
//! JSBSim) and a plain map; the work is `propbet_simexport`'s.

use std::path::{Path, PathBuf};

use anyhow::{bail, Result};
use clap::Args;
use propbet_pipeline::spec::{ModelSpec, PredictSpec, TableFormat};
use propbet_simexport::{self as simexport, ExportFrom, ExportSpec, Said, Target};

use crate::compare::RpmSourceArg;
use crate::predict::{FluidArgs, SweepArgs};

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
    pub rpm: Option<String>,
    /// Advance ratios of the prediction, same syntax (default: static only).
    #[arg(long, conflicts_with_all = ["v", "measured"], allow_hyphen_values = true)]
    pub j: Option<String>,
    /// Axial speeds of the prediction [m/s], same syntax.
    #[arg(long, conflicts_with = "measured", allow_hyphen_values = true)]
    pub v: Option<String>,
    /// Air of the prediction; --rho also overrides the measured files' density.
    #[command(flatten)]
    pub air: FluidArgs,
    /// Measured files instead of a prediction: RCbenchmark/Tyto CSV, UIUC .txt, generic CSV.
    #[arg(long, num_args = 1..)]
    pub measured: Vec<PathBuf>,
    #[arg(long = propbet_api::settings::POLES.flag, help = propbet_api::settings::POLES.help, requires = "measured")]
    pub poles: Option<u32>,
    #[arg(long = propbet_api::settings::RPM_SOURCE.flag, help = propbet_api::settings::RPM_SOURCE.help, value_enum, requires = "measured")]
    pub rpm_source: Option<RpmSourceArg>,
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

fn targets(names: &[String]) -> Result<Vec<Target>> {
    let mut out = Vec::new();
    for n in names {
        let n = n.trim();
        if n == "all" {
            out.extend(Target::ALL);
            continue;
        }
        match Target::ALL.iter().find(|t| t.name() == n) {
            Some(t) => out.push(*t),
            None => bail!("--to '{n}': unknown export (use gazebo, px4-sih, jsbsim, map or all)"),
        }
    }
    out.sort_by_key(|t| Target::ALL.iter().position(|a| a == t));
    out.dedup();
    Ok(out)
}

fn parse_diameter(text: &str) -> Result<f64> {
    let d = propbet_api::settings::values::parse_length("--diameter", text)?;
    if !(d.is_finite() && (0.01..=10.0).contains(&d)) {
        bail!("--diameter '{text}': {d} m is not a propeller's diameter (0.01 to 10 m)");
    }
    Ok(d)
}

fn parse_range(text: &str) -> Result<(f64, f64)> {
    let bad = || anyhow::anyhow!("--rpm-range '{text}': LO:HI in rpm, like 3000:6000");
    let (a, b) = text.split_once(':').ok_or_else(bad)?;
    let (lo, hi): (f64, f64) = (
        a.trim().parse().map_err(|_| bad())?,
        b.trim().parse().map_err(|_| bad())?,
    );
    if !(lo.is_finite() && hi.is_finite() && lo >= 0.0 && hi >= lo) {
        return Err(bad());
    }
    Ok((lo, hi))
}

impl ExportArgs {
    fn model_spec(&self, prop: &Path) -> Result<ModelSpec> {
        Ok(self.model.request(prop).spec()?)
    }

    fn inputs(&self) -> Vec<&Path> {
        let mut v: Vec<&Path> = self.measured.iter().map(PathBuf::as_path).collect();
        v.extend(self.prop.as_deref());
        v.extend(self.model.polars.as_deref());
        v.extend(self.columns.as_deref());
        v.extend(self.model.user_effects.as_deref());
        v
    }
}

impl ExportArgs {
    /// The stage's spec (flags in SI).
    pub fn spec(&self) -> Result<ExportSpec> {
        let from = if self.measured.is_empty() {
            let Some(prop) = &self.prop else {
                bail!("give --prop with --rpm (a prediction) or --measured (measurements)");
            };
            let sweep = SweepArgs {
                rpm: self.rpm.clone(),
                j: self.j.clone(),
                v: self.v.clone(),
            };
            let (omegas, axis) = sweep.spec()?;
            ExportFrom::Prediction(PredictSpec {
                model: self.model_spec(prop)?,
                omegas,
                axis,
                air: self.air.spec()?,
                format: TableFormat::Csv,
                out: None,
                stations: None,
                band: false,
            })
        } else {
            ExportFrom::Measured {
                measured: propbet_api::MeasuredRequest {
                    files: self.measured.clone(),
                    poles: self.poles,
                    rpm_source: self.rpm_source.map(|s| s.name().to_string()),
                    atmosphere: self.atmosphere.clone(),
                    rho: self.air.rho,
                    columns: self.columns.clone(),
                }
                .spec()?,
                model: self.prop.as_deref().map(|p| self.model_spec(p)).transpose()?,
                diameter: self.diameter.as_deref().map(parse_diameter).transpose()?,
                blades: self.blades,
            }
        };
        Ok(ExportSpec {
            from,
            targets: targets(&self.to)?,
            rpm_range: self.rpm_range.as_deref().map(parse_range).transpose()?,
            ixx: self.ixx,
            name: self.name.clone(),
        })
    }
}

/// Runs `propbet export`.
pub fn run(args: &ExportArgs) -> Result<bool> {
    let spec = args.spec()?;
    let inputs = args.inputs();
    propbet_api::files::refuse_inputs_inside(&args.out, &inputs)?;
    let made = simexport::exports(&spec, &|said| match said {
        Said::Warning(w) => eprintln!("propbet: warning: {w}"),
        Said::LeftOut(n) => eprintln!("propbet: {n}"),
    })?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| anyhow::anyhow!("{}: cannot create the output folder: {e}", args.out.display()))?;
    for e in &made {
        for (name, text) in &e.files {
            propbet_api::files::write_atomic(&args.out.join(name), &[text.as_bytes()], &inputs)?;
        }
        println!(
            "{:<8} {}: {}",
            e.target.name(),
            e.files.iter().map(|f| f.0.as_str()).collect::<Vec<_>>().join(", "),
            e.values
        );
        println!("         against the points it came from: {}", e.fit.against());
    }
    Ok(true)
}
