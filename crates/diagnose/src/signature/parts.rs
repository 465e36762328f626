//! The parts of a pattern: the error against J, with RPM at fixed J, from the first RPM group
//! to the last, and thrust against torque.

use super::*;

/// The error against J at fixed RPM: the two halves of the points split at the median J.
pub(super) fn j_part(
    pts: &[(f64, f64, i64, f64)],
    jm: f64,
    threshold: f64,
    torque: bool,
    torque_alone: bool,
    resp: &[(String, Vec<Parts>)],
    named: &mut Vec<EffectList>,
) -> Option<Part> {
    if let Some((ml, mh)) = j_halves(pts, jm) {
        let dj = mh - ml;
        if dj.abs() > threshold {
            let above = mh.abs() > ml.abs();
            let (there, elsewhere) = if above { (mh, ml) } else { (ml, mh) };
            let effects = (!torque_alone)
                .then(|| effect_list(&[dj], |p| vec![p.dj.unwrap_or(0.0)], resp, "it").map(|l| refer(l, torque, named)))
                .flatten();
            let shows = Shows::AgainstJ {
                median_j: jm,
                above,
                there,
                elsewhere,
                cause: !torque_alone,
            };
            return Some(Part::new(shows, effects));
        }
    }
    None
}

/// RPM at fixed J: what Reynolds (and Mach) number dependence shows.
#[allow(clippy::too_many_arguments)]
pub(super) fn rpm_trend_part(
    pts: &[(f64, f64, i64, f64)],
    bins: &BTreeMap<i64, (f64, f64, f64)>,
    trend: Option<RpmTrend>,
    seen: &Parts,
    torque: bool,
    torque_alone: bool,
    resp: &[(String, Vec<Parts>)],
    named: &mut Vec<EffectList>,
) -> Option<Part> {
    if let Some(t_fixed) = trend {
        let change = t_fixed.change;
        // Its own threshold: a trend with RPM is the signature of missing physics even
        // under a larger error of another kind.
        let stat = static_trend(bins);
        if change.abs() > 0.5 * QUIET || stat.is_some_and(|t| t.change.abs() > 0.5 * QUIET) {
            // The J sweeps and the static test disagreeing (opposite signs, or one a third
            // of the other): the larger says the direction, and where it is.
            // (The static test's sign where it alone makes the trend worth saying.)
            let (mut sign, mut regime) = match stat {
                Some(t) if change.abs() <= 0.5 * QUIET => (t.change, Regime::Both),
                _ => (change, Regime::Both),
            };
            // (Compared per unit ln RPM, the ranges differing; said where the larger changes
            // the error by more than QUIET over its own range.)
            if let (Some(f), Some(s), Some(t)) = (seen.forward, seen.stat, stat) {
                let big = f.abs().max(s.abs());
                let (dominant, its_change) = if f.abs() > s.abs() { (f, change) } else { (s, t.change) };
                if its_change.abs() > QUIET && (f * s < 0.0 || f.abs().min(s.abs()) < big / 3.0) {
                    (sign, regime) = (
                        dominant,
                        if f.abs() > s.abs() {
                            Regime::ForwardOnly
                        } else {
                            Regime::StaticOnly
                        },
                    );
                }
            }
            // A static test alone (a stand's step test) has one J: said as such.
            let all_static = pts.iter().all(|p| p.0 < 0.01);
            let mut effects = None;
            if !torque_alone {
                let seen_rpm: Vec<f64> = [seen.forward, seen.stat].into_iter().flatten().collect();
                let of = |p: &Parts| -> Vec<f64> {
                    [(seen.forward, p.forward), (seen.stat, p.stat)]
                        .into_iter()
                        .filter(|(o, _)| o.is_some())
                        .map(|(_, r)| r.unwrap_or(0.0))
                        .collect()
                };
                effects = effect_list(&seen_rpm, of, resp, "it").map(|l| refer(l, torque, named));
            }
            let shows = Shows::WithRpm {
                all_static,
                trend: t_fixed,
                statically: stat,
                faster: sign < 0.0,
                regime,
                cause: !torque_alone,
            };
            return Some(Part::new(shows, effects));
        }
    }
    None
}

/// RPM: the first RPM group's error against the last's.
pub(super) fn rpm_group_part(pts: &[(f64, f64, i64, f64)], threshold: f64, trend: bool) -> Option<Part> {
    // RPM: first against last group. Their errors mix RPM with the J each group covers (a J
    // sweep reaching higher J at the highest RPM is not an RPM trend): where their mean J
    // differ, the comparison is left to the trend at fixed J above, or said with both J
    // where there is none.
    // Each group's points as (J, rpm, error); their means (rpm, error, J).
    let mut groups: BTreeMap<i64, Vec<[f64; 3]>> = BTreeMap::new();
    for p in pts {
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
            if (eh - el).abs() > threshold && rh > rl && !(confounded && trend) {
                let power = (!confounded && el * eh > 0.0)
                    .then(|| (eh / el).ln() / (rh / rl).ln())
                    .filter(|n| n.abs() >= 0.7);
                let shows = Shows::RpmGroups {
                    growing: eh.abs() > el.abs(),
                    low: GroupMean {
                        rpm: rl,
                        error: el,
                        j: jl,
                    },
                    high: GroupMean {
                        rpm: rh,
                        error: eh,
                        j: jh,
                    },
                    confounded,
                    power,
                };
                return Some(Part::new(shows, None));
            }
        }
    }
    None
}

/// The pair: thrust against torque where both are off, and the one unaffected where only the
/// other is.
pub(super) fn thrust_and_torque(out: &mut [Signature], rows: &[crate::Row], residuals: &[f64], responses: &[Response]) {
    // "thrust unaffected" where only torque is off, and the other way round, with the
    // candidates that move the one alone: in the model, half of its error away with the
    // other kept within QUIET.
    let quiet: Vec<bool> = out.iter().map(|s| s.rms < QUIET).collect();
    let rows_of = |torque: bool| -> Vec<usize> { (0..rows.len()).filter(|&k| rows[k].torque == torque).collect() };
    let at = |idx: &[usize], add: Option<&Vec<f64>>| -> Vec<f64> {
        idx.iter().map(|&k| residuals[k] + add.map_or(0.0, |a| a[k])).collect()
    };
    let rms_at = |idx: &[usize], add: Option<&Vec<f64>>| -> f64 { crate::rms(&at(idx, add)) };
    if !quiet[0] && !quiet[1] {
        // Thrust against torque: their mean errors' signs and sizes, and the candidates
        // that can make the pair (probes that do not make the error larger overall).
        let (t, q) = (rows_of(false), rows_of(true));
        let (mt, mq) = (out[0].mean, out[1].mean);
        let relation = if mt * mq < 0.0 {
            Relation::Opposite
        } else if mq.abs() > 2.0 * mt.abs() {
            Relation::TorqueMore
        } else if mt.abs() > 2.0 * mq.abs() {
            Relation::ThrustMore
        } else {
            Relation::Similar
        };
        let both: Vec<usize> = (0..rows.len()).collect();
        let before = rms_at(&both, None);
        let levels: Vec<(String, Vec<[f64; 2]>)> = responses
            .iter()
            .map(|resp| {
                let probes = resp
                    .probes
                    .iter()
                    .filter(|p| rms_at(&both, Some(p)) <= before)
                    .map(|p| {
                        let m = |idx: &[usize]| mean(&idx.iter().map(|&k| p[k]).collect::<Vec<f64>>());
                        [m(&t), m(&q)]
                    })
                    .collect();
                (resp.id.clone(), probes)
            })
            .collect();
        out[1].parts.push(Part::new(
            Shows::ThrustTorque {
                relation,
                thrust: mt,
                torque: mq,
            },
            effect_list(&[mt, mq], |p: &[f64; 2]| p.to_vec(), &levels, "both"),
        ));
    }
    if quiet[0] != quiet[1] {
        let off_torque = quiet[0];
        let (off, on) = (rows_of(off_torque), rows_of(!off_torque));
        let base = rms_at(&off, None);
        let alone: Vec<&str> = responses
            .iter()
            .filter(|resp| {
                resp.probes
                    .iter()
                    .any(|p| rms_at(&off, Some(p)) <= CAN_MAKE * base && rms_at(&on, Some(p)) < QUIET)
            })
            .map(|resp| resp.id.as_str())
            .collect();
        let (moved, kept) = if off_torque {
            ("torque", "thrust")
        } else {
            ("thrust", "torque")
        };
        // After the last words of the pattern.
        if let Some(last) = out[usize::from(off_torque)].parts.last_mut() {
            last.unaffected = Some(Unaffected {
                kept: kept.into(),
                moved: moved.into(),
                alone: (!responses.is_empty()).then(|| alone.iter().map(|s| s.to_string()).collect()),
            });
        }
    }
}
