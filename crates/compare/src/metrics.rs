//! Error metrics per quantity, overall and by group (RPM, advance-ratio band, static vs
//! forward flight). Only scored (unflagged) points count.

use std::collections::BTreeMap;
use std::path::PathBuf;

use serde::Serialize;

use crate::{ComparedPoint, QUANTITIES};
use propbet_measure::MeasuredSet;
use propbet_units::stats::median;

/// Errors of one quantity over a set of points; error = predicted - measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Metric {
    /// Points with both values.
    pub n: usize,
    /// Mean error (SI units of the quantity).
    pub bias: f64,
    /// Root-mean-square error.
    pub rmse: f64,
    /// Mean relative error (signed).
    pub mean_rel: f64,
    /// Mean absolute relative error.
    pub mean_abs_rel: f64,
    /// Relative error of largest magnitude (signed).
    pub max_rel: f64,
    /// Label of the point where it occurs.
    pub max_rel_at: String,
}

/// Metrics of every quantity over one group of points.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MetricGroup {
    /// "all points", "5000 rpm", "J 0.2-0.4", "static".
    pub name: String,
    /// Points in the group.
    pub points: usize,
    /// By quantity name ([`crate::QUANTITIES`]); quantities without data are absent.
    pub metrics: BTreeMap<String, Metric>,
}

/// All groups.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Metrics {
    /// Every scored point.
    pub overall: MetricGroup,
    /// By RPM (the file's nominal RPM, else 1000-rpm bands).
    pub per_rpm: Vec<MetricGroup>,
    /// By advance-ratio band (static, then 0.2 wide).
    pub per_j: Vec<MetricGroup>,
    /// Static points (J < 0.01).
    pub static_points: Option<MetricGroup>,
    /// Forward-flight points.
    pub forward: Option<MetricGroup>,
    /// Points left out of the scores (flagged).
    pub unscored: usize,
    /// The headline: scored points inside the window ([`in_window`] with
    /// [`VALIDATION_J_WINDOW`], the window of validate and diagnose), static and forward flight.
    pub headline: Vec<MetricGroup>,
    /// Scored points outside the window (near zero thrust): shown, not in the headline.
    pub outside_window: usize,
}

fn metric(points: &[&ComparedPoint], q: &str) -> Option<Metric> {
    let mut n = 0;
    let (mut sum, mut sum2) = (0.0, 0.0);
    let mut rels = Vec::new();
    let mut max: Option<(f64, &str)> = None;
    for p in points {
        let (Some(m), Some(pr)) = (p.measured.get(q), p.predicted.get(q)) else {
            continue;
        };
        n += 1;
        let e = pr - m;
        sum += e;
        sum2 += e * e;
        if let Some(r) = p.relative_error(q) {
            rels.push(r);
            if max.is_none_or(|(x, _)| r.abs() > x.abs()) {
                max = Some((r, p.label.as_str()));
            }
        }
    }
    if n == 0 {
        return None;
    }
    let nr = rels.len().max(1) as f64;
    Some(Metric {
        n,
        bias: sum / n as f64,
        rmse: (sum2 / n as f64).sqrt(),
        mean_rel: if rels.is_empty() {
            f64::NAN
        } else {
            rels.iter().sum::<f64>() / nr
        },
        mean_abs_rel: if rels.is_empty() {
            f64::NAN
        } else {
            rels.iter().map(|r| r.abs()).sum::<f64>() / nr
        },
        max_rel: max.map_or(f64::NAN, |m| m.0),
        max_rel_at: max.map_or(String::new(), |m| m.1.to_string()),
    })
}

/// Metrics of every quantity over `points`.
pub fn group(name: impl Into<String>, points: &[&ComparedPoint]) -> MetricGroup {
    MetricGroup {
        name: name.into(),
        points: points.len(),
        metrics: QUANTITIES
            .iter()
            .filter_map(|q| metric(points, q).map(|m| (q.to_string(), m)))
            .collect(),
    }
}

/// The RPM group of a point: its file's nominal RPM, else its 1000-rpm band (as a sort key
/// and a name).
pub fn rpm_group(p: &ComparedPoint) -> (i64, String) {
    match p.nominal_rpm {
        Some(r) => (r.round() as i64, format!("{r:.0} rpm")),
        None => {
            // Points without a nominal speed (thrust-stand steps, UIUC static files) in
            // 1000-rpm bands, named as bands so they do not read as one speed.
            let b = (p.rpm / 1000.0).floor() as i64;
            let kind = if p.is_static() { "static, " } else { "" };
            (b * 1000, format!("{kind}{}-{} rpm band", b * 1000, b * 1000 + 1000))
        }
    }
}

/// The sweep a point belongs to in the figures: its nominal RPM to the nearest 100 (UIUC's
/// "5000 rpm" sweeps run at 4,997 and 5,018: one colour, one predicted curve), else its
/// logged RPM to the nearest 100.
pub fn sweep_group(p: &ComparedPoint) -> (i64, String) {
    let k = sweep_key(p.nominal_rpm.unwrap_or(p.rpm));
    (k, format!("{k} rpm"))
}

/// A sweep's RPM to the nearest 100: the runs of one UIUC sweep share it.
pub fn sweep_key(rpm: f64) -> i64 {
    (rpm / 100.0).round() as i64 * 100
}

fn j_group(p: &ComparedPoint) -> (i64, String) {
    if p.is_static() {
        return (-1, "static (J = 0)".into());
    }
    let b = (p.j / 0.2).floor() as i64;
    (b, format!("J {:.1}-{:.1}", b as f64 * 0.2, (b + 1) as f64 * 0.2))
}

/// Points grouped by `key` (sort key, name), in key order.
pub fn group_points<'a>(
    points: impl IntoIterator<Item = &'a ComparedPoint>,
    key: fn(&ComparedPoint) -> (i64, String),
) -> Vec<(String, Vec<&'a ComparedPoint>)> {
    let mut by: BTreeMap<i64, (String, Vec<&ComparedPoint>)> = BTreeMap::new();
    for p in points {
        let (k, name) = key(p);
        by.entry(k).or_insert_with(|| (name, Vec::new())).1.push(p);
    }
    by.into_values().collect()
}

fn grouped(points: &[&ComparedPoint], key: fn(&ComparedPoint) -> (i64, String)) -> Vec<MetricGroup> {
    group_points(points.iter().copied(), key)
        .into_iter()
        .map(|(name, pts)| group(name, &pts))
        .collect()
}

/// Scores the points.
pub fn metrics(points: &[ComparedPoint]) -> Metrics {
    let scored: Vec<&ComparedPoint> = points.iter().filter(|p| p.scored()).collect();
    let stat: Vec<&ComparedPoint> = scored.iter().copied().filter(|p| p.is_static()).collect();
    let fwd: Vec<&ComparedPoint> = scored.iter().copied().filter(|p| !p.is_static()).collect();
    let inside = in_window(points, VALIDATION_J_WINDOW);
    let windowed: Vec<&ComparedPoint> = points
        .iter()
        .zip(&inside)
        .filter(|(p, &i)| i && p.scored())
        .map(|(p, _)| p)
        .collect();
    let mut headline = Vec::new();
    for (name, is_static) in [
        ("static", true),
        ("forward flight, below 85 % of the zero-thrust J", false),
    ] {
        let part: Vec<&ComparedPoint> = windowed
            .iter()
            .copied()
            .filter(|p| p.is_static() == is_static)
            .collect();
        if !part.is_empty() {
            headline.push(group(name, &part));
        }
    }
    Metrics {
        outside_window: scored.len() - windowed.len(),
        headline,
        overall: group("all points", &scored),
        per_rpm: grouped(&scored, rpm_group),
        per_j: grouped(&scored, j_group),
        static_points: (!stat.is_empty()).then(|| group("static", &stat)),
        forward: (!fwd.is_empty()).then(|| group("forward flight", &fwd)),
        unscored: points.len() - scored.len(),
    }
}

/// Fraction of a sweep's measured zero-thrust J below which the validation scores a point:
/// near zero thrust a relative error says nothing, and the last points of a sweep are there.
pub const VALIDATION_J_WINDOW: f64 = 0.85;

/// Which points lie inside the scored window: below `window` times their file's measured
/// zero-thrust J (linear between the last positive and the first non-positive measured CT;
/// every point of a file whose CT never crosses zero, static files included). The one window
/// of validate, diagnose's ladder and the report's headline.
pub fn in_window(points: &[ComparedPoint], window: f64) -> Vec<bool> {
    let mut inside = vec![true; points.len()];
    for (pts, j0) in zero_thrust_js(points) {
        if let Some(j0) = j0 {
            for i in pts {
                inside[i] = points[i].j < window * j0;
            }
        }
    }
    inside
}

/// Each file's points (indices, by J) and its measured zero-thrust J: linear between the last
/// positive and the first non-positive measured CT; None where CT never crosses zero.
fn zero_thrust_js(points: &[ComparedPoint]) -> Vec<(Vec<usize>, Option<f64>)> {
    files_by_j(points)
        .into_iter()
        .map(|pts| {
            let j0 = first_zero(points, &pts, |p| p.measured.ct);
            (pts, j0)
        })
        .collect()
}

/// Each file's points (indices), sorted by J.
fn files_by_j(points: &[ComparedPoint]) -> Vec<Vec<usize>> {
    let mut files: Vec<usize> = points.iter().map(|p| p.file).collect();
    files.sort_unstable();
    files.dedup();
    files
        .into_iter()
        .map(|f| {
            let mut pts: Vec<usize> = (0..points.len()).filter(|&i| points[i].file == f).collect();
            pts.sort_by(|&a, &b| points[a].j.total_cmp(&points[b].j));
            pts
        })
        .collect()
}

/// Where `ct` (measured or predicted) of one file's points `pts` (by J) first crosses zero:
/// linear between the last positive and the first non-positive value.
fn first_zero(points: &[ComparedPoint], pts: &[usize], ct: impl Fn(&ComparedPoint) -> Option<f64>) -> Option<f64> {
    let c = |i: usize| ct(&points[i]).unwrap_or(f64::NAN);
    pts.windows(2).find(|w| c(w[0]) > 0.0 && c(w[1]) <= 0.0).map(|w| {
        let (a, b) = (c(w[0]), c(w[1]));
        points[w[0]].j + a / (a - b) * (points[w[1]].j - points[w[0]].j)
    })
}

/// How a prop's zero-thrust J moves with RPM over its J sweeps, measured and predicted: the
/// blade's effective pitch at each speed. The sections' Reynolds-number dependence moves it up
/// a little as the RPM rises (a zero-lift angle that grows more negative); a blade that twists
/// nose-down under load (a flexible blade's elastic washout) moves it down. Each is the
/// least-squares line of the sweeps' zero-thrust J against ln RPM, given at the lowest and the
/// highest sweep's RPM.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ZeroThrustShift {
    /// The lowest sweep's RPM (the median of its points').
    pub rpm_lo: f64,
    /// The highest sweep's RPM.
    pub rpm_hi: f64,
    /// Sweeps whose measured CT crosses zero.
    pub sweeps: usize,
    /// Measured zero-thrust J at `rpm_lo` and at `rpm_hi` (the fitted line's).
    pub measured: (f64, f64),
    /// The same of the prediction, over the sweeps where it crosses zero too; None where fewer
    /// than two do or they span less than 1.2x in RPM (a model that makes thrust beyond the
    /// measured J range).
    pub predicted: Option<(f64, f64)>,
}

impl ZeroThrustShift {
    /// Measured change from `rpm_lo` to `rpm_hi`, relative.
    pub fn measured_change(&self) -> f64 {
        self.measured.1 / self.measured.0 - 1.0
    }

    /// Predicted change, relative.
    pub fn predicted_change(&self) -> Option<f64> {
        self.predicted.map(|p| p.1 / p.0 - 1.0)
    }
}

/// The least-squares line through the points `(x, y)`: the means of x and y and the slope;
/// None with fewer than two points or no spread in x.
pub fn least_squares(s: &[(f64, f64)]) -> Option<(f64, f64, f64)> {
    if s.len() < 2 {
        return None;
    }
    let n = s.len() as f64;
    let mx = s.iter().map(|p| p.0).sum::<f64>() / n;
    let my = s.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = s.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = s.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| (mx, my, sxy / sxx))
}

/// The least-squares line of `y` against ln `rpm` over `s` (rpm, y), at `lo` and `hi` RPM;
/// None with fewer than two points or an RPM span below 1.2x.
fn line_in_ln_rpm(s: &[(f64, f64)], lo: f64, hi: f64) -> Option<(f64, f64)> {
    let (a, b) = s
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), p| (a.min(p.0), b.max(p.0)));
    if b < 1.2 * a {
        return None;
    }
    let ln: Vec<(f64, f64)> = s.iter().map(|p| (p.0.ln(), p.1)).collect();
    let (mx, my, slope) = least_squares(&ln)?;
    Some((my + slope * (lo.ln() - mx), my + slope * (hi.ln() - mx)))
}

/// [`ZeroThrustShift`] of the J sweeps (files without static points) whose measured CT crosses
/// zero; None with fewer than two such sweeps or an RPM span below 1.2x.
pub fn zero_thrust_shift(points: &[ComparedPoint]) -> Option<ZeroThrustShift> {
    // (rpm, measured J0, predicted J0) of each sweep whose measured CT crosses zero.
    let mut s: Vec<(f64, f64, Option<f64>)> = files_by_j(points)
        .into_iter()
        .filter(|pts| !pts.iter().any(|&i| points[i].is_static()))
        .filter_map(|pts| {
            let m = first_zero(points, &pts, |p| p.measured.ct)?;
            let q = first_zero(points, &pts, |p| p.predicted.ct);
            let mut rpm: Vec<f64> = pts
                .iter()
                .map(|&i| points[i].rpm)
                .filter(|r| r.is_finite() && *r > 0.0)
                .collect();
            rpm.sort_by(f64::total_cmp);
            Some((*rpm.get(rpm.len() / 2)?, m, q))
        })
        .collect();
    s.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (lo, hi) = (s.first()?.0, s.last()?.0);
    let m: Vec<(f64, f64)> = s.iter().map(|p| (p.0, p.1)).collect();
    let q: Vec<(f64, f64)> = s.iter().filter_map(|p| Some((p.0, p.2?))).collect();
    Some(ZeroThrustShift {
        rpm_lo: lo,
        rpm_hi: hi,
        sweeps: s.len(),
        measured: line_in_ln_rpm(&m, lo, hi)?,
        predicted: line_in_ln_rpm(&q, lo, hi),
    })
}

/// Where a prop's error lies: the median signed error (predicted / measured − 1) of CT and CP
/// over one regime's points inside the scored window.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RegimeError {
    /// Points in the regime.
    pub points: usize,
    /// CT's median signed error (NaN without points).
    pub ct: f64,
    /// CP's median signed error (NaN without points).
    pub cp: f64,
}

/// The signed errors of the three regimes of [`REGIMES`], by name.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Regimes {
    /// Static points.
    pub static_points: RegimeError,
    /// Forward flight below half the zero-thrust J.
    pub low_j: RegimeError,
    /// Forward flight from half the zero-thrust J to the window's end.
    pub high_j: RegimeError,
}

impl Regimes {
    /// The regimes of `points` ([`regime_errors`]).
    pub fn of(points: &[ComparedPoint], window: f64) -> Self {
        let [static_points, low_j, high_j] = regime_errors(points, window);
        Regimes {
            static_points,
            low_j,
            high_j,
        }
    }

    /// The three in [`REGIMES`]' order.
    pub fn all(&self) -> [&RegimeError; 3] {
        [&self.static_points, &self.low_j, &self.high_j]
    }
}

/// The regimes of [`regime_errors`], in order (J0: the prop's zero-thrust J).
pub const REGIMES: [&str; 3] = ["static", "forward, J < J0/2", "forward, J0/2 to 0.85 J0"];

/// The signed errors of the scored window ([`in_window`]) by regime ([`REGIMES`]): static
/// points; forward flight below half the prop's zero-thrust J; from there to the window's end.
/// The prop's zero-thrust J is the median of its files' (a UIUC sweep is often two files, one
/// of which never reaches zero thrust); without one, forward points are all in the first
/// regime. Where the validation's unsigned medians say how far, these say which way and where:
/// a pitch error grows towards zero thrust, a hover-efficiency error sits in the static points.
pub fn regime_errors(points: &[ComparedPoint], window: f64) -> [RegimeError; 3] {
    let j0s: Vec<f64> = zero_thrust_js(points).into_iter().filter_map(|(_, j0)| j0).collect();
    let j0 = median(j0s);
    let mut err: [(Vec<f64>, Vec<f64>); 3] = Default::default();
    for (p, inside) in points.iter().zip(in_window(points, window)) {
        if !inside {
            continue;
        }
        let k = if p.is_static() {
            0
        } else if j0.is_finite() && p.j >= 0.5 * j0 {
            2
        } else {
            1
        };
        let (ect, ecp) = &mut err[k];
        for (m, q, out) in [
            (p.measured.ct, p.predicted.ct, &mut *ect),
            (p.measured.cp, p.predicted.cp, &mut *ecp),
        ] {
            if let (Some(m), Some(q)) = (m, q) {
                if m.is_finite() && q.is_finite() && m > 0.0 {
                    out.push(q / m - 1.0);
                }
            }
        }
    }
    err.map(|(ct, cp)| RegimeError {
        points: ct.len(),
        ct: median(ct),
        cp: median(cp),
    })
}

/// How much a prop's static CT grows from its lowest to its highest static RPM, measured and
/// predicted: the Reynolds-number signature a static test holds (a model should follow the
/// measured rise within a third).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StaticRise {
    /// The lowest static RPM.
    pub rpm_lo: f64,
    /// The highest static RPM.
    pub rpm_hi: f64,
    /// Measured CT at `rpm_hi` over CT at `rpm_lo`, minus 1.
    pub measured: f64,
    /// The same of the prediction.
    pub predicted: f64,
}

/// [`StaticRise`] of the static points with a measured and a predicted CT above zero; None
/// where there are fewer than two or they span less than 1.3x in RPM.
pub fn static_rise(points: &[ComparedPoint]) -> Option<StaticRise> {
    let ok = |x: Option<f64>| x.filter(|v| v.is_finite() && *v > 0.0);
    let mut s: Vec<(f64, f64, f64)> = points
        .iter()
        .filter(|p| p.is_static() && p.rpm.is_finite() && p.rpm > 0.0)
        .filter_map(|p| Some((p.rpm, ok(p.measured.ct)?, ok(p.predicted.ct)?)))
        .collect();
    s.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (lo, hi) = (s.first()?, s.last()?);
    (hi.0 >= 1.3 * lo.0).then(|| StaticRise {
        rpm_lo: lo.0,
        rpm_hi: hi.0,
        measured: hi.1 / lo.1 - 1.0,
        predicted: hi.2 / lo.2 - 1.0,
    })
}

/// The validation metric's samples: |predicted/measured − 1| of CT and of CP at every point
/// inside the window ([`in_window`]). Points without a measured or predicted value are left
/// out.
pub fn window_errors(points: &[ComparedPoint], window: f64) -> (Vec<f64>, Vec<f64>) {
    let nan = f64::NAN;
    let (mut ect, mut ecp) = (Vec::new(), Vec::new());
    for (p, inside) in points.iter().zip(in_window(points, window)) {
        if !inside {
            continue;
        }
        let pairs = [
            (p.measured.ct, p.predicted.ct, &mut ect),
            (p.measured.cp, p.predicted.cp, &mut ecp),
        ];
        for (m, q, out) in pairs {
            let (m, q) = (m.unwrap_or(nan), q.unwrap_or(nan));
            if m.is_finite() && q.is_finite() && m > 0.0 {
                out.push((q / m - 1.0).abs());
            }
        }
    }
    (ect, ecp)
}

/// A static point's figure of merit from its coefficients, CT^1.5 / CP · sqrt(2/π):
/// [`propbet_bemt::check::figure_of_merit`] of the loads at ρ = n = D = 1 (T = CT, P = CP,
/// A = π/4); 1 for a lossless rotor, and `propbet_bemt::check` flags a prediction above it.
pub fn figure_of_merit(ct: f64, cp: f64) -> f64 {
    propbet_bemt::check::figure_of_merit(ct, cp, 1.0, std::f64::consts::FRAC_PI_4)
}

/// The median over the static points (V = 0) of the predicted figure of merit over the
/// measured one, minus 1 (the median of [`propbet_units::stats`]): how far the model's hover
/// efficiency is off, whatever the split between thrust and power. NaN without a static point with positive CT and CP on both sides.
pub fn static_figure_of_merit_error(points: &[ComparedPoint]) -> f64 {
    let ratios: Vec<f64> = points
        .iter()
        .filter(|p| p.v == 0.0)
        .filter_map(|p| {
            let (m, q) = (&p.measured, &p.predicted);
            let (mt, mp, qt, qp) = (m.ct?, m.cp?, q.ct?, q.cp?);
            (mt > 0.0 && mp > 0.0 && qt > 0.0 && qp > 0.0)
                .then(|| figure_of_merit(qt, qp) / figure_of_merit(mt, mp) - 1.0)
        })
        .filter(|r| r.is_finite())
        .collect();
    median(ratios)
}

/// Where [`twist_gap`] is averaged: r/R from 0.6 to 0.9 (where most of the thrust is made).
pub const TWIST_GAP_SPAN: (f64, f64) = (0.6, 0.9);

/// The blade's twist error: the mean of the design twist minus the measured β [deg] over the
/// stations within [`TWIST_GAP_SPAN`] (NaN if none is). `stations` are (r/R, measured β in
/// degrees); `design` gives the design twist in degrees at r/R.
pub fn twist_gap(stations: &[(f64, f64)], design: impl Fn(f64) -> f64) -> f64 {
    let d: Vec<f64> = stations
        .iter()
        .filter(|(r_r, _)| *r_r >= TWIST_GAP_SPAN.0 - 1e-9 && *r_r <= TWIST_GAP_SPAN.1 + 1e-9)
        .map(|&(r_r, beta)| design(r_r) - beta)
        .collect();
    if d.is_empty() {
        f64::NAN
    } else {
        d.iter().sum::<f64>() / d.len() as f64
    }
}

/// The two halves of a prop's measurements (`sets`, read from `files` in that order) for a
/// held-out calibration, each a fair sample of the whole: the runs of one sweep, UIUC's files
/// whose names give the same RPM to the nearest 100 ([`sweep_key`]: at the higher RPMs UIUC
/// measures a sweep's low and high advance ratios in two runs, "7013" and "7018"), go to the
/// same half, the sweeps sorted by RPM alternately to each half; a static test (no RPM in its
/// name; one row per RPM) is shared point by point, alternately in file order. So each half
/// holds whole sweeps across the RPM range and static points across theirs, and every point
/// is predicted by a ladder that did not see it. Runs dealt one by one would put every high-J
/// run in one half and every low-J run in the other; a whole static file in one half would
/// leave the other's ladder fitted to forward flight alone and scored on hover.
pub fn halves(files: &[PathBuf], sets: &[MeasuredSet]) -> [Vec<MeasuredSet>; 2] {
    let rpm = |p: &PathBuf| propbet_measure::uiuc::rpm_from_name(&p.to_string_lossy());
    let mut sweeps: Vec<(f64, &PathBuf, &MeasuredSet)> = Vec::new();
    let mut out: [Vec<MeasuredSet>; 2] = [Vec::new(), Vec::new()];
    for (file, set) in files.iter().zip(sets) {
        match rpm(file) {
            Some(r) => sweeps.push((r, file, set)),
            None => {
                for (k, half) in out.iter_mut().enumerate() {
                    let points: Vec<_> = set.points.iter().skip(k).step_by(2).cloned().collect();
                    if !points.is_empty() {
                        half.push(MeasuredSet {
                            rows: points.len(),
                            dropped: Vec::new(),
                            points,
                            ..set.clone()
                        });
                    }
                }
            }
        }
    }
    sweeps.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(b.1)));
    let (mut half, mut last) = (1, None);
    for (r, _, set) in sweeps {
        let key = Some(sweep_key(r));
        if key != last {
            half = 1 - half;
        }
        last = key;
        out[half].push(set.clone());
    }
    out
}

#[cfg(test)]
mod tests;
