//! A QPROP file that carries the prediction: QPROP 1.22 run on it gives what propbet's model
//! (tables, rotational augmentation, drag factor) predicts over the operating points it was fitted
//! on.
//!
//! The file's rows are the first and last radius of the blade and, between them, the 25
//! computational stations QPROP itself places (midpoints of 25 equal intervals): QPROP's spline
//! then returns each row's values at its own stations, so every station gets the coefficients
//! fitted to it. A station whose section is QPROP's law already (a prop file without tables, no
//! rotational augmentation or drag factor) keeps its coefficients, its drag moved to the common
//! REref exactly. At each other station QPROP's law is fitted by least squares to the angle of
//! attack, Reynolds and Mach number, lift and drag the model's own solution has there at every
//! operating point of the scored window (below 85 % of each RPM's zero-thrust J, as a comparison
//! scores), weighted so that an error in cl or cd counts as the relative error in thrust or
//! torque it makes, then refitted with each point weighted up by how far the last file left it
//! (the file with the smallest largest difference is kept): the lift line
//! through the lifts it works at (Prandtl-Glauert removed, as QPROP applies it), limits beyond
//! them, and the drag law `[CD0 + CD2 (cl - CLCD0)^2] (Re/REref)^REexp` for the best REexp and
//! CLCD0 on a grid, with one REref for every row (QPROP 1.22 uses the first station's everywhere).
//! The fidelity is measured, not assumed: the file is read back as QPROP reads it and solved at the
//! same points. QPROP's lift law has no Reynolds-number dependence: where the model's sections
//! lift differently at each RPM (XFOIL's low-Re tables), that difference is what the file cannot
//! carry (the default case: CT at J = 0 rises 3.7 % from 4000 to 6000 rpm in the tables).

use propbet_bemt::{OperatingPoint, PointResult, Rotor, SolverOptions};

use crate::{PropFile, PropRow};

/// The model a QPROP file is exported from: its rotor, how it is solved, and the prop file it
/// was read from (its ends and its accuracy line).
#[derive(Debug, Clone, Copy)]
pub struct Model<'a> {
    /// The rotor as the model solves it (its sections, tables or QPROP's law).
    pub rotor: &'a Rotor,
    /// How it is solved.
    pub opts: SolverOptions,
    /// The prop file the model was read from.
    pub file: &'a PropFile,
}

/// Why a prediction cannot be exported as a QPROP file.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The points cannot make the file (none solved at every station, none with thrust).
    #[error("{0}")]
    Unsuited(String),
    /// The exported file does not make a rotor when read back.
    #[error("the exported QPROP file: {0}")]
    ReadBack(#[from] propbet_bemt::RotorError),
}

type Result<T> = std::result::Result<T, ExportError>;

/// The exported file's name, beside the run's sweep.
pub const FILE_NAME: &str = "qprop_export.qprop";

/// Relative differences between two predictions over a set of points: their median and the
/// largest.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct Differences {
    /// The median [-].
    pub median: f64,
    /// The largest [-].
    pub largest: f64,
}

impl Differences {
    /// The median ([`propbet_units::stats::median`]) and the largest of `v` (zeros when it is
    /// empty).
    pub fn of(v: &[f64]) -> Differences {
        if v.is_empty() {
            return Differences::default();
        }
        Differences {
            median: propbet_units::stats::median(v.to_vec()),
            largest: v.iter().copied().max_by(f64::total_cmp).unwrap_or_default(),
        }
    }
}

/// How well QPROP's reading of the exported file reproduces the prediction.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Fidelity {
    /// Operating points compared (the scored window: below 85 % of each RPM's zero-thrust J).
    pub points: usize,
    /// Thrust's relative differences.
    pub thrust: Differences,
    /// Torque's relative differences.
    pub torque: Differences,
}

impl Fidelity {
    /// The relative thrust and torque differences `dt` and `dq`, summed up.
    pub fn of(dt: &[f64], dq: &[f64]) -> Fidelity {
        Fidelity {
            points: dt.len(),
            thrust: Differences::of(dt),
            torque: Differences::of(dq),
        }
    }

    /// "thrust within 0.8 % (median), 2.1 % at most; torque ..., over N points" (the exports'
    /// headers and lines).
    pub fn against(&self) -> String {
        format!(
            "thrust within {:.1} % (median), {:.1} % at most; torque within {:.1} %, {:.1} % at most; over {} points",
            100.0 * self.thrust.median,
            100.0 * self.thrust.largest,
            100.0 * self.torque.median,
            100.0 * self.torque.largest,
            self.points
        )
    }

    /// A short line for the terminal.
    pub fn brief(&self) -> String {
        format!(
            "QPROP 1.22 on it: thrust within {:.1} % (median), {:.1} % (worst) of the prediction, torque {:.1} %, {:.1} %",
            100.0 * self.thrust.median,
            100.0 * self.thrust.largest,
            100.0 * self.torque.median,
            100.0 * self.torque.largest
        )
    }

    /// One sentence for the report.
    pub fn sentence(&self) -> String {
        format!(
            "QPROP 1.22 on this file: thrust within {:.1} % (median), {:.1} % at most, torque within {:.1} %, {:.1} % at most of propbet's prediction, over the {} operating points of the scored window (read and solved as QPROP does)",
            100.0 * self.thrust.median,
            100.0 * self.thrust.largest,
            100.0 * self.torque.median,
            100.0 * self.torque.largest,
            self.points
        )
    }
}

/// The exported file and its fidelity.
#[derive(Debug, Clone)]
pub struct QpropExport {
    /// The prop file (metres, R on line 2).
    pub file: PropFile,
    /// QPROP's reading of it against the prediction.
    pub fidelity: Fidelity,
}

/// The seen state of one station at one point: (alpha [rad], Re, Mach, cl, cd, lift weight,
/// drag weight). A weight is the square of the station's share of the point's thrust (lift) or
/// torque (drag) per unit coefficient over that load: a squared error in cl or cd weighs as much
/// as the squared relative error in thrust or torque it makes.
type Seen = (f64, f64, f64, f64, f64, f64, f64);

/// QPROP's lift at `alpha` [rad] and Mach `m` for a line (cl0, cl_a) and limits: the line,
/// Prandtl-Glauert scaled, held at a limit by QPROP's `CLmax cos(alpha - CL0/CL_a)` beyond it
/// (FORMULATION.md); true when held (stalled).
fn qprop_lift(cl0: f64, cl_a: f64, cl_min: f64, cl_max: f64, alpha: f64, m: f64) -> (f64, bool) {
    let cl = (cl0 + cl_a * alpha) / (1.0 - (m * m).min(0.9)).sqrt();
    if cl > cl_max {
        (cl_max * (alpha - cl0 / cl_a).cos(), true)
    } else if cl < cl_min {
        (cl_min * (alpha - cl0 / cl_a).cos(), true)
    } else {
        (cl, false)
    }
}

/// The least-squares line through (alpha, cl sqrt(1 - M^2)) of `pts`, slope held in 0.5..8 per
/// rad (a single point, or points past stall: the offset refitted at the bound).
fn lift_line(pts: &[&Seen]) -> (f64, f64) {
    let pg = |m: f64| (1.0 - (m * m).min(0.9)).sqrt();
    let n: f64 = pts.iter().map(|s| s.5).sum();
    let am = pts.iter().map(|s| s.5 * s.0).sum::<f64>() / n;
    let ym = pts.iter().map(|s| s.5 * s.3 * pg(s.2)).sum::<f64>() / n;
    let sxx: f64 = pts.iter().map(|s| s.5 * (s.0 - am).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|s| s.5 * (s.0 - am) * (s.3 * pg(s.2) - ym)).sum();
    let slope = if sxx > 1e-8 { sxy / sxx } else { 5.7 };
    let cl_a = slope.clamp(0.5, 8.0);
    (ym - cl_a * am, cl_a)
}

/// Least squares of `rows . x = rhs` for x = (CD0, CD2u, CD2l), CD0 > 0 and the CD2s >= 0 (a
/// negative one is held at 0 and the rest refitted); None without a positive CD0.
fn drag_lsq(rows: &[[f64; 3]], rhs: &[f64]) -> Option<[f64; 3]> {
    use nalgebra::{DMatrix, DVector};
    let mut free = [true; 3];
    for _ in 0..3 {
        let cols: Vec<usize> = (0..3).filter(|&k| free[k]).collect();
        let a = DMatrix::from_fn(rows.len(), cols.len(), |i, j| rows[i][cols[j]]);
        let b = DVector::from_column_slice(rhs);
        let sol = a.svd(true, true).solve(&b, 1e-12).ok()?;
        let mut x = [0.0; 3];
        for (j, &k) in cols.iter().enumerate() {
            x[k] = sol[j];
        }
        match (1..3).find(|&k| free[k] && x[k] < 0.0) {
            Some(k) => free[k] = false,
            None => return (x[0] > 0.0 && x.iter().all(|v| v.is_finite())).then_some(x),
        }
    }
    None
}

/// QPROP's ten coefficients fitted to what one station sees (`re_ref` fixed).
fn fit_station(seen: &[Seen], re_ref: f64) -> [f64; 10] {
    // Lift: for each candidate CLmax (none, or one of the lifts seen), the line through the
    // points below it and QPROP's stall law above; the candidate with the least squared error
    // in lift wins.
    let observed_hi = seen.iter().map(|s| s.3).fold(f64::MIN, f64::max);
    let observed_lo = seen.iter().map(|s| s.3).fold(f64::MAX, f64::min);
    let mut candidates: Vec<Option<f64>> = vec![None];
    candidates.extend(seen.iter().map(|s| Some(s.3)).filter(|c| c.is_some_and(|c| c > 0.3)));
    let mut best_lift: Option<(f64, [f64; 4])> = None;
    for cmax in candidates {
        let below: Vec<&Seen> = seen.iter().filter(|s| cmax.is_none_or(|c| s.3 < c - 1e-9)).collect();
        if below.is_empty() {
            continue;
        }
        let (cl0, cl_a) = lift_line(&below);
        let line_hi = seen
            .iter()
            .map(|s| (cl0 + cl_a * s.0) / (1.0 - (s.2 * s.2).min(0.9)).sqrt())
            .fold(f64::MIN, f64::max);
        let cl_max = cmax.unwrap_or(line_hi.max(observed_hi) + 0.3);
        let cl_min = (observed_lo.min(cl0 + cl_a * seen.iter().map(|s| s.0).fold(f64::MAX, f64::min)) - 0.3).min(-0.2);
        let err: f64 = seen
            .iter()
            .map(|s| s.5 * (qprop_lift(cl0, cl_a, cl_min, cl_max, s.0, s.2).0 - s.3).powi(2))
            .sum();
        if best_lift.is_none_or(|b| err < b.0) {
            best_lift = Some((err, [cl0, cl_a, cl_min, cl_max]));
        }
    }
    let [cl0, cl_a, cl_min, cl_max] = best_lift.map_or([0.5, 5.7, -0.4, 1.2], |b| b.1);
    let lifts: Vec<(f64, bool)> = seen
        .iter()
        .map(|s| qprop_lift(cl0, cl_a, cl_min, cl_max, s.0, s.2))
        .collect();
    let hi = lifts.iter().map(|l| l.0).fold(f64::MIN, f64::max);
    let lo = lifts.iter().map(|l| l.0).fold(f64::MAX, f64::min);
    // Drag: for each REexp and CLCD0 of a grid, CD0 and CD2 >= 0 by least squares of the
    // relative error, QPROP's own additions (Mach above 0.7, 2 sin^2 on stalled stations) taken
    // out of the target; the best pair wins.
    let mut best = (f64::INFINITY, [0.02, 0.05, 0.05, 0.0, -0.5]);
    for ke in 0..=12 {
        let e = -1.2 + 0.1 * ke as f64;
        for kc in 0..=8 {
            let clcd0 = lo + (hi - lo) * kc as f64 / 8.0;
            let alpha_cd0 = (clcd0 - cl0) / cl_a;
            let weights: Vec<f64> = seen.iter().map(|s| s.6.sqrt()).collect();
            // Rows: (f, f (cl - clcd0)^2 above CLCD0, the same below) / target, right side 1.
            let rows: Vec<[f64; 3]> = seen
                .iter()
                .zip(&lifts)
                .map(|(s, &(cl, stalled))| {
                    let mach = if s.2 > 0.7 { 10.0 * (s.2 - 0.7).powi(3) } else { 0.0 };
                    let stall = if stalled {
                        2.0 * (s.0 - alpha_cd0).sin().powi(2)
                    } else {
                        0.0
                    };
                    let t = (s.4 - mach - stall).max(0.2 * s.4).max(1e-5);
                    let f = s.6.sqrt() * (s.1 / re_ref).powf(e) / t;
                    let q = f * (cl - clcd0).powi(2);
                    if cl > clcd0 {
                        [f, q, 0.0]
                    } else {
                        [f, 0.0, q]
                    }
                })
                .collect();
            let Some(x) = drag_lsq(&rows, &weights) else { continue };
            let err: f64 = rows
                .iter()
                .zip(&weights)
                .map(|(r, w)| (x[0] * r[0] + x[1] * r[1] + x[2] * r[2] - w).powi(2))
                .sum();
            if err < best.0 {
                best = (err, [x[0], x[1], x[2], clcd0, e]);
            }
        }
    }
    let [cd0, cd2u, cd2l, clcd0, e] = best.1;
    [cl0, cl_a, cl_min, cl_max, cd0, cd2u, cd2l, clcd0, re_ref, e]
}

/// The QPROP file that carries `model`'s prediction at `points` (`name` on its first line),
/// with its fidelity, fitted and checked on the points below `window` times each RPM's
/// zero-thrust J (a comparison's scored window). An error when the model has no point with
/// thrust to fit.
pub fn qprop_export(
    model: Model<'_>,
    fluid: &propbet_bemt::Fluid,
    points: &[OperatingPoint],
    name: &str,
    window: f64,
) -> Result<QpropExport> {
    let rotor = &model.rotor;
    let mut opts = model.opts;
    opts.keep_stations = true;
    let solved: Vec<PointResult> = points
        .iter()
        .map(|&op| propbet_bemt::solve_point(rotor, fluid, op, &opts))
        .collect();
    let n = rotor.stations.len();
    if solved.is_empty() || n < 2 || solved.iter().any(|p| p.stations.len() != n) {
        return Err(ExportError::Unsuited(
            "the QPROP export needs operating points the model solves at every station".into(),
        ));
    }
    // One REref for every row: the geometric mean of the first station's Re.
    let re_ref = (solved.iter().map(|p| p.stations[0].re.max(1.0).ln()).sum::<f64>() / solved.len() as f64)
        .exp()
        .round();
    // The points that count, for the fit as for the check: the scored window of a comparison
    // (below 85 % of each RPM's zero-thrust J, here the prediction's own), with thrust.
    let counted = scored_window(&solved, window);
    if !counted.iter().any(|&c| c) {
        return Err(ExportError::Unsuited(
            "the QPROP export needs an operating point with thrust".into(),
        ));
    }
    // The fit, then refits that weigh each point by how far the last file left it (towards the
    // smallest largest difference); the file with the smallest largest difference is kept.
    let mut weight = vec![1.0; solved.len()];
    let mut best: Option<(f64, PropFile, Fidelity)> = None;
    for _ in 0..REWEIGHTS {
        let file = fit_file(model, &solved, &counted, &weight, re_ref, name);
        let (dt, dq) = differences(model, &file, fluid, points, &solved, &counted)?;
        let fidelity = Fidelity::of(&dt, &dq);
        let worst = fidelity.thrust.largest.max(fidelity.torque.largest);
        if best.as_ref().is_none_or(|b| worst < b.0) {
            best = Some((worst, file, fidelity));
        }
        // Each point's next weight: times 1 + (its difference / the median difference)^2.
        let e: Vec<f64> = dt.iter().zip(&dq).map(|(t, q)| t.max(*q)).collect();
        let med = propbet_units::stats::median(e.clone()).max(1e-4);
        let mut k = 0;
        for (w, &c) in weight.iter_mut().zip(&counted) {
            if c {
                *w *= 1.0 + (e[k] / med).powi(2);
                k += 1;
            }
        }
    }
    let (_, file, fidelity) = best.expect("at least one fit");
    Ok(QpropExport { file, fidelity })
}

/// Fits and refits of [`qprop_export`].
const REWEIGHTS: usize = 6;

/// Which points a comparison would score: below `window`
/// times each RPM's zero-thrust J (linear between the last positive and the first non-positive
/// CT; every point of an RPM whose CT never crosses zero), with positive thrust and torque.
fn scored_window(solved: &[PointResult], window: f64) -> Vec<bool> {
    let mut inside: Vec<bool> = solved.iter().map(|p| p.thrust > 0.0 && p.torque > 0.0).collect();
    let mut rpms: Vec<f64> = solved.iter().map(|p| p.rpm).collect();
    rpms.sort_by(f64::total_cmp);
    rpms.dedup();
    for rpm in rpms {
        let mut idx: Vec<usize> = (0..solved.len()).filter(|&i| solved[i].rpm == rpm).collect();
        idx.sort_by(|&a, &b| solved[a].j.unwrap_or(0.0).total_cmp(&solved[b].j.unwrap_or(0.0)));
        let ct = |i: usize| solved[i].ct.unwrap_or(f64::NAN);
        let j = |i: usize| solved[i].j.unwrap_or(0.0);
        let j0 = idx
            .windows(2)
            .find(|w| ct(w[0]) > 0.0 && ct(w[1]) <= 0.0)
            .map(|w| j(w[0]) + ct(w[0]) / (ct(w[0]) - ct(w[1])) * (j(w[1]) - j(w[0])));
        if let Some(j0) = j0 {
            for i in idx {
                inside[i] &= j(i) < window * j0;
            }
        }
    }
    inside
}

/// The exported file fitted with each point's `weight` (points outside `counted` left out).
fn fit_file(
    model: Model<'_>,
    solved: &[PointResult],
    counted: &[bool],
    weight: &[f64],
    re_ref: f64,
    name: &str,
) -> PropFile {
    let rotor = &model.rotor;
    let n = rotor.stations.len();
    let fits: Vec<[f64; 10]> = (0..n)
        .map(|k| {
            // A station that is QPROP's law already keeps it, its drag moved to the common
            // REref: [CD0 + ...] (Re/REref_k)^e = [CD0 (REref/REref_k)^e + ...] (Re/REref)^e.
            if let Some(q) = rotor.stations[k].aero.as_qprop() {
                let c = &q.coeffs;
                let f = (re_ref / c.re_ref).powf(c.re_exp);
                return [
                    c.cl0,
                    c.cl_a,
                    c.cl_min,
                    c.cl_max,
                    c.cd0 * f,
                    c.cd2u * f,
                    c.cd2l * f,
                    c.clcd0,
                    re_ref,
                    c.re_exp,
                ];
            }
            let seen: Vec<Seen> = solved
                .iter()
                .zip(counted.iter().zip(weight))
                .filter(|(_, (c, _))| **c)
                .map(|(p, (_, w))| {
                    let s = &p.stations[k];
                    let q = s.w * s.w * s.chord;
                    (
                        s.alpha,
                        s.re,
                        s.mach,
                        s.cl,
                        s.cd,
                        w * (q / p.thrust).powi(2),
                        w * (q * s.r / p.torque.abs().max(1e-12)).powi(2),
                    )
                })
                .filter(|s| s.0.is_finite() && s.3.is_finite() && s.4.is_finite() && s.1 > 0.0)
                .collect();
            if seen.is_empty() {
                crate::GENERIC.to_array()
            } else {
                fit_station(&seen, re_ref)
            }
        })
        .collect();
    // Rows: the blade's first and last radius around QPROP's own 25 stations.
    let st = &rotor.stations;
    let (r0, r1) = (
        st[0].r - 0.5 * st[0].dr,
        propbet_units::at_most_tip(st[n - 1].r + 0.5 * st[n - 1].dr, rotor.tip_radius),
    );
    let row = |r: f64, k: usize, chord: f64, beta: f64| PropRow {
        r,
        chord,
        beta: beta.to_degrees(),
        coeffs: fits[k].to_vec(),
    };
    // The end rows are the blade's own first and last rows (QPROP never evaluates there).
    let ends = model.file.to_blade(crate::RadiusReading::Documented);
    let last = ends.r.len() - 1;
    let (c0, b0, c1, b1) = (ends.chord[0], ends.beta[0], ends.chord[last], ends.beta[last]);
    let mut rows = vec![row(r0, 0, c0, b0)];
    rows.extend(st.iter().enumerate().map(|(k, s)| row(s.r, k, s.chord, s.beta)));
    rows.push(row(r1, n - 1, c1, b1));
    let mut file = PropFile::metric(name.to_string(), rotor.blades, rotor.tip_radius, rows);
    file.global = fits[0];
    // The geometry's own accuracy (a scan's) travels with it: the file's band is the model's.
    file.accuracy = model.file.accuracy;
    file
}

/// The file read back as QPROP 1.22 reads it and solved at the counted points: the relative
/// thrust and torque differences from the prediction.
fn differences(
    model: Model<'_>,
    file: &PropFile,
    fluid: &propbet_bemt::Fluid,
    points: &[OperatingPoint],
    solved: &[PointResult],
    counted: &[bool],
) -> Result<(Vec<f64>, Vec<f64>)> {
    let blade = file.to_blade(crate::RadiusReading::Qprop122);
    let back = blade.to_rotor(propbet_bemt::Discretization {
        stations: 25,
        qprop_reref_quirk: true,
    })?;
    let mut plain = model.opts;
    plain.keep_stations = false;
    let (mut dt, mut dq) = (Vec::new(), Vec::new());
    for ((p, &op), _) in solved.iter().zip(points).zip(counted).filter(|(_, c)| **c) {
        let q = propbet_bemt::solve_point(&back, fluid, op, &plain);
        dt.push((q.thrust / p.thrust - 1.0).abs());
        dq.push((q.torque / p.torque - 1.0).abs());
    }
    Ok((dt, dq))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_station_that_sees_a_qprop_law_gets_it_back() {
        // cl = 0.4 + 5.5 alpha, cd = [0.012 + 0.03 (cl - 0.5)^2] (Re/60000)^-0.5, M 0.1.
        let law = |alpha: f64, re: f64| {
            let cl = (0.4 + 5.5 * alpha) / (1.0f64 - 0.01).sqrt();
            (
                cl,
                (0.012 + 0.03 * (cl - 0.5f64).powi(2)) * (re / 60_000.0f64).powf(-0.5),
            )
        };
        let seen: Vec<Seen> = (0..12)
            .map(|k| {
                let alpha = (-2.0 + k as f64).to_radians();
                let re = 40_000.0 + 5_000.0 * k as f64;
                let (cl, cd) = law(alpha, re);
                (alpha, re, 0.1, cl, cd, 1.0, 1.0)
            })
            .collect();
        let c = fit_station(&seen, 50_000.0);
        assert!((c[0] - 0.4).abs() < 1e-9 && (c[1] - 5.5).abs() < 1e-9, "{c:?}");
        assert_eq!(c[8], 50_000.0);
        for s in &seen {
            let (cl, stalled) = qprop_lift(c[0], c[1], c[2], c[3], s.0, s.2);
            assert!(!stalled && (cl - s.3).abs() < 1e-9);
            let cd2 = if cl > c[7] { c[5] } else { c[6] };
            let cd = (c[4] + cd2 * (cl - c[7]).powi(2)) * (s.1 / c[8]).powf(c[9]);
            assert!((cd / s.4 - 1.0).abs() < 0.02, "cd {cd} vs {}", s.4);
        }
    }
}
