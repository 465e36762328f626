//! `propbet validate`: every UIUC propeller that has a geometry file and a matching APC PE0
//! file is predicted (UIUC's r/R, c/R, β, or with `--geometry pe0` APC's design c and β at
//! UIUC's r/R; APC's airfoils scaled to the PE0 thickness ratio at
//! each station; XFOIL polars at each station's Re) and compared with every static and J-sweep
//! file, before and after the diagnosis' ladder. Each prop is run as the documented commands
//! (`polars`, `compare`, `diagnose`, `compare --effect ...`) in its own directory; the table of
//! relative CT and CP errors is written as Markdown and CSV.

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::Args;
use propbet_api::settings::Rotation;
use propbet_api::xfoil::SectionSettings;
use propbet_pipeline::run::StageRecord;
use propbet_pipeline::spec::{StageSpec, XfoilSpec};
use propbet_validate::{select_props, validate_all, GeometrySource, Sections, ValidateSpec, Validated};

use crate::polar::{Bar, XfoilProcess};
use propbet_api::files::write_atomic;

/// Arguments of `propbet validate`.
// Fields without a doc comment are documented by their declared setting's help (`settings`).
#[allow(missing_docs)]
#[derive(Debug, Args)]
pub struct ValidateArgs {
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
    /// XFOIL executable, polar cache, progress bars (passed on to the polars stages).
    #[command(flatten)]
    pub xfoil: XfoilProcess,
    #[arg(
        long = propbet_api::settings::SECTION_MODEL.flag,
        help = propbet_api::settings::SECTION_MODEL.help,
        value_parser = clap::builder::PossibleValuesParser::new(propbet_api::settings::SECTION_MODEL.names().iter().copied()),
        default_value = propbet_api::settings::SECTION_MODEL.default,
    )]
    pub section_model: String,
    /// APC's PER3 directory (`PER3_<D><P><type>.dat`): APC's own predictions scored on the same
    /// points beside propbet's.
    #[arg(long)]
    pub per3: Option<PathBuf>,
    #[arg(long = propbet_api::settings::NCRIT.flag, help = propbet_api::settings::NCRIT.help, default_value_t = propbet_api::settings::NCRIT.default)]
    pub ncrit: f64,
    #[arg(long = propbet_api::settings::NCRIT_EFFECT.flag, help = propbet_api::settings::NCRIT_EFFECT.help, value_delimiter = ',')]
    pub ncrit_effect: Vec<f64>,
    #[arg(long = propbet_api::settings::ROTATION.flag, help = propbet_api::settings::ROTATION.help, value_name = "off|snel")]
    pub rotation: Option<String>,
    #[arg(long = propbet_api::settings::DRAG_FACTOR.flag, help = propbet_api::settings::DRAG_FACTOR.help, value_name = "K")]
    pub drag_factor: Option<f64>,
    #[arg(long = propbet_api::settings::TRIP.flag, help = propbet_api::settings::TRIP.help, value_name = "X/C|free")]
    pub trip: Option<String>,
    /// Where each station's chord and twist come from: `uiuc` (UIUC's measured geometry file) or
    /// `pe0` (APC's design chord and twist, at UIUC's stations).
    #[arg(long, value_parser = ["uiuc", "pe0"], default_value = "uiuc")]
    pub geometry: String,
    /// The section of a prop without APC's (another maker's, or no PE0 file for it): an airfoil
    /// of `--airfoils` (or a NACA 4-digit name) at every station of UIUC's blade, `NAME` (as
    /// drawn) or `NAME:T/C`; `none` lists such props as not validated. Their rows are marked
    /// and kept out of the median over props (docs/studies/other-makers.md).
    #[arg(long, value_name = "NAME[:T/C]|none", default_value = propbet_validate::DEFAULT_GENERIC_SECTION)]
    pub generic_section: String,
    /// TOML file of user-defined effects (docs/effects.md): candidates of every prop's ladders
    /// (all files and each held-out half) beside the built-ins, to measure a new effect on
    /// every prop at once.
    #[arg(long)]
    pub user_effects: Option<PathBuf>,
}

/// The spec of `a`, its props and the generic section, checked before any prop; the output
/// folder is refused where it holds an input.
pub(crate) fn spec(a: &ValidateArgs) -> Result<(ValidateSpec, Vec<String>, Option<Sections>)> {
    let props = select_props(&a.uiuc, a.only.as_deref())?;
    let spec = ValidateSpec {
        uiuc: a.uiuc.clone(),
        pe0: a.pe0.clone(),
        airfoils: a.airfoils.clone(),
        out: a.out.clone(),
        xfoil: XfoilSpec {
            process: a.xfoil.spec()?,
            section: SectionSettings {
                ncrit: a.ncrit,
                trip: match &a.trip {
                    None => propbet_api::settings::default_trip(),
                    Some(t) => propbet_api::settings::values::parse_trip(t)?,
                },
                ..SectionSettings::new(propbet_api::settings::values::parse_list(
                    "",
                    propbet_api::settings::ALPHA.default,
                )?)
            },
        },
        tables: a.section_model == "tables",
        ncrit_effect: propbet_api::settings::check_ncrit_effect(&a.ncrit_effect, a.ncrit)?,
        rotation: Rotation::or_default(
            a.rotation.as_deref().map(Rotation::parse).transpose()?,
            a.section_model == "tables",
        ),
        drag_factor: propbet_api::settings::drag_factor_or_default(a.drag_factor, a.section_model == "tables"),
        per3: a.per3.clone(),
        geometry: GeometrySource::parse(&a.geometry)?,
        user_effects: a.user_effects.clone(),
    };
    let generic = Sections::parse_generic(&a.generic_section)?;
    // A setting or user-effects file that does not do stops here, before any prop.
    spec.check()?;
    let inputs: Vec<&Path> = [a.uiuc.as_path(), a.pe0.as_path(), a.airfoils.as_path()]
        .into_iter()
        .chain(a.per3.as_deref())
        .chain(a.user_effects.as_deref())
        .collect();
    propbet_api::files::refuse_inputs_inside(&a.out, &inputs)?;
    Ok((spec, props, generic))
}

/// What `propbet validate` wrote that a caller reads as data, as it wrote it.
#[derive(Debug, Default)]
pub struct Written {
    /// validation.md.
    pub markdown: String,
    /// validation.csv.
    pub csv: Vec<u8>,
}

/// Runs `propbet validate`: false when a prop reported problems; and what it wrote
/// ([`Written`]).
pub fn run(a: &ValidateArgs) -> Result<(bool, Written)> {
    let (spec, props, generic) = spec(a)?;
    let lock = propbet_api::files::claim_folder(&a.out, "propbet validate")?;
    let (quiet, engine) = (a.xfoil.quiet, a.xfoil.spec()?.engine);
    let validation = validate_all(
        &spec,
        &props,
        generic.as_ref(),
        &mut |k, total, prop| {
            eprintln!("propbet validate [{}/{total}] {prop}", k + 1);
            let bar = Bar::new(quiet, engine);
            Box::new(move |d, t| bar.tick(d, t))
        },
        &mut |prop, v| {
            write_prop_outputs(&spec, prop, v).map_err(|e| format!("{e:#}"))?;
            for (f, why) in &v.row.left_out {
                eprintln!("propbet: warning: {prop}: {f} left out: {why}");
            }
            Ok(())
        },
    )?;
    let model = spec.model_text();
    let md = propbet_report::validate::markdown(&validation.rows, &validation.skipped, &model);
    let csv = propbet_report::table::validation::csv(&validation.rows)?;
    write_atomic(&a.out.join("validation.md"), &[md.as_bytes()], &[])?;
    write_atomic(&a.out.join("validation.csv"), &[&csv], &[])?;
    let families = propbet_api::compare::expected::to_csv(&propbet_validate::summarise(&validation.rows));
    write_atomic(&a.out.join("families.csv"), &[families.as_bytes()], &[])?;
    let html = propbet_report::validate::html(&validation.rows, &validation.skipped, &model);
    write_atomic(&a.out.join("validation.html"), &[html.as_bytes()], &[])?;
    lock.finish()?;
    crate::output::print_page(&md);
    Ok((validation.clean, Written { markdown: md, csv }))
}

/// One prop's outputs: its geometry and sections, polars, and each stage's directory.
fn write_prop_outputs(spec: &ValidateSpec, prop: &str, v: &Validated) -> Result<()> {
    let dir = spec.out.join(prop);
    std::fs::create_dir_all(dir.join("airfoils"))?;
    for (i, t) in &v.airfoils {
        write_atomic(&dir.join(format!("airfoils/station_{i:02}.dat")), &[t], &[])?;
    }
    write_atomic(
        &dir.join("geometry.qprop"),
        &[propbet_api::qprop::write_prop(&v.geometry.file)],
        &[],
    )?;
    // The two comparisons, in the order of their stages.
    let mut compared = [&v.compared, &v.calibrated].into_iter();
    for StageRecord { spec, .. } in &v.stages {
        match spec {
            StageSpec::Polars(s) => {
                crate::polar::print_polars(s, &v.polars.1, &v.polars.0);
                crate::polar::write_polars(s, &v.polars.0)?;
            }
            StageSpec::Compare(s) => {
                let (c, model) = compared.next().expect("two comparisons");
                let other = crate::compare::reference(s, model.diameter)?;
                let reference = crate::compare::write(s, model, c, other.as_ref(), None)?.reference;
                crate::compare::print(s, c, reference.as_ref());
            }
            StageSpec::Diagnose(s) => {
                crate::diagnose::write(s, &v.diagnosed)?;
                crate::diagnose::print(s, &v.diagnosed);
            }
            StageSpec::Scan(_) | StageSpec::Predict(_) | StageSpec::Powered(_) => {}
        }
    }
    Ok(write_atomic(
        &dir.join("compare/band_sources.csv"),
        &[propbet_report::table::validation::band_sources(v)?],
        &[],
    )?)
}
