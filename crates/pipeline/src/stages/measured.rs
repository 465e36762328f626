//! The stages after the prediction: measurements read (every reader, the air they were
//! taken in), the comparison point by point, and the diagnosis.

use propbet_diagnose::provenance::Provenance;

use super::*;

// ---------------------------------------------------------------------------------------
// measurements, compare, diagnose

/// The measured files of a spec, each read or refused on its own.
#[derive(Debug, Clone)]
pub struct Batch {
    /// The air choice.
    pub air: AirChoice,
    /// Every series of every file read (a thrust-stand file of several powertrains gives one
    /// set per powertrain).
    pub sets: Vec<MeasuredSet>,
    /// Each set's name: its file, and its series when the file has several.
    pub names: Vec<String>,
    /// The files not read, with why.
    pub refused: Vec<Refused>,
}

/// Reads the measured files of a spec, each on its own: a file that cannot be read is
/// refused and named, the others read. An error for the command's own mistakes (a flag, a file
/// given twice, a column map) and when no file reads (then the only file's own error, or every
/// file's).
pub fn load_batch(spec: &MeasuredSpec) -> Result<Batch> {
    if let Some(p) = spec.poles {
        if p < 2 || p % 2 != 0 {
            out_of_range!("--poles {p}: a motor has an even number of poles, at least 2");
        }
    }
    if let Some(r) = spec.rho {
        let air = propbet_units::air::DENSITY;
        propbet_units::air::check("--rho", r, &air, "kg/m^3").map_err(Error::Range)?;
    }
    let air = AirChoice {
        given: spec.atmosphere,
        rho: spec.rho,
    };
    let column_map = spec.columns.as_deref().map(read_text).transpose()?;
    let opts = ReadOptions {
        poles: spec.poles,
        rpm_source: spec.rpm_source,
        column_map,
        ..Default::default()
    };
    // One file given twice would count its points twice (and cost a diagnosis its time).
    let mut seen: Vec<(PathBuf, &Path)> = Vec::new();
    for p in &spec.files {
        let real = std::fs::canonicalize(p).unwrap_or_else(|_| p.clone());
        if let Some((_, first)) = seen.iter().find(|(r, _)| *r == real) {
            return Err(Error::input(
                p,
                format!(
                    "given twice among the measured files (also as {}): each file once",
                    first.display()
                ),
            ));
        }
        seen.push((real, p));
    }
    let mut batch = Batch {
        air,
        sets: Vec::new(),
        names: Vec::new(),
        refused: Vec::new(),
    };
    let mut errors = Vec::new();
    for p in &spec.files {
        match read_measured(p, &opts) {
            Ok(sets) => {
                let several = sets.len() > 1;
                for s in sets {
                    batch.names.push(match (&s.series, several) {
                        (Some(series), true) => format!("{} [{series}]", p.display()),
                        _ => p.display().to_string(),
                    });
                    batch.sets.push(s);
                }
            }
            Err(e) => {
                batch.refused.push(Refused {
                    file: p.display().to_string(),
                    reason: match &e {
                        Error::Input { message, .. } => message.clone(),
                        e => e.to_string(),
                    },
                });
                errors.push(e);
            }
        }
    }
    if batch.sets.is_empty() {
        if errors.len() == 1 {
            return Err(errors.remove(0));
        }
        return Err(Error::Nothing(format!(
            "none of the {} measured files reads: {}",
            errors.len(),
            errors.iter().map(ToString::to_string).collect::<Vec<_>>().join("; ")
        )));
    }
    Ok(batch)
}

/// The operating points a prop's polars cover: its measured RPM range (three speeds, rounded
/// out to 100 rpm) with J from 0 to the largest measured, in steps of 0.05.
pub fn cover(measured: &MeasuredSpec) -> Result<(Vec<f64>, Vec<f64>)> {
    // The files that read (a refused one is the comparison's to report).
    let sets = load_batch(measured)?.sets;
    let points = sets.iter().flat_map(|s| &s.points);
    let (mut lo, mut hi, mut j_max) = (f64::INFINITY, 0.0f64, 0.0f64);
    for p in points {
        lo = lo.min(p.rpm());
        hi = hi.max(p.rpm());
        if let propbet_measure::Speed::AdvanceRatio(j) = p.speed {
            j_max = j_max.max(j);
        }
    }
    if !(lo.is_finite() && hi > 0.0) {
        return Err(Error::Nothing("no measured point to cover".into()));
    }
    let (lo, hi) = ((lo / 100.0).floor().max(1.0) * 100.0, (hi / 100.0).ceil() * 100.0);
    let rpms = vec![lo, (0.5 * (lo + hi) / 100.0).round() * 100.0, hi];
    let mut rpms: Vec<f64> = rpms.into_iter().map(propbet_bemt::units::rpm_to_omega).collect();
    rpms.dedup();
    let steps = (j_max / 0.05).ceil() as usize;
    let js = (0..=steps).map(|k| 0.05 * k as f64).collect();
    Ok((rpms, js))
}

/// Reads the measured files of a spec, every one of them: the air choice and the measured sets
/// (a file that cannot be read is the error).
pub fn load_measured(spec: &MeasuredSpec) -> Result<(AirChoice, Vec<MeasuredSet>)> {
    let batch = load_batch(spec)?;
    if let Some(r) = batch.refused.first() {
        return Err(Error::input(Path::new(&r.file), r.reason.clone()));
    }
    Ok((batch.air, batch.sets))
}

fn read_measured(path: &Path, opts: &ReadOptions) -> Result<Vec<MeasuredSet>> {
    let bytes = read_bytes(path)?;
    let opts = ReadOptions {
        name: path.file_name().map(|n| n.to_string_lossy().into_owned()),
        ..opts.clone()
    };
    propbet_measure::read_file(&bytes, &opts).map_err(|e| Error::input(path, e))
}

/// What the compare stage makes.
pub struct Compared {
    /// The measured sets as read.
    pub sets: Vec<MeasuredSet>,
    /// Each set's name ([`Batch::names`]).
    pub names: Vec<String>,
    /// The files not read.
    pub refused: Vec<Refused>,
    /// The air choice.
    pub air: AirChoice,
    /// Every point, measured and predicted.
    pub points: Vec<ComparedPoint>,
    /// Metrics by group.
    pub metrics: Metrics,
}

impl Compared {
    /// The model's curves through the measured points (`propbet_compare::curves`) and the
    /// uncertainty band along them, at every `band_every`-th of the curves' samples (1: at
    /// each; the workbench, which redraws on every change, takes fewer): what the comparison's
    /// figures draw.
    pub fn curves(
        &self,
        model: &Model,
        band_every: usize,
    ) -> Result<(propbet_compare::curves::Curves, propbet_compare::band::BandCurves)> {
        let setup = setup(model, self.air, model.effects.clone());
        let curves = propbet_compare::curves::curves(&setup, &self.points)?;
        let band = propbet_model::band::BandSpec::for_model(model).along_curves(
            model,
            self.air,
            &self.points,
            &curves.thinned(band_every),
        )?;
        Ok((curves, band))
    }

    /// Measurements that cannot be of this propeller (a warning, exit 1).
    pub fn mismatch(&self) -> Option<propbet_compare::plausible::Mismatch> {
        propbet_compare::plausible::of_points(&self.points)
    }

    /// Nothing to report: every file read, no faulty row, every station converged, every file
    /// a propeller's, measurements of this propeller's size.
    pub fn clean(&self) -> bool {
        self.problems() == (0, 0) && self.warnings().is_empty()
    }

    /// Every warning the terminal prints, as sentences: refused files, logs that cannot be a
    /// propeller's, measurements of another size (each makes the exit code 1).
    pub fn warnings(&self) -> Vec<String> {
        let mut out = batch_warnings(&self.names, &self.sets, &self.refused);
        if let Some(m) = self.mismatch() {
            out.push(m.message());
        }
        out
    }

    /// Rows dropped as faulty and stations that did not converge (all reported).
    pub fn problems(&self) -> (usize, usize) {
        (
            self.sets.iter().map(MeasuredSet::faults).sum(),
            self.points.iter().map(|p| p.not_converged).sum(),
        )
    }
}

/// The warnings of files read and refused: each refused file, each set's plausibility
/// warnings (named by `names`).
pub fn batch_warnings(names: &[String], sets: &[MeasuredSet], refused: &[Refused]) -> Vec<String> {
    let mut out: Vec<String> = refused
        .iter()
        .map(|r| format!("{}: not read: {}", r.file, r.reason))
        .collect();
    for (n, s) in names.iter().zip(sets) {
        out.extend(s.warnings.iter().map(|w| format!("{n}: {w}")));
    }
    out
}

/// Runs the compare stage on measurements read ([`load_batch`]; the workbench reads them once).
pub fn compare(
    model: &Model,
    Batch {
        air,
        sets,
        names,
        refused,
    }: Batch,
) -> Result<Compared> {
    let points = propbet_compare::compare(&setup(model, air, model.effects.clone()), &sets)?;
    let metrics = metrics(&points);
    Ok(Compared {
        names,
        refused,
        sets,
        air,
        points,
        metrics,
    })
}

/// What the diagnose stage makes.
pub struct Diagnosed {
    /// The measured sets as read.
    pub sets: Vec<MeasuredSet>,
    /// Each set's name ([`Batch::names`]).
    pub names: Vec<String>,
    /// The files not read.
    pub refused: Vec<Refused>,
    /// The air choice.
    pub air: AirChoice,
    /// The residual rows.
    pub data: Data,
    /// The diagnosis.
    pub diagnosis: Diagnosis,
}

/// Runs the diagnose stage.
pub fn diagnose(model: &Model, spec: &DiagnoseSpec) -> Result<Diagnosed> {
    diagnose_with(model, spec, true)
}

/// [`diagnose`], with the residuals' signatures before and after the ladder or without them
/// (`signatures`: what validate's held-out halves, which want the ladder alone, skip).
pub(crate) fn diagnose_with(model: &Model, spec: &DiagnoseSpec, signatures: bool) -> Result<Diagnosed> {
    // The command line's own mistakes are named before any file is read.
    let candidates = candidates(model, spec)?;
    let batch = load_batch(&spec.measured)?;
    diagnose_read(model, spec, candidates, batch, signatures)
}

/// [`diagnose_with`] of measurements already read (validate's held-out halves); `spec`'s
/// measured files are not read.
pub fn diagnose_sets(
    model: &Model,
    spec: &DiagnoseSpec,
    air: AirChoice,
    sets: Vec<MeasuredSet>,
    signatures: bool,
) -> Result<Diagnosed> {
    let candidates = candidates(model, spec)?;
    let names = (0..sets.len()).map(|k| format!("file {}", k + 1)).collect();
    let batch = Batch {
        air,
        sets,
        names,
        refused: Vec::new(),
    };
    diagnose_read(model, spec, candidates, batch, signatures)
}

/// The candidate effects `spec` names, less those already in the model's baseline.
pub fn candidates(model: &Model, spec: &DiagnoseSpec) -> Result<Vec<std::sync::Arc<dyn propbet_effects::Effect>>> {
    propbet_settings::FOLDS.check(spec.folds)?;
    let list: Vec<String> = spec
        .effects
        .iter()
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .collect();
    let mut candidates = model.registry.select(&list)?;
    candidates.retain(|c| !model.effects.active.iter().any(|a| a.effect.id() == c.id()));
    Ok(candidates)
}

/// What a diagnosis of `sets` runs on: their scored points (inside `spec`'s window) as residual
/// rows, the model as the diagnosis takes it (its own effects stay under the candidates), and
/// `spec`'s options.
pub fn diagnosis_inputs<'m>(
    model: &'m Model,
    spec: &DiagnoseSpec,
    air: AirChoice,
    sets: &[MeasuredSet],
    signatures: bool,
) -> Result<(Data, propbet_diagnose::Model<'m>, Options)> {
    let points = propbet_compare::compare(&setup(model, air, Stack::baseline()), sets)?;
    propbet_settings::WINDOW.check(spec.window)?;
    let data = Data::from_points(&points, spec.window)?;
    let dmodel = propbet_diagnose::Model {
        rotor: &model.rotor,
        opts: model.opts,
        diameter: model.diameter,
        fixed: model.effects.clone(),
    };
    let opts = Options {
        folds: spec.folds,
        max_steps: spec.max_steps,
        signatures,
        model_error: model_error(spec),
        ..Options::default()
    };
    Ok((data, dmodel, opts))
}

/// The default model's usual error on props of the kind `spec` diagnoses: validate's median
/// errors of the APC family that the prop file, its folder or a measured file names.
fn model_error(spec: &DiagnoseSpec) -> Option<propbet_diagnose::limits::ModelError> {
    let name = |p: &Path| p.file_name().and_then(|n| n.to_str()).map(str::to_string);
    let names: Vec<String> = std::iter::once(name(&spec.model.prop))
        .chain(std::iter::once(spec.model.prop.parent().and_then(name)))
        .chain(spec.measured.files.iter().map(|f| name(f)))
        .flatten()
        .collect();
    propbet_compare::expected::usual_error(names.iter().map(String::as_str)).map(|(thrust, torque, props, kind)| {
        propbet_diagnose::limits::ModelError {
            thrust,
            torque,
            props,
            kind,
        }
    })
}

/// The diagnosis of a batch of measurements read, over `candidates`.
fn diagnose_read(
    model: &Model,
    spec: &DiagnoseSpec,
    mut candidates: Vec<std::sync::Arc<dyn propbet_effects::Effect>>,
    Batch {
        air,
        sets,
        names,
        refused,
    }: Batch,
    signatures: bool,
) -> Result<Diagnosed> {
    // The files' provenance bounds some candidates (an optical RPM, a lab's own air).
    Provenance::of(&sets).narrow(&mut candidates);
    let (data, dmodel, opts) = diagnosis_inputs(model, spec, air, &sets, signatures)?;
    let diagnosis = discover(&dmodel, &data, &candidates, &opts)?;
    Ok(Diagnosed {
        names,
        refused,
        sets,
        air,
        data,
        diagnosis,
    })
}

/// Reads a QPROP output file (its printed sweep), naming the file in every error.
pub(crate) fn read_qprop_output(path: &Path) -> Result<propbet_qprop::output::QpropOutput> {
    let text = read_text(path)?;
    propbet_qprop::output::parse_output(&text).map_err(|e| Error::input(path, e))
}

/// Reads APC's predictions (a PER3 file), naming the file in every error.
pub fn read_per3(path: &Path) -> Result<propbet_qprop::apc::Per3> {
    let text = read_text(path)?;
    propbet_qprop::apc::read_per3(&text, &path.display().to_string()).map_err(|e| Error::input(path, e))
}
