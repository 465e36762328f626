//! Where the model fails, as findings: bias, dependence on advance ratio and on RPM at fixed J
//! (the J sweeps' and the static test's apart where they differ), thrust against torque, per
//! quantity; the report words them ("thrust over-predicted by 12 % on average, largest at
//! J > 0.5 (+18 %) ..."). Each part names the candidate effects that can make it and those that
//! cannot, from the model's own response to each ([`Response`], probed within its bounds by
//! `discover`), not from a list.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::Data;
use propbet_units::stats::median;

/// Errors below this RMS are called "within" it.
pub const QUIET: f64 = 0.02;

/// One quantity's residual pattern, as numbers and findings (the report words them:
/// `propbet_report::diagnose::signature_text`).
#[derive(Debug, Clone, Serialize)]
pub struct Signature {
    /// "thrust" or "torque".
    pub quantity: String,
    /// Mean relative error (predicted - measured)/measured.
    pub mean: f64,
    /// RMS relative error.
    pub rms: f64,
    /// The parts of the pattern, the bias first.
    pub parts: Vec<Part>,
}

/// One part of a pattern: what the points show, the candidates that can make it where they
/// were matched, and (on the last part) the other quantity left unaffected.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Part {
    /// What the points show.
    pub shows: Shows,
    /// The candidates that can make it.
    pub effects: Option<EffectList>,
    /// Where only this quantity is off: the other unaffected, and what moves this one alone.
    pub unaffected: Option<Unaffected>,
}

/// What a part of a pattern shows.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Shows {
    /// The error's RMS is below [`QUIET`].
    Quiet,
    /// The mean error (the signature's mean and RMS).
    Bias,
    /// The error changes with J at fixed RPM: the two halves split at the median J.
    AgainstJ {
        /// The median J.
        median_j: f64,
        /// The larger error is above the median J.
        above: bool,
        /// The mean error on the larger side.
        there: f64,
        /// The mean error on the other.
        elsewhere: f64,
        /// The cause is said (not where torque alone is off).
        cause: bool,
    },
    /// The error changes with RPM at fixed J.
    WithRpm {
        /// Every point is static (a stand's step test).
        all_static: bool,
        /// The trend at fixed J.
        trend: RpmTrend,
        /// The static test's own trend, where there are J sweeps beside it.
        statically: Option<RpmTrend>,
        /// The measured quantity grows faster with RPM than the model's.
        faster: bool,
        /// Where it shows.
        regime: Regime,
        /// The cause is said (not where torque alone is off).
        cause: bool,
    },
    /// The first RPM group's error against the last's.
    RpmGroups {
        /// The error grows with RPM (else it is largest at low RPM).
        growing: bool,
        /// The first group's mean RPM, error and J.
        low: GroupMean,
        /// The last group's.
        high: GroupMean,
        /// Their mean J differ: RPM and J are not told apart.
        confounded: bool,
        /// The error's power of RPM, where it is at least 0.7 in size and not confounded.
        power: Option<f64>,
    },
    /// Thrust against torque where both are off.
    ThrustTorque {
        /// How their mean errors relate.
        relation: Relation,
        /// Thrust's mean error.
        thrust: f64,
        /// Torque's mean error.
        torque: f64,
    },
}

/// An RPM group's means.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GroupMean {
    /// Mean RPM.
    pub rpm: f64,
    /// Mean error.
    pub error: f64,
    /// Mean J.
    pub j: f64,
}

/// Where an RPM trend shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Regime {
    /// In the J sweeps and statically alike (or only one of them measured).
    Both,
    /// In forward flight, not statically.
    ForwardOnly,
    /// Statically, not in forward flight.
    StaticOnly,
}

/// How thrust's and torque's mean errors relate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Relation {
    /// Opposite signs.
    Opposite,
    /// The same way, torque more than twice as much.
    TorqueMore,
    /// The same way, thrust more than twice as much.
    ThrustMore,
    /// The same way by similar amounts.
    Similar,
}

/// The candidates a part names, from their responses.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EffectList {
    /// What they make: "it" (the part), or "both" (thrust and torque).
    pub object: String,
    /// The effects that can make it, best first.
    pub can: Vec<String>,
    /// Those that cannot.
    pub cannot: Vec<String>,
    /// The same list as thrust's (torque's part refers to it).
    pub as_for_thrust: bool,
}

/// The other quantity unaffected.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Unaffected {
    /// The quantity within [`QUIET`].
    pub kept: String,
    /// The one that is off.
    pub moved: String,
    /// The candidates that move it alone (None: no candidates were probed).
    pub alone: Option<Vec<String>>,
}

impl Part {
    fn new(shows: Shows, effects: Option<EffectList>) -> Self {
        Self {
            shows,
            effects,
            unaffected: None,
        }
    }
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

/// Root-mean-square deviation from the mean.
fn spread(v: &[f64]) -> f64 {
    let m = mean(v);
    (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / v.len().max(1) as f64).sqrt()
}

/// How much of a pattern an effect must be able to take away to be named as one that can
/// make it: the best of its probes that do not make the error vary more leaves at most this
/// fraction of the pattern's size.
pub const CAN_MAKE: f64 = 0.5;

/// How one candidate effect moves the residual rows, from the model itself: the change of every
/// row (in [`Data::rows`] order) with the effect at each probe value of its parameters (within
/// their bounds), from the model without it.
#[derive(Debug, Clone)]
pub struct Response {
    /// The effect's id.
    pub id: String,
    /// Each probe's change of every residual row.
    pub probes: Vec<Vec<f64>>,
}

/// A quantity's pattern as numbers, each part where the points show it: what the words say,
/// and what an effect's response is matched against.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Parts {
    /// Mean error above the median J minus below it.
    dj: Option<f64>,
    /// The J sweeps' median slope of the error against ln RPM at fixed J.
    forward: Option<f64>,
    /// The static test's slope against ln RPM.
    stat: Option<f64>,
}

/// The mean error of the points of `pts` at J up to `jm` and above it, where each side has at
/// least two.
fn j_halves(pts: &[(f64, f64, i64, f64)], jm: f64) -> Option<(f64, f64)> {
    let lo: Vec<f64> = pts.iter().filter(|p| p.0 <= jm).map(|p| p.3).collect();
    let hi: Vec<f64> = pts.iter().filter(|p| p.0 > jm).map(|p| p.3).collect();
    (lo.len() >= 2 && hi.len() >= 2).then(|| (mean(&lo), mean(&hi)))
}

/// The median J of `pts` (non-empty), where [`j_halves`] splits them.
fn median_j(pts: &[(f64, f64, i64, f64)]) -> f64 {
    median(pts.iter().map(|p| p.0).collect())
}

/// The rows of one quantity (thrust, or torque) of `data` as (J, rpm, group, value), the
/// value of each from `values` (one per residual row, in [`Data::rows`] order).
fn quantity_points(data: &Data, rows: &[crate::Row], torque: bool, values: &[f64]) -> Vec<(f64, f64, i64, f64)> {
    rows.iter()
        .zip(values)
        .filter(|(row, _)| row.torque == torque)
        .map(|(row, &v)| {
            let o = &data.obs[row.point];
            (o.j, o.rpm(), o.rpm_group, v)
        })
        .collect()
}

/// The parts of the pattern of `pts` (J, rpm, group, error), split at J `jm`.
fn parts_of(pts: &[(f64, f64, i64, f64)], jm: f64) -> Parts {
    let bins = rpm_slopes(pts);
    let forward: Vec<f64> = bins.iter().filter(|(k, _)| **k >= 0).map(|(_, b)| b.0).collect();
    Parts {
        dj: j_halves(pts, jm).map(|(lo, hi)| hi - lo),
        forward: (!forward.is_empty()).then(|| median(forward)),
        stat: bins.get(&-1).map(|b| b.0),
    }
}

/// Which candidates can make a pattern: each response's best probe against the observed parts
/// `seen` (the parts of `of` that are there). None without responses (nothing to match).
fn effect_list<P>(
    seen: &[f64],
    of: impl Fn(&P) -> Vec<f64>,
    responses: &[(String, Vec<P>)],
    object: &str,
) -> Option<EffectList> {
    if responses.is_empty() {
        return None;
    }
    let size = seen.iter().map(|x| x * x).sum::<f64>().sqrt();
    let mut can: Vec<(f64, &str)> = Vec::new();
    let mut cannot: Vec<&str> = Vec::new();
    for (id, probes) in responses {
        let left = probes
            .iter()
            .map(|p| {
                let r = of(p);
                seen.iter().zip(&r).map(|(o, r)| (o + r).powi(2)).sum::<f64>().sqrt()
            })
            .fold(f64::INFINITY, f64::min);
        if size > 0.0 && left <= CAN_MAKE * size {
            can.push((left, id));
        } else {
            cannot.push(id);
        }
    }
    can.sort_by(|a, b| a.0.total_cmp(&b.0));
    Some(EffectList {
        object: object.to_string(),
        can: can.into_iter().map(|c| c.1.to_string()).collect(),
        cannot: cannot.into_iter().map(str::to_string).collect(),
        as_for_thrust: false,
    })
}

/// Width of the J bins within which RPM trends are measured (static points are one bin).
const J_BIN: f64 = 0.05;

/// An error's trend with RPM at fixed J: its change over an RPM range.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RpmTrend {
    /// The change of the relative error from `lo` to `hi`.
    pub change: f64,
    /// The RPM range it is measured over.
    pub lo: f64,
    /// The RPM range's upper end.
    pub hi: f64,
}

/// Each J bin's least-squares slope of the error against ln RPM, with the bin's ln-RPM range
/// `(slope, ln rpm min, ln rpm max)`, for the bins that span at least 5 % in RPM. The static
/// points (J < 0.01) are bin `-1`.
fn rpm_slopes(pts: &[(f64, f64, i64, f64)]) -> BTreeMap<i64, (f64, f64, f64)> {
    let mut bins: BTreeMap<i64, Vec<(f64, f64)>> = BTreeMap::new();
    for &(j, rpm, _, e) in pts {
        let key = if j < 0.01 { -1 } else { (j / J_BIN).floor() as i64 };
        if rpm > 0.0 && e.is_finite() {
            bins.entry(key).or_default().push((rpm.ln(), e));
        }
    }
    let mut out = BTreeMap::new();
    for (key, b) in bins {
        let (xmin, xmax) = b
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| (a.0.min(p.0), a.1.max(p.0)));
        if xmax - xmin < 0.05 {
            continue;
        }
        if let Some((_, _, slope)) = propbet_compare::metrics::least_squares(&b) {
            out.insert(key, (slope, xmin, xmax));
        }
    }
    out
}

impl RpmTrend {
    /// The change of a slope (per unit ln RPM) over ln-RPM `lo` to `hi`; None where that range
    /// is below 1.3x.
    fn over(slope: f64, lo: f64, hi: f64) -> Option<RpmTrend> {
        (hi - lo >= 1.3f64.ln()).then(|| RpmTrend {
            change: slope * (hi - lo),
            lo: lo.exp(),
            hi: hi.exp(),
        })
    }
}

/// The trend at fixed J of [`rpm_slopes`]' bins: the median slope over the median range of the
/// J sweeps' bins (the static test's is told beside it, [`static_trend`]), or of the static
/// bin where it is the only one.
fn fixed_j_trend(bins: &BTreeMap<i64, (f64, f64, f64)>) -> Option<RpmTrend> {
    let forward: Vec<&(f64, f64, f64)> = bins.iter().filter(|(k, _)| **k >= 0).map(|(_, b)| b).collect();
    let used: Vec<&(f64, f64, f64)> = if forward.is_empty() {
        bins.values().collect()
    } else {
        forward
    };
    if used.is_empty() {
        return None;
    }
    let slope = median(used.iter().map(|b| b.0).collect());
    let lo = median(used.iter().map(|b| b.1).collect());
    let hi = median(used.iter().map(|b| b.2).collect());
    RpmTrend::over(slope, lo, hi)
}

/// The static bin's own trend of [`rpm_slopes`]' bins, where there are J bins beside it.
fn static_trend(bins: &BTreeMap<i64, (f64, f64, f64)>) -> Option<RpmTrend> {
    if bins.len() < 2 {
        return None;
    }
    let &(slope, lo, hi) = bins.get(&-1)?;
    RpmTrend::over(slope, lo, hi)
}

/// The error's trend with RPM at fixed J: within J bins, the least-squares slope of the error
/// against ln RPM; the median over the J sweeps' bins that span at least 5 % in RPM (the static
/// test's where there are none; one bin of large
/// errors near zero thrust does not outvote the others), as the change over the RPM range the
/// bins typically span (the medians of their lowest and highest RPM: a slope of J sweeps at
/// 4,000-6,500 rpm is not stretched over a static test's 2,000-6,500). `pts`: (J, rpm, group,
/// error). None where that range is below 1.3x.
pub fn rpm_trend_at_fixed_j(pts: &[(f64, f64, i64, f64)]) -> Option<RpmTrend> {
    fixed_j_trend(&rpm_slopes(pts))
}

/// The static points' own trend with RPM (a static test spans a wider RPM range than J sweeps
/// and holds no J to confound it), where there are also J bins to set it beside; None where
/// the static points span less than 1.3x.
pub fn static_rpm_trend(pts: &[(f64, f64, i64, f64)]) -> Option<RpmTrend> {
    static_trend(&rpm_slopes(pts))
}

/// The thrust error's two trends that point at physics, for the ladder's rungs: its change
/// with J at fixed RPM (mean above the median J minus below) and with RPM at fixed J (over the
/// RPM range its J bins typically span, [`rpm_trend_at_fixed_j`]). Thrust rows of `residuals`
/// (in [`Data::rows`] order); None where the points do not show one.
pub fn thrust_trends(data: &Data, residuals: &[f64]) -> (Option<f64>, Option<f64>) {
    let pts = quantity_points(data, &data.rows(), false, residuals);
    if pts.is_empty() {
        return (None, None);
    }
    (
        parts_of(&pts, median_j(&pts)).dj,
        rpm_trend_at_fixed_j(&pts).map(|t| t.change),
    )
}

/// The residual patterns of the residual rows `residuals` of `data` (in [`Data::rows`] order:
/// relative errors with the floors), with the candidates that can make each part of them
/// (from their `responses`; none named without).
pub fn signatures(data: &Data, residuals: &[f64], responses: &[Response]) -> Vec<Signature> {
    let mut out: Vec<Signature> = Vec::new();
    // The effect lists thrust's pattern named, which torque's refers to where it names the same.
    let mut named: Vec<EffectList> = Vec::new();
    let rows = data.rows();
    for torque in [false, true] {
        let thrust = out.first();
        if let Some(sig) = quantity_signature(data, &rows, residuals, responses, torque, thrust, &mut named) {
            out.push(sig);
        }
    }
    if out.len() == 2 {
        thrust_and_torque(&mut out, &rows, residuals, responses);
    }
    out
}

/// An effect list once: torque's refers to thrust's where it is the same.
fn refer(list: EffectList, torque: bool, named: &mut Vec<EffectList>) -> EffectList {
    if torque && named.contains(&list) && !list.can.is_empty() {
        EffectList {
            as_for_thrust: true,
            ..list
        }
    } else {
        if !torque {
            named.push(list.clone());
        }
        list
    }
}

/// One quantity's pattern (thrust, or torque after `thrust`'s): its mean and RMS, and the parts
/// that stand out (against J, with RPM at fixed J, from the first RPM group to the last).
fn quantity_signature(
    data: &Data,
    rows: &[crate::Row],
    residuals: &[f64],
    responses: &[Response],
    torque: bool,
    thrust: Option<&Signature>,
    named: &mut Vec<EffectList>,
) -> Option<Signature> {
    let name = if torque { "torque" } else { "thrust" };
    let at = |values: &[f64]| quantity_points(data, rows, torque, values);
    let pts = at(residuals);
    if pts.is_empty() {
        return None;
    }
    let e: Vec<f64> = pts.iter().map(|p| p.3).collect();
    let (m, r) = (mean(&e), crate::rms(&e));
    if r < QUIET {
        return Some(Signature {
            quantity: name.into(),
            mean: m,
            rms: r,
            parts: vec![Part::new(Shows::Quiet, None)],
        });
    }
    let mut parts = vec![Part::new(Shows::Bias, None)];
    let threshold = QUIET.max(0.3 * r);
    // Torque off with thrust right: only what moves torque alone can make its patterns (said
    // once below), not the angles, air or RPM the general lists name.
    let torque_alone = torque && thrust.is_some_and(|s| s.rms < QUIET);
    // Advance ratio: split at the median J.
    let jm = median_j(&pts);
    let seen = parts_of(&pts, jm);
    // Each candidate's probes, as the same parts; a probe that makes this quantity's error
    // vary more (a tare at its bound swamping the loads near zero thrust) does not count as
    // making a part of it. Its mean is left out: where an effect's neutral level sits (re-lift's
    // Re of 1e5) is not its pattern.
    let resp: Vec<(String, Vec<Parts>)> = if torque_alone {
        Vec::new()
    } else {
        responses
            .iter()
            .map(|resp| {
                let probes = resp
                    .probes
                    .iter()
                    .map(|p| at(p))
                    .filter(|d| {
                        let moved: Vec<f64> = d.iter().zip(&e).map(|(d, e)| d.3 + e).collect();
                        spread(&moved) <= spread(&e)
                    })
                    .map(|d| parts_of(&d, jm))
                    .collect();
                (resp.id.clone(), probes)
            })
            .collect()
    };
    if let Some(part) = j_part(&pts, jm, threshold, torque, torque_alone, &resp, named) {
        parts.push(part);
    }
    let bins = rpm_slopes(&pts);
    let trend = fixed_j_trend(&bins);
    if let Some(part) = rpm_trend_part(&pts, &bins, trend, &seen, torque, torque_alone, &resp, named) {
        parts.push(part);
    }
    if let Some(part) = rpm_group_part(&pts, threshold, trend.is_some()) {
        parts.push(part);
    }
    Some(Signature {
        quantity: name.into(),
        mean: m,
        rms: r,
        parts,
    })
}

mod parts;

use parts::{j_part, rpm_group_part, rpm_trend_part, thrust_and_torque};

#[cfg(test)]
mod tests;
