//! Where the model fails, in words: bias, dependence on advance ratio and on RPM at fixed J (the
//! J sweeps' and the static test's apart where they differ), thrust against torque, per
//! quantity ("thrust over-predicted by 12 % on average, largest at J > 0.5 (+18 %) ...";
//! "torque under-predicted ..., largest at low RPM; thrust unaffected"). Each part names the
//! candidate effects that can make it and those that cannot, from the model's own response to
//! each ([`Response`], probed within its bounds by `discover`), not from a list.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::Data;

/// Errors below this RMS are called "within" it.
pub const QUIET: f64 = 0.02;

/// One quantity's residual pattern.
#[derive(Debug, Clone, Serialize)]
pub struct Signature {
    /// "thrust" or "torque".
    pub quantity: String,
    /// Mean relative error (predicted - measured)/measured.
    pub mean: f64,
    /// RMS relative error.
    pub rms: f64,
    /// The pattern in words: its parts' sentences, each followed by its effects'.
    pub text: String,
    /// The same, part by part (the bias first), for a page to lay out.
    pub parts: Vec<Part>,
}

/// One part of a pattern: what it says, and the candidates it names where they were matched.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Part {
    /// The sentence, without its full stop.
    pub text: String,
    /// The candidates that can make it.
    pub effects: Option<EffectList>,
}

/// The candidates a part names, from their responses: "{lead}{can, ...}{rest}", as in
/// "Effects that can make it (...): a, b; not c".
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EffectList {
    /// The words before the effects that can make it (all of the sentence where none can).
    pub lead: String,
    /// The effects that can make it, best first.
    pub can: Vec<String>,
    /// The words after them ("; not c, d").
    pub rest: String,
}

impl EffectList {
    /// The list as a sentence.
    pub fn sentence(&self) -> String {
        format!("{}{}{}", self.lead, self.can.join(", "), self.rest)
    }
}

impl Part {
    fn new(text: String, effects: Option<EffectList>) -> Self {
        Self { text, effects }
    }
}

/// The words of `parts`: each part's sentence, then its effects', joined by full stops.
fn render(parts: &[Part]) -> String {
    parts
        .iter()
        .flat_map(|p| std::iter::once(p.text.clone()).chain(p.effects.as_ref().map(EffectList::sentence)))
        .collect::<Vec<String>>()
        .join(". ")
}

fn pct(x: f64) -> String {
    format!("{:+.1} %", 100.0 * x)
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
    let mut js: Vec<f64> = pts.iter().map(|p| p.0).collect();
    js.sort_by(f64::total_cmp);
    js[js.len() / 2]
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
/// `seen` (the parts of `of` that are there), as "Effects that can make {object} (...): a, b;
/// not c". None without responses (nothing to match).
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
    let can: Vec<String> = can.into_iter().map(|c| c.1.to_string()).collect();
    Some(if can.is_empty() {
        EffectList {
            lead: format!(
                "No candidate effect can make {object} within its bounds (from the model's response to each)"
            ),
            can,
            rest: String::new(),
        }
    } else {
        EffectList {
            lead: format!("Effects that can make {object} (from the model's response to each, within its bounds): "),
            rest: if cannot.is_empty() {
                String::new()
            } else {
                format!("; not {}", cannot.join(", "))
            },
            can,
        }
    })
}

/// The RPM trend's qualifier where the J sweeps show it and the static test does not.
const FORWARD_ONLY: &str = " in forward flight, not statically";
/// ... and the other way round.
const STATIC_ONLY: &str = " statically, not in forward flight";

/// What the torque's pattern says in place of an effect list the thrust's already gave.
const SAME_EFFECTS: &str = "The effects named for thrust can make it";

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

/// The median of a non-empty list.
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
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

/// `s` with its first letter a capital.
fn capitalised(s: &str) -> String {
    let mut c = s.chars();
    c.next().map_or(String::new(), |f| f.to_uppercase().chain(c).collect())
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
    // The parts' sentences capitalised after the first (which starts with the quantity's
    // name), and the words.
    for sig in &mut out {
        for p in sig.parts.iter_mut().skip(1) {
            p.text = capitalised(&p.text);
        }
        sig.text = render(&sig.parts);
    }
    out
}

/// An effect list once: torque's refers to thrust's where it is the same.
fn refer(list: EffectList, torque: bool, named: &mut Vec<EffectList>) -> EffectList {
    if torque && named.contains(&list) && !list.can.is_empty() {
        EffectList {
            lead: SAME_EFFECTS.to_string(),
            can: Vec::new(),
            rest: String::new(),
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
            text: String::new(),
            parts: vec![Part::new(
                format!(
                    "{name} within {:.0} % everywhere (RMS {:.1} %)",
                    100.0 * QUIET,
                    100.0 * r
                ),
                None,
            )],
        });
    }
    let word = if m > 0.0 { "over-predicted" } else { "under-predicted" };
    let mut parts = vec![Part::new(
        format!(
            "{name} {word} by {:.1} % on average (RMS {:.1} %)",
            100.0 * m.abs(),
            100.0 * r
        ),
        None,
    )];
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
    if let Some(part) = rpm_trend_part(&pts, &bins, trend, &seen, name, torque, torque_alone, &resp, named) {
        parts.push(part);
    }
    if let Some(part) = rpm_group_part(&pts, threshold, trend.is_some()) {
        parts.push(part);
    }
    Some(Signature {
        quantity: name.into(),
        mean: m,
        rms: r,
        text: String::new(),
        parts,
    })
}

mod parts;

use parts::{j_part, rpm_group_part, rpm_trend_part, thrust_and_torque};

#[cfg(test)]
mod tests;
