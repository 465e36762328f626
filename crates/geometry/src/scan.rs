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

/// The frame from a manual alignment.
fn manual_frame<S: Surface>(m: &S, man: &MmManual) -> Result<Frame, ScanError> {
    let x = man.tip - man.root;
    if x.norm() == 0.0 {
        return Err(ScanError::Input(
            "manual alignment: root and tip are the same point".into(),
        ));
    }
    let x = x.normalize();
    // Rotation axis: the direction of least spread across the blade axis (the second-moment
    // tensor projected off x).
    let (_, c, second) = moments(&m.samples());
    let across = Matrix3::identity() - x * x.transpose();
    let e = nalgebra::SymmetricEigen::new(across * second * across);
    // The smallest eigenvalue across x (the one along x is ~0 by construction).
    let mut best = (f64::INFINITY, Vector3::z());
    for k in 0..3 {
        let v = e.eigenvectors.column(k).into_owned();
        if v.dot(&x).abs() < 0.5 && e.eigenvalues[k] < best.0 {
            best = (e.eigenvalues[k], v);
        }
    }
    let z = best.1 - x * x.dot(&best.1);
    let [ax, ay, az] = man.rotate_deg.map(f64::to_radians);
    let corr = nalgebra::Rotation3::from_euler_angles(ax, ay, az);
    // The hub: the root point moved along the blade axis to the station of the centroid.
    let origin = man.origin.unwrap_or_else(|| man.root + x * x.dot(&(c - man.root)));
    // Blade count, blade 0's azimuth and the nose / thrust checks about this axis (the blades
    // must still be alike); then the user's corrections.
    let mut f = align_about(m, origin, z, x, man.scale)?;
    f.rot = corr.matrix() * f.rot;
    f.notes.insert(0, "manual alignment (root and tip points)".into());
    Ok(f)
}

/// Hub radius: the largest radius below `limit` where the cut goes all round the axis (no
/// angular gap over 20°), by a scan in `step` then bisection.
fn hub_radius<S: Surface>(s: &S, limit: f64, step: f64) -> Option<f64> {
    // At most 2,000 cuts, whatever the size (a corrupt cloud reaches 1e34 mm).
    let step = step.max(limit / 2000.0);
    let full = |r: f64| {
        let mut th: Vec<f64> = s.cylinder_cut(r).iter().map(|p| p.0).collect();
        if th.len() < 18 {
            return false;
        }
        th.sort_by(f64::total_cmp);
        let gap = th.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
        let wrap = th[0] + 2.0 * std::f64::consts::PI - th[th.len() - 1];
        gap.max(wrap) < 20f64.to_radians()
    };
    // The outermost closed ring inside `limit` (below the blades' roots only blades cross a
    // ring): the hub's wall. Not the end of the first run of closed rings: near the axis a
    // cloud's end caps put few points in a cut, so a ring there can look closed with an open
    // one just beyond (a 6 mm hub was read as 1.3-2 mm).
    let mut r = step;
    let mut last = None;
    while r < limit {
        if full(r) {
            last = Some(r);
        }
        r += step;
    }
    let (mut lo, mut hi) = (last?, last? + step);
    for _ in 0..20 {
        let m = 0.5 * (lo + hi);
        if full(m) {
            lo = m;
        } else {
            hi = m;
        }
    }
    // A cloud's cut at r holds the points within half a slab of it: the wall is that much
    // inside the last closed ring.
    Some((lo - s.cut_half_width()).max(step))
}

/// The section of blade 0 at radius r in the frame, for either kind.
fn section_at<S: Surface + ScanSurface>(s: &S, r: f64, kind: SectionKind, blades: usize) -> Vec<Vec<CylPoint>> {
    match kind {
        SectionKind::Cylindrical => split_blades(&s.cylinder_cut(r), blades),
        SectionKind::Planar => vec![s.planar_cut(r, blades)],
    }
}

/// How much lower (relative) a neighbour-seeded NACA fit's objective must be to replace the
/// station's own fit. Smaller differences are what the noise moves: on the generated cloud a
/// 0.8 % lower objective came with a 0.4 % shorter chord, away from the truth; on meshes the
/// two starts end at the same fit. A station stuck in a wrong minimum gains far more.
const RESEED_GAIN: f64 = 0.02;

/// A station's section after the first fit.
struct Cut {
    x: f64,
    r: f64,
    secs: Vec<Vec<CylPoint>>,
    shape: SectionShape,
    uw: Vec<(f64, f64)>,
    naca: NacaFit,
}

fn finish<S: Surface + Sync + ScanSurface>(
    local: &S,
    mut frame: Frame,
    opts: &MmOptions,
    mut notes: Vec<String>,
    samples: usize,
    box_fit: Option<BoxFit>,
    colour: Option<ColourReport>,
) -> Result<Geometry, ScanError> {
    // The tip in mm, whatever unit the frame was found in.
    let tip = local.max_radius();
    frame.tip_radius = tip;
    if !(tip.is_finite() && tip <= MAX_RADIUS_MM) {
        return Err(ScanError::Input(format!(
            "the surface reaches {tip:.4e} mm from the axis: not a propeller (a corrupted file, stray points or \
             wrong units; --crop keeps a region)"
        )));
    }
    plausibility(tip, &mut notes);
    let blades = frame.blades;
    let hub = hub_radius(local, 0.5 * tip, 0.25);
    // Root: the first radius beyond the hub where blade 0 has a section.
    let mut root = hub.unwrap_or(0.0);
    {
        let step = 0.25f64.max(tip / 4000.0);
        let mut r = root + step;
        while r < tip {
            if split_blades(&local.cylinder_cut(r), blades)[0].len() >= 8 {
                root = r;
                break;
            }
            r += step;
        }
    }
    // First pass: each station cut, measured and fitted from its own measure.
    let cuts: Vec<Result<Cut, Failed>> = opts
        .stations
        .par_iter()
        .map(|&x| {
            let r = x * tip;
            let fail = |reason: String| Failed { r_r: x, reason };
            if r <= root {
                return Err(fail(format!("r = {r:.2} mm is inside the hub / root (blades begin at {root:.2} mm)")));
            }
            let secs = section_at(local, r, opts.kind, blades);
            let pts = &secs[0];
            if pts.len() < MIN_SECTION_POINTS {
                return Err(fail(format!(
                    "only {} points in the section at r = {r:.2} mm (at least {MIN_SECTION_POINTS} needed): the scan is too sparse here",
                    pts.len()
                )));
            }
            let shape = measure(pts, r).ok_or_else(|| fail("the section could not be measured".into()))?;
            let uw: Vec<(f64, f64)> = pts.iter().map(|&(t, z)| (r * t, z)).collect();
            let naca = fit_naca(&uw, &shape).ok_or_else(|| fail("the NACA fit failed".into()))?;
            Ok(Cut { x, r, secs, shape, uw, naca })
        })
        .collect();
    // Second pass: the NACA fit started again from each neighbour's shape where it differs
    // by more than 1 % t/c, 0.5 % camber or 0.1 camber position (closer starts end at the
    // station's own fit: tried on the APC, BladeX and Aerostar meshes);
    // it replaces the station's own fit when its objective is lower by more than RESEED_GAIN.
    let reseeded: Vec<Option<NacaFit>> = (0..cuts.len())
        .into_par_iter()
        .map(|i| {
            let c = cuts[i].as_ref().ok()?;
            let own = c.naca.shape();
            let starts: Vec<[f64; 3]> = [i.checked_sub(1), Some(i + 1)]
                .into_iter()
                .flatten()
                .filter_map(|j| cuts.get(j)?.as_ref().ok())
                .map(|n| n.naca.shape())
                .filter(|s| {
                    (s[0] - own[0]).abs() > 0.01 || (s[1] - own[1]).abs() > 0.005 || (s[2] - own[2]).abs() > 0.1
                })
                .collect();
            if starts.is_empty() {
                return None;
            }
            fit_naca_from(&c.uw, &c.shape, &starts).filter(|f| f.cost < c.naca.cost * (1.0 - RESEED_GAIN))
        })
        .collect();
    let improved = reseeded.iter().filter(|f| f.is_some()).count();
    if improved > 0 {
        notes.push(format!(
            "NACA fit: {improved} station(s) fit better from a neighbouring station's shape"
        ));
    }
    let results: Vec<Result<ScanStation, Failed>> = cuts
        .into_par_iter()
        .zip(reseeded)
        .map(|(cut, better)| {
            let Cut {
                x, r, secs, uw, naca, ..
            } = cut?;
            let naca = better.unwrap_or(naca);
            let cst = fit_cst(&uw, &naca);
            let ((t_c, t_pos), (camber, camber_pos)) = match &cst {
                Some(c) => c.thickness_camber(),
                None => ((naca.t_c, 0.3), (naca.camber, naca.camber_pos)),
            };
            let spread = {
                let b: Vec<f64> = secs.iter().filter_map(|p| measure(p, r)).map(|s| s.beta).collect();
                b.iter().copied().fold(f64::NEG_INFINITY, f64::max) - b.iter().copied().fold(f64::INFINITY, f64::min)
            };
            let (sb, cb) = naca.beta.sin_cos();
            let mid = (naca.le.0 - 0.5 * naca.chord * cb, naca.le.1 - 0.5 * naca.chord * sb);
            Ok(ScanStation {
                r_r: x,
                r: r / MM,
                chord: naca.chord / MM,
                beta: naca.beta,
                t_c,
                t_pos,
                camber,
                camber_pos,
                le_offset: naca.le.0 / MM,
                skew: mid.0 / r,
                rake: mid.1 / MM,
                naca: naca.scaled(1.0 / MM),
                cst: cst.map(|c| c.scaled(1.0 / MM)),
                points: secs[0].len(),
                blade_spread: spread,
                uw: uw.iter().map(|&(u, w)| (u / MM, w / MM)).collect(),
            })
        })
        .collect();
    let (mut stations, mut failed) = (Vec::new(), Vec::new());
    for r in results {
        match r {
            Ok(s) => stations.push(s),
            Err(f) => failed.push(f),
        }
    }
    if stations.is_empty() {
        return Err(ScanError::Input(format!(
            "no station could be measured: {}",
            failed
                .iter()
                .map(|f| format!("r/R {:.3}: {}", f.r_r, f.reason))
                .collect::<Vec<_>>()
                .join("; ")
        )));
    }
    Ok(Geometry {
        blades,
        tip_radius: tip / MM,
        hub_radius: hub.map(|h| h / MM),
        root_radius: root / MM,
        stations,
        failed,
        box_fit: box_fit.map(|b| BoxReport {
            scale: b.scale * opts.units / MM,
            rms: b.rms / MM,
            faces: b.faces,
            points: b.points,
        }),
        colour,
        samples,
        notes,
        kind: opts.kind,
        labelled: Labelled {
            surface: local.aligned(),
            blade: blade_labels(local, blades, root, tip),
        },
    })
}

/// What a scanned surface offers beyond [`Surface`].
pub trait ScanSurface {
    /// Planar sections: the points of the plane x = r within blade 0's sector, as (y / r, z)
    /// so that the unrolled measures apply unchanged (u = y).
    fn planar_cut(&self, r: f64, blades: usize) -> Vec<CylPoint>;
    /// The surface as kept for export.
    fn aligned(&self) -> Aligned;
}

fn in_sector(p: &Vector3<f64>, blades: usize) -> bool {
    p.y.atan2(p.x).abs() < std::f64::consts::PI / blades.max(1) as f64
}

impl ScanSurface for Mesh {
    fn planar_cut(&self, r: f64, blades: usize) -> Vec<CylPoint> {
        let mut out = Vec::new();
        for i in 0..self.triangles.len() {
            let c = self.corners(i);
            for k in 0..3 {
                let (a, b) = (c[k], c[(k + 1) % 3]);
                let (da, db) = (a.x - r, b.x - r);
                if (da < 0.0) != (db < 0.0) {
                    let t = da / (da - db);
                    let p = a + t * (b - a);
                    if in_sector(&p, blades) {
                        out.push((p.y / r, p.z));
                    }
                }
            }
        }
        out
    }
    fn aligned(&self) -> Aligned {
        Aligned::Mesh(self.clone())
    }
}

impl ScanSurface for Points {
    fn planar_cut(&self, r: f64, blades: usize) -> Vec<CylPoint> {
        self.points
            .iter()
            .filter(|p| (p.x - r).abs() <= 0.5 * self.slab && in_sector(p, blades))
            .map(|p| (p.y / r, p.z))
            .collect()
    }
    fn aligned(&self) -> Aligned {
        Aligned::Cloud(Cloud {
            points: self.points.clone(),
            colors: None,
        })
    }
}
