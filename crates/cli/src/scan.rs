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
    #[arg(long = propbet_api::settings::UNITS.flag, help = propbet_api::settings::UNITS.help)]
    pub units: Option<String>,
    #[arg(long = propbet_api::settings::STATIONS.flag, help = propbet_api::settings::STATIONS.help)]
    pub stations: Option<String>,
    /// Planar sections (the plane x = r across the blade) instead of cylindrical (r = const).
    #[arg(long)]
    pub planar: bool,
    /// Slab thickness of a cloud's sections [mm].
    #[arg(long, default_value_t = propbet_api::settings::scan::DEFAULT_SLAB_MM)]
    pub slab: f64,
    /// Widen a sparse cloud's slab (up to 4 times) until a section holds this many points per
    /// blade (0: keep the slab as given).
    #[arg(long, default_value_t = propbet_api::settings::scan::DEFAULT_SLAB_POINTS)]
    pub slab_points: usize,
    /// Blade colours to keep (clouds): names (orange, black, ...), #rrggbb or r/g/b, comma-separated.
    #[arg(long)]
    pub blade_colour: Option<String>,
    /// Colour-distance threshold (default: Otsu's suggestion from the histogram).
    #[arg(long)]
    pub colour_threshold: Option<f64>,
    /// Reference box edge lengths along the propeller's x, y, z [mm]: 50.8x48.26x50.8.
    #[arg(long = "box")]
    pub box_dims: Option<String>,
    /// The box centre in the propeller frame [mm]: x,y,z (the box is fixed to the hub).
    #[arg(long, default_value = propbet_api::settings::scan::DEFAULT_BOX_OFFSET, allow_hyphen_values = true)]
    pub box_offset: String,
    /// Colours of the box faces.
    #[arg(long, default_value = propbet_api::settings::scan::DEFAULT_BOX_COLOUR)]
    pub box_colour: String,
    /// One point on each visible box face (file units), `x,y,z;x,y,z;...`, instead of finding
    /// the faces automatically.
    #[arg(long, allow_hyphen_values = true)]
    pub box_seeds: Option<String>,
    /// Region of interest in file units: xmin,ymin,zmin,xmax,ymax,zmax.
    #[arg(long, allow_hyphen_values = true)]
    pub crop: Option<String>,
    /// Statistical outlier removal for clouds: neighbours,sigmas, or `off`.
    #[arg(long, default_value = propbet_api::settings::scan::DEFAULT_OUTLIERS)]
    pub outliers: String,
    /// Manual alignment: a point at the root of blade 0 (file units) x,y,z.
    #[arg(long, allow_hyphen_values = true, requires = "tip_point")]
    pub root_point: Option<String>,
    /// Manual alignment: a point at the tip of blade 0.
    #[arg(long, allow_hyphen_values = true, requires = "root_point")]
    pub tip_point: Option<String>,
    /// Manual alignment: the hub centre (default: the root point moved along the blade axis to
    /// the station of the scan's centroid).
    #[arg(long, allow_hyphen_values = true)]
    pub origin: Option<String>,
    /// Manual alignment: rotations about the frame's x, y, z [deg].
    #[arg(long, allow_hyphen_values = true, default_value = propbet_api::settings::scan::DEFAULT_ROTATE)]
    pub rotate: String,
    /// Manual scale from a known length: `x1,y1,z1,x2,y2,z2,L` (two points in file units and
    /// their true distance in mm).
    #[arg(long, allow_hyphen_values = true)]
    pub known_length: Option<String>,
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
            options: self.settings().options()?,
            reference: self.reference.clone(),
            name: self.name.clone(),
            out: self.out.clone(),
        })
    }

    /// The scan's settings, as a case's `[geometry]` keys give them too.
    pub fn settings(&self) -> ScanSettings {
        ScanSettings {
            units: self.units.clone(),
            stations: self.stations.clone(),
            planar: self.planar,
            slab: Some(self.slab),
            slab_points: Some(self.slab_points),
            blade_colour: self.blade_colour.clone(),
            colour_threshold: self.colour_threshold,
            box_dims: self.box_dims.clone(),
            box_offset: Some(self.box_offset.clone()),
            box_colour: Some(self.box_colour.clone()),
            box_seeds: self.box_seeds.clone(),
            crop: self.crop.clone(),
            outliers: Some(self.outliers.clone()),
            root_point: self.root_point.clone(),
            tip_point: self.tip_point.clone(),
            origin: self.origin.clone(),
            rotate: Some(self.rotate.clone()),
            known_length: self.known_length.clone(),
        }
    }
}

/// Runs `propbet scan`.
pub fn run(a: &ScanArgs) -> Result<bool> {
    Ok(propbet_api::commands::scan::run(
        &a.spec()?,
        &crate::output::Terminal::default(),
    )?)
}
