//! The stages as functions: each takes its spec (and, inside `run`, the artifact of the stage
//! before it, in memory) and returns typed artifacts. Files are read here when a spec names an
//! input; nothing is written here: the CLI writes the outputs.

use std::path::{Path, PathBuf};

use propbet_bemt::{Fluid, OperatingPoint, Solver};
use propbet_compare::metrics::{metrics, Metrics};
use propbet_compare::{AirChoice, ComparedPoint};
use propbet_diagnose::discover::{diagnose as discover, Diagnosis, Options};
use propbet_diagnose::Data;
use propbet_effects::Stack;
use propbet_geometry::cloud::read_cloud;
use propbet_geometry::mesh::read_stl;
use propbet_geometry::scan::{scan_cloud, scan_mesh, Geometry};
use propbet_measure::uiuc::GeometryRow;
use propbet_measure::{MeasuredSet, ReadOptions, Refused};
use propbet_polar::blade::{compute_blade, BladeJob, XfoilSettings, BLADE_PANELS};
use propbet_polar::{naca4_from_name, Airfoil, BladePolars, PolarCache, PolarEngine, Progress};
use propbet_qprop::{GeometryAccuracy, PropFile, PropRow};

use crate::{conflict, nothing, out_of_range, read_bytes, read_text, Error, Result};
use propbet_model::design::{parse_airfoil, read_airfoil};
use propbet_model::{as_written, load_prop, LoadedProp, Model};
use propbet_settings::spec::{DiagnoseSpec, MeasuredSpec, PolarsSpec, ScanSpec, XfoilProcessSpec};

// ---------------------------------------------------------------------------------------
// scan

/// What `propbet scan` makes.
pub struct Scanned {
    /// The geometry.
    pub geometry: Geometry,
    /// The reference table, when the spec names one.
    pub reference: Option<Vec<GeometryRow>>,
    /// Name of the propeller (prop file, airfoils).
    pub name: String,
    /// The prop file, as the file written for it holds it.
    pub prop: LoadedProp,
    /// Each station's fitted section as a Selig file: (station index, text).
    pub airfoils: Vec<(usize, String)>,
}

impl Scanned {
    /// Every station asked for was measured, and has its section file.
    pub fn clean(&self) -> bool {
        self.geometry.failed.is_empty() && self.airfoils.len() == self.geometry.stations.len()
    }
}

/// Reads a UIUC-style geometry table (r/R c/R β).
pub fn read_geometry_table(path: &Path) -> Result<Vec<GeometryRow>> {
    propbet_measure::uiuc::read_geometry(&read_text(path)?).map_err(|e| Error::input(path, e))
}

/// The most stations a scan cuts.
pub(crate) const MAX_STATIONS: usize = 200;

/// Runs the scan stage.
pub fn scan(spec: &ScanSpec) -> Result<Scanned> {
    let o = &spec.options;
    if o.stations.len() > MAX_STATIONS {
        out_of_range!(
            "--stations: {} stations; a blade is described by at most {MAX_STATIONS} (each one is a section fit and its polars)",
            o.stations.len()
        );
    }
    if let Some(x) = o.stations.iter().find(|&&x| !(x > 0.0 && x <= 1.0)) {
        out_of_range!("--stations: r/R {x} is outside (0, 1]");
    }
    if !(o.slab > 0.0 && o.slab.is_finite()) {
        out_of_range!("--slab {}: must be a positive thickness in mm", 1000.0 * o.slab);
    }
    let path = &spec.input;
    let bytes = crate::read_bytes(path)?;
    let label = path.display().to_string();
    let is_stl = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("stl"));
    let geometry = if is_stl {
        let mesh = read_stl(&bytes, &label)?;
        scan_mesh(&mesh, o)
    } else {
        let cloud = read_cloud(&bytes, &label)?;
        scan_cloud(&cloud, o)
    }
    .map_err(|e| Error::input(path, e))?;
    let reference = spec.reference.as_deref().map(read_geometry_table).transpose()?;
    let name = spec.name.clone().unwrap_or_else(|| {
        path.file_stem()
            .map_or("scan".into(), |s| s.to_string_lossy().into_owned())
    });
    let prop = as_written(&scan_prop_file(&name, &geometry), &spec.out.join("prop.qprop"))?;
    let (airfoils, notes) = station_airfoils(&name, &geometry);
    let mut geometry = geometry;
    geometry.notes.extend(notes);
    Ok(Scanned {
        geometry,
        reference,
        name,
        prop,
        airfoils,
    })
}

/// How well a scan measured its blade, from its own residuals, each at its median station: the
/// blade angle to the blades' spread of it (the largest minus the smallest blade's), the chord
/// to twice the section fit's RMS distance (each edge that far off), relative to the chord (the
/// CST fit's, the NACA fit's where a station has none). The prop file carries it; the
/// uncertainty band adds it to its stated ranges ([`propbet_model::band::BandSpec::for_file`]).
pub fn scan_accuracy(g: &Geometry) -> GeometryAccuracy {
    // A station whose blades could not be compared (a spread of -inf) says nothing; no value
    // beyond what the file's line may hold ([`GeometryAccuracy`]'s maxima).
    let median = |v: Vec<f64>, max: f64| {
        let v: Vec<f64> = v.into_iter().filter(|x| x.is_finite() && *x >= 0.0).collect();
        if v.is_empty() {
            0.0
        } else {
            // Rounded (0.0001° and 0.01 % of chord are far below what the band resolves), so
            // that the prop file's line reads plainly.
            (propbet_units::stats::median(v).min(max) * 1e4).round() / 1e4
        }
    };
    GeometryAccuracy {
        blade_angle_deg: median(
            g.stations.iter().map(|s| s.blade_spread.to_degrees()).collect(),
            GeometryAccuracy::MAX_ANGLE_DEG,
        ),
        chord: median(
            g.stations
                .iter()
                .filter(|s| s.chord > 0.0)
                .map(|s| 2.0 * s.cst.as_ref().map_or(s.naca.rms, |c| c.rms) / s.chord)
                .collect(),
            GeometryAccuracy::MAX_CHORD,
        ),
    }
}

/// The scan's prop file: radii and chords in metres, β in degrees; CL0 from thin-airfoil theory
/// on the fitted camber, the rest [`propbet_qprop::GENERIC`] until `propbet polars` (XFOIL at
/// each station's Re) replaces them; its accuracy ([`scan_accuracy`]) on a comment line.
pub(crate) fn scan_prop_file(name: &str, g: &Geometry) -> PropFile {
    let generic = propbet_qprop::GENERIC;
    let rows = g
        .stations
        .iter()
        .map(|s| {
            let cl0 = propbet_polar::airfoil::naca4_cl0(s.naca.camber, s.naca.camber_pos);
            let c = propbet_bemt::QpropCoefficients {
                cl0,
                clcd0: cl0,
                ..generic
            };
            PropRow {
                r: s.r,
                chord: s.chord,
                beta: s.beta.to_degrees(),
                coeffs: c.to_array().to_vec(),
            }
        })
        .collect();
    PropFile {
        accuracy: Some(scan_accuracy(g)),
        ..PropFile::metric(name.to_string(), g.blades as f64, g.tip_radius, rows)
    }
}

/// Each station's CST section as a Selig file (`airfoils/station_NN.dat`), with notes: where
/// the fit's surfaces were moved apart (a trailing edge that crossed itself, closed), and a
/// section that is still no airfoil XFOIL can take (checked as `polars` reads it: the station
/// gets no file and takes the airfoil or its neighbour's section).
pub(crate) fn station_airfoils(name: &str, g: &Geometry) -> (Vec<(usize, String)>, Vec<String>) {
    let mut notes = Vec::new();
    let mut files = Vec::new();
    for (i, s) in g.stations.iter().enumerate() {
        let Some(c) = s.cst.as_ref() else { continue };
        let (points, repaired) = c.selig_repaired(80);
        let mut t = format!("{name} r/R={:.4} (CST fit, rms {:.4} mm)\n", s.r_r, 1000.0 * c.rms);
        for (x, y) in points {
            t.push_str(&format!("{x:.6} {y:.6}\n"));
        }
        let file = format!("station_{i:02}.dat");
        match repaired {
            Some((from, _)) if from > 0.995 => notes.push(format!(
                "{file} (r/R {:.3}): the fitted trailing edge crossed itself (lower surface above the upper); closed",
                s.r_r
            )),
            Some((from, to)) => notes.push(format!(
                "{file} (r/R {:.3}): the fitted surfaces crossed or nearly touched at x/c {from:.2}-{to:.2}; set a \
                 wedge of {} % of chord apart there, the trailing edge closed",
                s.r_r,
                100.0 * propbet_geometry::fit::TE_WEDGE
            )),
            None => {}
        }
        match parse_airfoil(&t, Path::new(&file)) {
            Ok(_) => files.push((i, t)),
            Err(e) => notes.push(format!("{file} not written (r/R {:.3}): {e}", s.r_r)),
        }
    }
    (files, notes)
}

mod measured;
mod polar;
mod powered;
mod reference;
mod section;
mod side;
mod synth;

pub use measured::*;
pub use polar::*;
pub use powered::{
    electric, fit_motor, polar_omegas, powered, powered_table, read_motor, FittedMotor, PoweredPoint, PoweredTable,
};
pub(crate) use powered::{omega_ceiling, powered_stage};
use propbet_model::solve::grid;
use propbet_model::solve::{setup, solve};
pub use reference::Reference;
pub use section::{section, SectionPolars, SectionSpec};
pub use side::{overall_efficiency, side_by_side, FullRange, SideProp};
pub use synth::{parse_noise, synth, AnswerKey, SynthFiles, SynthFormat, SynthSpec, Synthesized};

#[cfg(test)]
mod tests;
