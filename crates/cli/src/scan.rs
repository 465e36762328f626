//! `propbet scan`: a mesh (STL) or a cloud (PLY, COLMAP points3D.txt, XYZ/XYZRGB) → the
//! propeller frame → sections → NACA and CST fits → geometry CSV, UIUC-style geom.txt, QPROP
//! prop file, per-station airfoil files (Selig), plots, the cleaned surface split by blade
//! (STL per blade for meshes, a PLY with a `blade` property for clouds), and a JSON summary.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use propbet_api::settings::scan::ScanSettings;
use propbet_api::spec::ScanSpec;

/// Arguments of `propbet scan`.
#[derive(Debug, Args)]
pub struct ScanArgs {
    /// The scan: .stl (ASCII or binary), .ply (ASCII or binary, colours), COLMAP
    /// points3D.txt, or .xyz / .txt (XYZ or XYZRGB rows).
    pub input: PathBuf,
    /// How the scan is read and cut (a case's `[geometry]` keys).
    #[command(flatten)]
    pub settings: ScanSettings,
    /// A UIUC-style geometry table (r/R c/R beta) to compare with.
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Name written in the prop file.
    #[arg(long)]
    pub name: Option<String>,
    /// Output directory.
    #[arg(long, short)]
    pub out: PathBuf,
}

impl ScanArgs {
    /// The stage's spec (flags in SI).
    pub fn spec(&self) -> Result<ScanSpec> {
        Ok(ScanSpec {
            input: self.input.clone(),
            options: self.settings.options()?,
            reference: self.reference.clone(),
            name: self.name.clone(),
            out: self.out.clone(),
        })
    }
}

/// Runs `propbet scan`.
pub fn run(a: &ScanArgs) -> Result<bool> {
    Ok(propbet_api::commands::scan::run(
        &a.spec()?,
        &crate::output::Terminal::default(),
    )?)
}
