//! The scan pipeline: a mesh or a cloud → the propeller frame → sections at chosen r/R →
//! NACA and CST fits → per-station geometry, hub and tip radius.
//!
//! Clouds: units → colour filter (blade colours kept, box colours set aside; thresholds by
//! Otsu unless given) → region-of-interest crop → statistical outlier removal → reference box
//! registration (scale, pose, hub at the known offset) or automatic alignment → slab sections.

use nalgebra::{Matrix3, Vector3};
use rayon::prelude::*;
use serde::Serialize;
use thiserror::Error;

use crate::align::{align_about, auto_align, moments, AlignError, Frame, Points, Surface};
use crate::boxfit::{register_box, BoxError, BoxFit};
use crate::cloud::{colour_distances, crop, outlier_mask, Cloud, Histogram};
use crate::fit::{fit_cst, fit_naca, fit_naca_from, Cst, NacaFit};
use crate::mesh::Mesh;
use crate::section::{circular_mean, measure, split_blades, CylPoint, SectionShape};

/// Fewest points a blade section needs.
pub const MIN_SECTION_POINTS: usize = 24;

/// How sections are cut.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum SectionKind {
    /// r = const (what blade-element theory needs).
    Cylindrical,
    /// The plane x = r across blade 0 (the published methods).
    Planar,
}

/// Manual alignment: a root and a tip point of blade 0 (input units) give the blade axis and
/// the hub (unless `origin` is given: the root point moved along the blade axis to the
/// station of the surface's centroid); the rotation axis is the direction of least spread
/// across the blade axis; then rotations about the frame's x, y, z.
#[derive(Debug, Clone, PartialEq)]
pub struct Manual {
    /// A point at the blade root (input units).
    pub root: Vector3<f64>,
    /// A point at the blade tip (input units).
    pub tip: Vector3<f64>,
    /// The hub centre (default: the root point moved along the blade axis to the centroid).
    pub origin: Option<Vector3<f64>>,
    /// Corrections about x, y, z [rad], applied in that order.
    pub rotate: [f64; 3],
    /// Length of one input unit [m] (e.g. from a known length).
    pub scale: f64,
}

/// Reference box.
#[derive(Debug, Clone, PartialEq)]
pub struct BoxSpec {
    /// Edge lengths along the propeller frame's x, y, z [m].
    pub dims: [f64; 3],
    /// The box centre in the propeller frame [m] (the box is fixed to the hub).
    pub offset: [f64; 3],
    /// Colours of its faces.
    pub colours: Vec<[u8; 3]>,
    /// One point on each visible face (input units); empty: faces found by RANSAC.
    pub seeds: Vec<Vector3<f64>>,
}

/// What the pipeline does.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanOptions {
    /// Length of one input unit [m] (0.001 for mm, 1 for m, 0.0254 for inches).
    pub scale: f64,
    /// Whether the user gave the scale (a unit or a known length); false: millimetres assumed,
    /// which a point cloud (photogrammetry has no scale of its own) says in its notes.
    pub scale_given: bool,
    /// Stations as r/R.
    pub stations: Vec<f64>,
    /// Section kind.
    pub kind: SectionKind,
    /// Slab thickness for clouds [m].
    pub slab: f64,
    /// A cloud's slab is widened (up to 4 times) until a section at 0.6 R holds this many
    /// points per blade (0: never widened).
    pub slab_points: usize,
    /// Blade colours to keep (empty: keep every point).
    pub blade_colours: Vec<[u8; 3]>,
    /// Colour distance threshold (None: Otsu's suggestion).
    pub colour_threshold: Option<f64>,
    /// Reference box.
    pub reference_box: Option<BoxSpec>,
    /// Region of interest (input units): keep points / triangles with all corners inside.
    pub crop: Option<(Vector3<f64>, Vector3<f64>)>,
    /// Statistical outlier removal: neighbours and standard deviations (None: off).
    pub outliers: Option<(usize, f64)>,
    /// Manual alignment instead of automatic.
    pub manual: Option<Manual>,
}

impl Default for ScanOptions {
    fn default() -> Self {
        Self {
            scale: 0.001,
            scale_given: false,
            stations: default_stations(),
            kind: SectionKind::Cylindrical,
            slab: 0.25e-3,
            slab_points: 400,
            blade_colours: Vec::new(),
            colour_threshold: None,
            reference_box: None,
            crop: None,
            outliers: Some((8, 2.5)),
            manual: None,
        }
    }
}

/// Millimetres per metre: the geometry pipeline works in millimetres inside (its tolerances,
/// slab widths and RANSAC thresholds are stated so); its public types are SI.
const MM: f64 = 1000.0;

impl ScanOptions {
    /// The options in the pipeline's working units (mm, degrees).
    fn to_mm(&self) -> MmOptions {
        MmOptions {
            units: self.scale * MM,
            stations: self.stations.clone(),
            kind: self.kind,
            slab: self.slab * MM,
            slab_points: self.slab_points,
            blade_colours: self.blade_colours.clone(),
            colour_threshold: self.colour_threshold,
            reference_box: self.reference_box.as_ref().map(|b| MmBox {
                dims: b.dims.map(|x| x * MM),
                offset: b.offset.map(|x| x * MM),
                colours: b.colours.clone(),
                seeds: b.seeds.clone(),
            }),
            crop: self.crop,
            outliers: self.outliers,
            manual: self.manual.as_ref().map(|m| MmManual {
                root: m.root,
                tip: m.tip,
                origin: m.origin,
                rotate_deg: m.rotate.map(f64::to_degrees),
                scale: m.scale * MM,
            }),
        }
    }
}

/// [`Manual`] in the working units: rotations [deg], input units → mm.
#[derive(Debug, Clone, PartialEq)]
struct MmManual {
    root: Vector3<f64>,
    tip: Vector3<f64>,
    origin: Option<Vector3<f64>>,
    rotate_deg: [f64; 3],
    scale: f64,
}

/// [`BoxSpec`] in the working units [mm].
#[derive(Debug, Clone, PartialEq)]
struct MmBox {
    dims: [f64; 3],
    offset: [f64; 3],
    colours: Vec<[u8; 3]>,
    seeds: Vec<Vector3<f64>>,
}

/// [`ScanOptions`] in the working units: input units → mm, slab [mm].
#[derive(Debug, Clone, PartialEq)]
struct MmOptions {
    units: f64,
    stations: Vec<f64>,
    kind: SectionKind,
    slab: f64,
    slab_points: usize,
    blade_colours: Vec<[u8; 3]>,
    colour_threshold: Option<f64>,
    reference_box: Option<MmBox>,
    crop: Option<(Vector3<f64>, Vector3<f64>)>,
    outliers: Option<(usize, f64)>,
    manual: Option<MmManual>,
}

/// 25 stations from r/R 0.15 to 0.97.
pub fn default_stations() -> Vec<f64> {
    (0..25).map(|k| 0.15 + 0.82 * k as f64 / 24.0).collect()
}

/// Why a scan cannot be processed.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ScanError {
    /// Alignment.
    #[error(transparent)]
    Align(#[from] AlignError),
    /// Reference box.
    #[error(transparent)]
    Box(#[from] BoxError),
    /// Nothing left after filtering, or a bad option.
    #[error("{0}")]
    Input(String),
}

/// One measured station of a scan (SI: the geometry pipeline's millimetres and degrees are
/// converted here).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScanStation {
    /// r/R.
    pub r_r: f64,
    /// Radius [m].
    pub r: f64,
    /// Chord [m].
    pub chord: f64,
    /// Blade angle to the rotation plane [rad].
    pub beta: f64,
    /// Maximum thickness / chord (CST shape).
    pub t_c: f64,
    /// Chord position of the maximum thickness.
    pub t_pos: f64,
    /// Maximum camber / chord (CST shape).
    pub camber: f64,
    /// Its chord position.
    pub camber_pos: f64,
    /// Leading edge's circumferential offset from the blade axis [m] (sweep).
    pub le_offset: f64,
    /// Angular position of the mid-chord point [rad] (skew).
    pub skew: f64,
    /// Axial position of the mid-chord point [m] (rake, positive towards thrust).
    pub rake: f64,
    /// The NACA 4-digit fit (lengths [m]).
    pub naca: NacaFit,
    /// The CST fit (rms [m]).
    pub cst: Option<Cst>,
    /// Points of blade 0 in the section.
    pub points: usize,
    /// Spread of the blade angle between blades [rad] (max − min of the quick measure).
    pub blade_spread: f64,
    /// The section's points (u, w) [m], for plots.
    #[serde(skip)]
    pub uw: Vec<(f64, f64)>,
}

/// What the reference box registration found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BoxReport {
    /// Length of one input unit [m], as the box's known size says.
    pub scale: f64,
    /// RMS point-to-face distance [m].
    pub rms: f64,
    /// Faces found.
    pub faces: usize,
    /// Box points used.
    pub points: usize,
}

/// A station that could not be measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Failed {
    /// r/R.
    pub r_r: f64,
    /// Why.
    pub reason: String,
}

/// What the colour filter did.
#[derive(Debug, Clone, PartialEq)]
pub struct ColourReport {
    /// Histogram of distances to the blade colours.
    pub histogram: Histogram,
    /// The threshold used.
    pub threshold: f64,
    /// Otsu's suggestion.
    pub suggested: f64,
    /// Points kept as blade.
    pub kept: usize,
    /// Points in all.
    pub total: usize,
}

/// The geometry found in a scan.
#[derive(Debug, Clone)]
pub struct Geometry {
    /// Blade count.
    pub blades: usize,
    /// Tip radius [m].
    pub tip_radius: f64,
    /// Hub radius [m]: the largest radius where the surface goes all round the axis (None: no
    /// hub in the scan).
    pub hub_radius: Option<f64>,
    /// Where the blades begin [m].
    pub root_radius: f64,
    /// Measured stations.
    pub stations: Vec<ScanStation>,
    /// Stations that failed.
    pub failed: Vec<Failed>,
    /// The reference box registration.
    pub box_fit: Option<BoxReport>,
    /// The colour filter.
    pub colour: Option<ColourReport>,
    /// Points or triangles used, after cleaning.
    pub samples: usize,
    /// What was decided, in order.
    pub notes: Vec<String>,
    /// Section kind.
    pub kind: SectionKind,
    /// The cleaned surface in the propeller frame [mm], each triangle or point labelled by blade.
    pub labelled: Labelled,
}

/// The cleaned surface in the propeller frame [mm].
#[derive(Debug, Clone)]
pub enum Aligned {
    /// A mesh: labels are per triangle.
    Mesh(Mesh),
    /// A cloud (with its colours when it had them): labels are per point.
    Cloud(Cloud),
}

/// The surface and, for each triangle or point, its blade (0 along +x, counted towards
/// +theta) or `None` for the hub (inside the blade root radius).
#[derive(Debug, Clone)]
pub struct Labelled {
    /// The surface in the frame.
    pub surface: Aligned,
    /// One entry per triangle or point.
    pub blade: Vec<Option<u8>>,
}

impl Labelled {
    /// How many elements each blade holds, and the hub last.
    pub fn counts(&self, blades: usize) -> (Vec<usize>, usize) {
        let mut n = vec![0; blades];
        let mut hub = 0;
        for b in &self.blade {
            match b {
                Some(k) => n[*k as usize] += 1,
                None => hub += 1,
            }
        }
        (n, hub)
    }
}

/// Labels each sample of the surface (in the frame) by blade: the sections at 48 radii from
/// the root to the tip give each blade's middle angle there (skew included), and an element
/// goes to the blade whose middle, interpolated at its radius, is nearest in angle. Elements
/// inside `root` are hub (`None`).
pub fn blade_labels<S: Surface + Sync>(s: &S, blades: usize, root: f64, tip: f64) -> Vec<Option<u8>> {
    use std::f64::consts::PI;
    let n = blades.max(1);
    let step = 2.0 * PI / n as f64;
    let wrap = |a: f64| (a + PI).rem_euclid(2.0 * PI) - PI;
    const RINGS: usize = 48;
    // (radius, each blade's middle angle offset from its axis, when the ring found it).
    let table: Vec<(f64, Vec<Option<f64>>)> = (0..RINGS)
        .into_par_iter()
        .map(|i| {
            let r = root + (tip - root) * (i as f64 + 0.5) / RINGS as f64;
            let mids = split_blades(&s.cylinder_cut(r), n)
                .iter()
                .map(|p| (!p.is_empty()).then(|| circular_mean(p.iter().map(|&(t, _)| t))))
                .collect();
            (r, mids)
        })
        .collect();
    // Per blade, the rings that found it (ascending radius).
    let found: Vec<Vec<(f64, f64)>> = (0..n)
        .map(|k| table.iter().filter_map(|(r, m)| Some((*r, m[k]?))).collect())
        .collect();
    // A blade's middle at radius r: linear between the nearest rings that found it.
    let middle = |k: usize, r: f64| -> f64 {
        let f = &found[k];
        let i = f.partition_point(|(rr, _)| *rr < r);
        match (i.checked_sub(1).map(|j| f[j]), f.get(i)) {
            (Some((ra, a)), Some(&(rb, b))) if rb > ra => a + (r - ra) / (rb - ra) * wrap(b - a),
            (_, Some(&(_, m))) | (Some((_, m)), None) => m,
            (None, None) => 0.0,
        }
    };
    s.samples()
        .par_iter()
        .map(|(g, _)| {
            let r = g.x.hypot(g.y);
            if r < root {
                return None;
            }
            let th = g.y.atan2(g.x);
            (0..n)
                .map(|k| (k, wrap(th - k as f64 * step - middle(k, r)).abs()))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(k, _)| k as u8)
        })
        .collect()
}

/// Propeller sizes this tool expects [mm]: a warning outside.
pub const PLAUSIBLE_DIAMETER_MM: (f64, f64) = (25.0, 3000.0);

/// Largest radius a scan may reach [mm] (100 m): beyond it the input is not a propeller.
const MAX_RADIUS_MM: f64 = 1.0e5;

fn plausibility(tip: f64, notes: &mut Vec<String>) {
    let d = 2.0 * tip;
    if d < PLAUSIBLE_DIAMETER_MM.0 || d > PLAUSIBLE_DIAMETER_MM.1 {
        notes.push(format!(
            "warning: diameter {d:.1} mm is implausible for a propeller ({:.0}-{:.0} mm); are the units right (--units)?",
            PLAUSIBLE_DIAMETER_MM.0, PLAUSIBLE_DIAMETER_MM.1
        ));
    }
}

/// Processes a mesh.
pub fn scan_mesh(mesh: &Mesh, opts: &ScanOptions) -> Result<Geometry, ScanError> {
    let opts = &opts.to_mm();
    let mut mesh = mesh.clone();
    if let Some((lo, hi)) = opts.crop {
        let inside = |v: &Vector3<f64>| (0..3).all(|k| v[k] >= lo[k] && v[k] <= hi[k]);
        let before = mesh.triangles.len();
        mesh.triangles
            .retain(|t| t.iter().all(|&i| inside(&mesh.vertices[i as usize])));
        if mesh.triangles.is_empty() {
            return Err(ScanError::Input(format!(
                "the crop box keeps none of the {before} triangles"
            )));
        }
    }
    let mut notes = Vec::new();
    let frame = match &opts.manual {
        Some(m) => manual_frame(&mesh, m)?,
        None => {
            let mut f = auto_align(&mesh)?;
            f.scale = opts.units;
            f
        }
    };
    let samples = mesh.triangles.len();
    let local = mesh.in_frame(&frame);
    notes.extend(frame.notes.iter().cloned());
    finish(&local, frame, opts, notes, samples, None, None)
}

/// The points within a colour distance of some colours.
struct ColourSelection {
    keep: Vec<bool>,
    histogram: Histogram,
    suggested: f64,
    threshold: f64,
}

/// Selects by RGB distance to `colours`: the given threshold, or Otsu's suggestion.
fn colour_select(
    cloud: &Cloud,
    colours: &[[u8; 3]],
    given: Option<f64>,
    no_colours: &str,
) -> Result<ColourSelection, ScanError> {
    if cloud.colors.is_none() {
        return Err(ScanError::Input(no_colours.into()));
    }
    let d = colour_distances(cloud, colours);
    let histogram = Histogram::of(&d);
    let suggested = histogram.otsu();
    let threshold = given.unwrap_or(suggested);
    Ok(ColourSelection {
        keep: d.iter().map(|&x| x <= threshold).collect(),
        histogram,
        suggested,
        threshold,
    })
}

/// Processes a cloud.
pub fn scan_cloud(cloud: &Cloud, opts: &ScanOptions) -> Result<Geometry, ScanError> {
    scan_cloud_mm(cloud, &opts.to_mm(), opts.scale_given).map_err(|e| {
        // A coloured cloud scanned without its blade colours keeps the background: say which
        // option drops it.
        if cloud.colors.is_some() && opts.blade_colours.is_empty() {
            ScanError::Input(format!(
                "{e}\nthe cloud has colours: give the blade's with --blade-colour (for example \
                 --blade-colour orange,black) to drop the background and the reference box"
            ))
        } else {
            e
        }
    })
}

/// A cloud filtered: the blade's points, the colour filter's report, the reference box's points.
struct Filtered {
    blade: Cloud,
    colour: Option<ColourReport>,
    box_pts: Vec<Vector3<f64>>,
}

/// The cloud's points that are blade (its colours, the crop, without outliers), with the colour
/// filter's report, and the reference box's points (its colours).
fn filtered(cloud: &Cloud, opts: &MmOptions, notes: &mut Vec<String>) -> Result<Filtered, ScanError> {
    let total = cloud.points.len();
    let mut blade = cloud.clone();
    let mut colour = None;
    let mut box_pts = Vec::new();
    if let Some(spec) = &opts.reference_box {
        let sel = colour_select(
            cloud,
            &spec.colours,
            opts.colour_threshold,
            "the reference box is found by its colours, and the cloud has none",
        )?;
        box_pts = cloud
            .points
            .iter()
            .zip(&sel.keep)
            .filter(|(_, &k)| k)
            .map(|(p, _)| *p)
            .collect();
        notes.push(format!(
            "{} box points (colour distance <= {:.0})",
            box_pts.len(),
            sel.threshold
        ));
    }
    if !opts.blade_colours.is_empty() {
        let sel = colour_select(
            cloud,
            &opts.blade_colours,
            opts.colour_threshold,
            "blade colours were given, but the cloud has no colours",
        )?;
        blade.retain(&sel.keep);
        notes.push(format!(
            "colour filter: {} of {total} points within {:.0} of the blade colours (Otsu suggests {:.0})",
            blade.points.len(),
            sel.threshold,
            sel.suggested
        ));
        colour = Some(ColourReport {
            histogram: sel.histogram,
            threshold: sel.threshold,
            suggested: sel.suggested,
            kept: blade.points.len(),
            total,
        });
    }
    if let Some((lo, hi)) = opts.crop {
        let keep = crop(&blade, lo, hi);
        blade.retain(&keep);
        notes.push(format!("crop: {} points inside", blade.points.len()));
    }
    if let Some((k, sig)) = opts.outliers {
        let keep = outlier_mask(&blade.points, k, sig);
        let before = blade.points.len();
        blade.retain(&keep);
        notes.push(format!(
            "outlier removal ({k} neighbours, {sig} sd): {} of {before} points dropped",
            before - blade.points.len()
        ));
    }
    if blade.points.len() < 100 {
        return Err(ScanError::Input(format!(
            "only {} points left after filtering (of {total}): check the colours and the crop",
            blade.points.len()
        )));
    }
    Ok(Filtered { blade, colour, box_pts })
}

fn scan_cloud_mm(cloud: &Cloud, opts: &MmOptions, scale_given: bool) -> Result<Geometry, ScanError> {
    let mut notes = Vec::new();
    if !scale_given && opts.reference_box.is_none() {
        notes.push(
            "SCALE ASSUMED: 1 file unit = 1 mm (no --units, --known-length or --box given). A point \
             cloud from photogrammetry has no scale of its own: every length below is only right if \
             the cloud is in millimetres"
                .to_string(),
        );
    }
    let Filtered { blade, colour, box_pts } = filtered(cloud, opts, &mut notes)?;
    let pts = Points {
        points: blade.points.clone(),
        slab: opts.slab / opts.units,
    };
    let (frame, box_fit) = match (&opts.reference_box, &opts.manual) {
        (_, Some(m)) => (manual_frame(&pts, m)?, None),
        (Some(spec), None) => {
            let centre: Vector3<f64> = pts.points.iter().sum::<Vector3<f64>>() / pts.points.len() as f64;
            let offset = Vector3::from(spec.offset);
            let scaled: Vec<Vector3<f64>> = box_pts.iter().map(|p| p * opts.units).collect();
            let seeds: Vec<Vector3<f64>> = spec.seeds.iter().map(|p| p * opts.units).collect();
            let fit = register_box(&scaled, spec.dims, Some((centre * opts.units, offset)), &seeds)?;
            // Cloud → box frame (mm) → propeller frame: p = s R u p_in + t + offset.
            let s = fit.scale * opts.units;
            let origin = -(fit.rot.transpose() * (fit.trans + offset)) / s;
            // Axis: the box's z; blade azimuth and thrust from the blades.
            let z = fit.rot.row(2).transpose();
            let x0 = fit.rot.row(0).transpose();
            let mut f = align_about(&pts, origin, z, x0, s)?;
            f.notes
                .insert(0, "frame from the reference box (its z is the shaft)".into());
            (f, Some(fit))
        }
        (None, None) => {
            let mut f = auto_align(&pts)?;
            f.scale = opts.units;
            (f, None)
        }
    };
    if let Some(b) = &box_fit {
        notes.extend(b.notes.iter().cloned());
    }
    notes.extend(frame.notes.iter().cloned());
    let mut local = pts.in_frame(&frame);
    local.slab = opts.slab;
    if opts.slab_points > 0 && frame.blades > 0 {
        let per_blade = local.cylinder_cut(0.6 * local.max_radius()).len() / frame.blades;
        if per_blade < opts.slab_points {
            let f = (opts.slab_points as f64 / per_blade.max(1) as f64).min(4.0);
            local.slab *= f;
            notes.push(format!(
                "sparse cloud: {per_blade} points per blade in a {} mm slab at 0.6 R; slab widened to {:.2} mm",
                opts.slab, local.slab
            ));
        }
    }
    let samples = local.points.len();
    let mut g = finish(&local, frame, opts, notes, samples, box_fit, colour)?;
    if let Aligned::Cloud(c) = &mut g.labelled.surface {
        c.colors = blade.colors;
    }
    Ok(g)
}

mod sections;

use sections::*;
