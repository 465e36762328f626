//! `propbet validate`: every UIUC propeller that has a geometry file and a matching APC PE0
//! file is predicted (UIUC's r/R, c/R, β, or with `--geometry pe0` APC's design c and β at
//! UIUC's r/R; APC's airfoils scaled to the PE0 thickness ratio at
//! each station; XFOIL polars at each station's Re) and compared with every static and J-sweep
//! file, before and after the diagnosis' ladder. Each prop is run as the documented commands
//! (`polars`, `compare`, `diagnose`, `compare --effect ...`) in its own directory; the table of
//! relative CT and CP errors is written as Markdown and CSV.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;

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
    /// XFOIL, its cache and how each section's polar is asked (passed on to the polars stages).
    #[command(flatten)]
    pub xfoil: crate::polar::XfoilArgs,
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
    #[arg(long = propbet_api::settings::NCRIT_EFFECT.flag, help = propbet_api::settings::NCRIT_EFFECT.help, value_delimiter = ',')]
    pub ncrit_effect: Vec<f64>,
    #[arg(long = propbet_api::settings::ROTATION.flag, help = propbet_api::settings::ROTATION.help, value_name = "off|snel")]
    pub rotation: Option<String>,
    #[arg(long = propbet_api::settings::DRAG_FACTOR.flag, help = propbet_api::settings::DRAG_FACTOR.help, value_name = "K")]
    pub drag_factor: Option<f64>,
    /// Where each station's chord and twist come from: `uiuc` (UIUC's measured geometry file) or
    /// `pe0` (APC's design chord and twist, at UIUC's stations).
    #[arg(long, value_parser = ["uiuc", "pe0"], default_value = "uiuc")]
    pub geometry: String,
    /// The section of a prop without APC's (another maker's, or no PE0 file for it): an airfoil
    /// of `--airfoils` (or a NACA 4-digit name) at every station of UIUC's blade, `NAME` (as
    /// drawn) or `NAME:T/C`; `none` lists such props as not validated. Their rows are marked
    /// and kept out of the median over props (docs/studies/other-makers.md).
    #[arg(long, value_name = "NAME[:T/C]|none", default_value = propbet_api::commands::validate::DEFAULT_GENERIC_SECTION)]
    pub generic_section: String,
    /// TOML file of user-defined effects (docs/effects.md): candidates of every prop's ladders
    /// (all files and each held-out half) beside the built-ins, to measure a new effect on
    /// every prop at once.
    #[arg(long)]
    pub user_effects: Option<PathBuf>,
}

/// What the flags ask for.
pub(crate) fn request(a: &ValidateArgs) -> propbet_api::commands::validate::ValidateRequest {
    propbet_api::commands::validate::ValidateRequest {
        uiuc: a.uiuc.clone(),
        pe0: a.pe0.clone(),
        airfoils: a.airfoils.clone(),
        only: a.only.clone(),
        out: a.out.clone(),
        section: a.xfoil.request(),
        section_model: Some(a.section_model.clone()),
        per3: a.per3.clone(),
        ncrit_effect: a.ncrit_effect.clone(),
        rotation: a.rotation.clone(),
        drag_factor: a.drag_factor,
        geometry: Some(a.geometry.clone()),
        generic_section: Some(a.generic_section.clone()),
        user_effects: a.user_effects.clone(),
    }
}

/// Runs `propbet validate`: false when a prop reported problems; and what it wrote.
pub fn run(a: &ValidateArgs) -> Result<(bool, propbet_api::commands::validate::Written)> {
    let (spec, props, generic) = request(a).spec()?;
    let term = crate::output::Terminal::default();
    Ok(propbet_api::commands::validate::validate(
        &spec,
        &props,
        generic.as_ref(),
        &term,
    )?)
}
