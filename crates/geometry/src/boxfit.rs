//! Registration to a reference box of known size: rotation, translation and scale together.
//!
//! 1. The box faces: RANSAC planes among the box's points (deterministic sampling), refined by
//!    least squares; faces grouped by direction (three orthogonal groups, one or two parallel
//!    faces each; at least one opposite pair, or the scale cannot be seen).
//! 2. For each of the 24 ways the groups can map to the box axes: a start from the face
//!    normals (Kabsch), the separations (scale) and the offsets (translation), then the
//!    point-to-plane registration of the published method: the 7-unknown linear system
//!    (rotation increment, relative scale increment, translation) solved and re-linearised
//!    until it settles.
//! 3. The mapping kept: dimensions consistent, smallest residual, and (when the caller gives
//!    where the propeller's points are) the propeller centre nearest the known box→hub offset;
//!    this settles boxes with two equal sides.
//!
//! The result maps cloud points into the box frame [mm]: `q = s R p + t`, box centred at 0,
//! faces at ±dims/2.

use nalgebra::{Matrix3, SymmetricEigen, Vector3};
use thiserror::Error;

/// Why the box registration failed.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum BoxError {
    /// Not enough faces.
    #[error("reference box: {0}")]
    Faces(String),
}

/// A plane n·p = d with its inlier points.
#[derive(Debug, Clone, PartialEq)]
pub struct Plane {
    /// Unit normal (outward from the box once oriented).
    pub n: Vector3<f64>,
    /// Offset.
    pub d: f64,
    /// Indices of the inlier points.
    pub inliers: Vec<usize>,
}

/// The registration.
#[derive(Debug, Clone, PartialEq)]
pub struct BoxFit {
    /// Cloud units → mm.
    pub scale: f64,
    /// Rotation cloud → box frame.
    pub rot: Matrix3<f64>,
    /// Translation [mm].
    pub trans: Vector3<f64>,
    /// RMS point-to-face distance [mm].
    pub rms: f64,
    /// Faces found.
    pub faces: usize,
    /// Box points used.
    pub points: usize,
    /// What was decided.
    pub notes: Vec<String>,
}

impl BoxFit {
    /// A cloud point in the box frame [mm].
    pub fn apply(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.scale * (self.rot * p) + self.trans
    }
}

/// A small deterministic generator (xorshift64*) for RANSAC samples.
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 33) as usize % n.max(1)
    }
}

fn fit_plane(pts: &[Vector3<f64>], idx: &[usize]) -> (Vector3<f64>, f64) {
    let c: Vector3<f64> = idx.iter().map(|&i| pts[i]).sum::<Vector3<f64>>() / idx.len() as f64;
    let mut m = Matrix3::zeros();
    for &i in idx {
        let d = pts[i] - c;
        m += d * d.transpose();
    }
    let e = SymmetricEigen::new(m);
    let k = e.eigenvalues.imin();
    let n = e.eigenvectors.column(k).into_owned();
    (n, n.dot(&c))
}

/// Finds up to `max` planes by RANSAC with inlier distance `tol`; stops when the best plane
/// holds fewer than `min_inliers` points.
pub fn ransac_planes(pts: &[Vector3<f64>], tol: f64, max: usize, min_inliers: usize) -> Vec<Plane> {
    let mut free: Vec<usize> = (0..pts.len()).collect();
    let mut out = Vec::new();
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    while out.len() < max && free.len() >= min_inliers.max(3) {
        let mut best: (usize, Vector3<f64>, f64) = (0, Vector3::z(), 0.0);
        for _ in 0..400 {
            let (a, b, c) = (
                pts[free[rng.below(free.len())]],
                pts[free[rng.below(free.len())]],
                pts[free[rng.below(free.len())]],
            );
            let n = (b - a).cross(&(c - a));
            if n.norm() < 1e-12 {
                continue;
            }
            let n = n.normalize();
            let d = n.dot(&a);
            // Count on a stride of the free points: cheap and enough to rank.
            let step = (free.len() / 4000).max(1);
            let cnt = free
                .iter()
                .step_by(step)
                .filter(|&&i| (n.dot(&pts[i]) - d).abs() < tol)
                .count();
            if cnt > best.0 {
                best = (cnt, n, d);
            }
        }
        let (_, mut n, mut d) = best;
        let mut inl: Vec<usize> = Vec::new();
        for _ in 0..3 {
            inl = free
                .iter()
                .copied()
                .filter(|&i| (n.dot(&pts[i]) - d).abs() < tol)
                .collect();
            if inl.len() < 3 {
                break;
            }
            (n, d) = fit_plane(pts, &inl);
        }
        if inl.len() < min_inliers {
            break;
        }
        let set: std::collections::HashSet<usize> = inl.iter().copied().collect();
        free.retain(|i| !set.contains(i));
        out.push(Plane { n, d, inliers: inl });
    }
    out
}

/// Faces from seed points: the box points within `reach` of each seed give a first plane, then
/// the box points within `tol` of that plane a refined one.
fn seeded_planes(pts: &[Vector3<f64>], seeds: &[Vector3<f64>], tol: f64, reach: f64) -> Result<Vec<Plane>, BoxError> {
    let mut out = Vec::new();
    for (k, s) in seeds.iter().enumerate() {
        let near: Vec<usize> = (0..pts.len()).filter(|&i| (pts[i] - s).norm() < reach).collect();
        if near.len() < 10 {
            return Err(BoxError::Faces(format!(
                "seed {} ({:.3}, {:.3}, {:.3}) has only {} box points within {reach:.3}",
                k + 1,
                s.x,
                s.y,
                s.z,
                near.len()
            )));
        }
        let (mut n, mut d) = fit_plane(pts, &near);
        let mut inl = near;
        for _ in 0..2 {
            inl = (0..pts.len()).filter(|&i| (n.dot(&pts[i]) - d).abs() < tol).collect();
            (n, d) = fit_plane(pts, &inl);
        }
        out.push(Plane { n, d, inliers: inl });
    }
    Ok(out)
}

/// The box fitted in one orientation: the plane groups' directions onto the axes `perm` with
/// the signs `signs` (bit g for group g), None where the rotation does not exist, the normals do
/// not line up or the opposite faces' scales disagree.
fn orientation(
    pts: &[Vector3<f64>],
    planes: &[Plane],
    groups: &[Vec<usize>],
    dims: [f64; 3],
    perm: [usize; 3],
    signs: u32,
) -> Option<BoxFit> {
    let sg = |g: usize| if signs >> g & 1 == 1 { -1.0 } else { 1.0 };
    // Kabsch: R n_g ≈ sg e_perm(g).
    let mut h = Matrix3::zeros();
    for (g, grp) in groups.iter().enumerate() {
        let mut e = Vector3::zeros();
        e[perm[g]] = sg(g);
        h += e * planes[grp[0]].n.transpose();
    }
    let svd = h.svd(true, true);
    let (Some(u), Some(vt)) = (svd.u, svd.v_t) else {
        return None;
    };
    let rot = u * vt;
    if rot.determinant() < 0.0 {
        return None;
    }
    let ok = groups.iter().enumerate().all(|(g, grp)| {
        let mut e = Vector3::zeros();
        e[perm[g]] = sg(g);
        (rot * planes[grp[0]].n - e).norm() < 0.3
    });
    if !ok {
        return None;
    }
    // Face of each plane: (axis, sign).
    let faces: Vec<(usize, f64)> = planes
        .iter()
        .map(|p| {
            let v = rot * p.n;
            let a = v.iamax();
            (a, v[a].signum())
        })
        .collect();
    // Scale from the opposite pairs.
    let scales: Vec<f64> = groups
        .iter()
        .filter(|g| g.len() == 2)
        .map(|g| dims[faces[g[0]].0] / (planes[g[0]].d + planes[g[1]].d))
        .collect();
    let s0 = scales.iter().sum::<f64>() / scales.len() as f64;
    let spread = scales.iter().map(|s| (s / s0 - 1.0).abs()).fold(0.0, f64::max);
    if spread > 0.03 {
        return None;
    }
    let mut t = Vector3::zeros();
    let mut cnt = Vector3::<f64>::zeros();
    for (p, &(a, sgn)) in planes.iter().zip(&faces) {
        t[a] += sgn * (0.5 * dims[a] - s0 * p.d);
        cnt[a] += 1.0;
    }
    let t = t.component_div(&cnt);
    Some(refine(pts, planes, &faces, dims, rot, s0, t))
}

/// Registers box points to a box of `dims` [mm]. `hub_hint`: the centre of the propeller's
/// points in cloud coordinates and the box centre's position in the propeller frame [mm]; the
/// mapping that puts the propeller nearest the hub is kept.
/// `seeds`: one point on each visible face (cloud units) instead of RANSAC: each face is the
/// plane fitted to the box points near its seed, then every box point within the tolerance.
pub fn register_box(
    pts: &[Vector3<f64>],
    dims: [f64; 3],
    hub_hint: Option<(Vector3<f64>, Vector3<f64>)>,
    seeds: &[Vector3<f64>],
) -> Result<BoxFit, BoxError> {
    if pts.len() < 60 {
        return Err(BoxError::Faces(format!(
            "only {} box points after the colour filter",
            pts.len()
        )));
    }
    let (lo, hi) = pts.iter().fold(
        (Vector3::repeat(f64::INFINITY), Vector3::repeat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.inf(p), hi.sup(p)),
    );
    let diag = (hi - lo).norm();
    let tol = 0.006 * diag;
    let planes = if seeds.is_empty() {
        ransac_planes(pts, tol, 6, (pts.len() / 40).max(20))
    } else {
        seeded_planes(pts, seeds, tol, 0.08 * diag)?
    };
    let centre: Vector3<f64> = pts.iter().sum::<Vector3<f64>>() / pts.len() as f64;
    // Outward normals.
    let planes: Vec<Plane> = planes
        .into_iter()
        .map(|mut p| {
            if p.n.dot(&centre) > p.d {
                p.n = -p.n;
                p.d = -p.d;
            }
            p
        })
        .collect();
    // Group by direction.
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for (i, p) in planes.iter().enumerate() {
        match groups.iter_mut().find(|g| planes[g[0]].n.dot(&p.n).abs() > 0.95) {
            Some(g) => g.push(i),
            None => groups.push(vec![i]),
        }
    }
    let describe = || {
        planes
            .iter()
            .map(|p| {
                format!(
                    "{} points normal ({:.2}, {:.2}, {:.2})",
                    p.inliers.len(),
                    p.n.x,
                    p.n.y,
                    p.n.z
                )
            })
            .collect::<Vec<_>>()
            .join("; ")
    };
    if groups.len() != 3 || groups.iter().any(|g| g.len() > 2) {
        return Err(BoxError::Faces(format!(
            "found {} plane(s) in {} direction(s), not the faces of a box in three directions: {}",
            planes.len(),
            groups.len(),
            describe()
        )));
    }
    if groups.iter().all(|g| g.len() < 2) {
        return Err(BoxError::Faces(format!(
            "no two opposite faces seen ({}): the scale cannot be found; scan the box from more sides",
            describe()
        )));
    }
    let perms = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];
    let mut cands = Vec::new();
    for perm in perms {
        for signs in 0..8u32 {
            cands.extend(orientation(pts, &planes, &groups, dims, perm, signs));
        }
    }
    if cands.is_empty() {
        return Err(BoxError::Faces(format!(
            "the faces' separations do not match the box {:?} mm in any orientation: {}",
            dims,
            describe()
        )));
    }
    let best_rms = cands.iter().map(|c| c.rms).fold(f64::INFINITY, f64::min);
    let tol = 1.5 * best_rms + 1e-3;
    let mut kept: Vec<BoxFit> = cands.into_iter().filter(|c| c.rms <= tol).collect();
    let mut notes = vec![format!(
        "{} faces, {} points; {} orientation(s) fit within {:.3} mm",
        planes.len(),
        pts.len(),
        kept.len(),
        tol
    )];
    if let Some((prop_centre, offset)) = hub_hint {
        kept.sort_by(|a, b| {
            let d = |c: &BoxFit| (c.apply(&prop_centre) + offset).norm();
            d(a).total_cmp(&d(b))
        });
        let d0 = (kept[0].apply(&prop_centre) + offset).norm();
        notes.push(format!(
            "orientation chosen with the propeller {d0:.2} mm from the expected hub"
        ));
    } else {
        kept.sort_by(|a, b| a.rms.total_cmp(&b.rms));
    }
    let mut fit = kept.swap_remove(0);
    fit.notes = notes;
    fit.notes.push(format!(
        "scale {:.6} (cloud units to mm), RMS {:.4} mm",
        fit.scale, fit.rms
    ));
    Ok(fit)
}

/// Point-to-plane registration with scale: each iteration solves the 7 × 7 normal equations of
/// r_i = n_f · (q_i + ω × v_i + δs v_i + δt) − h_f, with v_i = s R p_i and q_i = v_i + t.
fn refine(
    pts: &[Vector3<f64>],
    planes: &[Plane],
    faces: &[(usize, f64)],
    dims: [f64; 3],
    mut rot: Matrix3<f64>,
    mut s: f64,
    mut t: Vector3<f64>,
) -> BoxFit {
    let mut rms = f64::INFINITY;
    let mut used = 0;
    for _ in 0..30 {
        let mut ata = nalgebra::SMatrix::<f64, 7, 7>::zeros();
        let mut atb = nalgebra::SVector::<f64, 7>::zeros();
        let (mut ss, mut n) = (0.0, 0usize);
        for (p, &(a, sgn)) in planes.iter().zip(faces) {
            let mut nf = Vector3::zeros();
            nf[a] = sgn;
            let h = 0.5 * dims[a];
            for &i in &p.inliers {
                let v = s * (rot * pts[i]);
                let q = v + t;
                let r = nf.dot(&q) - h;
                let vxn = v.cross(&nf);
                let row = nalgebra::SVector::<f64, 7>::from_column_slice(&[
                    vxn.x,
                    vxn.y,
                    vxn.z,
                    nf.dot(&v),
                    nf.x,
                    nf.y,
                    nf.z,
                ]);
                ata += row * row.transpose();
                atb -= row * r;
                ss += r * r;
                n += 1;
            }
        }
        rms = (ss / n.max(1) as f64).sqrt();
        used = n;
        let Some(x) = ata.cholesky().map(|c| c.solve(&atb)) else {
            break;
        };
        let w = Vector3::new(x[0], x[1], x[2]);
        let dr = nalgebra::Rotation3::new(w);
        // q' = (1 + ds) dR v + t + dt
        rot = dr.matrix() * rot;
        s *= 1.0 + x[3];
        t += Vector3::new(x[4], x[5], x[6]);
        if w.norm() < 1e-10 && x[3].abs() < 1e-10 {
            break;
        }
    }
    BoxFit {
        scale: s,
        rot,
        trans: t,
        rms,
        faces: planes.len(),
        points: used,
        notes: Vec::new(),
    }
}
