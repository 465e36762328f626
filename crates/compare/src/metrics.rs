//! Error metrics per quantity, overall and by group (RPM, advance-ratio band, static vs
//! forward flight). Only scored (unflagged) points count.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::{ComparedPoint, QUANTITIES};

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
    let k = (p.nominal_rpm.unwrap_or(p.rpm) / 100.0).round() as i64 * 100;
    (k, format!("{k} rpm"))
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
    let j0 = quantile(j0s, 0.5);
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
        ct: quantile(ct, 0.5),
        cp: quantile(cp, 0.5),
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
/// measured one, minus 1 (the median as validate's, [`quantile`]): how far the model's hover
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
    quantile(ratios, 0.5)
}

/// The `q`-quantile of `v` (the sample nearest to rank q (n − 1)); NaN for no samples.
pub fn quantile(mut v: Vec<f64>, q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Quantities;
    use approx::assert_relative_eq;

    #[test]
    fn the_figure_of_merit_is_one_for_an_actuator_disc_and_compared_at_static_points() {
        // An actuator disc's power P = T^1.5 / sqrt(2 rho A): FM 1 from its coefficients.
        let (rho, d, n, t) = (1.2, 0.25, 100.0, 5.0);
        let area = std::f64::consts::PI * d * d / 4.0;
        let p = t * f64::sqrt(t) / (2.0 * rho * area).sqrt();
        let (ct, cp) = (t / (rho * n * n * d.powi(4)), p / (rho * n.powi(3) * d.powi(5)));
        assert_relative_eq!(figure_of_merit(ct, cp), 1.0, epsilon = 1e-12);
        // Thrust 10 % high at the same power: FM 1.1^1.5 - 1 = 15.4 % high; forward points and
        // points without power are left out.
        let with = |v: f64, ct: [f64; 2], cp: [Option<f64>; 2]| {
            let mut x = pt("s", 5000.0, 0.0, 1.0, 1.0);
            x.v = v;
            x.measured.ct = Some(ct[0]);
            x.predicted.ct = Some(ct[1]);
            x.measured.cp = cp[0];
            x.predicted.cp = cp[1];
            x
        };
        let pts = [
            with(0.0, [0.10, 0.11], [Some(0.04), Some(0.04)]),
            with(0.0, [0.10, 0.11], [Some(0.04), None]),
            with(5.0, [0.05, 0.10], [Some(0.03), Some(0.03)]),
        ];
        assert_relative_eq!(
            static_figure_of_merit_error(&pts),
            1.1f64.powf(1.5) - 1.0,
            epsilon = 1e-12
        );
        assert!(static_figure_of_merit_error(&pts[2..]).is_nan(), "no static point: NaN");
    }

    fn pt(label: &str, rpm: f64, j: f64, meas: f64, pred: f64) -> ComparedPoint {
        let q = |t: f64| Quantities {
            thrust: Some(t),
            ..Default::default()
        };
        ComparedPoint {
            label: label.into(),
            lines: (1, 1),
            rpm,
            j,
            measured: q(meas),
            predicted: q(pred),
            ..Default::default()
        }
    }

    #[test]
    fn window_errors_stop_below_85_percent_of_the_zero_thrust_j() {
        // Measured CT crosses zero at J = 0.5: J 0.45 (>= 0.425) is left out.
        let mk = |j: f64, ct: f64, ctp: f64, cp: f64, cpp: f64| {
            let mut p = pt("x", 5000.0, j, 1.0, 1.0);
            p.measured.ct = Some(ct);
            p.predicted.ct = Some(ctp);
            p.measured.cp = Some(cp);
            p.predicted.cp = Some(cpp);
            p
        };
        let pts = vec![
            mk(0.2, 0.08, 0.08, 0.04, 0.044),
            mk(0.0, 0.1, 0.11, 0.05, 0.05),
            mk(0.45, 0.01, 0.02, 0.02, 0.02),
            mk(0.55, -0.01, 0.0, 0.01, 0.01),
        ];
        let (ct, cp) = window_errors(&pts, VALIDATION_J_WINDOW);
        // In the points' order.
        assert_eq!(ct.len(), 2);
        assert!(ct[0].abs() < 1e-12 && (ct[1] - 0.1).abs() < 1e-12, "{ct:?}");
        assert!((cp[0] - 0.1).abs() < 1e-12, "{cp:?}");
        assert_eq!(in_window(&pts, VALIDATION_J_WINDOW), vec![true, true, false, false]);
        // A wider window takes J = 0.45 in.
        assert_eq!(in_window(&pts, 0.95), vec![true, true, true, false]);
        assert_eq!(quantile(vec![3.0, 1.0, 2.0], 0.5), 2.0);
        assert!(quantile(vec![], 0.5).is_nan());
    }

    #[test]
    fn regime_errors_are_signed_and_split_at_half_the_prop_s_zero_thrust_j() {
        let mk = |file: usize, j: f64, ct: [f64; 2], cp: [f64; 2]| {
            let mut p = pt("x", 5000.0, j, 1.0, 1.0);
            p.file = file;
            p.measured.ct = Some(ct[0]);
            p.predicted.ct = Some(ct[1]);
            p.measured.cp = Some(cp[0]);
            p.predicted.cp = Some(cp[1]);
            p
        };
        // File 0: static, thrust 10 % high, power 5 % low. File 1: a low-J sweep that never
        // reaches zero thrust (no zero-thrust J of its own). File 2: crosses zero at J = 0.6.
        let pts = vec![
            mk(0, 0.0, [0.10, 0.11], [0.05, 0.0475]),
            mk(0, 0.0, [0.10, 0.11], [0.05, 0.0475]),
            mk(1, 0.1, [0.09, 0.0855], [0.05, 0.05]),
            mk(1, 0.25, [0.08, 0.076], [0.05, 0.05]),
            mk(2, 0.35, [0.05, 0.06], [0.04, 0.044]),
            mk(2, 0.55, [0.01, 0.02], [0.02, 0.02]),
            mk(2, 0.65, [-0.01, 0.0], [0.01, 0.01]),
        ];
        let [st, low, high] = regime_errors(&pts, VALIDATION_J_WINDOW);
        assert_eq!((st.points, low.points, high.points), (2, 2, 1));
        assert!((st.ct - 0.1).abs() < 1e-12 && (st.cp + 0.05).abs() < 1e-12, "{st:?}");
        // File 1's points are below half of the prop's zero-thrust J (0.6, file 2's).
        assert!((low.ct + 0.05).abs() < 1e-12 && low.cp.abs() < 1e-12, "{low:?}");
        // J = 0.35 is above 0.3; J = 0.55 is outside the window (0.85 x 0.6 = 0.51).
        assert!(
            (high.ct - 0.2).abs() < 1e-12 && (high.cp - 0.1).abs() < 1e-12,
            "{high:?}"
        );
        // Without a zero-thrust J every forward point is in the first regime; no static: NaN.
        let [st, low, high] = regime_errors(&pts[2..4], VALIDATION_J_WINDOW);
        assert_eq!((st.points, low.points, high.points), (0, 2, 0));
        assert!(st.ct.is_nan() && high.cp.is_nan());
    }

    #[test]
    fn the_static_rise_is_from_the_lowest_to_the_highest_static_rpm() {
        let mk = |rpm: f64, j: f64, ct: [f64; 2]| {
            let mut p = pt("x", rpm, j, 1.0, 1.0);
            p.measured.ct = Some(ct[0]);
            p.predicted.ct = Some(ct[1]);
            p
        };
        // Out of order, with a forward point (not static) at a higher RPM and a point without
        // a prediction.
        let mut none = mk(7000.0, 0.0, [0.13, 0.1]);
        none.predicted.ct = None;
        let pts = vec![
            mk(6000.0, 0.0, [0.12, 0.105]),
            mk(2400.0, 0.0, [0.10, 0.1]),
            mk(4000.0, 0.0, [0.11, 0.102]),
            mk(8000.0, 0.3, [0.05, 0.06]),
            none,
        ];
        let r = static_rise(&pts).unwrap();
        assert_eq!((r.rpm_lo, r.rpm_hi), (2400.0, 6000.0));
        assert!(
            (r.measured - 0.2).abs() < 1e-12 && (r.predicted - 0.05).abs() < 1e-12,
            "{r:?}"
        );
        // Less than 1.3x in RPM, or one point: none.
        assert!(static_rise(&[mk(2400.0, 0.0, [0.1, 0.1]), mk(3000.0, 0.0, [0.1, 0.1])]).is_none());
        assert!(static_rise(&pts[..1]).is_none());
    }

    #[test]
    fn the_zero_thrust_shift_follows_the_sweeps_crossings() {
        // Three J sweeps (files by label) whose measured CT crosses zero at 0.65, 0.64, 0.62
        // and whose predicted CT at 0.60, 0.61, 0.62 (CT = k (J0 - J) through J = 0.5 and 0.7),
        // and a static file at a higher RPM.
        let mut pts = Vec::new();
        for (f, (rpm, jm, jp)) in [(4000.0, 0.65, 0.60), (5000.0, 0.64, 0.61), (6800.0, 0.62, 0.62)]
            .into_iter()
            .enumerate()
        {
            for j in [0.5, 0.7] {
                let mut p = pt("x", rpm, j, 1.0, 1.0);
                p.file = f;
                p.measured.ct = Some(0.3 * (jm - j));
                p.predicted.ct = Some(0.3 * (jp - j));
                pts.push(p);
            }
        }
        let mut st = pt("s", 9000.0, 0.0, 1.0, 1.0);
        st.file = 3;
        st.measured.ct = Some(0.1);
        st.predicted.ct = Some(-0.1);
        pts.push(st);
        let z = zero_thrust_shift(&pts).unwrap();
        assert_eq!((z.rpm_lo, z.sweeps), (4000.0, 3));
        assert_eq!(z.rpm_hi, 6800.0);
        // Falling measured, rising predicted: the fitted lines' ends, near the sweeps' own.
        let q = z.predicted.unwrap();
        assert!(
            z.measured_change() < -0.03 && z.predicted_change().unwrap() > 0.02,
            "{z:?}"
        );
        assert!(
            (z.measured.0 - 0.652).abs() < 0.005 && (q.1 - 0.621).abs() < 0.005,
            "{z:?}"
        );
        // One sweep, or sweeps within 1.2x in RPM: none.
        assert!(zero_thrust_shift(&pts[..2]).is_none());
        let mut near: Vec<ComparedPoint> = pts[..4].to_vec();
        near[2].rpm = 4400.0;
        near[3].rpm = 4400.0;
        assert!(zero_thrust_shift(&near).is_none());
        // A sweep whose prediction never reaches zero thrust is left out of the predicted line
        // (the other two still span 1.7x); with two such sweeps there is no predicted line,
        // and the measured one stays.
        let mut short = pts.clone();
        short[3].predicted.ct = Some(0.01);
        let z = zero_thrust_shift(&short).unwrap();
        assert_eq!(z.sweeps, 3);
        assert!(
            z.predicted
                .is_some_and(|q| (q.0 - 0.60).abs() < 1e-9 && (q.1 - 0.62).abs() < 1e-9),
            "{z:?}"
        );
        short[5].predicted.ct = Some(0.01);
        let z = zero_thrust_shift(&short).unwrap();
        assert!(z.predicted.is_none() && z.measured_change() < -0.03, "{z:?}");
    }

    #[test]
    fn sweeps_of_one_nominal_speed_share_a_group() {
        let mut a = pt("a", 4997.0, 0.3, 1.0, 1.0);
        a.nominal_rpm = Some(4997.0);
        let mut b = pt("b", 5018.0, 0.3, 1.0, 1.0);
        b.nominal_rpm = Some(5018.0);
        let c = pt("c", 6023.0, 0.0, 1.0, 1.0);
        assert_eq!(sweep_group(&a), (5000, "5000 rpm".to_string()));
        assert_eq!(sweep_group(&a), sweep_group(&b));
        assert_eq!(sweep_group(&c).0, 6000);
    }

    #[test]
    fn bias_rmse_and_relative_errors() {
        let pts = vec![
            pt("a", 4100.0, 0.0, 1.0, 1.1),
            pt("b", 4900.0, 0.0, 2.0, 1.8),
            pt("c", 5500.0, 0.3, 4.0, 4.0),
        ];
        let m = metrics(&pts);
        let t = &m.overall.metrics["thrust"];
        assert_eq!(t.n, 3);
        assert_relative_eq!(t.bias, (0.1 - 0.2) / 3.0, epsilon = 1e-12);
        assert_relative_eq!(t.rmse, ((0.01 + 0.04) / 3.0f64).sqrt(), epsilon = 1e-12);
        assert_relative_eq!(t.mean_rel, (0.1 - 0.1 + 0.0) / 3.0, epsilon = 1e-12);
        assert_relative_eq!(t.mean_abs_rel, 0.2 / 3.0, epsilon = 1e-12);
        assert_relative_eq!(t.max_rel.abs(), 0.1, epsilon = 1e-12);
        assert_eq!(m.per_rpm.len(), 2);
        assert_eq!(m.per_rpm[0].name, "static, 4000-5000 rpm band");
        assert_eq!(m.per_rpm[0].points, 2);
        assert_eq!(m.per_j[0].name, "static (J = 0)");
        assert_eq!(m.per_j[1].name, "J 0.2-0.4");
        assert_eq!(m.static_points.unwrap().points, 2);
        assert!(!m.overall.metrics.contains_key("torque"));
    }

    #[test]
    fn flagged_points_are_not_scored() {
        let mut bad = pt("bad", 5000.0, 0.0, 1.0, 3.0);
        bad.flags.push("unsteady".into());
        let m = metrics(&[pt("a", 5000.0, 0.0, 1.0, 1.0), bad]);
        assert_eq!(m.unscored, 1);
        assert_eq!(m.overall.metrics["thrust"].rmse, 0.0);
    }
}
