//! Cylindrical sections: the mesh cut by the cylinder r = const (exact triangle-edge
//! intersections), points split by blade, and each section measured on the unrolled cylinder
//! (u = r theta, w = z).

use nalgebra::Vector3;

use crate::mesh::Mesh;

/// A point on a cylinder: angle [rad] and height.
pub type CylPoint = (f64, f64);

/// Intersections of the mesh's edges with the cylinder of radius `r` about z.
pub fn cut_points(m: &Mesh, r: f64) -> Vec<CylPoint> {
    let mut out = Vec::new();
    let r2 = r * r;
    for i in 0..m.triangles.len() {
        let c = m.corners(i);
        for k in 0..3 {
            let (a, b) = (c[k], c[(k + 1) % 3]);
            crossing(a, b, r2, &mut out);
        }
    }
    out
}

/// Points of a cloud within `slab / 2` of the cylinder of radius `r` about z, projected on it.
pub fn slab_points(pts: &[Vector3<f64>], r: f64, slab: f64) -> Vec<CylPoint> {
    let (lo, hi) = ((r - 0.5 * slab).max(0.0).powi(2), (r + 0.5 * slab).powi(2));
    pts.iter()
        .filter(|p| {
            let q = p.x * p.x + p.y * p.y;
            q >= lo && q <= hi
        })
        .map(|p| (p.y.atan2(p.x), p.z))
        .collect()
}

/// Where the segment a-b crosses the cylinder of radius `r` about z.
pub fn crossing_points(a: Vector3<f64>, b: Vector3<f64>, r: f64, out: &mut Vec<CylPoint>) {
    crossing(a, b, r * r, out)
}

fn crossing(a: Vector3<f64>, b: Vector3<f64>, r2: f64, out: &mut Vec<CylPoint>) {
    let d = b - a;
    let (qa, qb, qc) = (
        d.x * d.x + d.y * d.y,
        2.0 * (a.x * d.x + a.y * d.y),
        a.x * a.x + a.y * a.y - r2,
    );
    if qa <= 0.0 {
        return;
    }
    let disc = qb * qb - 4.0 * qa * qc;
    if disc < 0.0 {
        return;
    }
    let s = disc.sqrt();
    for t in [(-qb - s) / (2.0 * qa), (-qb + s) / (2.0 * qa)] {
        if (0.0..1.0).contains(&t) {
            let p = a + t * d;
            out.push((p.y.atan2(p.x), p.z));
        }
    }
}

/// The mean direction of angles [rad] (the angle of the summed unit vectors).
pub fn circular_mean(angles: impl Iterator<Item = f64>) -> f64 {
    let (s, c) = angles.fold((0.0, 0.0), |(s, c), a| (s + a.sin(), c + a.cos()));
    s.atan2(c)
}

/// Splits cut points into `n` blades: the section's points sorted by angle are cut at the `n`
/// widest angular gaps (wide, skewed blades can reach past the half-way angle to the next
/// blade's axis, so nearest-axis assignment would mix them); each group goes to the blade whose
/// axis (2 pi k / n, blade 0 along +x) is nearest its middle. Angles come back relative to that
/// axis.
pub fn split_blades(pts: &[CylPoint], n: usize) -> Vec<Vec<CylPoint>> {
    use std::f64::consts::PI;
    let n = n.max(1);
    let mut out = vec![Vec::new(); n];
    let step = 2.0 * PI / n as f64;
    let rel = |th: f64, k: usize| (th - k as f64 * step + PI).rem_euclid(2.0 * PI) - PI;
    let nearest = |th: f64| ((th / step).round() as i64).rem_euclid(n as i64) as usize;
    if pts.len() < 2 * n || n == 1 {
        for &(th, z) in pts {
            let k = nearest(th);
            out[k].push((rel(th, k), z));
        }
        return out;
    }
    let mut order: Vec<usize> = (0..pts.len()).collect();
    order.sort_by(|&a, &b| pts[a].0.total_cmp(&pts[b].0));
    let ang = |i: usize| pts[order[i]].0;
    let m = order.len();
    // Gap after sorted position i (the last one wraps round).
    let gap = |i: usize| {
        if i + 1 < m {
            ang(i + 1) - ang(i)
        } else {
            ang(0) + 2.0 * PI - ang(m - 1)
        }
    };
    let mut gaps: Vec<usize> = (0..m).collect();
    gaps.sort_by(|&a, &b| gap(b).total_cmp(&gap(a)));
    let mut cuts: Vec<usize> = gaps[..n].to_vec();
    cuts.sort_unstable();
    for g in 0..n {
        // Group: from after cut g to cut g+1 (wrapping).
        let (from, to) = (cuts[g] + 1, if g + 1 < n { cuts[g + 1] } else { cuts[0] + m });
        let idx: Vec<usize> = (from..=to).map(|i| order[i % m]).collect();
        let k = nearest(circular_mean(idx.iter().map(|&i| pts[i].0)));
        out[k].extend(idx.iter().map(|&i| (rel(pts[i].0, k), pts[i].1)));
    }
    out
}

/// The vector from the trailing to the leading edge on the unrolled cylinder (du, dw), with
/// the leading edge told from the trailing edge by thickness (a rounded nose is thicker near
/// its end than a sharp tail).
pub fn unrolled_chord(pts: &[CylPoint], r: f64) -> Option<(f64, f64)> {
    let s = measure_with(pts, r, Nose::Thicker)?;
    Some((s.le.0 - s.te.0, s.le.1 - s.te.1))
}

/// A measured section on the unrolled cylinder.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionShape {
    /// Radius.
    pub r: f64,
    /// Leading edge (u, w).
    pub le: (f64, f64),
    /// Trailing edge (u, w).
    pub te: (f64, f64),
    /// Chord length.
    pub chord: f64,
    /// Blade angle: the chord line against the rotation plane [rad], positive with the leading
    /// edge at higher z.
    pub beta: f64,
    /// Maximum thickness / chord.
    pub t_c: f64,
    /// Its chord position (0 at the leading edge).
    pub t_pos: f64,
    /// Maximum camber / chord (signed, towards the suction side +n).
    pub camber: f64,
    /// Its chord position.
    pub camber_pos: f64,
    /// Number of points.
    pub points: usize,
}

/// How the leading edge is told from the trailing edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Nose {
    /// The end that is thicker at 10 % of the chord (before the frame is known).
    Thicker,
    /// The end at larger theta (the propeller frame's convention).
    PlusTheta,
}

/// Measures one blade's section in the propeller frame (leading edge at +theta).
pub fn measure(pts: &[CylPoint], r: f64) -> Option<SectionShape> {
    measure_with(pts, r, Nose::PlusTheta)
}

/// Measures one blade's section from its cut points (angle relative to the blade axis, z).
pub fn measure_with(pts: &[CylPoint], r: f64, nose: Nose) -> Option<SectionShape> {
    if pts.len() < 8 {
        return None;
    }
    let uw: Vec<(f64, f64)> = pts.iter().map(|&(th, z)| (r * th, z)).collect();
    // Farthest pair: from an extreme point, the farthest; then the farthest from that.
    let far = |p: (f64, f64)| {
        uw.iter()
            .copied()
            .max_by(|a, b| {
                let d = |q: &(f64, f64)| (q.0 - p.0).powi(2) + (q.1 - p.1).powi(2);
                d(a).total_cmp(&d(b))
            })
            .unwrap_or(p)
    };
    let mut a = far(uw[0]);
    let mut b = far(a);
    for _ in 0..3 {
        a = far(b);
        b = far(a);
    }
    let chord = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
    if chord <= 0.0 {
        return None;
    }
    // Chordwise profile from a: thickness bins.
    let (ex, ey) = ((b.0 - a.0) / chord, (b.1 - a.1) / chord);
    const BINS: usize = 50;
    let mut hi = [f64::NEG_INFINITY; BINS];
    let mut lo = [f64::INFINITY; BINS];
    for &(u, w) in &uw {
        let s = ((u - a.0) * ex + (w - a.1) * ey) / chord;
        let n = (-(u - a.0) * ey + (w - a.1) * ex) / chord;
        let k = ((s * BINS as f64) as isize).clamp(0, BINS as isize - 1) as usize;
        hi[k] = hi[k].max(n);
        lo[k] = lo[k].min(n);
    }
    let thick: Vec<f64> = (0..BINS)
        .map(|k| if hi[k] >= lo[k] { hi[k] - lo[k] } else { 0.0 })
        .collect();
    // The nose is the thicker end (10 % of chord from each end).
    let (from_a, from_b) = (thick[BINS / 10], thick[BINS - 1 - BINS / 10]);
    let a_is_le = match nose {
        Nose::Thicker => from_a >= from_b,
        Nose::PlusTheta => a.0 >= b.0,
    };
    let (le, te, flip) = if a_is_le { (a, b, false) } else { (b, a, true) };
    let at = |k: usize| if flip { BINS - 1 - k } else { k };
    let mut best_t: (f64, f64) = (0.0, 0.0);
    let mut best_c: (f64, f64) = (0.0, 0.0);
    // Normal pointing to the suction side: +90 deg from the TE->LE direction.
    let sign = if flip { -1.0 } else { 1.0 };
    for k in 0..BINS {
        let i = at(k);
        let t = thick[i];
        let pos = (k as f64 + 0.5) / BINS as f64;
        if t > best_t.0 {
            best_t = (t, pos);
        }
        if hi[i] >= lo[i] {
            // a->b direction has normal (-ey, ex); TE->LE is the opposite when a is the LE.
            let c = -sign * 0.5 * (hi[i] + lo[i]);
            if c.abs() > best_c.0.abs() {
                best_c = (c, pos);
            }
        }
    }
    let beta = (le.1 - te.1).atan2(le.0 - te.0);
    Some(SectionShape {
        r,
        le,
        te,
        chord,
        beta,
        t_c: best_t.0,
        t_pos: best_t.1,
        camber: best_c.0,
        camber_pos: best_c.1,
        points: pts.len(),
    })
}
