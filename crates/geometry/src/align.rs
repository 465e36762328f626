//! The propeller frame of a mesh: rotation axis from the surface's second-moment tensor (the
//! axis along which the blades are thinnest), hub centre at the area centroid, blade count
//! from the angular distribution of area in a mid-radius ring (which must be N-fold
//! symmetric), blade 0 along +x, thrust (+z) chosen so that the leading edge is at +theta
//! and higher z.

use nalgebra::{Matrix3, SymmetricEigen, Vector3};
use thiserror::Error;

use crate::mesh::Mesh;
use crate::section::{cut_points, measure, slab_points, split_blades, unrolled_chord, CylPoint};

/// Why a mesh cannot be aligned.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum AlignError {
    /// Not a propeller.
    #[error("no rotational symmetry: {0}")]
    NoSymmetry(String),
    /// Every point in one plane.
    #[error("not a propeller: {0}")]
    Flat(String),
}

/// Where the propeller frame sits in the input coordinates:
/// `p_frame = scale * rot * (p - origin)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Hub centre in input coordinates.
    pub origin: Vector3<f64>,
    /// Rows: the frame's x, y, z axes in input coordinates.
    pub rot: Matrix3<f64>,
    /// Input units → millimetres in the frame (1 for meshes unless `--units` says otherwise;
    /// found by the reference box for clouds).
    pub scale: f64,
    /// Blade count.
    pub blades: usize,
    /// Tip radius in the frame (largest distance of the surface from the axis).
    pub tip_radius: f64,
    /// What was decided and why.
    pub notes: Vec<String>,
}

impl Frame {
    /// A point in the frame.
    pub fn apply(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.scale * (self.rot * (p - self.origin))
    }
}

/// A scanned surface: a mesh, or the points of a cloud.
pub trait Surface: Sized {
    /// Weighted samples of the surface (triangle centroids by area, or points by 1).
    fn samples(&self) -> Vec<(Vector3<f64>, f64)>;
    /// The surface in a frame.
    fn in_frame(&self, f: &Frame) -> Self;
    /// The section by the cylinder of radius `r` about z (surface already in the frame).
    fn cylinder_cut(&self, r: f64) -> Vec<CylPoint>;
    /// Largest distance from the z axis.
    fn max_radius(&self) -> f64;
    /// Half the radial width of a cut: 0 for a mesh (exact intersections), half the slab for
    /// points (a cut at r holds every point within it).
    fn cut_half_width(&self) -> f64 {
        0.0
    }
    /// How much of the surface lies at each whole degree of azimuth in the ring `lo..hi`
    /// (surface already in the frame).
    fn ring_weights(&self, lo: f64, hi: f64) -> Vec<f64> {
        let mut bins = vec![0.0; 360];
        for (g, w) in self.samples() {
            let r = g.x.hypot(g.y);
            if r >= lo && r <= hi {
                let th = g.y.atan2(g.x).to_degrees().rem_euclid(360.0);
                bins[(th as usize).min(359)] += w;
            }
        }
        bins
    }
}

impl Surface for Mesh {
    fn samples(&self) -> Vec<(Vector3<f64>, f64)> {
        (0..self.triangles.len())
            .map(|i| {
                let [a, b, c] = self.corners(i);
                ((a + b + c) / 3.0, 0.5 * (b - a).cross(&(c - a)).norm())
            })
            .collect()
    }
    fn in_frame(&self, f: &Frame) -> Self {
        Mesh {
            vertices: self.vertices.iter().map(|v| f.apply(v)).collect(),
            triangles: self.triangles.clone(),
        }
    }
    fn cylinder_cut(&self, r: f64) -> Vec<CylPoint> {
        cut_points(self, r)
    }
    fn max_radius(&self) -> f64 {
        self.vertices.iter().map(|v| v.x.hypot(v.y)).fold(0.0, f64::max)
    }
    /// Exact cuts at seven radii: every degree a cut segment spans counts, so that large
    /// triangles leave no false gaps.
    fn ring_weights(&self, lo: f64, hi: f64) -> Vec<f64> {
        let mut bins = vec![0.0; 360];
        for k in 0..7 {
            let r = lo + (hi - lo) * k as f64 / 6.0;
            for i in 0..self.triangles.len() {
                let c = self.corners(i);
                let mut th = Vec::with_capacity(2);
                let mut pts = Vec::new();
                for e in 0..3 {
                    pts.clear();
                    crate::section::crossing_points(c[e], c[(e + 1) % 3], r, &mut pts);
                    th.extend(pts.iter().map(|p| p.0));
                }
                if th.len() < 2 {
                    continue;
                }
                let (a, b) = (th[0].to_degrees(), th[1].to_degrees());
                let span = (b - a + 540.0).rem_euclid(360.0) - 180.0;
                let n = span.abs().ceil().max(1.0) as usize;
                for j in 0..=n {
                    let t = (a + span * j as f64 / n as f64).rem_euclid(360.0);
                    bins[(t as usize).min(359)] += 1.0;
                }
            }
        }
        bins
    }
}

/// The points of a cloud, cut by slabs `slab` thick (same unit as the points).
#[derive(Debug, Clone, PartialEq)]
pub struct Points {
    /// Positions.
    pub points: Vec<Vector3<f64>>,
    /// Slab thickness of a cylindrical section.
    pub slab: f64,
}

impl Surface for Points {
    fn samples(&self) -> Vec<(Vector3<f64>, f64)> {
        self.points.iter().map(|p| (*p, 1.0)).collect()
    }
    fn in_frame(&self, f: &Frame) -> Self {
        Points {
            points: self.points.iter().map(|p| f.apply(p)).collect(),
            slab: self.slab * f.scale,
        }
    }
    fn cylinder_cut(&self, r: f64) -> Vec<CylPoint> {
        slab_points(&self.points, r, self.slab)
    }
    fn cut_half_width(&self) -> f64 {
        0.5 * self.slab
    }
    fn max_radius(&self) -> f64 {
        // The 99.98th percentile: a stray point must not set the tip.
        let mut r: Vec<f64> = self.points.iter().map(|v| v.x.hypot(v.y)).collect();
        if r.is_empty() {
            return 0.0;
        }
        let k = ((r.len() as f64 * 0.9998) as usize).min(r.len() - 1);
        *r.select_nth_unstable_by(k, f64::total_cmp).1
    }
}

/// Total weight, centroid and second-moment tensor about the centroid of weighted samples.
pub(crate) fn moments(samples: &[(Vector3<f64>, f64)]) -> (f64, Vector3<f64>, Matrix3<f64>) {
    let area: f64 = samples.iter().map(|s| s.1).sum();
    let first: Vector3<f64> = samples.iter().map(|s| s.0 * s.1).sum();
    let centroid = first / area.max(f64::MIN_POSITIVE);
    let mut second = Matrix3::zeros();
    for (p, w) in samples {
        let d = p - centroid;
        second += *w * d * d.transpose();
    }
    (area, centroid, second)
}

/// Blade count from the angular distribution of the surface in a ring ([`Surface::ring_weights`]):
/// contiguous occupied arcs of a 360-bin histogram (bins under 1 % of the fullest
/// count as empty, so that a few stray points do not bridge two blades).
fn blade_arcs(bins: &[f64]) -> Vec<(f64, f64)> {
    let floor = 0.01 * bins.iter().copied().fold(0.0, f64::max);
    let start = match bins.iter().position(|&x| x <= floor) {
        Some(s) => s,
        None => return Vec::new(),
    };
    // Arcs: (weight, mean angle in degrees), walking from an empty bin.
    let mut arcs = Vec::new();
    let mut cur: Option<(f64, f64, f64)> = None; // weight, sum sin, sum cos
    for k in 0..=360 {
        let i = (start + k) % 360;
        let w = bins[i];
        if w > floor {
            let t = (i as f64 + 0.5).to_radians();
            let e = cur.get_or_insert((0.0, 0.0, 0.0));
            e.0 += w;
            e.1 += w * t.sin();
            e.2 += w * t.cos();
        } else if let Some((a, s, c)) = cur.take() {
            arcs.push((a, s.atan2(c).to_degrees().rem_euclid(360.0)));
        }
    }
    arcs
}

/// Largest relative L1 difference between the blades' radial weight profiles (10 bands from
/// 20 % to 100 % of the tip radius), each blade taking the sector around its arc.
fn radial_mismatch(samples: &[(Vector3<f64>, f64)], arcs: &[(f64, f64)], tip: f64) -> f64 {
    let n = arcs.len();
    let mut prof = vec![[0.0f64; 10]; n];
    for (g, w) in samples {
        let r = g.x.hypot(g.y) / tip;
        if !(0.2..1.0).contains(&r) {
            continue;
        }
        let th = g.y.atan2(g.x).to_degrees();
        let k = (0..n)
            .min_by(|&p, &q| {
                let d = |j: usize| ((th - arcs[j].1 + 540.0).rem_euclid(360.0) - 180.0).abs();
                d(p).total_cmp(&d(q))
            })
            .unwrap_or(0);
        prof[k][(((r - 0.2) / 0.08) as usize).min(9)] += w;
    }
    let mut worst: f64 = 0.0;
    for p in &prof[1..] {
        let diff: f64 = p.iter().zip(&prof[0]).map(|(x, y)| (x - y).abs()).sum();
        let tot: f64 = prof[0].iter().sum::<f64>().max(1e-300);
        worst = worst.max(diff / tot);
    }
    worst
}

/// The least ratio of a surface's spread (rms) across its plane to its spread along it: the
/// flattest propeller meshes have a few percent (blade thickness, twist, the hub).
const FLAT: f64 = 0.005;

/// Finds the propeller frame of a surface: axis and hub centre from its second moments.
pub fn auto_align<S: Surface>(m: &S) -> Result<Frame, AlignError> {
    let samples = m.samples();
    let (area, centroid, second) = moments(&samples);
    if area.is_nan() || area <= 0.0 {
        return Err(AlignError::NoSymmetry("the surface has no area (or no point)".into()));
    }
    let eig = SymmetricEigen::new(second);
    let mut order = [0usize, 1, 2];
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let ev = |k: usize| eig.eigenvectors.column(order[k]).into_owned();
    let (l0, l1, l2) = (
        eig.eigenvalues[order[0]],
        eig.eigenvalues[order[1]],
        eig.eigenvalues[order[2]],
    );
    // A flattened mesh (every point in one plane: a projection, an export that dropped a
    // coordinate) has no blade thickness or twist to measure.
    if l0 < FLAT * FLAT * l2 {
        return Err(AlignError::Flat(format!(
            "the surface is flat: its spread across its plane is {:.2} % of its spread along it (a propeller's blades \
             have thickness and twist; was a coordinate lost in the export?)",
            100.0 * (l0.max(0.0) / l2).sqrt()
        )));
    }
    if l2 < 3.0 * l1 && l1 < 1.5 * l0 {
        return Err(AlignError::NoSymmetry(format!(
            "the shape is not flat like a propeller disc (second moments {:.3e}, {:.3e}, {:.3e}: no axis stands out)",
            l0, l1, l2
        )));
    }
    // The axis is the direction of least spread; for two slender blades the chordwise spread
    // can come close, so the second direction is tried when the blades are not alike about
    // the first.
    match align_about(m, centroid, ev(0), ev(2), 1.0) {
        Ok(f) => Ok(f),
        Err(e) if l1 < 2.0 * l0 => align_about(m, centroid, ev(1), ev(2), 1.0).map_err(|_| e),
        Err(e) => Err(e),
    }
}

/// The frame for a known axis `z` through `origin` (`x0` any direction across it), with the
/// input scaled by `scale`: blade count and symmetry check, blade 0 along +x, thrust direction.
pub fn align_about<S: Surface>(
    m: &S,
    origin: Vector3<f64>,
    z: Vector3<f64>,
    x0: Vector3<f64>,
    scale: f64,
) -> Result<Frame, AlignError> {
    let z = z.normalize();
    let x0 = (x0 - z * z.dot(&x0)).normalize();
    let y0 = z.cross(&x0);
    let rot = Matrix3::from_rows(&[x0.transpose(), y0.transpose(), z.transpose()]);
    let mut frame = Frame {
        origin,
        rot,
        scale,
        blades: 0,
        tip_radius: 0.0,
        notes: Vec::new(),
    };
    let local = m.in_frame(&frame);
    let tip = local.max_radius();
    let samples = local.samples();
    let arcs = blade_arcs(&local.ring_weights(0.45 * tip, 0.75 * tip));
    let n = arcs.len();
    let total: f64 = arcs.iter().map(|a| a.0).sum();
    let even = n >= 2
        && arcs.iter().all(|a| (a.0 * n as f64 / total - 1.0).abs() < 0.25)
        && arcs.windows(2).all(|w| {
            let d = (w[1].1 - w[0].1).rem_euclid(360.0);
            (d - 360.0 / n as f64).abs() < 6.0
        });
    // Each blade must carry the same area at every radius (a single blade about its own middle
    // also shows two arcs, but its root half and tip half differ).
    let profile_mismatch = if even {
        radial_mismatch(&samples, &arcs, tip)
    } else {
        0.0
    };
    let even = even && profile_mismatch < 0.3;
    if !even {
        return Err(AlignError::NoSymmetry(format!(
            "the surface at 45-75 % of the largest radius ({tip:.3}) forms {n} arc(s) that are not alike and evenly spaced \
             (weights {:?}); is this a propeller, cropped to it?",
            arcs.iter().map(|a| format!("{:.3}", a.0)).collect::<Vec<_>>()
        )));
    }
    // Blade 0 along +x.
    let a0 = arcs[0].1.to_radians();
    let rz = Matrix3::new(a0.cos(), a0.sin(), 0.0, -a0.sin(), a0.cos(), 0.0, 0.0, 0.0, 1.0);
    frame.rot = rz * frame.rot;
    frame.blades = n;
    frame.tip_radius = tip;
    // Hand: the chord line at mid-span of blade 0 must rise towards +theta (the sign of
    // du dw does not depend on which end is the nose); a left-handed propeller is mirrored in y.
    let local = m.in_frame(&frame);
    let mid = split_blades(&local.cylinder_cut(0.6 * tip), n)
        .first()
        .and_then(|b| unrolled_chord(b, 0.6 * tip));
    let mut thicker_end_behind = false;
    if let Some((du, dw)) = mid {
        if du * dw < 0.0 {
            frame.rot = Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, 1.0)) * frame.rot;
            frame
                .notes
                .push("left-handed (pusher) propeller: mirrored in y to the right-handed frame".into());
        }
        // After the mirror du has dw's sign: the thicker end is at -theta when dw < 0.
        thicker_end_behind = dw < 0.0;
    }
    // Nose and thrust: at four radii the maximum thickness sits ahead of mid-chord and the
    // section is cambered towards the suction side (+z); the majority decides, and on a tie
    // the end that is thicker at 10 % of the chord. Turning is 180 deg about x (theta and z
    // change sign).
    let local = m.in_frame(&frame);
    let (mut agree, mut disagree) = (0, 0);
    for x in [0.4, 0.5, 0.6, 0.7] {
        let pts = local.cylinder_cut(x * tip);
        if let Some(s) = split_blades(&pts, n).first().and_then(|b| measure(b, x * tip)) {
            agree += usize::from(s.t_pos < 0.5) + usize::from(s.camber > 0.005);
            disagree += usize::from(s.t_pos > 0.5) + usize::from(s.camber < -0.005);
        }
    }
    if disagree > agree || (disagree == agree && thicker_end_behind) {
        frame.rot = Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, -1.0)) * frame.rot;
        frame.notes.push(if disagree > agree {
            format!(
                "thrust the other way along the axis: {disagree} of {} thickness-position and camber signs put the leading edge there",
                agree + disagree
            )
        } else {
            "thrust the other way along the axis: the thicker end (the nose) is there".into()
        });
    }
    // The blade count and tip radius are the scan's summary line (with the length unit), not
    // a note of the alignment's choices.
    Ok(frame)
}
