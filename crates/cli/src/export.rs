//! `propbet export`: a prediction or measurements as flight-simulator files (Gazebo, PX4 SIH,
//! JSBSim) and a plain map; the work is `propbet_pipeline::simexport`'s.

use std::path::{Path, PathBuf};

use anyhow::{bail, Result};
use clap::Args;
use propbet_pipeline::measure::{Loads, Speed};
use propbet_pipeline::model::Model;
use propbet_pipeline::simexport::{self, Point, Source, Target};
use propbet_pipeline::spec::{drag_factor_or_default, ModelSpec, PredictSpec, Rotation, TableFormat};
use propbet_pipeline::values::parse_length_unit;

use crate::compare::RpmSourceArg;
use crate::output;
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
    /// QPROP prop file: the propeller to predict (with --rpm), or, with --measured, where the
    /// diameter, blade count and inertia come from.
    #[arg(long, required_unless_present = "measured")]
    pub prop: Option<PathBuf>,
    /// Tabulated polars for the prediction (`propbet polars --out-polars`), as `predict --polars`.
    #[arg(long, requires = "prop")]
    pub polars: Option<PathBuf>,
    #[arg(long = propbet_pipeline::settings::ROTATION.flag, help = propbet_pipeline::settings::ROTATION.help, value_name = "off|snel", requires = "prop")]
    pub rotation: Option<String>,
    #[arg(long = propbet_pipeline::settings::DRAG_FACTOR.flag, help = propbet_pipeline::settings::DRAG_FACTOR.help, value_name = "K", requires = "prop")]
    pub drag_factor: Option<f64>,
    #[arg(long = propbet_pipeline::settings::UNITS.flag, help = propbet_pipeline::settings::UNITS.help, requires = "prop")]
    pub units: Option<String>,
    /// Collective blade-angle change of the prediction [deg].
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true, requires = "prop")]
    pub dbeta: f64,
    /// Read the prop file as QPROP 1.22 does (as `predict --qprop-compat`).
    #[arg(long, requires = "prop")]
    pub qprop_compat: bool,
    /// Switch the tip-loss factor off.
    #[arg(long, requires = "prop")]
    pub no_tip_loss: bool,
    /// An effect added to the prediction (as `predict --effect`; repeatable).
    #[arg(long = "effect", value_name = "SPEC", requires = "prop")]
    pub effect: Vec<String>,
    /// TOML file of user-defined effects, usable by --effect.
    #[arg(long, requires = "prop")]
    pub user_effects: Option<PathBuf>,
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
    #[arg(long = propbet_pipeline::settings::POLES.flag, help = propbet_pipeline::settings::POLES.help, requires = "measured")]
    pub poles: Option<u32>,
    #[arg(long = propbet_pipeline::settings::RPM_SOURCE.flag, help = propbet_pipeline::settings::RPM_SOURCE.help, value_enum, requires = "measured")]
    pub rpm_source: Option<RpmSourceArg>,
    #[arg(long = propbet_pipeline::settings::AIR.flag, help = propbet_pipeline::settings::AIR.help, requires = "measured")]
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
    let t = text.trim();
    let split = t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len());
    let (num, unit) = t.split_at(split);
    let v: f64 = num
        .trim()
        .parse()
        .map_err(|_| anyhow::anyhow!("--diameter '{text}': a number with its unit, like 10in or 0.254m"))?;
    let scale = if unit.is_empty() {
        1.0
    } else {
        parse_length_unit(unit.trim())?
    };
    let d = v * scale;
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
        let mut spec = ModelSpec::prop(prop.to_path_buf());
        spec.units = self.units.as_deref().map(parse_length_unit).transpose()?;
        spec.dbeta = self.dbeta.to_radians();
        spec.qprop_compat = self.qprop_compat;
        spec.no_tip_loss = self.no_tip_loss;
        spec.effects = self.effect.clone();
        spec.user_effects = self.user_effects.clone();
        spec.polars = self.polars.clone();
        spec.rotation = Rotation::or_default(
            self.rotation.as_deref().map(Rotation::parse).transpose()?,
            self.polars.is_some(),
        );
        spec.drag_factor = drag_factor_or_default(self.drag_factor, self.polars.is_some());
        Ok(spec)
    }

    fn inputs(&self) -> Vec<&Path> {
        let mut v: Vec<&Path> = self.measured.iter().map(PathBuf::as_path).collect();
        v.extend(self.prop.as_deref());
        v.extend(self.polars.as_deref());
        v.extend(self.columns.as_deref());
        v.extend(self.user_effects.as_deref());
        v
    }
}

/// The blade's inertia from the prop file, or the one given.
fn inertia(args: &ExportArgs, model: Option<&Model>) -> Option<(f64, String)> {
    if let Some(i) = args.ixx {
        return Some((i, "given (--ixx)".into()));
    }
    let m = model?;
    let blade = m
        .loaded
        .file
        .to_blade(propbet_pipeline::qprop::RadiusReading::Documented);
    let (t_c, density) = simexport::IXX_ASSUMED;
    let i = simexport::blade_ixx(blade.blades, &blade.r, &blade.chord, t_c, density);
    Some((
        i,
        format!(
            "estimated from the prop file's chords: {} blades, section area 0.685 t c at t/c {t_c}, \
             {density} kg/m^3 (glass-filled nylon), hub left out; a weighed value belongs here (the ixx option)",
            blade.blades
        ),
    ))
}

fn predicted(args: &ExportArgs, prop: &Path) -> Result<Source> {
    let model_spec = args.model_spec(prop)?;
    let model = crate::predict::load_model(&model_spec, false)?;
    let sweep = SweepArgs {
        rpm: args.rpm.clone().unwrap_or_default(),
        j: args.j.clone(),
        v: args.v.clone(),
    };
    let (omegas, axis) = sweep.spec()?;
    let spec = PredictSpec {
        model: model_spec,
        omegas,
        axis,
        air: args.air.spec()?,
        format: TableFormat::Csv,
        out: None,
        stations: None,
    };
    let (fluid, fluid_source) = spec.air.fluid()?;
    let ops = propbet_pipeline::stages::operating_points(&spec, model.rotor.tip_radius)?;
    let results = propbet_pipeline::stages::sweep(&model, &fluid, &ops)?;
    let unconverged = results.iter().filter(|p| p.not_converged > 0).count();
    if unconverged > 0 {
        eprintln!("propbet: {unconverged} operating points did not converge everywhere; they are left out");
    }
    let points: Vec<Point> = results
        .iter()
        .filter(|p| p.not_converged == 0)
        .filter_map(|p| {
            Some(Point {
                rpm: p.rpm,
                j: p.j?,
                ct: p.ct?,
                cp: p.cp?,
            })
        })
        .collect();
    let m = &spec.model;
    let section = format!(
        "{}, drag factor {}, rotation {}",
        m.polars.as_ref().map_or_else(
            || "the prop file's QPROP coefficients".to_string(),
            |p| format!("XFOIL polars {} as tables", p.display())
        ),
        m.drag_factor,
        m.rotation.name()
    );
    let ixx = inertia(args, Some(&model));
    Ok(Source {
        points,
        diameter: model.diameter,
        blades: model.rotor.blades,
        ixx,
        origin: format!(
            "propbet's prediction of {} ({section}) at {} rpm, {} ({fluid_source}, rho {} kg/m^3)",
            prop.display(),
            args.rpm.as_deref().unwrap_or(""),
            match (&args.j, &args.v) {
                (Some(j), _) => format!("J {j}"),
                (None, Some(v)) => format!("V {v} m/s"),
                _ => "static".to_string(),
            },
            fluid.rho
        ),
        name: args.name.clone().unwrap_or_else(|| model.loaded.file.name.clone()),
        measured: false,
    })
}

fn measured(args: &ExportArgs) -> Result<Source> {
    let model = match &args.prop {
        Some(p) => Some(crate::predict::load_model(&args.model_spec(p)?, false)?),
        None => None,
    };
    let diameter = match (&model, &args.diameter) {
        (Some(m), _) => m.diameter,
        (None, Some(d)) => parse_diameter(d)?,
        (None, None) => bail!(
            "the measurements' propeller diameter is needed for its coefficients: give --diameter (like 10in) or --prop"
        ),
    };
    let spec = propbet_pipeline::spec::MeasuredSpec {
        files: args.measured.clone(),
        poles: args.poles,
        rpm_source: args.rpm_source.map(RpmSourceArg::source),
        atmosphere: args
            .atmosphere
            .as_deref()
            .map(propbet_pipeline::values::parse_atmosphere)
            .transpose()?,
        rho: args.air.rho,
        columns: args.columns.clone(),
    };
    let (air, sets) = propbet_pipeline::stages::load_measured(&spec)?;
    let mut points = Vec::new();
    let mut flagged = 0;
    for (file, set) in args.measured.iter().zip(&sets) {
        if !set.has_torque {
            bail!(
                "{}: no torque or power measured; every export needs the torque (momentConstant, CP)",
                file.display()
            );
        }
        for p in &set.points {
            if !p.flags.is_empty() {
                flagged += 1;
                continue;
            }
            let rho = propbet_pipeline::compare::point_air(p, &air).fluid.rho;
            let omega = p.omega.mean;
            let n = propbet_pipeline::units::omega_to_rev_per_s(omega);
            let j = match p.speed {
                Speed::Airspeed(v) => v.mean / (n * diameter),
                Speed::AdvanceRatio(j) => j,
            };
            let (ct, cp) = match p.loads {
                Loads::Coefficients { ct, cp } => (ct, cp),
                Loads::Forces { thrust, torque } => {
                    let q = propbet_pipeline::compare::Quantities::from_forces(
                        thrust.mean,
                        torque.map(|q| q.mean),
                        omega,
                        j * n * diameter,
                        rho,
                        diameter,
                    );
                    match (q.ct, q.cp) {
                        (Some(ct), Some(cp)) => (ct, cp),
                        _ => continue,
                    }
                }
            };
            points.push(Point {
                rpm: p.rpm(),
                j,
                ct,
                cp,
            });
        }
    }
    if flagged > 0 {
        eprintln!("propbet: {flagged} measured points flagged as unsteady or implausible are left out");
    }
    let first = args.measured[0]
        .file_stem()
        .map_or_else(|| "propeller".to_string(), |s| s.to_string_lossy().into_owned());
    Ok(Source {
        points,
        diameter,
        blades: model.as_ref().map_or(args.blades.unwrap_or(2.0), |m| m.rotor.blades),
        ixx: inertia(args, model.as_ref()),
        origin: format!(
            "measurements {} ({} points, diameter {:.4} m{})",
            args.measured
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
            sets.iter().map(|s| s.points.len()).sum::<usize>(),
            diameter,
            if model.is_some() { " from the prop file" } else { "" }
        ),
        name: args
            .name
            .clone()
            .or_else(|| model.as_ref().map(|m| m.loaded.file.name.clone()))
            .unwrap_or(first),
        measured: true,
    })
}

/// Runs `propbet export`.
pub fn run(args: &ExportArgs) -> Result<bool> {
    let targets = targets(&args.to)?;
    let rpm_range = args.rpm_range.as_deref().map(parse_range).transpose()?;
    if let Some(i) = args.ixx {
        if !(i.is_finite() && i > 0.0 && i < 100.0) {
            bail!("--ixx {i}: a moment of inertia in kg m^2, above 0 (a small propeller's is about 1e-5)");
        }
    }
    let inputs = args.inputs();
    output::refuse_inputs_inside(&args.out, &inputs)?;
    let src = if args.measured.is_empty() {
        let Some(prop) = &args.prop else {
            bail!("give --prop with --rpm (a prediction) or --measured (measurements)");
        };
        predicted(args, prop)?
    } else {
        measured(args)?
    };
    // Every export is made before any file is written: one the data cannot support stops
    // them all, nothing written.
    let made = targets
        .iter()
        .map(|&t| match t {
            Target::Gazebo => simexport::gazebo(&src, rpm_range),
            t => simexport::export(t, &src),
        })
        .collect::<std::result::Result<Vec<_>, _>>()?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| anyhow::anyhow!("{}: cannot create the output folder: {e}", args.out.display()))?;
    for e in &made {
        for (name, text) in &e.files {
            output::write_atomic(&args.out.join(name), &[text.as_bytes()], &inputs)?;
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
