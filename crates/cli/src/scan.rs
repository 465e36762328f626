//! `propbet scan`: a mesh (STL) or a cloud (PLY, COLMAP points3D.txt, XYZ/XYZRGB) → the
//! propeller frame → sections → NACA and CST fits → geometry CSV, UIUC-style geom.txt, QPROP
//! prop file, per-station airfoil files (Selig), plots, the cleaned surface split by blade
//! (STL per blade for meshes, a PLY with a `blade` property for clouds), and a JSON summary.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use propbet_api::geometry::cloud::to_ply;
use propbet_api::geometry::scan::{Aligned, Geometry};
use propbet_api::measure::uiuc::{geometry_at, GeometryRow};
use propbet_api::qprop::write_prop;
use propbet_api::settings::scan::ScanSettings;
use propbet_pipeline::spec::ScanSpec;
use propbet_pipeline::stages::{self, Scanned};
use serde_json::json;

use propbet_api::files::{write_atomic, write_figure};
use propbet_report::table::{csv_rows, Num};

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

/// A row of geometry.csv (the reference table's columns empty without one).
#[derive(serde::Serialize)]
struct GeometryCsvRow {
    r_mm: Num,
    #[serde(rename = "r_R")]
    r_r: Num,
    chord_mm: Num,
    #[serde(rename = "c_R")]
    c_r: Num,
    beta_deg: Num,
    t_c: Num,
    t_pos: Num,
    camber: Num,
    camber_pos: Num,
    le_offset_mm: Num,
    skew_deg: Num,
    rake_mm: Num,
    naca: String,
    naca_t_c: Num,
    naca_camber: Num,
    naca_camber_pos: Num,
    rms_naca_mm: Num,
    rms_cst_mm: Num,
    points: usize,
    blade_spread_deg: Num,
    #[serde(rename = "ref_c_R")]
    ref_c_r: Num,
    ref_beta_deg: Num,
}

/// Linear interpolation in a reference table at r/R `x`: column 1 c/R, 2 β [deg] (None outside).
fn interp(table: &[GeometryRow], x: f64, k: usize) -> Option<f64> {
    geometry_at(table, x).map(|(c, b)| if k == 1 { c } else { b.to_degrees() })
}

/// Runs `propbet scan`.
pub fn run(a: &ScanArgs) -> Result<bool> {
    run_spec(&a.spec()?)
}

/// Runs a scan stage: its files written, its summary printed.
pub fn run_spec(spec: &ScanSpec) -> Result<bool> {
    let inputs: Vec<&Path> = std::iter::once(spec.input.as_path())
        .chain(spec.reference.as_deref())
        .collect();
    propbet_api::files::refuse_inputs_inside(&spec.out, &inputs)?;
    let s = stages::scan(spec)?;
    write(spec, &s)?;
    print_summary(&s);
    println!("wrote {}", spec.out.display());
    Ok(s.clean())
}

/// geometry.csv: one row per station, with the reference table's c/R and beta where given.
fn geometry_csv(g: &Geometry, reference: Option<&[GeometryRow]>) -> Result<Vec<u8>> {
    let big_r = g.tip_radius;
    let rows = g.stations.iter().map(|s| {
        let reference = |k| reference.and_then(|t| interp(t, s.r_r, k));
        GeometryCsvRow {
            r_mm: (1000.0 * s.r).into(),
            r_r: s.r_r.into(),
            chord_mm: (1000.0 * s.chord).into(),
            c_r: (s.chord / big_r).into(),
            beta_deg: s.beta.to_degrees().into(),
            t_c: s.t_c.into(),
            t_pos: s.t_pos.into(),
            camber: s.camber.into(),
            camber_pos: s.camber_pos.into(),
            le_offset_mm: (1000.0 * s.le_offset).into(),
            skew_deg: s.skew.to_degrees().into(),
            rake_mm: (1000.0 * s.rake).into(),
            naca: s.naca.designation(),
            naca_t_c: s.naca.t_c.into(),
            naca_camber: s.naca.camber.into(),
            naca_camber_pos: s.naca.camber_pos.into(),
            rms_naca_mm: (1000.0 * s.naca.rms).into(),
            rms_cst_mm: s.cst.as_ref().map(|c| 1000.0 * c.rms).into(),
            points: s.points,
            blade_spread_deg: s.blade_spread.to_degrees().into(),
            ref_c_r: reference(1).into(),
            ref_beta_deg: reference(2).into(),
        }
    });
    Ok(csv_rows(rows, true)?)
}

/// The cleaned surface in the propeller frame, by blade: one STL per blade and the hub's, or
/// the labelled cloud.
fn write_blades(out: &Path, g: &Geometry, inputs: &[&Path]) -> Result<()> {
    std::fs::create_dir_all(out.join("blades")).with_context(|| format!("{}: cannot create", out.display()))?;
    let lab = &g.labelled;
    match &lab.surface {
        Aligned::Mesh(m) => {
            for k in 0..g.blades {
                let part = m.subset(|i| lab.blade[i] == Some(k as u8));
                write_atomic(&out.join(format!("blades/blade_{k}.stl")), &[part.to_stl()], inputs)?;
            }
            let hub = m.subset(|i| lab.blade[i].is_none());
            if !hub.triangles.is_empty() {
                write_atomic(&out.join("blades/hub.stl"), &[hub.to_stl()], inputs)?;
            }
        }
        Aligned::Cloud(c) => {
            write_atomic(&out.join("blades/labelled.ply"), &[to_ply(c, Some(&lab.blade))], inputs)?;
        }
    }
    Ok(())
}

/// Writes the scan stage's outputs: geometry.csv, geom.txt, prop.qprop, airfoils/,
/// plots/, blades/, scan.json.
pub fn write(a: &ScanSpec, sc: &Scanned) -> Result<()> {
    let g = &sc.geometry;
    let command = crate::argv::command(&propbet_pipeline::spec::StageSpec::Scan(a.clone()));
    let lock = propbet_api::files::claim_folder(&a.out, &command)?;
    std::fs::create_dir_all(a.out.join("airfoils")).with_context(|| format!("{}: cannot create", a.out.display()))?;
    std::fs::create_dir_all(a.out.join("plots")).with_context(|| format!("{}: cannot create", a.out.display()))?;
    let inputs: Vec<&Path> = std::iter::once(a.input.as_path())
        .chain(a.reference.as_deref())
        .collect();
    let reference = sc.reference.as_deref();
    let big_r = g.tip_radius;
    // Geometry CSV.
    write_atomic(&a.out.join("geometry.csv"), &[geometry_csv(g, reference)?], &inputs)?;
    // UIUC-style table.
    let mut geom = String::from("r/R    c/R     beta\n");
    for s in &g.stations {
        geom.push_str(&format!(
            "{:.4} {:.4} {:.2}\n",
            s.r_r,
            s.chord / big_r,
            s.beta.to_degrees()
        ));
    }
    write_atomic(&a.out.join("geom.txt"), &[geom], &inputs)?;
    // QPROP prop file.
    write_atomic(&a.out.join("prop.qprop"), &[write_prop(&sc.prop.file)], &inputs)?;
    // Airfoils, Selig order.
    for (i, t) in &sc.airfoils {
        write_atomic(
            &a.out.join("airfoils").join(format!("station_{i:02}.dat")),
            &[t],
            &inputs,
        )?;
    }
    // Plots.
    write_figure(
        &a.out.join("plots/sections.svg"),
        &propbet_report::scan::sections_figure(g),
        &inputs,
    )?;
    write_figure(
        &a.out.join("plots/distributions.svg"),
        &propbet_report::scan::distributions_figure(g, reference),
        &inputs,
    )?;
    if let Some(c) = &g.colour {
        let fig = propbet_report::scan::colour_figure(c);
        write_figure(&a.out.join("plots/colour_histogram.svg"), &fig, &inputs)?;
    }
    write_blades(&a.out, g, &inputs)?;
    let lab = &g.labelled;
    let (per_blade, hub_elements) = lab.counts(g.blades);
    // Summary.
    let summary = json!({
        "labels": {
            "elements": if matches!(lab.surface, Aligned::Mesh(_)) { "triangles" } else { "points" },
            "per_blade": per_blade,
            "hub": hub_elements,
        },
        "input": a.input.display().to_string(),
        "blades": g.blades,
        "tip_radius_mm": 1000.0 * g.tip_radius,
        "hub_radius_mm": g.hub_radius.map(|h| 1000.0 * h),
        "root_radius_mm": 1000.0 * g.root_radius,
        "section_kind": g.kind,
        "samples": g.samples,
        // Millimetres per input unit, as the box's known size says.
        "box": g.box_fit.as_ref().map(|b| json!({"scale": 1000.0 * b.scale, "rms_mm": 1000.0 * b.rms, "faces": b.faces})),
        "notes": g.notes,
        "stations": g.stations,
        "failed": g.failed,
    });
    write_atomic(
        &a.out.join("scan.json"),
        &[serde_json::to_string_pretty(&summary)?],
        &inputs,
    )?;
    lock.finish()
}

/// The scan on the terminal.
pub fn print_summary(sc: &Scanned) {
    let (g, reference) = (&sc.geometry, sc.reference.as_deref());
    println!("{}", propbet_report::scan::summary(g));
    println!("  {}", propbet_report::scan::accuracy(g));
    for n in &g.notes {
        println!("  {n}");
    }
    for f in &g.failed {
        println!("  r/R {:.3}: {}", f.r_r, f.reason);
    }
    if let Some(line) = reference.and_then(|t| propbet_report::scan::reference_check(g, t)) {
        println!("{line}");
    }
}
