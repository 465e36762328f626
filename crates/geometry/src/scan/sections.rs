//! From an aligned scan to the blade: the hub radius, each station's section cut (cylindrical
//! or planar, reseeded where a cut is poor) and fitted, and the surfaces a scan can be cut
//! from (a mesh, a point cloud).

use super::*;

/// The frame from a manual alignment.
pub(super) fn manual_frame<S: Surface>(m: &S, man: &MmManual) -> Result<Frame, ScanError> {
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
pub(super) fn hub_radius<S: Surface>(s: &S, limit: f64, step: f64) -> Option<f64> {
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
pub(super) fn section_at<S: Surface + ScanSurface>(
    s: &S,
    r: f64,
    kind: SectionKind,
    blades: usize,
) -> Vec<Vec<CylPoint>> {
    match kind {
        SectionKind::Cylindrical => split_blades(&s.cylinder_cut(r), blades),
        SectionKind::Planar => vec![s.planar_cut(r, blades)],
    }
}

/// How much lower (relative) a neighbour-seeded NACA fit's objective must be to replace the
/// station's own fit. Smaller differences are what the noise moves: on the generated cloud a
/// 0.8 % lower objective came with a 0.4 % shorter chord, away from the truth; on meshes the
/// two starts end at the same fit. A station stuck in a wrong minimum gains far more.
pub(super) const RESEED_GAIN: f64 = 0.02;

/// A station's section after the first fit.
pub(super) struct Cut {
    x: f64,
    r: f64,
    secs: Vec<Vec<CylPoint>>,
    shape: SectionShape,
    uw: Vec<(f64, f64)>,
    naca: NacaFit,
}

pub(super) fn finish<S: Surface + Sync + ScanSurface>(
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
    let root = root_radius(local, hub, tip, blades);
    // First pass: each station cut, measured and fitted from its own measure.
    let cuts: Vec<Result<Cut, Failed>> = opts
        .stations
        .par_iter()
        .map(|&x| cut_station(local, x, tip, root, opts, blades))
        .collect();
    // Second pass: the NACA fit started again from each neighbour's shape where it differs
    // by more than 1 % t/c, 0.5 % camber or 0.1 camber position (closer starts end at the
    // station's own fit: tried on the APC, BladeX and Aerostar meshes);
    // it replaces the station's own fit when its objective is lower by more than RESEED_GAIN.
    let reseeded: Vec<Option<NacaFit>> = (0..cuts.len()).into_par_iter().map(|i| reseed(&cuts, i)).collect();
    let improved = reseeded.iter().filter(|f| f.is_some()).count();
    if improved > 0 {
        notes.push(format!(
            "NACA fit: {improved} station(s) fit better from a neighbouring station's shape"
        ));
    }
    let results: Vec<Result<ScanStation, Failed>> = cuts
        .into_par_iter()
        .zip(reseeded)
        .map(|(cut, better)| station(cut?, better))
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

/// The root: the first radius beyond the hub where blade 0 has a section.
fn root_radius<S: Surface + ScanSurface>(local: &S, hub: Option<f64>, tip: f64, blades: usize) -> f64 {
    let mut root = hub.unwrap_or(0.0);
    let step = 0.25f64.max(tip / 4000.0);
    let mut r = root + step;
    while r < tip {
        if split_blades(&local.cylinder_cut(r), blades)[0].len() >= 8 {
            root = r;
            break;
        }
        r += step;
    }
    root
}

/// One station cut, measured and fitted from its own measure (the first pass).
fn cut_station<S: Surface + ScanSurface>(
    local: &S,
    x: f64,
    tip: f64,
    root: f64,
    opts: &MmOptions,
    blades: usize,
) -> Result<Cut, Failed> {
    let r = x * tip;
    let fail = |reason: String| Failed { r_r: x, reason };
    if r <= root {
        return Err(fail(format!(
            "r = {r:.2} mm is inside the hub / root (blades begin at {root:.2} mm)"
        )));
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
    Ok(Cut {
        x,
        r,
        secs,
        shape,
        uw,
        naca,
    })
}

/// Station `i`'s NACA fit started again from its neighbours' shapes (the second pass), where
/// one differs and the fit is better by more than [`RESEED_GAIN`].
fn reseed(cuts: &[Result<Cut, Failed>], i: usize) -> Option<NacaFit> {
    let c = cuts[i].as_ref().ok()?;
    let own = c.naca.shape();
    let starts: Vec<[f64; 3]> = [i.checked_sub(1), Some(i + 1)]
        .into_iter()
        .flatten()
        .filter_map(|j| cuts.get(j)?.as_ref().ok())
        .map(|n| n.naca.shape())
        .filter(|s| (s[0] - own[0]).abs() > 0.01 || (s[1] - own[1]).abs() > 0.005 || (s[2] - own[2]).abs() > 0.1)
        .collect();
    if starts.is_empty() {
        return None;
    }
    fit_naca_from(&c.uw, &c.shape, &starts).filter(|f| f.cost < c.naca.cost * (1.0 - RESEED_GAIN))
}

/// A station from its cut and, where the second pass found one, its better NACA fit: the CST
/// fit, thickness and camber, and the section's place on the blade in SI.
fn station(cut: Cut, better: Option<NacaFit>) -> Result<ScanStation, Failed> {
    let Cut {
        x, r, secs, uw, naca, ..
    } = cut;
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
}

/// What a scanned surface offers beyond [`Surface`].
pub trait ScanSurface {
    /// Planar sections: the points of the plane x = r within blade 0's sector, as (y / r, z)
    /// so that the unrolled measures apply unchanged (u = y).
    fn planar_cut(&self, r: f64, blades: usize) -> Vec<CylPoint>;
    /// The surface as kept for export.
    fn aligned(&self) -> Aligned;
}

pub(super) fn in_sector(p: &Vector3<f64>, blades: usize) -> bool {
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
