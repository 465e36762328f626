//! `propbet validate`: every UIUC propeller with a matching APC PE0 file predicted and
//! compared with every static and J-sweep file, before and after the diagnosis' ladder
//! (`propbet_validate`); each prop's stages written in its own folder and told as their
//! commands tell them, the table of relative CT and CP errors written as Markdown, CSV and
//! HTML. `propbet hidden`: known effects added to those measurements, and how often the
//! diagnosis finds them.

use propbet_pipeline::run::StageRecord;
use propbet_settings::spec::StageSpec;
use std::path::{Path, PathBuf};

use propbet_validate::{
    hidden_prop, sections_for, select_props, validate_all, GeometrySource, PropSections, Sections, ValidateSpec,
    Validated,
};

use crate::settings::{Rotation, DRAG_FACTOR, NCRIT_EFFECT, ROTATION, SECTION_MODEL};
pub use propbet_validate::DEFAULT_GENERIC_SECTION;

use crate::command_error::with_causes;
use crate::console::{print_page, Console};
use crate::diagnose::inject::{Finding, Injection};
use crate::files::write_atomic;
use crate::{CommandError, CommandResult as Result};

/// What `propbet validate` (and `propbet hidden`) is asked: its flags.
// Fields without a help are documented by their declared setting's (`settings`).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ValidateRequest {
    /// UIUC directory: each prop's static and J-sweep files and its `<prop>_geom.txt` (without
    /// one, the blade is APC's design from the PE0 file).
    #[arg(long)]
    pub uiuc: PathBuf,
    /// APC PE0 directory (`<D><P><type>-PERF.PE0`, in any case, with or without the size's point).
    #[arg(long)]
    pub pe0: PathBuf,
    /// Airfoil coordinates of APC's sections: `e63.dat`, `clarky.dat`, or `<name>.dat` for
    /// another (APC12 is NACA 4412, and NACA 4-digit names are generated).
    #[arg(long)]
    pub airfoils: PathBuf,
    /// Only the props whose name contains one of these (comma-separated).
    #[arg(long)]
    pub only: Option<String>,
    /// Output directory.
    #[arg(long, short)]
    pub out: PathBuf,
    /// XFOIL, its cache and how each section's polar is asked (passed on to the polars stages).
    #[command(flatten)]
    pub section: crate::SectionRequest,
    /// `qprop` or `tables` (None: the setting's default).
    #[arg(
        long = SECTION_MODEL.flag,
        help = SECTION_MODEL.help,
        value_parser = SECTION_MODEL.choices(),
        default_value = SECTION_MODEL.default,
    )]
    pub section_model: Option<String>,
    /// APC's PER3 directory (`PER3_<D><P><type>.dat`): APC's own predictions scored on the same
    /// points beside propbet's.
    #[arg(long)]
    pub per3: Option<PathBuf>,
    /// Other Ncrit values the transition effect may move to.
    #[arg(long = NCRIT_EFFECT.flag, help = NCRIT_EFFECT.help, value_delimiter = ',')]
    pub ncrit_effect: Vec<f64>,
    /// Rotational augmentation (`off`, `snel`; None: the section model's default).
    #[arg(long = ROTATION.flag, help = ROTATION.help, value_name = "off|snel")]
    pub rotation: Option<String>,
    /// The drag factor (None: the section model's default).
    #[arg(long = DRAG_FACTOR.flag, help = DRAG_FACTOR.help, value_name = "K")]
    pub drag_factor: Option<f64>,
    /// Where each station's chord and twist come from: `uiuc` (UIUC's measured geometry file) or
    /// `pe0` (APC's design chord and twist, at UIUC's stations).
    #[arg(long, value_parser = ["uiuc", "pe0"], default_value = "uiuc")]
    pub geometry: Option<String>,
    /// The section of a prop without APC's (another maker's, or no PE0 file for it): an airfoil
    /// of `--airfoils` (or a NACA 4-digit name) at every station of UIUC's blade, `NAME` (as
    /// drawn) or `NAME:T/C`; `none` lists such props as not validated. Their rows are marked
    /// and kept out of the median over props (docs/studies/other-makers.md).
    #[arg(long, value_name = "NAME[:T/C]|none", default_value = DEFAULT_GENERIC_SECTION)]
    pub generic_section: Option<String>,
    /// TOML file of user-defined effects (docs/effects.md): candidates of every prop's ladders
    /// (all files and each held-out half) beside the built-ins, to measure a new effect on
    /// every prop at once.
    #[arg(long)]
    pub user_effects: Option<PathBuf>,
}

impl ValidateRequest {
    /// The spec, its props and the generic section, checked before any prop; the output
    /// folder is refused where it holds an input.
    pub fn spec(&self) -> Result<(ValidateSpec, Vec<String>, Option<Sections>)> {
        let props = select_props(&self.uiuc, self.only.as_deref())?;
        let model = self
            .section_model
            .as_deref()
            .unwrap_or(crate::settings::SECTION_MODEL.default);
        crate::settings::SECTION_MODEL.choose(model)?;
        let tables = model == "tables";
        let xfoil = self
            .section
            .spec(crate::settings::NCRIT.default, crate::settings::default_trip())?;
        let spec = ValidateSpec {
            uiuc: self.uiuc.clone(),
            pe0: self.pe0.clone(),
            airfoils: self.airfoils.clone(),
            out: self.out.clone(),
            ncrit_effect: crate::settings::check_ncrit_effect(&self.ncrit_effect, xfoil.section.ncrit)?,
            xfoil,
            tables,
            rotation: Rotation::or_default(self.rotation.as_deref().map(Rotation::parse).transpose()?, tables),
            drag_factor: crate::settings::drag_factor_or_default(self.drag_factor, tables),
            per3: self.per3.clone(),
            geometry: GeometrySource::parse(self.geometry.as_deref().unwrap_or("uiuc"))?,
            user_effects: self.user_effects.clone(),
        };
        let generic = Sections::parse_generic(
            self.generic_section
                .as_deref()
                .unwrap_or(propbet_validate::DEFAULT_GENERIC_SECTION),
        )?;
        // A setting or user-effects file that does not do stops here, before any prop.
        spec.check()?;
        let inputs: Vec<&Path> = [self.uiuc.as_path(), self.pe0.as_path(), self.airfoils.as_path()]
            .into_iter()
            .chain(self.per3.as_deref())
            .chain(self.user_effects.as_deref())
            .collect();
        crate::files::refuse_inputs_inside(&self.out, &inputs)?;
        Ok((spec, props, generic))
    }
}

/// What `propbet validate` wrote that a caller reads as data, as it wrote it.
#[derive(Debug, Default)]
pub struct Written {
    /// validation.md.
    pub markdown: String,
    /// validation.csv.
    pub csv: Vec<u8>,
}

/// Runs `propbet validate` on `props` (`generic`: the section of props without a PE0 file):
/// false when a prop reported problems; and what it wrote ([`Written`]).
pub fn validate(
    spec: &ValidateSpec,
    props: &[String],
    generic: Option<&Sections>,
    console: &dyn Console,
) -> Result<(bool, Written)> {
    let lock = crate::files::claim_folder(&spec.out, "propbet validate")?;
    let process = &spec.xfoil.process;
    let validation = validate_all(
        spec,
        props,
        generic,
        &mut |k, total, prop| {
            console.progress_done();
            console.err(&format!("propbet validate [{}/{total}] {prop}", k + 1));
        },
        &|d, t| console.progress(process, d, t),
        &mut |prop, v| {
            console.progress_done();
            write_prop_outputs(spec, prop, v, console).map_err(|e| with_causes(&e))?;
            for (f, why) in &v.row.left_out {
                console.err(&format!("propbet: warning: {prop}: {f} left out: {why}"));
            }
            Ok(())
        },
    );
    console.progress_done();
    let validation = validation?;
    let model = spec.model_text();
    let md = propbet_report::validate::markdown(&validation.rows, &validation.skipped, &model);
    let csv = propbet_report::table::validation::csv(&validation.rows)?;
    write_atomic(&spec.out.join("validation.md"), &[md.as_bytes()], &[])?;
    write_atomic(&spec.out.join("validation.csv"), &[&csv], &[])?;
    let families = crate::compare::expected::to_csv(&propbet_validate::summarise(&validation.rows));
    write_atomic(&spec.out.join("families.csv"), &[families.as_bytes()], &[])?;
    let html = propbet_report::validate::html(&validation.rows, &validation.skipped, &model);
    write_atomic(&spec.out.join("validation.html"), &[html.as_bytes()], &[])?;
    lock.finish()?;
    print_page(console, &md);
    Ok((validation.clean, Written { markdown: md, csv }))
}

/// One prop's outputs: its geometry and sections, polars, and each stage's directory.
fn write_prop_outputs(spec: &ValidateSpec, prop: &str, v: &Validated, console: &dyn Console) -> Result<()> {
    let dir = spec.out.join(prop);
    std::fs::create_dir_all(dir.join("airfoils"))
        .map_err(|e| CommandError::io(format!("{}: cannot create", dir.join("airfoils").display()), e))?;
    for (i, t) in &v.airfoils {
        write_atomic(&dir.join(format!("airfoils/station_{i:02}.dat")), &[t], &[])?;
    }
    write_atomic(
        &dir.join("geometry.qprop"),
        &[crate::qprop::write_prop(&v.geometry.file)],
        &[],
    )?;
    // The two comparisons, in the order of their stages.
    let mut compared = [&v.compared, &v.calibrated].into_iter();
    for StageRecord { spec, .. } in &v.stages {
        match spec {
            StageSpec::Polars(s) => {
                super::polar::print_polars(s, &v.polars.1, &v.polars.0, console);
                super::polar::write_polars(s, &v.polars.0)?;
            }
            StageSpec::Compare(s) => {
                let (c, model) = compared.next().expect("two comparisons");
                let other = super::compare::reference(s, model.diameter, console)?;
                let reference = super::compare::write(s, model, c, other.as_ref(), None, console)?.reference;
                super::compare::print(s, c, reference.as_ref(), console);
            }
            StageSpec::Diagnose(s) => {
                super::diagnose::write(s, &v.diagnosed, console)?;
                super::diagnose::print(s, &v.diagnosed, console);
            }
            StageSpec::Scan(_) | StageSpec::Predict(_) | StageSpec::Powered(_) => {}
        }
    }
    write_atomic(
        &dir.join("compare/band_sources.csv"),
        &[propbet_report::table::validation::band_sources(v)?],
        &[],
    )
}

/// What `propbet hidden` adds to the measurements: its flags.
#[derive(Debug, Clone, clap::Args)]
pub struct InjectRequest {
    /// The effects added to the measurements, each at every size.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "thrust-tare,torque-tare,rpm-scale,density"
    )]
    pub inject: Vec<String>,
    /// Sizes: each effect's relative change of the static loads (0.05: 5 %).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "0.03,0.05,0.1",
        allow_negative_numbers = true
    )]
    pub sizes: Vec<f64>,
}

impl InjectRequest {
    /// Every effect at every size, refused (naming the flag) before anything runs.
    pub fn injections(&self) -> Result<Vec<Injection>> {
        let mut injections = Vec::new();
        for e in &self.inject {
            for &s in &self.sizes {
                injections.push(
                    Injection::new(e.trim(), s)
                        .map_err(|why| CommandError::Message(format!("--inject/--sizes: {why}")))?,
                );
            }
        }
        Ok(injections)
    }
}

/// Runs `propbet hidden`: each of `injections` added to each prop's measured files and
/// diagnosed; false when a prop could not be diagnosed (said in hidden.md).
pub fn hidden(
    spec: &ValidateSpec,
    props: &[String],
    generic: Option<&Sections>,
    injections: &[Injection],
    console: &dyn Console,
) -> Result<bool> {
    let lock = crate::files::claim_folder(&spec.out, "propbet hidden")?;
    let mut rows: Vec<(String, Finding)> = Vec::new();
    let mut skipped = Vec::new();
    for (k, prop) in props.iter().enumerate() {
        let sections = match sections_for(spec, prop, generic) {
            PropSections::Use(s) => s,
            PropSections::NotValidated(why) => {
                skipped.push((prop.clone(), why));
                continue;
            }
        };
        console.err(&format!("propbet hidden [{}/{}] {prop}", k + 1, props.len()));
        let found = hidden_prop(spec, prop, &sections, injections, &|d, t| {
            console.progress(&spec.xfoil.process, d, t)
        });
        console.progress_done();
        match found {
            Ok(found) => rows.extend(found.into_iter().map(|f| (prop.clone(), f))),
            Err(e) => skipped.push((prop.clone(), with_causes(&e))),
        }
    }
    if rows.is_empty() {
        return Err(CommandError::Message(format!(
            "no prop could be diagnosed: {skipped:?}"
        )));
    }
    write_hidden(&spec.out, &rows, &skipped, console)?;
    lock.finish()?;
    Ok(skipped.is_empty())
}

/// hidden.csv and hidden.md into `out`, and the page on the console.
fn write_hidden(
    out: &Path,
    rows: &[(String, Finding)],
    skipped: &[(String, String)],
    console: &dyn Console,
) -> Result<()> {
    let md = propbet_report::hidden::markdown(rows, skipped);
    write_atomic(&out.join("hidden.csv"), &[propbet_report::hidden::csv(rows)?], &[])?;
    write_atomic(&out.join("hidden.md"), &[md.as_bytes()], &[])?;
    print_page(console, &md);
    Ok(())
}

/// Runs `propbet hidden log`: each of `injections` added to the measured files of `measured`
/// (a stand log with its propeller's file) and diagnosed with the model of `model`, beside the
/// clean files.
pub fn hidden_log(
    model: &propbet_settings::spec::ModelSpec,
    measured: &propbet_settings::spec::MeasuredSpec,
    injections: &[Injection],
    out: &Path,
    console: &dyn Console,
) -> Result<()> {
    let lock = crate::files::claim_folder(out, "propbet hidden log")?;
    let loaded = propbet_model::Model::load(model, false)?;
    let dspec = propbet_validate::ladder_spec(model, measured, out);
    let name = model
        .prop
        .file_stem()
        .map_or_else(|| "prop".to_string(), |s| s.to_string_lossy().into_owned());
    let rows: Vec<(String, Finding)> = propbet_validate::hidden_measured(&loaded, &dspec, injections)?
        .into_iter()
        .map(|f| (name.clone(), f))
        .collect();
    if rows.is_empty() {
        return Err(CommandError::Message(
            "no injection applies to these measurements (a torque tare needs a measured torque)".into(),
        ));
    }
    write_hidden(out, &rows, &[], console)?;
    lock.finish()?;
    Ok(())
}
