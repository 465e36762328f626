//! Where the model fails, in words: bias, dependence on advance ratio and on RPM, per
//! quantity ("thrust over-predicted by 12 % on average, largest at J > 0.5 (+18 %), growing
//! with RPM (about RPM^2)"; "torque under-predicted ..., largest at low RPM; thrust
//! unaffected").

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
    /// The pattern in words.
    pub text: String,
}

fn pct(x: f64) -> String {
    format!("{:+.1} %", 100.0 * x)
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

/// Which effects can make an error that changes with J at fixed RPM, and which cannot.
pub const J_TREND_EFFECTS: &str =
    "Effects that can make it: pitch-offset and elastic-twist (an angle error weighs more where the sections' \
     angles are small, at high J), rpm-scale (a wrong RPM is a wrong J), tip-loss and hub-loss (the inflow), \
     the tares (loads that do not scale as the propeller's); not density, which scales every load alike";

/// Which effects can make an error that changes with RPM at fixed J, and which cannot.
pub const RPM_TREND_EFFECTS: &str =
    "Effects that can make it: re-lift (section lift with Re), re-scaling (drag with Re, \
     mostly torque), transition (Ncrit, from polars at several: --ncrit-effect), compressibility (tip Mach above 0.3), \
     elastic-twist (thrust falling at high RPM), torque-tare (a friction torque weighs most at low RPM: torque \
     alone); not density, rpm-scale, chord-scale, pitch-offset or thrust-tare, which act alike at every RPM";

/// What the torque's pattern says in place of an effect list the thrust's already gave.
const SAME_EFFECTS: &str = "The effects named for thrust can make it";

/// Width of the J bins within which RPM trends are measured (static points are one bin).
const J_BIN: f64 = 0.05;

/// An error's trend with RPM at fixed J: its change over an RPM range.
#[derive(Clone, Copy, Debug, PartialEq)]
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
        let xs: Vec<f64> = b.iter().map(|p| p.0).collect();
        let (xmin, xmax) = xs
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |a, &x| (a.0.min(x), a.1.max(x)));
        if b.len() < 2 || xmax - xmin < 0.05 {
            continue;
        }
        let (mx, me) = (mean(&xs), mean(&b.iter().map(|p| p.1).collect::<Vec<_>>()));
        let sxx: f64 = b.iter().map(|p| (p.0 - mx).powi(2)).sum();
        let sxy: f64 = b.iter().map(|p| (p.0 - mx) * (p.1 - me)).sum();
        out.insert(key, (sxy / sxx, xmin, xmax));
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

/// The trend at fixed J of [`rpm_slopes`]' bins: the median slope over the median range.
fn fixed_j_trend(bins: &BTreeMap<i64, (f64, f64, f64)>) -> Option<RpmTrend> {
    if bins.is_empty() {
        return None;
    }
    let slope = median(bins.values().map(|b| b.0).collect());
    let lo = median(bins.values().map(|b| b.1).collect());
    let hi = median(bins.values().map(|b| b.2).collect());
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
/// against ln RPM; the median over the bins that span at least 5 % in RPM (one bin of large
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

/// The parts of a pattern as sentences: the first as it is (it starts with the quantity's
/// name), each other capitalised, all joined by full stops.
fn sentences(parts: &[String]) -> String {
    parts
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let mut c = p.chars();
            match c.next() {
                Some(f) if i > 0 => f.to_uppercase().chain(c).collect(),
                _ => p.clone(),
            }
        })
        .collect::<Vec<String>>()
        .join(". ")
}

/// The residual patterns of the residual rows `residuals` of `data` (in [`Data::rows`] order:
/// relative errors with the floors).
pub fn signatures(data: &Data, residuals: &[f64]) -> Vec<Signature> {
    let mut out: Vec<Signature> = Vec::new();
    for torque in [false, true] {
        let name = if torque { "torque" } else { "thrust" };
        // (J, rpm, group, relative error)
        let pts: Vec<(f64, f64, i64, f64)> = data
            .rows()
            .iter()
            .zip(residuals)
            .filter(|(row, _)| row.torque == torque)
            .map(|(row, &e)| {
                let o = &data.obs[row.point];
                (o.j, o.rpm(), o.rpm_group, e)
            })
            .collect();
        if pts.is_empty() {
            continue;
        }
        let e: Vec<f64> = pts.iter().map(|p| p.3).collect();
        let (m, r) = (mean(&e), crate::rms(&e));
        if r < QUIET {
            out.push(Signature {
                quantity: name.into(),
                mean: m,
                rms: r,
                text: format!(
                    "{name} within {:.0} % everywhere (RMS {:.1} %)",
                    100.0 * QUIET,
                    100.0 * r
                ),
            });
            continue;
        }
        let word = if m > 0.0 { "over-predicted" } else { "under-predicted" };
        let mut parts = vec![format!(
            "{name} {word} by {:.1} % on average (RMS {:.1} %)",
            100.0 * m.abs(),
            100.0 * r
        )];
        let threshold = QUIET.max(0.3 * r);
        // Torque off with thrust right: only what moves torque alone can make its patterns (said
        // once below), not the angles, air or RPM the general lists name.
        let torque_alone = torque && out.first().is_some_and(|s| s.rms < QUIET);
        // Advance ratio: split at the median J.
        let mut js: Vec<f64> = pts.iter().map(|p| p.0).collect();
        js.sort_by(f64::total_cmp);
        let jm = js[js.len() / 2];
        let lo: Vec<f64> = pts.iter().filter(|p| p.0 <= jm).map(|p| p.3).collect();
        let hi: Vec<f64> = pts.iter().filter(|p| p.0 > jm).map(|p| p.3).collect();
        if lo.len() >= 2 && hi.len() >= 2 {
            let (ml, mh) = (mean(&lo), mean(&hi));
            if (mh - ml).abs() > threshold {
                let (side, a, b) = if mh.abs() > ml.abs() {
                    (format!("J > {jm:.2}"), mh, ml)
                } else {
                    (format!("J <= {jm:.2}"), ml, mh)
                };
                parts.push(if torque_alone {
                    format!("largest at {side} ({} there, {} elsewhere)", pct(a), pct(b))
                } else {
                    format!(
                        "largest at {side} ({} there, {} elsewhere): an error that changes with J at fixed RPM comes \
                         from the angles or the inflow. {J_TREND_EFFECTS}",
                        pct(a),
                        pct(b)
                    )
                });
            }
        }
        // RPM at fixed J: what Reynolds (and Mach) number dependence shows.
        let bins = rpm_slopes(&pts);
        let trend = fixed_j_trend(&bins);
        if let Some(RpmTrend { change, lo: rl, hi: rh }) = trend {
            // Its own threshold: a trend with RPM is the signature of missing physics even
            // under a larger error of another kind.
            let stat = static_trend(&bins);
            if change.abs() > 0.5 * QUIET || stat.is_some_and(|t| t.change.abs() > 0.5 * QUIET) {
                let faster = if change < 0.0 { "faster" } else { "slower" };
                // A static test alone (a stand's step test) has one J: said as such.
                let all_static = pts.iter().all(|p| p.0 < 0.01);
                let mut head = format!(
                    "{} the error changes by {} from {rl:.0} to {rh:.0} rpm",
                    if all_static { "statically" } else { "at fixed J" },
                    pct(change)
                );
                if let Some(t) = stat {
                    head.push_str(&format!(
                        " (statically by {} from {:.0} to {:.0} rpm)",
                        pct(t.change),
                        t.lo,
                        t.hi
                    ));
                }
                head.push_str(&format!(
                    ": the measured {name} grows {faster} with RPM than the model's"
                ));
                parts.push(if torque_alone {
                    head
                } else {
                    format!(
                        "{head} (a Reynolds-number effect on the sections; Mach at high tip speeds). {RPM_TREND_EFFECTS}"
                    )
                });
            }
        }
        // RPM: first against last group. Their errors mix RPM with the J each group covers (a J
        // sweep reaching higher J at the highest RPM is not an RPM trend): where their mean J
        // differ, the comparison is left to the trend at fixed J above, or said with both J
        // where there is none.
        // Each group's points as (J, rpm, error); their means (rpm, error, J).
        let mut groups: BTreeMap<i64, Vec<[f64; 3]>> = BTreeMap::new();
        for p in &pts {
            groups.entry(p.2).or_default().push([p.0, p.1, p.3]);
        }
        let means = |g: &Vec<[f64; 3]>| {
            let m = |k: usize| mean(&g.iter().map(|p| p[k]).collect::<Vec<_>>());
            (m(1), m(2), m(0))
        };
        if groups.len() >= 2 {
            let first = groups.values().next().map(means);
            let last = groups.values().last().map(means);
            if let (Some((rl, el, jl)), Some((rh, eh, jh))) = (first, last) {
                let confounded = (jh - jl).abs() > J_BIN;
                if (eh - el).abs() > threshold && rh > rl && !(confounded && trend.is_some()) {
                    let growing = eh.abs() > el.abs();
                    let mut s = format!(
                        "{} ({} at {rl:.0} rpm, {} at {rh:.0} rpm",
                        if growing {
                            "growing with RPM"
                        } else {
                            "largest at low RPM"
                        },
                        pct(el),
                        pct(eh)
                    );
                    if confounded {
                        s.push_str(&format!(
                            "; at mean J {jl:.2} and {jh:.2}: RPM and J are not told apart"
                        ));
                    } else if el * eh > 0.0 {
                        let n = (eh / el).ln() / (rh / rl).ln();
                        if n.abs() >= 0.7 {
                            s.push_str(&format!(", about RPM^{n:.0}"));
                        }
                    }
                    s.push(')');
                    parts.push(s);
                }
            }
        }
        out.push(Signature {
            quantity: name.into(),
            mean: m,
            rms: r,
            text: sentences(&parts),
        });
    }
    if out.len() == 2 {
        // An effect list is given once: where torque's pattern repeats one thrust's named, it
        // says so.
        for list in [J_TREND_EFFECTS, RPM_TREND_EFFECTS] {
            if out[0].text.contains(list) {
                out[1].text = out[1].text.replace(list, SAME_EFFECTS);
            }
        }
        // "thrust unaffected" where only torque is off, and the other way round.
        let quiet: Vec<bool> = out.iter().map(|s| s.rms < QUIET).collect();
        if quiet[0] && !quiet[1] {
            out[1].text.push_str(
                "; thrust unaffected: torque alone (a friction torque, torque-tare, or the sections' drag, \
                 re-scaling), not what changes the angles, the air or the RPM, which move both",
            );
        } else if quiet[1] && !quiet[0] {
            out[0].text.push_str(
                "; torque unaffected: thrust alone (a load on the balance that is not the propeller's, \
                 thrust-tare), not what changes the angles, the air or the RPM, which move both",
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Observation;

    /// Thrust-only data: (rpm group's RPM, J) per point.
    fn data(points: &[(f64, f64)]) -> Data {
        let obs = points
            .iter()
            .enumerate()
            .map(|(index, &(rpm, j))| Observation {
                index,
                file: 0,
                label: format!("line {index}"),
                omega: propbet_units::rpm_to_omega(rpm),
                v: 0.0,
                j,
                fluid: propbet_bemt::Fluid::QPROP_DEFAULT,
                thrust: 1.0,
                torque: None,
                rpm_group: rpm as i64,
                rpm_name: format!("{rpm} rpm"),
                mach_tip: 0.1,
            })
            .collect();
        Data {
            obs,
            thrust_floor: 0.05,
            torque_floor: 0.0,
        }
    }

    #[test]
    fn rpm_groups_at_other_j_are_not_called_an_rpm_trend() {
        // A low-J sweep at 3000 rpm and a high-J one at 6000 rpm, the error a function of J
        // alone: no J bin holds both speeds, and the groups' errors differ through J only.
        let pts: Vec<(f64, f64)> = (0..6)
            .map(|k| (3000.0, 0.05 * k as f64))
            .chain((0..6).map(|k| (6000.0, 0.42 + 0.05 * k as f64)))
            .collect();
        let e: Vec<f64> = pts.iter().map(|p| -p.1).collect();
        let text = &signatures(&data(&pts), &e)[0].text;
        assert!(text.contains("RPM and J are not told apart"), "{text}");
        assert!(!text.contains("about RPM^"), "{text}");
        // Both speeds at the same J: the trend at fixed J says it, once.
        let pts: Vec<(f64, f64)> = [3000.0, 6000.0]
            .into_iter()
            .flat_map(|r| (0..6).map(move |k| (r, 0.05 * k as f64)))
            .collect();
        let e: Vec<f64> = pts.iter().map(|p| -0.2 * (p.0 / 3000.0 - 1.0)).collect();
        let text = &signatures(&data(&pts), &e)[0].text;
        assert!(text.contains("At fixed J the error changes by -20.0 %"), "{text}");
        assert!(!text.contains("not told apart"), "{text}");
        // The high-J sweep reaching further at 6000 rpm, the error growing with J: the trend at
        // fixed J is measured on the J both speeds share, the groups are not compared.
        let mut pts = pts;
        pts.extend((1..5).map(|k| (6000.0, 0.25 + 0.1 * k as f64)));
        let e: Vec<f64> = pts.iter().map(|p| -0.2 * (p.0 / 3000.0 - 1.0) - p.1).collect();
        let text = &signatures(&data(&pts), &e)[0].text;
        assert!(text.contains("At fixed J the error changes by -20.0 %"), "{text}");
        assert!(
            !text.contains("growing with RPM") && !text.contains("not told apart"),
            "{text}"
        );
    }

    #[test]
    fn the_rpm_trend_is_measured_at_fixed_j() {
        // At each J the error falls by 5 % per doubling of RPM; across J it varies much more
        // (a J pattern the trend must not mistake for an RPM one).
        let mut pts = Vec::new();
        for (k, j) in [0.0, 0.2, 0.4].into_iter().enumerate() {
            for rpm in [3000.0f64, 6000.0] {
                let e = -0.3 * k as f64 - 0.05 * (rpm / 3000.0).log2();
                pts.push((j, rpm, 0, e));
            }
        }
        let t = rpm_trend_at_fixed_j(&pts).unwrap();
        assert!((t.change + 0.05).abs() < 1e-9, "{t:?}");
        assert_eq!((t.lo.round(), t.hi.round()), (3000.0, 6000.0));
        // J sweeps at 4000-6000 rpm with that trend, a static test at 2000-6000 rpm without
        // one (an 11x7 E's pattern): the sweeps' slope is told over their own range, not
        // stretched over the static test's, and the static trend beside it.
        let mut mixed = Vec::new();
        for k in 0..5 {
            for rpm in [4000.0f64, 5000.0, 6000.0] {
                mixed.push((0.1 + 0.1 * k as f64, rpm, 0, -0.1 * (rpm / 4000.0).ln()));
            }
        }
        for k in 0..5 {
            mixed.push((0.0, 2000.0 + 1000.0 * k as f64, 1, 0.08));
        }
        let t = rpm_trend_at_fixed_j(&mixed).unwrap();
        assert!((t.change + 0.1 * 1.5f64.ln()).abs() < 1e-9, "{t:?}");
        assert_eq!((t.lo.round(), t.hi.round()), (4000.0, 6000.0));
        let s = static_rpm_trend(&mixed).unwrap();
        assert!(
            s.change.abs() < 1e-9 && s.lo.round() == 2000.0 && s.hi.round() == 6000.0,
            "{s:?}"
        );
        let obs: Vec<(f64, f64)> = mixed.iter().map(|p| (p.1, p.0)).collect();
        let e: Vec<f64> = mixed.iter().map(|p| p.3).collect();
        let text = &signatures(&data(&obs), &e)[0].text;
        assert!(
            text.contains("At fixed J the error changes by -4.1 % from 4000 to 6000 rpm (statically by +0.0 % from 2000 to 6000 rpm)"),
            "{text}"
        );
        // A static test alone: its trend is said as static.
        let stat_only: Vec<(f64, f64)> = (0..5).map(|k| (2000.0 + 1000.0 * k as f64, 0.0)).collect();
        let e: Vec<f64> = stat_only.iter().map(|p| -0.1 * (p.0 / 2000.0).ln()).collect();
        let text = &signatures(&data(&stat_only), &e)[0].text;
        assert!(
            text.contains("Statically the error changes by -11.0 % from 2000 to 6000 rpm"),
            "{text}"
        );
        // No static test: no static trend.
        let forward: Vec<_> = pts.iter().filter(|p| p.0 > 0.0).copied().collect();
        assert!(rpm_trend_at_fixed_j(&forward).is_some() && static_rpm_trend(&forward).is_none());
        // No bin spans 1.3x in RPM: no trend to tell.
        let narrow: Vec<_> = pts.iter().filter(|p| p.1 == 3000.0).copied().collect();
        assert!(rpm_trend_at_fixed_j(&narrow).is_none());
    }
}
