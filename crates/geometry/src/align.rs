//! The propeller frame of a mesh: rotation axis from the surface's second-moment tensor (the
//! axis along which the blades are thinnest), hub centre at the area centroid, blade count
//! from the angular distribution of area in a mid-radius ring (which must be N-fold
//! symmetric), blade 0 along +x, thrust (+z) chosen so that the leading edge is at +theta
//! and higher z.

use nalgebra::{Matrix3, SymmetricEigen, Vector3};
use thiserror::Error;

use crate::mesh::Mesh;
use crate::section::{cut_points, split_blades, unrolled_chord};

/// Why a mesh cannot be aligned.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum AlignError {
    /// Not a propeller.
    #[error("no rotational symmetry: {0}")]
    NoSymmetry(String),
}

/// Where the propeller frame sits in the input coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Hub centre in input coordinates.
    pub origin: Vector3<f64>,
    /// Rows: the frame's x, y, z axes in input coordinates (`p_frame = rot (p - origin)`).
    pub rot: Matrix3<f64>,
    /// Blade count.
    pub blades: usize,
    /// Tip radius (largest vertex distance from the axis).
    pub tip_radius: f64,
    /// What was decided and why.
    pub notes: Vec<String>,
}

fn moments(m: &Mesh) -> (f64, Vector3<f64>, Matrix3<f64>) {
    let (mut area, mut first) = (0.0, Vector3::zeros());
    for i in 0..m.triangles.len() {
        let [a, b, c] = m.corners(i);
        let ar = 0.5 * (b - a).cross(&(c - a)).norm();
        area += ar;
        first += ar * (a + b + c) / 3.0;
    }
    let centroid = first / area.max(f64::MIN_POSITIVE);
    let mut second = Matrix3::zeros();
    for i in 0..m.triangles.len() {
        let [a, b, c] = m.corners(i).map(|p| p - centroid);
        let ar = 0.5 * (b - a).cross(&(c - a)).norm();
        let s = a + b + c;
        second += ar / 12.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    }
    (area, centroid, second)
}

/// Transforms a mesh into a frame.
pub fn to_frame(m: &Mesh, f: &Frame) -> Mesh {
    Mesh {
        vertices: m.vertices.iter().map(|v| f.rot * (v - f.origin)).collect(),
        triangles: m.triangles.clone(),
    }
}

/// Blade count from the angular distribution of triangle area in the ring `lo..hi` (radii in
/// the frame): contiguous occupied arcs of a 360-bin histogram.
fn blade_arcs(m: &Mesh, lo: f64, hi: f64) -> Vec<(f64, f64)> {
    let mut bins = vec![0.0; 360];
    for i in 0..m.triangles.len() {
        let [a, b, c] = m.corners(i);
        let g = (a + b + c) / 3.0;
        let r = g.x.hypot(g.y);
        if r >= lo && r <= hi {
            let th = g.y.atan2(g.x).to_degrees().rem_euclid(360.0);
            bins[(th as usize).min(359)] += 0.5 * (b - a).cross(&(c - a)).norm();
        }
    }
    let start = match bins.iter().position(|&x| x == 0.0) {
        Some(s) => s,
        None => return Vec::new(),
    };
    // Arcs: (area, mean angle in degrees), walking from an empty bin.
    let mut arcs = Vec::new();
    let mut cur: Option<(f64, f64, f64)> = None; // area, sum sin, sum cos
    for k in 0..=360 {
        let i = (start + k) % 360;
        let w = bins[i];
        if w > 0.0 {
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

/// Largest relative L1 difference between the blades' radial area profiles (10 bands from
/// 20 % to 100 % of the tip radius), each blade taking the sector around its arc.
fn radial_mismatch(m: &Mesh, arcs: &[(f64, f64)], tip: f64) -> f64 {
    let n = arcs.len();
    let mut prof = vec![[0.0f64; 10]; n];
    for i in 0..m.triangles.len() {
        let [a, b, c] = m.corners(i);
        let g = (a + b + c) / 3.0;
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
        prof[k][(((r - 0.2) / 0.08) as usize).min(9)] += 0.5 * (b - a).cross(&(c - a)).norm();
    }
    let mut worst: f64 = 0.0;
    for p in &prof[1..] {
        let diff: f64 = p.iter().zip(&prof[0]).map(|(x, y)| (x - y).abs()).sum();
        let tot: f64 = prof[0].iter().sum::<f64>().max(1e-300);
        worst = worst.max(diff / tot);
    }
    worst
}

/// Finds the propeller frame of a mesh (millimetres or any unit).
pub fn auto_align(m: &Mesh) -> Result<Frame, AlignError> {
    let (area, centroid, second) = moments(m);
    if area.is_nan() || area <= 0.0 {
        return Err(AlignError::NoSymmetry("the mesh has no area".into()));
    }
    let eig = SymmetricEigen::new(second);
    let mut order = [0usize, 1, 2];
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let ev = |k: usize| eig.eigenvectors.column(order[k]).into_owned();
    let (z, x0) = (ev(0), ev(2));
    let y0 = z.cross(&x0);
    let mut rot = Matrix3::from_rows(&[x0.transpose(), y0.transpose(), z.transpose()]);
    let mut frame = Frame {
        origin: centroid,
        rot,
        blades: 0,
        tip_radius: 0.0,
        notes: Vec::new(),
    };
    let local = to_frame(m, &frame);
    let tip = local.vertices.iter().map(|v| v.x.hypot(v.y)).fold(0.0, f64::max);
    let (l0, l1, l2) = (
        eig.eigenvalues[order[0]],
        eig.eigenvalues[order[1]],
        eig.eigenvalues[order[2]],
    );
    if l1 < 4.0 * l0 {
        return Err(AlignError::NoSymmetry(format!(
            "the mesh is not flat like a propeller disc (second moments {:.3e}, {:.3e}, {:.3e}: no axis stands out)",
            l0, l1, l2
        )));
    }
    let arcs = blade_arcs(&local, 0.45 * tip, 0.75 * tip);
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
    let profile_mismatch = if even { radial_mismatch(&local, &arcs, tip) } else { 0.0 };
    let even = even && profile_mismatch < 0.3;
    if !even {
        return Err(AlignError::NoSymmetry(format!(
            "the area at 45-75 % of the largest radius ({tip:.3}) forms {n} arc(s) that are not alike and evenly spaced \
             (areas {:?}); is this a propeller, cropped to it?",
            arcs.iter().map(|a| format!("{:.3}", a.0)).collect::<Vec<_>>()
        )));
    }
    // Blade 0 along +x.
    let a0 = arcs[0].1.to_radians();
    let rz = Matrix3::new(a0.cos(), a0.sin(), 0.0, -a0.sin(), a0.cos(), 0.0, 0.0, 0.0, 1.0);
    rot = rz * rot;
    frame.rot = rot;
    frame.blades = n;
    frame.tip_radius = tip;
    // Thrust direction: the leading edge at +theta and higher z at mid-span of blade 0.
    let local = to_frame(m, &frame);
    let pts = cut_points(&local, 0.6 * tip);
    let blades = split_blades(&pts, n);
    if let Some((du, dw)) = blades.first().and_then(|b| unrolled_chord(b, 0.6 * tip)) {
        if du < 0.0 && dw < 0.0 {
            // Rotate 180 deg about x: theta and z change sign.
            frame.rot = Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, -1.0)) * frame.rot;
            frame
                .notes
                .push("thrust direction: the other way along the axis of least spread".into());
        } else if du * dw < 0.0 {
            // A left-handed propeller: mirror y so that it reads as the documented hand.
            frame.rot = Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, 1.0)) * frame.rot;
            frame
                .notes
                .push("left-handed (pusher) propeller: mirrored in y to the right-handed frame".into());
        }
    }
    frame.notes.push(format!("{n} blades, tip radius {tip:.3}"));
    Ok(frame)
}
