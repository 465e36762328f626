//! The comparison's figures: the coefficients against J (measured with error bars, the
//! model's curve and another code's), the static sweep against RPM, and the residuals.

use super::*;

pub(super) fn measured_series(
    name: String,
    pts: &[&ComparedPoint],
    x: impl Fn(&ComparedPoint) -> f64,
    q: &str,
    k: usize,
) -> Series {
    let mut s = Series::new(
        name,
        pts.iter()
            .map(|p| (x(p), p.measured.get(q).unwrap_or(f64::NAN)))
            .collect(),
        Mark::Dots,
        Some(k),
    );
    s.y_err = pts.iter().map(|p| p.measured_sd.get(q).unwrap_or(0.0)).collect();
    s
}

/// A band's shaded outline along a curve for quantity `q` (`ct`, `cp`, `eta`; efficiency
/// where its band is positive), in colour `k`.
pub(super) fn band_series(band: &propbet_compare::band::BandCurve, q: &str, k: usize) -> Series {
    let pick = |b: &propbet_compare::band::PointBand| match q {
        "ct" => b.ct,
        "cp" => b.cp,
        _ => b.eta,
    };
    let kept: Vec<(f64, propbet_compare::band::Bounds)> = band
        .iter()
        .map(|(x, b)| (*x, pick(b)))
        .filter(|(x, b)| x.is_finite() && b.lo.is_finite() && b.hi.is_finite() && (q != "eta" || b.lo > 0.0))
        .collect();
    let outline = kept
        .iter()
        .map(|(x, b)| (*x, b.lo))
        .chain(kept.iter().rev().map(|(x, b)| (*x, b.hi)))
        .collect();
    Series::new("", outline, Mark::Area, Some(k))
}

pub(super) fn coefficient_figure(
    curves: &Curves,
    band: Option<&propbet_compare::band::BandCurves>,
    points: &[ComparedPoint],
    reference: Option<&Scored>,
) -> Option<Figure> {
    if points.iter().all(ComparedPoint::is_static) {
        return None;
    }
    // Static points of the same RPM groups belong on the J axis too.
    let groups = group_points(points, sweep_group);
    let mut panels: Vec<Panel> = ["ct", "cp", "eta"]
        .iter()
        .map(|q| Panel {
            title: format!("{} vs advance ratio", label(q).0),
            x_label: "J = V/(nD)".into(),
            y_label: label(q).0.into(),
            series: Vec::new(),
            zero_line: false,
            y_clip: None,
            equal_aspect: false,
        })
        .collect();
    for (k, (name, pts)) in groups.iter().enumerate() {
        if pts.iter().all(|p| p.is_static()) {
            continue;
        }
        let Some(Some((_, curve))) = curves.j_sweeps.get(k) else {
            continue;
        };
        // One legend, on the first panel: the sweeps' colours (measured dots); the caption says
        // which line is whose, so that no legend hides data.
        for (i, (panel, q)) in panels.iter_mut().zip(["ct", "cp", "eta"]).enumerate() {
            let legend = if i == 0 { name.clone() } else { String::new() };
            if let Some(Some(b)) = band.and_then(|b| b.j_sweeps.get(k)) {
                panel.series.push(band_series(b, q, k));
            }
            panel.series.push(measured_series(legend, pts, |p| p.j, q, k));
            // Efficiency only where it is defined (positive).
            let line = |c: &[(f64, propbet_compare::Quantities)]| -> Vec<(f64, f64)> {
                c.iter()
                    .filter_map(|(j, c)| c.get(q).filter(|v| q != "eta" || *v > 0.0).map(|v| (*j, v)))
                    .collect()
            };
            panel.series.push(Series::new("", line(curve), Mark::Line, Some(k)));
            if let Some(Some((_, c))) = reference.map(|r| &r.curves).and_then(|c| c.j_sweeps.get(k)) {
                panel.series.push(Series::new("", line(c), Mark::Dashed, Some(k)));
            }
        }
    }
    Some(Figure {
        panels,
        columns: 3,
        width: 1500,
        height: 520,
    })
}

pub(super) fn static_figure(
    curves: &Curves,
    band: Option<&propbet_compare::band::BandCurves>,
    points: &[ComparedPoint],
    reference: Option<&Scored>,
) -> Option<Figure> {
    let stat: Vec<&ComparedPoint> = points.iter().filter(|p| p.is_static()).collect();
    if stat.is_empty() {
        return None;
    }
    let has_torque = stat.iter().any(|p| p.measured.torque.is_some());
    let curve: &[(f64, propbet_compare::Quantities)] = curves.statics.as_deref().unwrap_or_default();
    let qs: &[&str] = if has_torque {
        &["thrust", "torque", "ct", "cp"]
    } else {
        &["thrust", "ct"]
    };
    let panels = qs
        .iter()
        .map(|q| {
            let (name, unit) = label(q);
            Panel {
                title: format!("static {name} vs RPM"),
                x_label: "RPM".into(),
                y_label: if unit.is_empty() {
                    name.into()
                } else {
                    format!("{name} [{unit}]")
                },
                series: band
                    .and_then(|b| b.statics.as_ref())
                    .filter(|_| matches!(*q, "ct" | "cp"))
                    .map(|b| band_series(b, q, 1))
                    .into_iter()
                    .chain(std::iter::once(measured_series(
                        "measured".into(),
                        &stat,
                        |p| p.rpm,
                        q,
                        0,
                    )))
                    .chain(std::iter::once(Series::new(
                        "predicted",
                        curve.iter().filter_map(|(r, c)| c.get(q).map(|v| (*r, v))).collect(),
                        Mark::Line,
                        Some(1),
                    )))
                    .chain(reference.and_then(|r| {
                        let c = r.curves.statics.as_ref()?;
                        Some(Series::new(
                            &r.score.name,
                            c.iter().filter_map(|(x, c)| c.get(q).map(|v| (*x, v))).collect(),
                            Mark::Dashed,
                            Some(2),
                        ))
                    }))
                    .collect(),
                zero_line: false,
                y_clip: None,
                equal_aspect: false,
            }
        })
        .collect();
    Some(Figure {
        panels,
        columns: 2,
        width: 1200,
        height: if has_torque { 900 } else { 450 },
    })
}

pub(super) fn residual_figure(points: &[ComparedPoint]) -> Figure {
    type Axis = (&'static str, fn(&ComparedPoint) -> f64);
    let axes: [Axis; 4] = [
        ("advance ratio J", |p| p.j),
        ("RPM", |p| p.rpm),
        ("Reynolds number at 0.75 R", |p| p.re75),
        ("tip Mach number", |p| p.mach_tip),
    ];
    let scored: Vec<&ComparedPoint> = points.iter().filter(|p| p.scored()).collect();
    let forward = scored.iter().any(|p| !p.is_static());
    let panels: Vec<Panel> = axes
        .iter()
        .filter(|(name, _)| forward || !name.starts_with("advance"))
        .map(|(name, x)| Panel {
            title: format!("relative error vs {name}"),
            x_label: (*name).into(),
            y_label: "(predicted − measured)/measured [%]".into(),
            series: ["thrust", "torque"]
                .iter()
                .enumerate()
                .map(|(k, q)| {
                    Series::new(
                        *q,
                        scored
                            .iter()
                            .filter_map(|p| p.relative_error(q).map(|e| (x(p), 100.0 * e)))
                            .collect(),
                        Mark::Dots,
                        Some(k),
                    )
                })
                .filter(|s| !s.points.is_empty())
                .collect(),
            zero_line: true,
            y_clip: Some(ERROR_AXIS),
            equal_aspect: false,
        })
        .collect();
    let rows = panels.len().div_ceil(2) as u32;
    Figure {
        panels,
        columns: 2,
        width: 1200,
        height: 430 * rows,
    }
}
