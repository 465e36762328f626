//! Validation over many props: which props a UIUC directory holds (and `--only` keeps), where
//! each one's sections come from, the spec's checks and its model in words, and the loop that
//! validates each prop and hands it to the caller to write.

use std::path::Path;

use propbet_qprop::apc::{pe0_name, pe0_unknown};

use super::{find_apc_file, uiuc_props, validate_prop, Row, Sections, ValidateSpec, Validated};
use propbet_model::{nothing, Result};

/// The props of the UIUC directory `uiuc` to validate: all of them, or those whose name
/// contains one of `only`'s comma-separated keys.
pub fn select_props(uiuc: &Path, only: Option<&str>) -> Result<Vec<String>> {
    let mut props = uiuc_props(uiuc)?;
    if props.is_empty() {
        nothing!(
            "{}: no UIUC propeller files in it (<family>_<D>x<P>_geom.txt, _static_*.txt or _<run>_<rpm>.txt)",
            uiuc.display()
        );
    }
    if let Some(only) = only {
        let keys: Vec<&str> = only.split(',').map(str::trim).collect();
        props.retain(|g| keys.iter().any(|k| g.contains(k)));
        if props.is_empty() {
            nothing!("{}: no UIUC propeller matches --only {only}", uiuc.display());
        }
    }
    Ok(props)
}

/// Where one prop's sections come from, or why it is not validated.
#[derive(Debug, Clone, PartialEq)]
pub enum PropSections {
    /// APC's PE0 file, or the generic section (with why APC's are not used).
    Use(Sections),
    /// Not validated: no PE0 file and no generic section (`--generic-section none`).
    NotValidated(String),
}

/// APC's sections from the prop's PE0 file in `spec.pe0`; without one, `generic` (saying why),
/// or the reason it is not validated.
pub fn sections_for(spec: &ValidateSpec, prop: &str, generic: Option<&Sections>) -> PropSections {
    let apc = match pe0_name(prop) {
        Some(n) => find_apc_file(&spec.pe0, &n)
            .map(Sections::Apc)
            .ok_or_else(|| format!("no PE0 file {n} in {}", spec.pe0.display())),
        None => Err(pe0_unknown(prop)),
    };
    match (apc, generic) {
        (Ok(apc), _) => PropSections::Use(apc),
        (Err(why), Some(Sections::Assumed { airfoil, thickness, .. })) => PropSections::Use(Sections::Assumed {
            airfoil: airfoil.clone(),
            thickness: *thickness,
            why,
        }),
        (Err(why), _) => PropSections::NotValidated(why),
    }
}

impl ValidateSpec {
    /// The settings are ones XFOIL and the model take (the same checks and words as the
    /// polars stage's), and the user-effects file reads: before any prop.
    pub fn check(&self) -> Result<()> {
        self.xfoil.check()?;
        propbet_model::effect_registry(self.user_effects.as_deref())?;
        Ok(())
    }

    /// The model in words, for the table's introduction.
    pub fn model_text(&self) -> String {
        let mut text = format!(
            "{}, section model {}, Ncrit {}{}, rotational augmentation {}, drag factor {}",
            self.geometry.description(),
            if self.tables { "tables" } else { "qprop" },
            self.xfoil.section.ncrit,
            self.xfoil
                .section
                .trip
                .map_or(", free transition".to_string(), |x| format!(
                    ", transition forced at x/c {x} at the latest"
                )),
            self.rotation.name(),
            self.drag_factor
        );
        let size = self
            .xfoil
            .process
            .neuralfoil_size
            .as_deref()
            .unwrap_or(propbet_settings::NEURALFOIL_SIZE.default);
        match self.xfoil.process.engine {
            propbet_polar::Engine::Xfoil => {}
            propbet_polar::Engine::NeuralFoil => {
                text.push_str(&format!(
                    ", the polars from NeuralFoil's {size} network instead of XFOIL"
                ));
            }
            propbet_polar::Engine::Auto => {
                text.push_str(&format!(", what XFOIL leaves out from NeuralFoil's {size} network"));
            }
        }
        if let Some(p) = &self.user_effects {
            text.push_str(&format!(", user effects of {} among the candidates", p.display()));
        }
        if !self.ncrit_effect.is_empty() {
            text.push_str(&format!(
                ", transition effect from tables at Ncrit {}",
                self.ncrit_effect
                    .iter()
                    .map(|x| x.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        text
    }
}

/// The validation of many props: the table's rows, the props not validated (name, why), and
/// whether every file read and every stage ran clean.
#[derive(Debug, Default)]
pub struct Validation {
    /// One row per validated prop.
    pub rows: Vec<Row>,
    /// (prop, why) for each prop not validated.
    pub skipped: Vec<(String, String)>,
    /// Every prop validated, every file read and every stage clean.
    pub clean: bool,
}

/// Validates each of `props` (sections from [`sections_for`]): `start` is told of each prop as
/// it starts (its index, the count, its name), `progress` of each prop's polars (done, total);
/// `done` gets each validated prop to write, and its error (or the prop's) lists the prop as
/// not validated. An error when no prop could be validated.
pub fn validate_all(
    spec: &ValidateSpec,
    props: &[String],
    generic: Option<&Sections>,
    start: &mut dyn FnMut(usize, usize, &str),
    progress: &propbet_polar::Progress<'_>,
    done: &mut dyn FnMut(&str, &Validated) -> std::result::Result<(), String>,
) -> Result<Validation> {
    let mut out = Validation {
        clean: true,
        ..Validation::default()
    };
    for (k, prop) in props.iter().enumerate() {
        let sections = match sections_for(spec, prop, generic) {
            PropSections::Use(s) => s,
            PropSections::NotValidated(why) => {
                out.skipped.push((prop.clone(), why));
                continue;
            }
        };
        start(k, props.len(), prop);
        let result = validate_prop(spec, prop, &sections, progress)
            .map_err(|e| propbet_units::with_causes(&e))
            .and_then(|v| done(prop, &v).map(|()| v));
        match result {
            Ok(v) => {
                out.clean &= v.clean();
                out.rows.push(v.row);
            }
            Err(why) => {
                out.clean = false;
                out.skipped.push((prop.clone(), why));
            }
        }
    }
    if out.rows.is_empty() {
        nothing!(
            "{}: no propeller could be validated: {}",
            spec.uiuc.display(),
            out.skipped
                .iter()
                .map(|(p, why)| format!("{p}: {why}"))
                .collect::<Vec<_>>()
                .join("; ")
        );
    }
    Ok(out)
}
