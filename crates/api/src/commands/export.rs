//! `propbet export`: a prediction or measurements as flight-simulator files (Gazebo, PX4 SIH,
//! JSBSim) and a plain map, written; the work is `propbet_simexport`'s.

use std::path::{Path, PathBuf};

use propbet_settings::spec::{PredictSpec, TableFormat};
use propbet_simexport::{ExportFrom, ExportSpec, Said, Target};

use crate::command_error::refuse;
use crate::console::Console;
use crate::{AirRequest, MeasuredRequest, ModelRequest, SweepRequest};
use crate::{CommandError, CommandResult as Result};

/// What `propbet export` is asked: a prediction (a model over a sweep) or measured files,
/// and what to write of it.
#[derive(Debug, Clone, Default)]
pub struct ExportRequest {
    /// What to write: `gazebo`, `px4-sih`, `jsbsim`, `map` or `all`.
    pub to: Vec<String>,
    /// The propeller: predicted over `sweep`, or with measured files where the diameter,
    /// blade count and inertia come from.
    pub model: Option<ModelRequest>,
    /// The prediction's operating points.
    pub sweep: SweepRequest,
    /// The prediction's air (its density also overrides the measured files').
    pub air: AirRequest,
    /// Measured files instead of a prediction (no files: a prediction).
    pub measured: MeasuredRequest,
    /// The measured propeller's diameter with its unit (`10in`) without a model.
    pub diameter: Option<String>,
    /// The measured propeller's blade count without a model (None: 2).
    pub blades: Option<f64>,
    /// The moment of inertia about the shaft [kg m^2] (None: estimated from the prop file).
    pub ixx: Option<f64>,
    /// Gazebo's fit over this RPM range only, `LO:HI`.
    pub rpm_range: Option<String>,
    /// The propeller's name in the files.
    pub name: Option<String>,
}

impl ExportRequest {
    /// The export's spec, in SI.
    pub fn spec(&self) -> Result<ExportSpec> {
        let from = if self.measured.files.is_empty() {
            let Some(model) = &self.model else {
                refuse!("give --prop with --rpm (a prediction) or --measured (measurements)");
            };
            let (omegas, axis) = self.sweep.spec()?;
            ExportFrom::Prediction(PredictSpec {
                model: model.spec()?,
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
                measured: self.measured.spec()?,
                model: self.model.as_ref().map(ModelRequest::spec).transpose()?,
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

    /// The files it reads (never overwritten).
    pub fn inputs(&self) -> Vec<&Path> {
        let mut v: Vec<&Path> = self.measured.files.iter().map(PathBuf::as_path).collect();
        if let Some(m) = &self.model {
            v.push(&m.prop);
            v.extend(m.polars.as_deref());
        }
        v.extend(self.measured.columns.as_deref());
        v.extend(self.model.as_ref().and_then(|m| m.user_effects.as_deref()));
        v
    }
}

/// The formats `--to` names, in [`Target::ALL`]'s order.
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
            None => refuse!("--to '{n}': unknown export (use gazebo, px4-sih, jsbsim, map or all)"),
        }
    }
    out.sort_by_key(|t| Target::ALL.iter().position(|a| a == t));
    out.dedup();
    Ok(out)
}

fn parse_diameter(text: &str) -> Result<f64> {
    let d = crate::settings::values::parse_length("--diameter", text)?;
    if !(d.is_finite() && (0.01..=10.0).contains(&d)) {
        refuse!("--diameter '{text}': {d} m is not a propeller's diameter (0.01 to 10 m)");
    }
    Ok(d)
}

fn parse_range(text: &str) -> Result<(f64, f64)> {
    let bad = || CommandError::Message(format!("--rpm-range '{text}': LO:HI in rpm, like 3000:6000"));
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

/// Runs `propbet export` of `spec` into the folder `out` (`inputs`: the files it reads,
/// never overwritten).
pub fn export(spec: &ExportSpec, out: &Path, inputs: &[&Path], console: &dyn Console) -> Result<bool> {
    crate::files::refuse_inputs_inside(out, inputs)?;
    let made = propbet_simexport::exports(spec, &|said| match said {
        Said::Warning(w) => console.err(&format!("propbet: warning: {w}")),
        Said::LeftOut(n) => console.err(&format!("propbet: {n}")),
    })?;
    std::fs::create_dir_all(out)
        .map_err(|e| CommandError::Message(format!("{}: cannot create the output folder: {e}", out.display())))?;
    for e in &made {
        for (name, text) in &e.files {
            crate::files::write_atomic(&out.join(name), &[text.as_bytes()], inputs)?;
        }
        console.out(&format!(
            "{:<8} {}: {}",
            e.target.name(),
            e.files.iter().map(|f| f.0.as_str()).collect::<Vec<_>>().join(", "),
            e.values
        ));
        console.out(&format!(
            "         against the points it came from: {}",
            e.fit.against()
        ));
    }
    Ok(true)
}
