//! `run_case`: a case's plan of stages run in memory, each stage handed the artifacts of the
//! ones before it, returning every artifact; the caller writes the files.

use propbet_model::solve;
use std::time::Instant;

use propbet_bemt::{Fluid, PointResult};

use crate::case::RunPlan;
use crate::stages::{self, Compared, Diagnosed, Polars, PolarsInput, Scanned};
use crate::{Error, Result};
use propbet_model::{LoadedProp, Model};
use propbet_settings::spec::StageSpec;

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
    /// The sweeps, and the QPROP file that carries them (or why there is none).
    Predict(
        &'a [PointResult],
        &'a Model,
        &'a std::result::Result<propbet_qprop::export::QpropExport, String>,
    ),
    /// The propeller on its motor, with the model and the air of the sweeps.
    Powered(&'a stages::PoweredTable, &'a Model, &'a (Fluid, String)),
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
    /// The calibrated model's scores at the measured points (the prediction with the
    /// diagnosis's effects), where the diagnosis found effects.
    pub calibrated: Option<propbet_compare::metrics::Metrics>,
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
    /// The QPROP file fitted to carry the sweeps' prediction (or why there is none).
    pub qprop_export: std::result::Result<propbet_qprop::export::QpropExport, String>,
    /// The propeller on its motor (cases with `[motor]` and a driver).
    pub powered: Option<stages::PoweredTable>,
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

/// Runs one stage without events: its command, time and whether it ran clean (`clean` of its
/// result) go into `records`.
pub fn timed<T>(
    records: &mut Vec<StageRecord>,
    spec: StageSpec,
    run: impl FnOnce() -> Result<T>,
    clean: impl Fn(&T) -> bool,
) -> Result<T> {
    let t0 = Instant::now();
    let out = run()?;
    records.push(StageRecord {
        clean: clean(&out),
        spec,
        seconds: t0.elapsed().as_secs_f64(),
    });
    Ok(out)
}

/// The stages' bookkeeping: numbering, timing, records, and the events the caller hears.
struct Book<'o> {
    on: &'o mut dyn for<'a> FnMut(Event<'a>),
    records: Vec<StageRecord>,
    total: usize,
}

impl Book<'_> {
    /// A stage starts.
    fn start(&mut self, spec: StageSpec) -> (StageSpec, Instant) {
        let n = self.records.len() + 1;
        (self.on)(Event::Start {
            n,
            total: self.total,
            spec: &spec,
        });
        (spec, Instant::now())
    }

    /// It finished, clean or with reported problems, having made `made`.
    fn done(&mut self, (spec, t0): (StageSpec, Instant), clean: bool, made: Finished) {
        self.records.push(StageRecord {
            spec,
            seconds: t0.elapsed().as_secs_f64(),
            clean,
        });
        (self.on)(Event::Done {
            n: self.records.len(),
            total: self.total,
            record: self.records.last().expect("pushed"),
            made,
        });
    }
}

/// Runs a plan. `progress` is the XFOIL stage's (jobs done, jobs in all); `on` hears each
/// stage start and finish.
pub fn run_case(
    plan: &RunPlan,
    progress: &propbet_polar::Progress<'_>,
    on: &mut dyn FnMut(Event),
) -> Result<RunOutcome> {
    let mut book = Book {
        on,
        records: Vec::new(),
        total: plan.stages().len() + 1,
    };
    let stage_err = |name: &str, e: Error| Error::about(format!("{name} stage"), e);

    // 1. Geometry.
    let mut scanned = None;
    let mut geometry: Option<LoadedProp> = None;
    if let Some(spec) = &plan.scan {
        let t = book.start(StageSpec::Scan(spec.clone()));
        let r = stages::scan(spec).map_err(|e| stage_err("scan", e))?;
        if let Some(want) = plan.blades {
            if want != r.geometry.blades {
                return Err(Error::input(
                    plan.dir.join("case.toml"),
                    format!("case.toml says {want} blades, the scan found {}", r.geometry.blades),
                ));
            }
        }
        book.done(t, r.clean(), Finished::Scan(&r));
        geometry = Some(r.prop.clone());
        scanned = Some(r);
    }

    // 2. Polars.
    let mut polars = None;
    if let Some((spec, scanned_sections)) = &plan.polars {
        let t = book.start(StageSpec::Polars(spec.clone()));
        let run = || -> Result<(Polars, PolarsInput)> {
            // A scan's blade and sections are in memory; any other blade file is read as the
            // polars command reads it.
            let input = match &geometry {
                None => stages::polars_input(spec)?,
                Some(geometry) => scan_input(spec, geometry, *scanned_sections, scanned.as_ref())?,
            };
            let engine = stages::polar_engine(&spec.xfoil.process)?;
            Ok((stages::polars(spec, &input, &engine, progress)?, input))
        };
        let (p, input) = run().map_err(|e| stage_err("polars", e))?;
        book.done(
            t,
            p.clean_for(plan.predict.model.polars.is_some()),
            Finished::Polars(&p, &input),
        );
        polars = Some(p);
    }

    // 3. Sweeps: the polars' prop file in memory, else the case's own.
    let spec = &plan.predict;
    let t = book.start(StageSpec::Predict(spec.clone()));
    let build = |m: &propbet_settings::spec::ModelSpec| match &polars {
        Some(p) => Model::from_parts(m, p.prop.clone(), Some(&p.blade), false),
        None => Model::load(m, false),
    };
    let model = build(&spec.model).map_err(|e| stage_err("predict", e))?;
    let fluid = spec.air.fluid().map_err(|e| stage_err("predict", e.into()))?;
    let points = solve::operating_points(spec, model.rotor.tip_radius).map_err(|e| stage_err("predict", e))?;
    let sweep = solve::sweep(&model, &fluid.0, &points).map_err(|e| stage_err("predict", e))?;
    let clean = sweep.iter().all(|p| p.not_converged == 0);
    let qprop_export = propbet_qprop::export::qprop_export(
        propbet_qprop::export::Model {
            rotor: &model.rotor,
            opts: model.opts,
            file: &model.loaded.file,
        },
        &fluid.0,
        &points,
        &plan.name,
        propbet_compare::metrics::VALIDATION_J_WINDOW,
    )
    .map_err(|e| e.to_string());
    book.done(t, clean, Finished::Predict(&sweep, &model, &qprop_export));

    // 3b. On the motor: the sweeps' model and air.
    let mut powered = None;
    if let Some(spec) = &plan.powered {
        let t = book.start(StageSpec::Powered(spec.clone()));
        let p = stages::powered_stage(&model, &fluid.0, spec).map_err(|e| stage_err("motor", e))?;
        book.done(t, p.clean(), Finished::Powered(&p, &model, &fluid));
        powered = Some(p);
    }

    // 4-5. Comparison and diagnosis.
    let (compared, diagnosed) = match &plan.compare {
        Some(specs) => {
            let (c, d) = compare_and_diagnose(specs, &model, &build, &mut book)?;
            (Some(c), Some(d))
        }
        None => (None, None),
    };
    Ok(RunOutcome {
        calibrated: calibrated(&model, compared.as_ref(), diagnosed.as_ref()),
        scanned,
        polars,
        model,
        fluid,
        sweep,
        qprop_export,
        powered,
        compared,
        diagnosed,
        stages: book.records,
    })
}

/// The compare and diagnose stages of a case, in `book`; `build` makes the diagnosis's own
/// model where the case gives it user effects.
fn compare_and_diagnose(
    (cspec, dspec): &(
        propbet_settings::spec::CompareSpec,
        propbet_settings::spec::DiagnoseSpec,
    ),
    model: &Model,
    build: &dyn Fn(&propbet_settings::spec::ModelSpec) -> Result<Model>,
    book: &mut Book<'_>,
) -> Result<(Compared, Diagnosed)> {
    let stage_err = |name: &str, e: Error| Error::about(format!("{name} stage"), e);
    let t = book.start(StageSpec::Compare(cspec.clone()));
    let compare = |b| stages::compare(model, b);
    let c = stages::load_batch(&cspec.measured)
        .and_then(compare)
        .map_err(|e| stage_err("compare", e))?;
    book.done(t, c.clean(), Finished::Compare(&c, model));
    let t = book.start(StageSpec::Diagnose(dspec.clone()));
    // The case's user effects (`[measured] user_effects`) are the diagnosis's alone.
    let d = match dspec.model.user_effects {
        Some(_) => build(&dspec.model).and_then(|m| stages::diagnose(&m, dspec)),
        None => stages::diagnose(model, dspec),
    }
    .map_err(|e| stage_err("diagnose", e))?;
    book.done(t, true, Finished::Diagnose(&d));
    Ok((c, d))
}

/// The polars stage's inputs from a scan's blade in memory: each station's scanned section
/// (`scanned_sections`), or the spec's airfoil at every station.
fn scan_input(
    spec: &propbet_settings::spec::PolarsSpec,
    geometry: &LoadedProp,
    scanned_sections: bool,
    scanned: Option<&Scanned>,
) -> Result<PolarsInput> {
    let (foil, mut notes) = stages::spec_airfoil(spec)?;
    let foils = match (scanned_sections, scanned, &spec.station_airfoils) {
        (true, Some(sc), Some(dir)) => {
            let mut texts = vec![None; geometry.file.rows.len()];
            for (i, t) in &sc.airfoils {
                if *i < texts.len() {
                    texts[*i] = Some((dir.join(format!("station_{i:02}.dat")), t.clone()));
                }
            }
            stages::station_foils(dir, texts, foil.as_ref(), &mut notes)?
        }
        _ => vec![foil
            .clone()
            .ok_or_else(|| crate::Error::Conflict("[polars] airfoil: the section of every station".into()))?],
    };
    Ok(PolarsInput {
        geometry: geometry.clone(),
        foils,
        foil_name: stages::foil_name(foil.as_ref()),
        notes,
    })
}

/// The calibrated model (the prediction with the diagnosis's effects) scored at the measured
/// points: where it is worse than the prediction, the report says so.
fn calibrated(
    model: &Model,
    compared: Option<&Compared>,
    diagnosed: Option<&Diagnosed>,
) -> Option<propbet_compare::metrics::Metrics> {
    let (c, d) = (compared?, diagnosed?);
    if !d.diagnosis.found {
        return None;
    }
    let setup = solve::setup(model, c.air, d.diagnosis.final_stack.clone());
    propbet_compare::compare(&setup, &c.sets)
        .ok()
        .map(|p| propbet_compare::metrics::metrics(&p))
}
