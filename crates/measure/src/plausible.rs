//! Checks that a thrust-stand log can be a propeller's at all: its thrust rises with RPM, and
//! its torque and thrust have the signs of a propeller pulling. What fails is a warning naming
//! the rows (the command exits 1), not a refusal: the file is read and shown.

use crate::set::{Loads, MeasuredPoint, MeasuredSet, Speed};

/// Fewest points, and least ratio of highest to lowest RPM, over which the thrust's growth with
/// RPM is judged.
const MIN_POINTS: usize = 3;
const MIN_RPM_RATIO: f64 = 1.5;

/// A propeller's static thrust grows as RPM to the power 2 (1.8-2.2 on real stands); a log
/// whose thrust grows as RPM to less than this power over its spinning range is not a
/// propeller's thrust (an unplugged load cell, a column of the wrong sensor).
pub const MIN_THRUST_EXPONENT: f64 = 1.0;

fn forces(p: &MeasuredPoint) -> Option<(f64, Option<f64>)> {
    match (p.loads, p.speed) {
        (Loads::Forces { thrust, torque }, Speed::Airspeed(v)) if v.mean < 0.5 => {
            Some((thrust.mean, torque.map(|q| q.mean)))
        }
        _ => None,
    }
}

fn lines(p: &MeasuredPoint) -> String {
    if p.lines.0 == p.lines.1 {
        format!("line {}", p.lines.0)
    } else {
        format!("lines {}-{}", p.lines.0, p.lines.1)
    }
}

/// The warnings of a set of static thrust-stand points.
pub fn warnings(set: &MeasuredSet) -> Vec<String> {
    let mut out = Vec::new();
    let pts: Vec<(&MeasuredPoint, f64, Option<f64>)> = set
        .points
        .iter()
        .filter(|p| p.flags.is_empty())
        .filter_map(|p| forces(p).map(|(t, q)| (p, t, q)))
        .filter(|(_, t, _)| *t > 0.0)
        .collect();
    if pts.len() >= MIN_POINTS {
        let lo = pts
            .iter()
            .min_by(|a, b| a.0.omega.mean.total_cmp(&b.0.omega.mean))
            .unwrap();
        let hi = pts
            .iter()
            .max_by(|a, b| a.0.omega.mean.total_cmp(&b.0.omega.mean))
            .unwrap();
        let ratio = hi.0.omega.mean / lo.0.omega.mean;
        if ratio >= MIN_RPM_RATIO {
            // Least squares of ln T on ln RPM.
            let xy: Vec<(f64, f64)> = pts.iter().map(|(p, t, _)| (p.omega.mean.ln(), t.ln())).collect();
            let n = xy.len() as f64;
            let mx = xy.iter().map(|v| v.0).sum::<f64>() / n;
            let my = xy.iter().map(|v| v.1).sum::<f64>() / n;
            let sxx: f64 = xy.iter().map(|v| (v.0 - mx).powi(2)).sum();
            let sxy: f64 = xy.iter().map(|v| (v.0 - mx) * (v.1 - my)).sum();
            let exponent = sxy / sxx;
            if exponent < MIN_THRUST_EXPONENT {
                out.push(format!(
                    "thrust does not rise with RPM as a propeller's does: {:.3} N at {:.0} rpm ({}) and {:.3} N at \
                     {:.0} rpm ({}), thrust growing as RPM^{exponent:.2} over {} points where a propeller's grows \
                     as RPM^2 ({:.3} N expected at the top): is the thrust column a load cell's or the propeller's?",
                    lo.1,
                    lo.0.rpm(),
                    lines(lo.0),
                    hi.1,
                    hi.0.rpm(),
                    lines(hi.0),
                    pts.len(),
                    lo.1 * ratio * ratio
                ));
            }
        }
    }
    let top = pts.iter().map(|(_, t, _)| *t).fold(0.0, f64::max);
    let wrong: Vec<&MeasuredPoint> = pts
        .iter()
        .filter(|(_, t, q)| *t > 0.1 * top && q.is_some_and(|q| q < 0.0))
        .map(|(p, _, _)| *p)
        .collect();
    if let Some(first) = wrong.first() {
        out.push(format!(
            "torque of the wrong sign against thrust at {} of {} points (first at {}): a pulling propeller absorbs \
             power, and its torque has the sign of the rows at the highest RPM",
            wrong.len(),
            pts.len(),
            lines(first)
        ));
    }
    out
}
