//! The section stage (`propbet polar`): one airfoil's XFOIL polars at several Reynolds numbers
//! and one Mach number, and QPROP's law fitted at each.

use propbet_polar::{fit_qprop, Airfoil, AlphaWeights, Polar, PolarJob, Progress, QpropFit, DEFAULT_RE_EXP};

use crate::{nothing, out_of_range, Result};
use propbet_settings::spec::XfoilSpec;

/// What the section stage is asked: Reynolds numbers, Mach number and how XFOIL runs.
#[derive(Debug, Clone, PartialEq)]
pub struct SectionSpec {
    /// Chord Reynolds numbers [-].
    pub res: Vec<f64>,
    /// Mach number [-].
    pub mach: f64,
    /// Transition, angles, panels, iterations, the process.
    pub xfoil: XfoilSpec,
}

impl SectionSpec {
    /// Reynolds numbers XFOIL can take and a Mach number below its limit.
    pub fn check(&self) -> Result<()> {
        if let Some(bad) = self.res.iter().find(|r| !(r.is_finite() && **r > 0.0)) {
            out_of_range!("--re: Reynolds number must be positive, found {bad}");
        }
        if !(self.mach.is_finite() && (0.0..0.9).contains(&self.mach)) {
            out_of_range!("--mach: {} must be in [0, 0.9)", self.mach);
        }
        Ok(())
    }
}

/// One airfoil's polars: each Reynolds number's run (its polar, or why there is none), the
/// cache's complaint if it could not store them, and QPROP's law fitted at each polar's Re.
#[derive(Debug)]
pub struct SectionPolars {
    /// The section's name.
    pub name: String,
    /// (Re, its polar or the error), in the order asked.
    pub runs: Vec<(f64, std::result::Result<Polar, String>)>,
    /// The cache could not store the polars XFOIL computed (they were used).
    pub cache_error: Option<String>,
    /// (Re, the fit at it or why none), for each polar.
    pub fits: Vec<(f64, std::result::Result<QpropFit, String>)>,
}

impl SectionPolars {
    /// The polars computed.
    pub fn polars(&self) -> Vec<Polar> {
        self.runs.iter().filter_map(|(_, r)| r.as_ref().ok().cloned()).collect()
    }

    /// The fits made.
    pub fn fitted(&self) -> Vec<QpropFit> {
        self.fits.iter().filter_map(|(_, r)| r.as_ref().ok().cloned()).collect()
    }

    /// Every polar computed, with points, no XFOIL fault, and fitted.
    pub fn clean(&self) -> bool {
        self.runs
            .iter()
            .all(|(_, r)| r.as_ref().is_ok_and(|p| p.faults.is_empty() && !p.points.is_empty()))
            && self.fits.iter().all(|(_, f)| f.is_ok())
    }

    /// An error where no polar could be computed.
    pub fn check(&self) -> Result<()> {
        if self.polars().is_empty() {
            nothing!("no polar could be computed for {}", self.name);
        }
        Ok(())
    }

    /// The polars as one CSV table (the polar table's header, then each polar's rows).
    pub fn csv(&self) -> String {
        let mut csv = format!("{}\n", propbet_polar::table::CSV_HEADER);
        for (_, p) in &self.runs {
            let Ok(p) = p else { continue };
            csv.push_str(&p.csv_rows());
        }
        csv
    }
}

/// Computes `foil`'s polars at each Reynolds number of `spec` (through the polar cache), and
/// fits QPROP's law at each polar's Re with the others giving its Reynolds exponent.
pub fn section(spec: &SectionSpec, foil: &Airfoil, progress: &Progress) -> Result<SectionPolars> {
    spec.check()?;
    let xs = &spec.xfoil;
    let engine = super::polar_engine(&xs.process)?;
    let jobs: Vec<PolarJob> = spec
        .res
        .iter()
        .map(|&re| PolarJob {
            airfoil: foil.clone(),
            re,
            mach: spec.mach,
            section: xs.section(xfoil_runner::DEFAULT_PANELS),
        })
        .collect();
    let runs: Vec<(f64, std::result::Result<Polar, String>)> = jobs
        .iter()
        .zip(engine.compute_all(&jobs, progress))
        .map(|(job, r)| (job.re, r.map(|(p, _)| p).map_err(|e| e.to_string())))
        .collect();
    let polars: Vec<Polar> = runs.iter().filter_map(|(_, r)| r.as_ref().ok().cloned()).collect();
    let fits = polars
        .iter()
        .map(|p| {
            let fit = fit_qprop(&polars, p.re, &AlphaWeights::Uniform, DEFAULT_RE_EXP).map_err(|e| e.to_string());
            (p.re, fit)
        })
        .collect();
    Ok(SectionPolars {
        name: foil.name.clone(),
        runs,
        cache_error: engine.cache_error(),
        fits,
    })
}
