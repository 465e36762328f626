//! A propeller's model, as every stage of the pipeline solves it: a prop file read and
//! discretised ([`Model`]), optionally with tabulated polars as the section model and effects on
//! top; the blade files other than QPROP's it is read from ([`design`]: APC's PE0, UIUC tables,
//! blade tables); its solves at operating points ([`solve`]); its uncertainty band ([`band`]);
//! and the error of reading and running it ([`Error`], the pipeline's).
#![deny(missing_docs)]

#[macro_use]
mod error;
pub mod band;
pub mod design;
pub mod solve;

pub use error::{read_bytes, read_text, read_titled_text, Error, Result};

use std::path::Path;

use propbet_bemt::{Discretization, Rotor, SolverOptions};
use propbet_effects::spec::Registry;
use propbet_effects::{parse_spec, Stack};
use propbet_qprop::{parse_prop, PropFile, RadiusReading};

use propbet_settings::spec::ModelSpec;

/// A prop file read and checked, with its warnings (each naming the file).
#[derive(Debug, Clone)]
pub struct LoadedProp {
    /// The file as written.
    pub file: PropFile,
    /// Warnings for the user.
    pub warnings: Vec<String>,
}

/// Reads a prop file, naming the file in every error; `units` [m per unit] replaces its Rfac
/// and Cfac.
pub fn load_prop(path: &Path, units: Option<f64>) -> Result<LoadedProp> {
    let text = crate::error::read_titled_text(path).map_err(|e| match e {
        Error::Input { path, message } => Error::input(path, format!("{message} (is it a QPROP prop file?)")),
        e => e,
    })?;
    prop_from_text(&text, path, units)
}

/// A prop file's text, read as [`load_prop`] reads the file `path`.
pub(crate) fn prop_from_text(text: &str, path: &Path, units: Option<f64>) -> Result<LoadedProp> {
    let (mut file, warnings) = parse_prop(text).map_err(|e| Error::input(path, e))?;
    let mut warnings: Vec<String> = warnings
        .into_iter()
        .map(|w| match w.line {
            0 => format!("{}: {}", path.display(), w.message),
            l => format!("{}: line {l}: {}", path.display(), w.message),
        })
        .collect();
    if let Some(f) = units {
        warnings.push(format!(
            "{}: --units {} replaces the file's Rfac = {} and Cfac = {} with {f}",
            path.display(),
            propbet_settings::values::length_unit_name(f).unwrap_or("?"),
            file.scale[0],
            file.scale[1]
        ));
        file.scale[0] = f;
        file.scale[1] = f;
    }
    Ok(LoadedProp { file, warnings })
}

/// A prop file as the file `propbet` writes for it holds it: written and read back, so that
/// a stage that passes it on in memory computes exactly what the equivalent command, reading
/// the file, computes.
pub fn as_written(file: &PropFile, path: &Path) -> Result<LoadedProp> {
    prop_from_text(&propbet_qprop::write_prop(file), path, None)
}

/// A model ready to solve.
#[derive(Clone)]
pub struct Model {
    /// The prop file as read.
    pub loaded: LoadedProp,
    /// The rotor the solver sees.
    pub rotor: Rotor,
    /// Solver options.
    pub opts: SolverOptions,
    /// Propeller diameter of the blade as documented (2 x its last station radius, or line 2's
    /// R in the table's units) [m]: the D of the coefficients even when `qprop_compat` gives
    /// the tip-loss factor QPROP's unscaled R.
    pub diameter: f64,
    /// The effects known (built-in and user-defined).
    pub registry: Registry,
    /// The effects added to the model.
    pub effects: Stack,
    /// The uncertainty band's section-model source: the tables at the band's two ends (early
    /// and late transition, `propbet_polar::blade::BAND_ENDS`, keyed by their Ncrit) as a
    /// `transition` effect kept out of the registry (never a diagnosis candidate). None
    /// without tables that carry them.
    pub band_sections: Option<std::sync::Arc<dyn propbet_effects::Effect>>,
}

impl Model {
    /// Reads the spec's prop file (and polars, user effects) and builds the rotor.
    pub fn load(spec: &ModelSpec, keep_stations: bool) -> Result<Model> {
        let loaded = load_prop(&spec.prop, spec.units)?;
        Model::from_loaded(spec, loaded, keep_stations)
    }

    /// Builds the model from a prop file already read (the spec's `prop` names it in messages).
    pub fn from_loaded(spec: &ModelSpec, loaded: LoadedProp, keep_stations: bool) -> Result<Model> {
        Model::from_parts(spec, loaded, None, keep_stations)
    }

    /// Builds the model from a prop file and, where the spec names a polars file, the polars
    /// already in memory (`polars`, the content of that file); None reads the file.
    pub fn from_parts(
        spec: &ModelSpec,
        mut loaded: LoadedProp,
        polars: Option<&propbet_polar::BladePolars>,
        keep_stations: bool,
    ) -> Result<Model> {
        let differences: Vec<String> = loaded.file.qprop_differences().into_iter().map(|w| w.message).collect();
        for w in &mut loaded.warnings {
            if differences.iter().any(|d| w.ends_with(d.as_str())) {
                w.push_str(if spec.qprop_compat {
                    " (reproduced as QPROP reads it: --qprop-compat)"
                } else {
                    " (--qprop-compat reproduces QPROP)"
                });
            }
        }
        let reading = if spec.qprop_compat {
            RadiusReading::Qprop122
        } else {
            RadiusReading::Documented
        };
        let mut rotor = loaded
            .file
            .to_blade(reading)
            .to_rotor(Discretization {
                stations: 25,
                qprop_reref_quirk: spec.qprop_compat,
            })
            .map_err(|e| Error::input(&spec.prop, e))?;
        let read;
        let blade = match (&spec.polars, polars) {
            (Some(_), Some(blade)) => Some(blade),
            (Some(path), None) => {
                let text = read_text(path)?;
                read = propbet_polar::BladePolars::from_json(&text).map_err(|e| Error::input(path, e))?;
                Some(&read)
            }
            (None, _) => None,
        };
        let (mut transition, mut band_sections) = (None, None);
        if let (Some(path), Some(blade)) = (&spec.polars, blade) {
            // The tables at the polars' own Ncrit, built once: the rotor's, and the base of
            // both `transition` effects.
            let base = blade.models().map_err(|e| Error::input(path, e))?;
            tabulate(&mut rotor, &base, path)?;
            transition = transition_effect(blade, &base, path, &blade.other_ncrits(), |n| blade.models_at_ncrit(n))?;
            let band: Vec<f64> = propbet_polar::blade::BAND_NCRIT
                .into_iter()
                .filter(|&n| blade.stations.iter().any(|s| s.band.iter().any(|p| p.ncrit == n)))
                .collect();
            band_sections = transition_effect(blade, &base, path, &band, |n| blade.band_models(n))?;
        }
        propbet_settings::DRAG_FACTOR.check(spec.drag_factor)?;
        let rotor = rotor
            .with_rotational_augmentation(spec.rotation.coefficient())
            .with_drag_factor(spec.drag_factor);
        if !spec.dbeta.is_finite() {
            out_of_range!("--dbeta: not a finite number");
        }
        let opts = SolverOptions {
            tip_loss: !spec.no_tip_loss,
            dbeta: spec.dbeta,
            keep_stations,
            ..SolverOptions::default()
        };
        let diameter = 2.0 * loaded.file.tip_radius(RadiusReading::Documented);
        let mut registry = effect_registry(spec.user_effects.as_deref())?;
        registry.effects.extend(transition);
        let effects = stack_of(&registry, &spec.effects, "--effect")?;
        Ok(Model {
            loaded,
            rotor,
            opts,
            diameter,
            registry,
            effects,
            band_sections,
        })
    }
}

/// The stack of effects written as `--effect` writes them (`pitch-offset:deg=-0.8`), each
/// resolved among `registry`'s; an effect given twice is refused (it would stack on itself).
/// `named`: what the specs were given as, in the errors (`--effect`).
pub fn stack_of(registry: &Registry, specs: &[String], named: &str) -> Result<Stack> {
    let mut active: Vec<propbet_effects::Active> = Vec::new();
    for s in specs {
        let a = parse_spec(s)
            .and_then(|spec| registry.resolve(&spec))
            .map_err(|e| Error::about(named, e))?;
        if active.iter().any(|b| b.effect.id() == a.effect.id()) {
            return Err(Error::value(
                named,
                &a.describe(),
                format!("{} is given twice (each effect once)", a.effect.id()),
            ));
        }
        active.push(a);
    }
    Ok(Stack { active })
}

/// The built-in effects and those of a user file (read, parsed and checked against the
/// built-ins' ids: what `--user-effects` and a case's `user_effects` name).
pub fn effect_registry(user_effects: Option<&Path>) -> Result<Registry> {
    let Some(path) = user_effects else {
        return Ok(Registry::default());
    };
    let text = read_text(path)?;
    let user = propbet_effects::user::parse(&text, &path.display().to_string())?;
    Registry::with_user(user).map_err(|e| Error::input(path, e.to_string()))
}

/// The `transition` effect of polars that have tables at other Ncrit values than their own
/// (`others`, their tables `models_at` each: `propbet polars --ncrit-effect`, or the band's),
/// about the tables at their own (`base`); None when they have none.
fn transition_effect(
    blade: &propbet_polar::BladePolars,
    base: &propbet_polar::blade::StationModels,
    path: &Path,
    others: &[f64],
    models_at: impl Fn(f64) -> propbet_polar::blade::StationModels,
) -> Result<Option<std::sync::Arc<dyn propbet_effects::Effect>>> {
    use propbet_effects::transition::{Level, Transition};
    if others.is_empty() {
        return Ok(None);
    }
    let level = |ncrit: f64, (r, models): propbet_polar::blade::StationModels| Level {
        ncrit,
        r,
        models: models
            .into_iter()
            .map(|m| std::sync::Arc::new(m) as std::sync::Arc<dyn propbet_bemt::SectionAero>)
            .collect(),
    };
    let own = blade
        .stations
        .iter()
        .flat_map(|s| s.polars.first())
        .map(|p| p.ncrit)
        .next()
        .ok_or_else(|| Error::input(path, "no station has a polar"))?;
    let base = level(own, base.clone());
    // A level whose every polar failed is left out (each failure is in its station's problem).
    let levels: Vec<Level> = others
        .iter()
        .map(|&n| level(n, models_at(n)))
        .filter(|l| !l.models.is_empty())
        .collect();
    if levels.is_empty() {
        return Ok(None);
    }
    let t = Transition::new(base, levels).map_err(|e| Error::input(path, e))?;
    Ok(Some(std::sync::Arc::new(t)))
}

/// Replaces the rotor's section models by the tabulated polars of a `propbet polars` file
/// (`(r, models)`: its tables at their own Ncrit; `path` names it in messages).
fn tabulate(rotor: &mut Rotor, (r, models): &propbet_polar::blade::StationModels, path: &Path) -> Result<()> {
    let (lo, hi) = (rotor.stations[0].r, rotor.stations[rotor.stations.len() - 1].r);
    if r[0] > hi || r[r.len() - 1] < lo {
        return Err(Error::input(
            path,
            format!(
                "its stations (r = {:.4}..{:.4} m) do not overlap the blade (r = {lo:.4}..{hi:.4} m)",
                r[0],
                r[r.len() - 1]
            ),
        ));
    }
    propbet_polar::tabulated::apply_to_rotor(rotor, r, models);
    Ok(())
}
