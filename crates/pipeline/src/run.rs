//! `run_case`: a case's plan of stages run in memory, each stage handed the artifacts of the
//! ones before it, returning every artifact; the caller writes the files.

use std::time::Instant;

use propbet_bemt::{Fluid, PointResult};

use crate::case::RunPlan;
use crate::model::{LoadedProp, Model};
use crate::spec::StageSpec;
use crate::stages::{self, Compared, Diagnosed, Polars, PolarsInput, Scanned};
use crate::{Error, Result};

/// A stage that has run.
#[derive(Debug, Clone)]
pub struct StageRecord {
    /// What it was asked (its command line).
    pub spec: StageSpec,
    /// Wall time [s].
    pub seconds: f64,
    /// Ran without reported problems.
    pub clean: bool,
}

/// What a finished stage made, for the caller to report as it goes.
pub enum Finished<'a> {
    /// The scan.
    Scan(&'a Scanned),
    /// The polars, with their inputs.
    Polars(&'a Polars, &'a PolarsInput),
    /// The sweeps.
    Predict(&'a [PointResult], &'a Model),
    /// The comparison, with the model it was made with.
    Compare(&'a Compared, &'a Model),
    /// The diagnosis.
    Diagnose(&'a Diagnosed),
}

/// Progress of a run.
pub enum Event<'a> {
    /// Stage `n` of `total` starts.
    Start {
        /// 1-based.
        n: usize,
        /// Stages in all (the report included).
        total: usize,
        /// The stage.
        spec: &'a StageSpec,
    },
    /// It finished.
    Done {
        /// 1-based.
        n: usize,
        /// Stages in all.
        total: usize,
        /// The record.
        record: &'a StageRecord,
        /// What it made.
        made: Finished<'a>,
    },
}

/// Everything a run made.
pub struct RunOutcome {
    /// The scan (cases with a scan).
    pub scanned: Option<Scanned>,
    /// The polars (cases with `[polars]`).
    pub polars: Option<Polars>,
    /// The model of the sweeps and the comparison.
    pub model: Model,
    /// The air of the sweeps, and where it came from.
    pub fluid: (Fluid, String),
    /// The sweeps.
    pub sweep: Vec<PointResult>,
    /// The comparison (cases with measurements).
    pub compared: Option<Compared>,
    /// The diagnosis (cases with measurements).
    pub diagnosed: Option<Diagnosed>,
    /// The stages in order.
    pub stages: Vec<StageRecord>,
}

impl RunOutcome {
    /// Every stage ran clean.
    pub fn clean(&self) -> bool {
        self.stages.iter().all(|s| s.clean)
    }
}

/// Runs a plan. `progress` is the XFOIL stage's (jobs done, jobs in all); `on` hears each
/// stage start and finish.
pub fn run_case(
    plan: &RunPlan,
    progress: &propbet_polar::Progress<'_>,
    on: &mut dyn FnMut(Event),
) -> Result<RunOutcome> {
    let specs = plan.stages();
    let total = specs.len() + 1;
    let mut records: Vec<StageRecord> = Vec::new();
    let mut n = 0;
    let mut start = |spec: &StageSpec, on: &mut dyn FnMut(Event)| {
        n += 1;
        on(Event::Start { n, total, spec });
        (n, Instant::now())
    };
    let record = |spec: &StageSpec, t0: Instant, clean: bool| StageRecord {
        spec: spec.clone(),
        seconds: t0.elapsed().as_secs_f64(),
        clean,
    };
    let stage_err = |name: &str, e: Error| Error::Invalid(format!("{name} stage: {e}"));
    let mut it = specs.iter();

    // 1. Geometry.
    let mut scanned = None;
    let mut geometry: Option<LoadedProp> = None;
    if let Some(spec) = &plan.scan {
        let s = it.next().expect("the scan stage");
        let (k, t0) = start(s, on);
        let r = stages::scan(spec).map_err(|e| stage_err("scan", e))?;
        if let Some(want) = plan.blades {
            if want != r.geometry.blades {
                return Err(Error::input(
                    plan.dir.join("case.toml"),
                    format!("case.toml says {want} blades, the scan found {}", r.geometry.blades),
                ));
            }
        }
        records.push(record(s, t0, true));
        on(Event::Done {
            n: k,
            total,
            record: records.last().expect("pushed"),
            made: Finished::Scan(&r),
        });
        geometry = Some(r.prop.clone());
        scanned = Some(r);
    }

    // 2. Polars.
    let mut polars = None;
    if let Some((spec, scanned_sections)) = &plan.polars {
        let s = it.next().expect("the polars stage");
        let (k, t0) = start(s, on);
        let run = || -> Result<(Polars, PolarsInput)> {
            let (foil, mut notes) = stages::load_airfoil(&spec.airfoil, spec.thickness)?;
            let geometry = match &geometry {
                Some(g) => g.clone(),
                None => crate::model::load_prop(&spec.geometry, spec.units)?,
            };
            let foils = match (scanned_sections, &scanned, &spec.station_airfoils) {
                (true, Some(sc), Some(dir)) => {
                    let mut texts = vec![None; geometry.file.rows.len()];
                    for (i, t) in &sc.airfoils {
                        if *i < texts.len() {
                            texts[*i] = Some((dir.join(format!("station_{i:02}.dat")), t.clone()));
                        }
                    }
                    stages::station_foils(dir, texts, &foil, &mut notes)?
                }
                _ => vec![foil.clone()],
            };
            let input = PolarsInput {
                geometry,
                foils,
                foil_name: foil.name.clone(),
                notes,
            };
            let engine = stages::polar_engine(&spec.xfoil.process)?;
            Ok((stages::polars(spec, &input, &engine, progress)?, input))
        };
        let (p, input) = run().map_err(|e| stage_err("polars", e))?;
        records.push(record(s, t0, p.all_fitted()));
        on(Event::Done {
            n: k,
            total,
            record: records.last().expect("pushed"),
            made: Finished::Polars(&p, &input),
        });
        polars = Some(p);
    }

    // 3. Sweeps: the polars' prop file in memory, else the case's own.
    let spec = &plan.predict;
    let s = it.next().expect("the predict stage");
    let (k, t0) = start(s, on);
    let model = match &polars {
        Some(p) => Model::from_parts(&spec.model, p.prop.clone(), Some(&p.blade), false),
        None => Model::load(&spec.model, false),
    }
    .map_err(|e| stage_err("predict", e))?;
    let fluid = spec.air.fluid().map_err(|e| stage_err("predict", e))?;
    let points = stages::operating_points(spec, model.rotor.tip_radius).map_err(|e| stage_err("predict", e))?;
    let sweep = stages::sweep(&model, &fluid.0, &points).map_err(|e| stage_err("predict", e))?;
    records.push(record(s, t0, sweep.iter().all(|p| p.not_converged == 0)));
    on(Event::Done {
        n: k,
        total,
        record: records.last().expect("pushed"),
        made: Finished::Predict(&sweep, &model),
    });

    // 4-5. Comparison and diagnosis.
    let (mut compared, mut diagnosed) = (None, None);
    if let Some((cspec, dspec)) = &plan.compare {
        let s = it.next().expect("the compare stage");
        let (k, t0) = start(s, on);
        let c = stages::compare(&model, &cspec.measured).map_err(|e| stage_err("compare", e))?;
        records.push(record(s, t0, c.problems() == (0, 0)));
        on(Event::Done {
            n: k,
            total,
            record: records.last().expect("pushed"),
            made: Finished::Compare(&c, &model),
        });
        compared = Some(c);
        let s = it.next().expect("the diagnose stage");
        let (k, t0) = start(s, on);
        let d = stages::diagnose(&model, dspec).map_err(|e| stage_err("diagnose", e))?;
        records.push(record(s, t0, true));
        on(Event::Done {
            n: k,
            total,
            record: records.last().expect("pushed"),
            made: Finished::Diagnose(&d),
        });
        diagnosed = Some(d);
    }
    Ok(RunOutcome {
        scanned,
        polars,
        model,
        fluid,
        sweep,
        compared,
        diagnosed,
        stages: records,
    })
}
