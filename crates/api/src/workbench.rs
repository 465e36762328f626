//! The workbench's engine (`propbet serve`): a case read once (its model with the polars
//! computed, its measurements read), then any state of effects evaluated against the
//! measurements in memory, one effect fitted as the diagnosis fits it, the ladder run, and a
//! state saved as a case folder. The state is one JSON document spelled with a case file's
//! keys ([`State`]); what an evaluation returns is `compare`'s `summary.json` with the curves.

use std::path::{Path, PathBuf};

use propbet_compare::ComparedPoint;
use propbet_effects::Stack;
use propbet_model::Model;
use propbet_pipeline::stages::{self, Batch, Compared};
use propbet_settings::spec::{
    AirSpec, DiagnoseSpec, MeasuredSpec, ModelSpec, PredictSpec, SweepAxis, TableFormat, XfoilProcessSpec,
};
use propbet_simexport::{ExportFrom, ExportSpec, Target};
use serde::{Deserialize, Serialize};

use crate::command_error::refuse;
use crate::commands::predict::load_model_at;
use crate::console::Console;
use crate::{CommandError, CommandResult as Result};

/// The band is solved at every this-th of the curves' samples
/// ([`propbet_compare::curves::SAMPLES`] intervals: at a quarter of them), the page redrawing
/// on every change.
pub const BAND_EVERY: usize = 4;

/// Steps of J from 0 to 1 an export of a static log's state is predicted at.
const STATIC_J_STEPS: usize = 20;

/// The page's state: what a case file's keys hold that the page can change.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct State {
    /// The effects applied, as `--effect` writes them (`"pitch-offset:deg=-0.8"`).
    #[serde(default)]
    pub effects: Vec<String>,
}

/// A case read once, evaluated under any [`State`].
pub struct Workbench {
    /// The case's name.
    pub name: String,
    /// The case directory.
    pub dir: PathBuf,
    /// The model with the case's own effects (the state replaces them).
    model: Model,
    /// The measurements, read.
    batch: Batch,
    diagnose: DiagnoseSpec,
    /// The files the case reads (what Save copies).
    inputs: Vec<PathBuf>,
    /// The state the case starts from (its `effects`).
    pub start: State,
    /// Whether it was started from a case folder (Save writes one only then).
    pub from_case: bool,
}

/// One effect the page offers: its parameters with their bounds and expected range.
#[derive(Debug, Clone, Serialize)]
pub struct Offer {
    /// Effect id.
    pub id: String,
    /// What it models.
    pub explanation: String,
    /// Its parameters.
    pub params: Vec<propbet_effects::Param>,
}

impl Workbench {
    /// Reads the case in `dir` (None: the shipped default case): its model (polars computed
    /// or taken from the cache, as `run` computes them) and its measurements.
    pub fn open(dir: Option<&Path>, xfoil: &XfoilProcessSpec, anywhere: bool) -> Result<Self> {
        // Nothing is written: the plan's output folder only names where a run would write.
        let nowhere = std::env::temp_dir().join("propbet-serve-plan");
        let (dir, out) = crate::case::case_and_out(dir, Some(&nowhere))?;
        let plan = crate::case::plan(&dir, &out, xfoil)?;
        crate::case::check_paths(&plan, &dir, &out, anywhere)?;
        let Some((_, diagnose)) = plan.compare.clone() else {
            refuse!(
                "{}: the case has no [measured] files: the workbench compares a model with measurements",
                dir.join("case.toml").display()
            );
        };
        // The case run once as `run` runs it: its model (polars from the cache or XFOIL) and
        // its measurements as read.
        let outcome = propbet_pipeline::run::run_case(&plan, &propbet_polar::no_progress, &mut |_| {})?;
        let compared = outcome
            .compared
            .ok_or_else(|| CommandError::Message("the case compared nothing".into()))?;
        let batch = Batch {
            air: compared.air,
            sets: compared.sets,
            names: compared.names,
            refused: compared.refused,
        };
        let mut model = outcome.model;
        offer_user_effects(&mut model, &diagnose)?;
        let start = State {
            effects: plan.predict.model.effects.clone(),
        };
        Ok(Self {
            name: plan.name.clone(),
            dir,
            model,
            batch,
            diagnose,
            inputs: plan.inputs(),
            start,
            from_case: true,
        })
    }

    /// The workbench of `compare`'s flags: the blade of `model` (its polars made to cover the
    /// measurements, as `compare` makes them) against `measured`, the diagnosis at its
    /// defaults. Save needs a case folder and refuses such a workbench.
    pub fn of_specs(model: &ModelSpec, measured: &MeasuredSpec, console: &dyn Console) -> Result<Self> {
        let mut m = load_model_at(model, || crate::model::cover(measured), false, console)?;
        let batch = stages::load_batch(measured)?;
        if let Some(r) = batch.refused.first() {
            refuse!("{}: not read: {}", r.file, r.reason);
        }
        let diagnose = DiagnoseSpec {
            model: model.clone(),
            measured: measured.clone(),
            effects: vec!["all".into()],
            folds: propbet_settings::FOLDS.default,
            max_steps: propbet_settings::MAX_STEPS.default,
            window: propbet_compare::metrics::VALIDATION_J_WINDOW,
            out: std::env::temp_dir().join("propbet-serve-plan"),
        };
        offer_user_effects(&mut m, &diagnose)?;
        let name = model
            .prop
            .file_stem()
            .map_or_else(|| "propbet".into(), |n| n.to_string_lossy().into_owned());
        Ok(Self {
            name,
            dir: std::env::current_dir().map_err(|e| CommandError::io(".", e))?,
            start: State {
                effects: model.effects.clone(),
            },
            model: m,
            batch,
            diagnose,
            inputs: Vec::new(),
            from_case: false,
        })
    }

    /// Every effect the model knows (built-in and the case's user effects), with its
    /// parameters.
    pub fn offers(&self) -> Vec<Offer> {
        self.model
            .registry
            .effects
            .iter()
            .map(|e| Offer {
                id: e.id().to_string(),
                explanation: e.explanation().to_string(),
                params: e.params().to_vec(),
            })
            .collect()
    }

    /// The stack of `state`'s effects, each checked as `--effect` checks them (an unknown
    /// effect, a value out of its bounds, an effect given twice: the command line's error).
    pub fn stack(&self, state: &State) -> Result<Stack> {
        Ok(propbet_model::stack_of(
            &self.model.registry,
            &state.effects,
            "--effect",
        )?)
    }

    /// The model under `state`.
    fn model_at(&self, state: &State) -> Result<Model> {
        let mut m = self.model.clone();
        m.effects = self.stack(state)?;
        Ok(m)
    }

    /// Compares the model under `state` with the measurements, as `compare --effect` does.
    pub fn compare(&self, state: &State) -> Result<(Model, Compared)> {
        let m = self.model_at(state)?;
        let c = stages::compare(&m, self.batch.clone())?;
        Ok((m, c))
    }

    /// `compare`'s `summary.json` for `state`, with the curves, the band, the measured points
    /// and their errors (what the page draws).
    pub fn evaluate(&self, state: &State) -> Result<serde_json::Value> {
        let (m, c) = self.compare(state)?;
        let command = format!(
            "propbet compare {}",
            state
                .effects
                .iter()
                .map(|e| format!("--effect {e}"))
                .collect::<Vec<_>>()
                .join(" ")
        );
        let mut summary = propbet_report::compare::summary_json(
            command.trim(),
            &c.metrics,
            &c.points,
            c.problems(),
            &c.warnings(),
            None,
            None,
        );
        let (curves, band) = c.curves(&m, BAND_EVERY)?;
        if let serde_json::Value::Object(o) = &mut summary {
            o.insert("state".into(), serde_json::to_value(state)?);
            o.insert("curves".into(), curves_json(&curves, &band));
            o.insert("points_measured".into(), points_json(&c.points));
        }
        Ok(summary)
    }

    /// Fits the effect `id` alone on top of `state`'s other effects, as the diagnosis fits a
    /// candidate (its bounds narrowed by the files' provenance): its `--effect` spec, and the
    /// state with it in place of the one given.
    pub fn fit(&self, state: &State, id: &str) -> Result<(String, State)> {
        let mut others = State {
            effects: state
                .effects
                .iter()
                .filter(|e| e.split(':').next() != Some(id))
                .cloned()
                .collect(),
        };
        let m = self.model_at(&others)?;
        let mut candidates = m
            .registry
            .select(&[id.to_string()])
            .map_err(|e| CommandError::from(propbet_model::Error::from(e)))?;
        propbet_diagnose::provenance::Provenance::of(&self.batch.sets).narrow(&mut candidates);
        let (data, dmodel, _) = stages::diagnosis_inputs(&m, &self.diagnose, self.batch.air, &self.batch.sets, false)?;
        let start: Vec<f64> = candidates
            .iter()
            .flat_map(|c| c.params().iter().map(|p| p.start))
            .collect();
        let fitted = propbet_diagnose::fit::fit(&dmodel, &data, &candidates, &start)
            .map_err(|e| CommandError::from(propbet_model::Error::from(e)))?;
        let spec = fitted.stack.describe();
        others.effects.push(spec.clone());
        Ok((spec, others))
    }

    /// Runs the diagnosis' ladder on the measurements with `state`'s effects as the baseline:
    /// `diagnosis.json`'s document.
    pub fn diagnose(&self, state: &State) -> Result<serde_json::Value> {
        let m = self.model_at(state)?;
        let d = stages::diagnose_sets(&m, &self.diagnose, self.batch.air, self.batch.sets.clone(), true)?;
        Ok(serde_json::to_value(&d.diagnosis)?)
    }

    /// Writes a case folder `name` under `root` holding the case's files and its `case.toml`
    /// with `state`'s effects (`propbet run` on it gives the page's numbers); refused where
    /// the folder exists or the name is not one plain folder name. Returns the folder.
    pub fn save(&self, state: &State, root: &Path, name: &str) -> Result<PathBuf> {
        if !self.from_case {
            refuse!(
                "save: this workbench was started from compare's flags; Save writes a case folder from a case: \
                 start `propbet serve CASE_DIR`"
            );
        }
        self.stack(state)?;
        let (tmp, target) = new_folder(root, name, "save")?;
        for f in &self.inputs {
            let Ok(rel) = f.strip_prefix(&self.dir) else { continue };
            let to = tmp.path().join(rel);
            if let Some(parent) = to.parent() {
                std::fs::create_dir_all(parent).map_err(|e| CommandError::io(parent.display().to_string(), e))?;
            }
            std::fs::copy(f, &to).map_err(|e| CommandError::io(format!("save: copying {}", f.display()), e))?;
        }
        let case_file = self.dir.join("case.toml");
        let text = std::fs::read_to_string(&case_file)
            .map_err(|e| CommandError::io(format!("save: reading {}", case_file.display()), e))?;
        crate::files::write_atomic(
            &tmp.path().join("case.toml"),
            &[with_effects(&text, &state.effects)],
            &[case_file.as_path()],
        )?;
        name_folder(tmp, &target, "save")
    }

    /// Writes the flight-simulator files (Gazebo's motor model, PX4 SIH's parameters, a JSBSim
    /// propeller, the CT/CP map) of `state`'s prediction, its effects included, over the
    /// measurements' RPMs and advance ratios (a static log's: J from 0 to 1 in steps of 0.05),
    /// into a new folder `name` under `root`: what
    /// `propbet export --to all` writes of the same model and effects over those points (the
    /// air: the measurements' `--rho` or `--air` where given, else ISA sea level). Returns the
    /// folder and one line per export (its files and values).
    pub fn export(&self, state: &State, root: &Path, name: &str) -> Result<(PathBuf, Vec<String>)> {
        let model = self.model_at(state)?;
        let measured = &self.diagnose.measured;
        let (omegas, mut js) = stages::cover(measured)?;
        // A static log: forward flight over the J a small propeller's thrust reaches zero by
        // (the exports keep the points with thrust).
        if js.len() < 3 {
            js = (0..=STATIC_J_STEPS).map(|k| k as f64 / STATIC_J_STEPS as f64).collect();
        }
        let predict = PredictSpec {
            model: ModelSpec {
                effects: state.effects.clone(),
                ..self.diagnose.model.clone()
            },
            omegas,
            axis: SweepAxis::J(js),
            air: AirSpec {
                rho: measured.rho,
                mu: None,
                a: None,
                state: measured.atmosphere,
            },
            format: TableFormat::Csv,
            out: None,
            stations: None,
            band: false,
        };
        let spec = ExportSpec {
            from: ExportFrom::Prediction(predict.clone()),
            targets: Target::ALL.to_vec(),
            rpm_range: None,
            ixx: None,
            name: Some(self.name.clone()),
        };
        let exported = propbet_simexport::predicted_by(&model, &predict, &spec, &|_| {})
            .and_then(|src| propbet_simexport::exports_of(&src, &spec))
            .map_err(CommandError::from)?;
        let (tmp, target) = new_folder(root, name, "export")?;
        let mut lines = Vec::new();
        for e in &exported {
            for (file, text) in &e.files {
                crate::files::write_atomic(&tmp.path().join(file), &[text.as_bytes()], &[])?;
            }
            let files: Vec<&str> = e.files.iter().map(|f| f.0.as_str()).collect();
            lines.push(format!("{}: {}: {}", e.target.name(), files.join(", "), e.values));
        }
        Ok((name_folder(tmp, &target, "export")?, lines))
    }
}

/// A temporary folder under `root` that becomes `root/name` once complete ([`name_folder`]);
/// refused where `name` is not one plain folder name or the folder exists (`what`: the
/// action, in the message).
fn new_folder(root: &Path, name: &str, what: &str) -> Result<(tempfile::TempDir, PathBuf)> {
    let plain = !name.is_empty()
        && name.len() <= 100
        && name != "."
        && name != ".."
        && name.chars().all(|c| c.is_ascii_alphanumeric() || "-_.".contains(c));
    if !plain {
        refuse!("{what}: {name:?} is not a plain folder name (letters, digits, '-', '_', '.')");
    }
    let target = root.join(name);
    if target.exists() {
        refuse!("{what}: {} exists; nothing was written", target.display());
    }
    let tmp = tempfile::Builder::new()
        .prefix(".propbet-save-")
        .tempdir_in(root)
        .map_err(|e| CommandError::io(root.display().to_string(), e))?;
    Ok((tmp, target))
}

/// Names the complete folder `tmp` as `target`: a folder that cannot be named is removed with
/// its files.
fn name_folder(tmp: tempfile::TempDir, target: &Path, what: &str) -> Result<PathBuf> {
    let kept = tmp.keep();
    if let Err(e) = std::fs::rename(&kept, target) {
        let _ = std::fs::remove_dir_all(&kept);
        return Err(CommandError::io(format!("{what}: naming {}", target.display()), e));
    }
    Ok(target.to_path_buf())
}

/// The user effects the diagnosis of `diagnose` reads (a case's `[measured] user_effects`,
/// `--user-effects`), offered beside the built-ins.
fn offer_user_effects(model: &mut Model, diagnose: &DiagnoseSpec) -> Result<()> {
    if let Some(file) = &diagnose.model.user_effects {
        for e in propbet_model::effect_registry(Some(file))?.effects {
            if model.registry.get(e.id()).is_none() {
                model.registry.effects.push(e);
            }
        }
    }
    Ok(())
}

/// `text` (a case.toml) with its top-level `effects` key set to `effects`: a line of its own
/// before the first table (one written there before is replaced).
pub fn with_effects(text: &str, effects: &[String]) -> String {
    let line = format!(
        "effects = [{}]",
        effects
            .iter()
            .map(|e| format!("{:?}", e))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let mut out = Vec::new();
    let mut placed = false;
    for l in text.lines() {
        let top = !placed;
        if top && l.trim_start().starts_with("effects") && l.contains('=') {
            continue;
        }
        if top && l.trim_start().starts_with('[') {
            out.push(line.clone());
            out.push(String::new());
            placed = true;
        }
        out.push(l.to_string());
    }
    if !placed {
        out.push(line);
    }
    let mut s = out.join("\n");
    s.push('\n');
    s
}

/// The model's curves and band as the page draws them: per J sweep its speed, (J, CT, CP,
/// thrust, torque) and the band of CT and CP on its own grid; the static curve against RPM
/// likewise.
fn curves_json(
    curves: &propbet_compare::curves::Curves,
    band: &propbet_compare::band::BandCurves,
) -> serde_json::Value {
    let num = |x: Option<f64>| x.filter(|v| v.is_finite());
    let rows = |c: &propbet_compare::curves::Curve| {
        c.iter()
            .map(|(x, q)| {
                serde_json::json!({
                    "x": x, "ct": num(q.ct), "cp": num(q.cp), "thrust": num(q.thrust), "torque": num(q.torque),
                })
            })
            .collect::<Vec<_>>()
    };
    let band_rows = |b: Option<&propbet_compare::band::BandCurve>| {
        b.map(|b| {
            b.iter()
                .map(|(x, p)| {
                    serde_json::json!({"x": x, "ct_lo": p.ct.lo, "ct_hi": p.ct.hi, "cp_lo": p.cp.lo, "cp_hi": p.cp.hi})
                })
                .collect::<Vec<_>>()
        })
        .unwrap_or_default()
    };
    let sweeps: Vec<serde_json::Value> = curves
        .j_sweeps
        .iter()
        .enumerate()
        .filter_map(|(k, s)| {
            let (rpm, c) = s.as_ref()?;
            let b = band.j_sweeps.get(k).and_then(Option::as_ref);
            Some(serde_json::json!({"rpm": rpm, "rows": rows(c), "band": band_rows(b)}))
        })
        .collect();
    let statics = curves
        .statics
        .as_ref()
        .map(|c| serde_json::json!({"rows": rows(c), "band": band_rows(band.statics.as_ref())}));
    serde_json::json!({"j_sweeps": sweeps, "statics": statics})
}

/// `scored`: inside the window validate scores (below 85 % of the sweep's zero-thrust J) and
/// not flagged.
fn points_json(points: &[ComparedPoint]) -> serde_json::Value {
    let window = propbet_compare::metrics::in_window(points, propbet_compare::metrics::VALIDATION_J_WINDOW);
    let rel = |p: Option<f64>, m: Option<f64>| match (p, m) {
        (Some(p), Some(m)) if m.abs() > 0.0 => Some(p / m - 1.0),
        _ => None,
    };
    points
        .iter()
        .zip(window)
        .map(|(p, inside)| {
            serde_json::json!({
                "rpm": p.rpm, "j": p.j, "static": p.is_static(),
                "scored": inside && p.scored(),
                "ct": p.measured.ct, "cp": p.measured.cp,
                "thrust": p.measured.thrust, "torque": p.measured.torque,
                "ct_model": p.predicted.ct, "cp_model": p.predicted.cp,
                "ct_error": rel(p.predicted.ct, p.measured.ct),
                "cp_error": rel(p.predicted.cp, p.measured.cp),
            })
        })
        .collect::<Vec<_>>()
        .into()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_case_file_gets_its_effects_before_its_first_table_and_keeps_the_rest() {
        let text = "# a case\nname = \"x\"\neffects = [\"old:a=1\"]\n\n[geometry]\npe0 = \"f\"\n";
        let out = with_effects(text, &["pitch-offset:deg=-0.8".into()]);
        assert_eq!(
            out,
            "# a case\nname = \"x\"\n\neffects = [\"pitch-offset:deg=-0.8\"]\n\n[geometry]\npe0 = \"f\"\n"
        );
        let parsed: toml::Value = toml::from_str(&out).unwrap();
        assert_eq!(parsed["effects"][0].as_str(), Some("pitch-offset:deg=-0.8"));
        assert!(with_effects("name = \"x\"\n", &[]).ends_with("effects = []\n"));
    }
}
