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
                parts.push(format!("largest at {side} ({} there, {} elsewhere)", pct(a), pct(b)));
            }
        }
        // RPM: first against last group.
        let mut groups: BTreeMap<i64, (Vec<f64>, Vec<f64>)> = BTreeMap::new();
        for p in &pts {
            let g = groups.entry(p.2).or_default();
            g.0.push(p.1);
            g.1.push(p.3);
        }
        if groups.len() >= 2 {
            let first = groups.values().next().map(|g| (mean(&g.0), mean(&g.1)));
            let last = groups.values().last().map(|g| (mean(&g.0), mean(&g.1)));
            if let (Some((rl, el)), Some((rh, eh))) = (first, last) {
                if (eh - el).abs() > threshold && rh > rl {
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
                    if el * eh > 0.0 {
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
            text: parts.join(", "),
        });
    }
    // "thrust unaffected" where only torque is off, and the other way round.
    if out.len() == 2 {
        let quiet: Vec<bool> = out.iter().map(|s| s.rms < QUIET).collect();
        if quiet[0] && !quiet[1] {
            out[1].text.push_str("; thrust unaffected");
        } else if quiet[1] && !quiet[0] {
            out[0].text.push_str("; torque unaffected");
        }
    }
    out
}
