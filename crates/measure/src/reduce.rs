//! Samples to steady points: row checks, sign orientation, step detection with transient
//! removal, or RPM binning for ramps.

use std::collections::BTreeMap;

use serde::Serialize;

use propbet_units::stats::median;

use crate::set::{DropReason, Dropped, Loads, LoggedAir, MeasuredPoint, Speed, Value};
use crate::table::Sample;

pub use crate::set::Reduction;

/// Settings of the reduction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ReduceOptions {
    /// A step has settled when its RPM is within this fraction of the steady RPM.
    pub settle_tolerance: f64,
    /// Fewest consecutive samples at one ESC value that make a step.
    pub min_step_samples: usize,
    /// Points whose RPM scatter (sd/mean) exceeds this are flagged unsteady.
    pub unsteady_rpm: f64,
    /// RPM bin width for ramps [rad/s]; `None`: 1/30 of the RPM range, at least 50 rpm.
    pub rpm_bin: Option<f64>,
}

impl Default for ReduceOptions {
    fn default() -> Self {
        Self {
            settle_tolerance: 0.02,
            min_step_samples: 5,
            unsteady_rpm: 0.03,
            rpm_bin: None,
        }
    }
}

/// The median absolute deviation of `xs` from `center`, scaled to a normal distribution's
/// standard deviation (1.4826): a scatter that a few outliers do not move.
fn sigma_mad(xs: impl Iterator<Item = f64>, center: f64) -> f64 {
    let dev: Vec<f64> = xs.map(|x| (x - center).abs()).collect();
    1.4826 * median(dev)
}

/// Row checks that do not depend on the reduction: not spinning, negative RPM, duplicate and
/// stray time stamps. Returns the rows kept.
fn check_rows(samples: Vec<Sample>, dropped: &mut Vec<Dropped>) -> Vec<Sample> {
    let mut kept: Vec<Sample> = Vec::with_capacity(samples.len());
    // A stray row jumps above both neighbours by much more than the sampling interval.
    let dts: Vec<f64> = samples
        .windows(2)
        .filter_map(|w| Some(w[1].time? - w[0].time?))
        .filter(|d| *d > 0.0)
        .collect();
    let spike = (10.0 * median(dts)).max(1.0);
    // A log that writes each sensor on its own row stamps several rows alike: then a repeated
    // time stamp is how it writes, not a fault.
    let repeats = samples
        .windows(2)
        .filter(|w| w[0].time.is_some() && w[0].time == w[1].time)
        .count();
    let repeats_are_style = repeats * 20 > samples.len();
    let first_time = samples.first().and_then(|s| s.time);
    let drop = |dropped: &mut Vec<Dropped>, s: &Sample, reason, detail: String| {
        dropped.push(Dropped {
            line: s.line,
            reason,
            detail,
        })
    };
    for (i, s) in samples.iter().enumerate() {
        if s.omega == 0.0 {
            drop(dropped, s, DropReason::NotSpinning, "RPM = 0".into());
            continue;
        }
        if s.omega < 0.0 {
            drop(
                dropped,
                s,
                DropReason::NegativeRpm,
                format!("RPM = {:.0}", propbet_units::omega_to_rpm(s.omega)),
            );
            continue;
        }
        if let Some(t) = s.time {
            if !repeats_are_style && kept.last().and_then(|k| k.time) == Some(t) {
                // The log's first time stamp repeated: the motor's first rows.
                let (reason, why) = if Some(t) == first_time {
                    (DropReason::Idle, "the log's first time stamp, repeated")
                } else {
                    (DropReason::DuplicateTime, "as the row before")
                };
                drop(dropped, s, reason, format!("t = {t} s, {why}"));
                continue;
            }
            let prev = i.checked_sub(1).and_then(|j| samples[j].time);
            let next = samples.get(i + 1).and_then(|n| n.time);
            if let Some(next) = next {
                if t > next + spike && prev.is_none_or(|p| t > p + spike) {
                    drop(
                        dropped,
                        s,
                        DropReason::TimeOutOfOrder,
                        match prev {
                            Some(p) => format!("t = {t} s between {p} s and {next} s"),
                            None => format!("t = {t} s, first row, before the next row's {next} s"),
                        },
                    );
                    continue;
                }
            }
        }
        kept.push(*s);
    }
    kept
}

/// The sign that makes `pick` positive on the rows at the top of the RPM range (at least 90 %
/// of the highest RPM): there the propeller pulls and absorbs power. When they read zero,
/// the sign of the trend against RPM squared (thrust grows with it). +1 when neither tells.
pub(crate) fn pull_sign(samples: &[Sample], pick: impl Fn(&Sample) -> Option<f64>) -> f64 {
    let top = samples.iter().map(|s| s.omega).fold(0.0, f64::max);
    let high: Vec<f64> = samples
        .iter()
        .filter(|s| s.omega >= 0.9 * top)
        .filter_map(&pick)
        .collect();
    let m = median(high);
    if m.is_finite() && m != 0.0 {
        return m.signum();
    }
    let xy: Vec<(f64, f64)> = samples
        .iter()
        .filter_map(|s| pick(s).map(|y| (s.omega * s.omega, y)))
        .collect();
    let n = xy.len() as f64;
    let (mx, my) = xy.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let slope: f64 = xy.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    if slope < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// Orients thrust and torque by physics, each file on its own: both are made positive on the
/// rows at the highest RPM ([`pull_sign`]), whatever most rows read. Then rows below
/// [`limits::IDLE`](crate::set::limits::IDLE) of the highest RPM, and rows of negative thrust
/// within the load cell's zero ([`limits::ZERO_THRUST`](crate::set::limits::ZERO_THRUST)) on a
/// static stand, are left out as idle; a negative thrust beyond it is kept as data
/// (windmilling: the flow drives the propeller; its point is flagged) unless the rows at the
/// same RPM and airspeed pull, when it is a fault.
fn orient(samples: Vec<Sample>, dropped: &mut Vec<Dropped>, notes: &mut Vec<String>) -> Vec<Sample> {
    use crate::set::limits::{IDLE, ZERO_THRUST};
    if samples.is_empty() {
        return samples;
    }
    let top = samples.iter().map(|s| s.omega).fold(0.0, f64::max);
    let (idle, samples): (Vec<Sample>, Vec<Sample>) = samples.into_iter().partition(|s| s.omega < IDLE * top);
    for s in &idle {
        dropped.push(Dropped {
            line: s.line,
            reason: DropReason::Idle,
            detail: format!(
                "{:.0} rpm, below {:.0} % of the log's highest ({:.0} rpm)",
                propbet_units::omega_to_rpm(s.omega),
                100.0 * IDLE,
                propbet_units::omega_to_rpm(top)
            ),
        });
    }
    let sign_t = pull_sign(&samples, |s| Some(s.thrust));
    let sign_q = pull_sign(&samples, |s| s.torque);
    if sign_t < 0.0 {
        notes.push(
            "thrust is logged negative when the propeller pulls (the stand's sign convention, read from the rows at \
             the highest RPM): sign flipped"
                .into(),
        );
    }
    if samples.iter().any(|s| s.torque.is_some()) && sign_q < 0.0 {
        notes.push(
            "torque is logged negative (the stand's sign convention for this rotation direction, read from the rows \
             at the highest RPM): sign flipped"
                .into(),
        );
    }
    let mut samples = samples;
    for s in samples.iter_mut() {
        s.thrust *= sign_t;
        s.torque = s.torque.map(|q| q * sign_q);
    }
    let zero = ZERO_THRUST * samples.iter().map(|s| s.thrust.abs()).fold(0.0, f64::max);
    // Rows by RPM, to find a negative row's neighbours at the same RPM and airspeed.
    let mut by_omega: Vec<(f64, f64, bool)> = samples.iter().map(|s| (s.omega, s.airspeed, s.thrust > zero)).collect();
    by_omega.sort_by(|a, b| a.0.total_cmp(&b.0));
    let pulling_beside = |s: &Sample| {
        let lo = by_omega.partition_point(|r| r.0 < 0.97 * s.omega);
        let hi = by_omega.partition_point(|r| r.0 <= 1.03 * s.omega);
        let near = by_omega[lo..hi].iter().filter(|r| (r.1 - s.airspeed).abs() <= 0.5);
        let (pull, all) = near.fold((0, 0), |(p, a), r| (p + usize::from(r.2), a + 1));
        pull * 2 > all
    };
    let mut out = Vec::with_capacity(samples.len());
    let mut windmilling = 0;
    for s in samples.iter() {
        if s.thrust >= 0.0 {
            out.push(*s);
            continue;
        }
        let at = format!(
            "thrust {:.4} N at {:.0} rpm, {:.2} m/s",
            s.thrust,
            propbet_units::omega_to_rpm(s.omega),
            s.airspeed
        );
        let reason = if s.airspeed <= 0.0 && -s.thrust <= zero {
            Some((
                DropReason::Idle,
                format!("{at}: within the load cell's zero ({zero:.4} N)"),
            ))
        } else if pulling_beside(s) {
            Some((
                DropReason::NegativeThrust,
                format!("{at}, while the rows at the same RPM and airspeed pull"),
            ))
        } else {
            None
        };
        match reason {
            Some((reason, detail)) => dropped.push(Dropped {
                line: s.line,
                reason,
                detail,
            }),
            None => {
                windmilling += 1;
                out.push(*s);
            }
        }
    }
    if windmilling > 0 {
        notes.push(format!(
            "{windmilling} rows of negative thrust (below the load cell's zero, where no row at the same RPM and \
             airspeed pulls) kept as data: the flow drives the propeller (windmilling); their points are shown, \
             flagged, not scored"
        ));
    }
    out
}

fn mean_of(xs: impl Iterator<Item = Option<f64>>) -> Option<f64> {
    let (mut sum, mut n) = (0.0, 0usize);
    for x in xs.flatten() {
        sum += x;
        n += 1;
    }
    (n > 0).then(|| sum / n as f64)
}

/// The supply's voltage and current of a point whose every sample logged them.
fn electric(s: &[Sample], averaged: bool) -> Option<crate::set::Electric> {
    let volts: Option<Vec<f64>> = s.iter().map(|x| x.volts).collect();
    let amps: Option<Vec<f64>> = s.iter().map(|x| x.amps).collect();
    let value = |xs: Vec<f64>| if averaged { Value::single(xs[0]) } else { Value::of(&xs) };
    Some(crate::set::Electric {
        volts: value(volts?),
        amps: value(amps?),
        esc: mean_of(s.iter().map(|x| x.esc)),
    })
}

/// One point from samples (already steady).
fn point(label: String, s: &[Sample], transient: usize, opts: &ReduceOptions, averaged: bool) -> MeasuredPoint {
    let col = |f: &dyn Fn(&Sample) -> f64| -> Value {
        let xs: Vec<f64> = s.iter().map(f).collect();
        if averaged {
            Value::single(xs[0])
        } else {
            Value::of(&xs)
        }
    };
    // A sparse log's point: each load the mean of the readings logged within it (the rows
    // between repeat the latest one).
    let mut stale = Vec::new();
    let mut own = |name: &str, fresh: fn(&Sample) -> bool, f: &dyn Fn(&Sample) -> f64| -> Value {
        let xs: Vec<f64> = s.iter().filter(|x| fresh(x)).map(f).collect();
        if averaged || xs.len() == s.len() {
            return col(f);
        }
        if xs.is_empty() {
            stale.push(name.to_string());
            return col(f);
        }
        Value::of(&xs)
    };
    let omega = own("RPM", |x| x.fresh.omega, &|x| x.omega);
    let thrust = own("thrust", |x| x.fresh.thrust, &|x| x.thrust);
    let torque = s[0]
        .torque
        .is_some()
        .then(|| own("torque", |x| x.fresh.torque, &|x| x.torque.unwrap_or(f64::NAN)));
    let airspeed = col(&|x| x.airspeed);
    let mut flags = Vec::new();
    if !stale.is_empty() {
        flags.push(format!(
            "no {} reading logged within the point (a sparse log's earlier value only)",
            stale.join(" or ")
        ));
    }
    if thrust.mean < 0.0 {
        flags.push("negative thrust: windmilling (the flow drives the propeller), shown, not scored".to_string());
    }
    if omega.relative_sd() > opts.unsteady_rpm {
        flags.push(format!(
            "unsteady RPM: scatter {:.1} % of the mean (limit {:.0} %)",
            100.0 * omega.relative_sd(),
            100.0 * opts.unsteady_rpm
        ));
    }
    MeasuredPoint {
        label,
        lines: (s[0].line, s[s.len() - 1].line),
        omega,
        speed: Speed::Airspeed(airspeed),
        loads: Loads::Forces { thrust, torque },
        air: LoggedAir {
            temperature: mean_of(s.iter().map(|x| x.temperature)),
            pressure: mean_of(s.iter().map(|x| x.pressure)),
            humidity: mean_of(s.iter().map(|x| x.humidity)),
        },
        transient,
        nominal_omega: None,
        flags,
        electric: electric(s, averaged),
    }
}

/// The steady part of one step: leading samples are dropped until the RPM is within the
/// settle tolerance of the median RPM of the step's second half; then samples whose RPM is
/// far from the step's median (sensor dropouts) are removed. Returns (steady, dropped count).
fn steady_part(s: &[Sample], opts: &ReduceOptions) -> (Vec<Sample>, usize, usize) {
    let tail: Vec<f64> = s[s.len() / 2..].iter().map(|x| x.omega).collect();
    let target = median(tail);
    let start = s
        .iter()
        .position(|x| (x.omega - target).abs() <= opts.settle_tolerance * target)
        .unwrap_or(s.len() / 2);
    let settled = &s[start..];
    let om: Vec<f64> = settled.iter().map(|x| x.omega).collect();
    let med = median(om);
    let mad = sigma_mad(settled.iter().map(|x| x.omega), med);
    let limit = (5.0 * mad).max(0.05 * med);
    let steady: Vec<Sample> = settled
        .iter()
        .copied()
        .filter(|x| (x.omega - med).abs() <= limit)
        .collect();
    let outliers = settled.len() - steady.len();
    (steady, start, outliers)
}

/// Consecutive samples at one ESC command; none when a sample has no ESC value.
fn esc_runs(samples: &[Sample]) -> Vec<std::ops::Range<usize>> {
    let mut runs = Vec::new();
    if samples.is_empty() || samples.iter().any(|s| s.esc.is_none()) {
        return runs;
    }
    let mut start = 0;
    for i in 1..=samples.len() {
        let same = i < samples.len()
            && samples[i]
                .esc
                .zip(samples[start].esc)
                .is_some_and(|(a, b)| (a - b).abs() < 0.5);
        if !same {
            runs.push(start..i);
            start = i;
        }
    }
    runs
}

/// The densest cluster of positive readings whose largest is within `width` (relative) of its
/// smallest: (median of the cluster, its size). The steady reading of a sensor that misses
/// pulses (an optical probe reads low or zero, never high) or now and then doubles them.
fn densest(readings: &[f64], width: f64) -> Option<(f64, usize)> {
    let mut x: Vec<f64> = readings.iter().copied().filter(|v| *v > 0.0).collect();
    x.sort_by(f64::total_cmp);
    let mut best = (0, 0);
    let mut j = 0;
    for i in 0..x.len() {
        j = j.max(i);
        while j + 1 < x.len() && x[j + 1] <= x[i] * (1.0 + width) {
            j += 1;
        }
        if j + 1 - i > best.1 - best.0 {
            best = (i, j + 1);
        }
    }
    (best.1 > best.0).then(|| (median(x[best.0..best.1].to_vec()), best.1 - best.0))
}

/// A reading this far (relative) below its step's steady RPM, while the thrust holds steady, is
/// a sensor dropout: thrust goes with RPM squared, so a real 10 % change moves it by 20 %.
const DROPOUT: f64 = 0.1;

/// Fills RPM sensor dropouts instead of dropping the rows (thrust, torque and air of the row
/// are good): first from the log's other RPM sensor, scaled by the two sensors' median ratio
/// where both read; then, within an ESC step, a reading of zero or far below the step's steady
/// reading, on a row whose thrust is the step's steady thrust, takes that steady reading. Says
/// what it filled; a zero reading on a row whose thrust is not steady is dropped as a dropout.
fn fill_dropouts(
    mut samples: Vec<Sample>,
    opts: &ReduceOptions,
    dropped: &mut Vec<Dropped>,
    notes: &mut Vec<String>,
) -> Vec<Sample> {
    let ratios: Vec<f64> = samples
        .iter()
        .filter_map(|s| s.omega_other.filter(|o| *o > 0.0 && s.omega > 0.0).map(|o| s.omega / o))
        .collect();
    if ratios.len() >= 3 {
        let ratio = median(ratios.to_vec());
        let mut filled = 0;
        for s in samples.iter_mut() {
            if let Some(o) = s.omega_other.filter(|o| *o > 0.0 && s.omega == 0.0) {
                s.omega = o * ratio;
                filled += 1;
            }
        }
        if filled > 0 {
            notes.push(format!(
                "{filled} rows where the RPM sensor read 0 take the other RPM sensor's reading times {ratio:.4} \
                 (the two sensors' median ratio over {} rows where both read)",
                ratios.len()
            ));
        }
    }
    let mut filled = Vec::new();
    let mut lost = Vec::new();
    for run in esc_runs(&samples) {
        let step = &mut samples[run];
        if step.len() < opts.min_step_samples {
            continue;
        }
        let omegas: Vec<f64> = step.iter().map(|s| s.omega).collect();
        let Some((steady, n)) = densest(&omegas, 2.0 * opts.unsteady_rpm) else {
            continue;
        };
        if n < 5.max(step.len() / 20) || n == step.len() {
            continue;
        }
        let near = |w: f64| (w - steady).abs() <= opts.unsteady_rpm * steady;
        let thrusts: Vec<f64> = step.iter().filter(|s| near(s.omega)).map(|s| s.thrust).collect();
        let t = median(thrusts);
        let band = (4.0 * sigma_mad(step.iter().map(|s| s.thrust), t)).max(DROPOUT * t.abs());
        // A dropout reads low (missed pulses) after the step has settled; a high reading or
        // one before the step first reaches its steady RPM is the motor getting there.
        let settled = step.iter().position(|s| near(s.omega)).unwrap_or(step.len());
        let mut count = 0;
        for s in step[settled..].iter_mut() {
            if s.omega >= (1.0 - DROPOUT) * steady || s.omega < 0.0 {
                continue;
            }
            if (s.thrust - t).abs() <= band {
                s.omega = steady;
                count += 1;
            } else if s.omega == 0.0 {
                lost.push(s.line);
            }
        }
        if count > 0 {
            filled.push((step[0].esc.unwrap_or(f64::NAN), count, steady, n));
        }
    }
    if !filled.is_empty() {
        let total: usize = filled.iter().map(|f| f.1).sum();
        let steps: Vec<String> = filled
            .iter()
            .take(5)
            .map(|(esc, count, steady, n)| {
                format!(
                    "ESC {esc} µs: {count} rows at {:.0} rpm, from {n} readings within {:.0} %",
                    propbet_units::omega_to_rpm(*steady),
                    200.0 * opts.unsteady_rpm
                )
            })
            .collect();
        notes.push(format!(
            "RPM sensor dropouts: {total} rows read 0 or more than {:.0} % below their ESC step's steady RPM while their \
             thrust held steady; their RPM is the step's steady reading ({}{})",
            100.0 * DROPOUT,
            steps.join("; "),
            if filled.len() > 5 { format!("; and {} more steps", filled.len() - 5) } else { String::new() }
        ));
    }
    if lost.is_empty() {
        return samples;
    }
    samples.retain(|s| {
        let drop = lost.binary_search(&s.line).is_ok();
        if drop {
            dropped.push(Dropped {
                line: s.line,
                reason: DropReason::RpmDropout,
                detail: format!("RPM 0, thrust {:.4} N", s.thrust),
            });
        }
        !drop
    });
    samples
}

/// Reduces checked samples of a log to points.
///
/// `rows_are_points`: each row is already a steady point (tables, averaged exports).
pub fn reduce_log(
    samples: Vec<Sample>,
    rows_are_points: bool,
    dropped: &mut Vec<Dropped>,
    notes: &mut Vec<String>,
    opts: &ReduceOptions,
) -> (Reduction, Vec<MeasuredPoint>) {
    let mut samples = samples;
    if !rows_are_points {
        samples = fill_dropouts(samples, opts, dropped, notes);
    }
    let samples = check_rows(samples, dropped);
    let samples = orient(samples, dropped, notes);
    if samples.is_empty() {
        return (Reduction::Rows, Vec::new());
    }
    let rows = |samples: &[Sample]| -> Vec<MeasuredPoint> {
        samples
            .iter()
            .map(|s| point(format!("line {}", s.line), std::slice::from_ref(s), 0, opts, true))
            .collect()
    };
    if rows_are_points {
        return (Reduction::Rows, rows(&samples));
    }
    let groups: Vec<&[Sample]> = esc_runs(&samples).into_iter().map(|r| &samples[r]).collect();
    let n = samples.len();
    let largest = groups.iter().map(|g| g.len()).max().unwrap_or(0);
    if !groups.is_empty() && largest <= 2 && n <= 200 {
        notes.push(format!(
            "one averaged row per ESC step ({n} steps): no scatter is known, the app averaged each step"
        ));
        let mut pts = rows(&samples);
        for (p, s) in pts.iter_mut().zip(&samples) {
            p.label = format!("ESC {} µs", s.esc.unwrap_or(f64::NAN));
        }
        return (Reduction::AveragedSteps, pts);
    }
    // Holds: runs of one ESC value. A step test holds each value (and may log the ramps in
    // between); a ramp or a closed-loop run changes the command nearly every sample.
    let holds = groups.iter().filter(|g| g.len() >= opts.min_step_samples);
    let in_steps: usize = holds.clone().map(|g| g.len()).sum();
    if holds.count() >= 3 && in_steps as f64 >= 0.3 * n as f64 {
        return (Reduction::Steps, steps(&groups, opts, notes));
    }
    // Ramp: bin by RPM and airspeed.
    match ramp(&samples, opts, notes) {
        Some(pts) => (Reduction::Ramp, pts),
        None => (Reduction::Rows, rows(&samples)),
    }
}

/// One point per ESC step held long enough: its steady part averaged (transients dropped, RPM
/// outliers left out), with what was not used in `notes`.
fn steps(groups: &[&[Sample]], opts: &ReduceOptions, notes: &mut Vec<String>) -> Vec<MeasuredPoint> {
    let mut pts = Vec::new();
    let (mut transient, mut between, mut outliers, mut short) = (0, 0, 0, 0);
    for g in groups {
        if g.len() < opts.min_step_samples {
            between += g.len();
            continue;
        }
        let (steady, t, o) = steady_part(g, opts);
        transient += t;
        outliers += o;
        if steady.len() < 3 {
            short += 1;
            continue;
        }
        let escs: Vec<f64> = g.iter().filter_map(|x| x.esc).collect();
        let esc = median(escs);
        let mut p = point(
            format!("ESC {} µs", (esc * 10.0).round() / 10.0),
            &steady,
            t,
            opts,
            false,
        );
        // A few readings far from the step's median are left out (the count is in the
        // notes); a step of which a fifth is left out is not trusted.
        if o * 4 > steady.len() {
            p.flags.push(format!(
                "{o} samples with RPM far from the step's median left out: more than a fifth of the step"
            ));
        }
        pts.push(p);
    }
    notes.push(format!(
        "{} ESC steps detected; {transient} transient samples dropped at step starts, {outliers} RPM outliers left out, \
         {between} samples between steps (ESC ramping) not used{}",
        pts.len(),
        if short > 0 { format!(", {short} steps too short to average") } else { String::new() }
    ));
    pts
}

/// A ramp or closed-loop run: the samples binned by RPM and airspeed, one point per bin of at
/// least three; None where most rows would be alone in their bins (rows of distinct points).
fn ramp(samples: &[Sample], opts: &ReduceOptions, notes: &mut Vec<String>) -> Option<Vec<MeasuredPoint>> {
    let n = samples.len();
    let mut om: Vec<f64> = samples.iter().map(|s| s.omega).collect();
    om.sort_by(f64::total_cmp);
    let span = om[(n * 95) / 100] - om[n / 20];
    let width = opts.rpm_bin.unwrap_or_else(|| {
        propbet_units::rpm_to_omega(nice(propbet_units::omega_to_rpm(
            (span / 30.0).max(propbet_units::rpm_to_omega(50.0)),
        )))
    });
    let vmax = samples.iter().map(|s| s.airspeed).fold(0.0, f64::max);
    let vwidth = 0.5;
    let mut bins: BTreeMap<(i64, i64), Vec<Sample>> = BTreeMap::new();
    for s in samples {
        let key = ((s.omega / width).round() as i64, (s.airspeed / vwidth).round() as i64);
        bins.entry(key).or_default().push(*s);
    }
    let mut pts = Vec::new();
    let mut sparse = 0;
    for ((k, _), s) in &bins {
        if s.len() < 3 {
            sparse += s.len();
            continue;
        }
        let label = format!(
            "{:.0} ± {:.0} rpm",
            propbet_units::omega_to_rpm(*k as f64 * width),
            propbet_units::omega_to_rpm(0.5 * width)
        );
        pts.push(point(label, s, 0, opts, false));
    }
    if sparse * 2 > n {
        // Rows of distinct operating points with a time column (a table of averaged points,
        // a hand log): binning would leave most of them alone in their bins.
        notes.push(format!(
            "the RPM changes from row to row with no ESC column and {sparse} of {n} rows would be alone in \
             their {:.0} rpm bins: each row is used as a point",
            propbet_units::omega_to_rpm(width)
        ));
        return None;
    }
    let why = if samples.iter().all(|s| s.esc.is_none()) {
        "no ESC command logged"
    } else {
        "the ESC command is not held in steps"
    };
    notes.push(format!(
        "{why}: samples binned by RPM ({:.0} rpm bins{}); {} bins, {sparse} samples in bins of fewer than 3 not used",
        propbet_units::omega_to_rpm(width),
        if vmax > vwidth {
            ", and 0.5 m/s airspeed bins"
        } else {
            ""
        },
        pts.len()
    ));
    Some(pts)
}

/// 1, 2, 2.5 or 5 times a power of ten, not below `x`.
fn nice(x: f64) -> f64 {
    let p = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&v| v >= x)
        .unwrap_or(10.0 * p)
}

#[cfg(test)]
mod tests;
