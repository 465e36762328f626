//! Figures of a scan: the sections with their fits, and the blade along the radius.

use propbet_geometry::scan::{ColourReport, Geometry};
use propbet_measure::uiuc::GeometryRow;
use propbet_plot::{Figure, Mark, Panel, Series};

/// The scan in one sentence (terminal and page): blades, tip, hub and root radius, stations.
pub fn summary(g: &Geometry) -> String {
    format!(
        "{} blades, tip radius {:.2} mm, hub radius {}, blades from {:.2} mm; {} stations measured, {} failed",
        g.blades,
        1000.0 * g.tip_radius,
        g.hub_radius.map_or("none".into(), |h| format!("{:.2} mm", 1000.0 * h)),
        1000.0 * g.root_radius,
        g.stations.len(),
        g.failed.len()
    )
}

/// How well the scan measured its blade, in one sentence
/// (`propbet_pipeline::stages::scan_accuracy`).
pub fn accuracy(g: &Geometry) -> String {
    let a = propbet_pipeline::stages::scan_accuracy(g);
    format!(
        "measured to {:.2}° of blade angle and {:.1} % of chord (the blades' spread, the section fits' residuals; \
         the prop file carries them to the uncertainty band)",
        a.blade_angle_deg,
        100.0 * a.chord
    )
}

/// The scan against a reference table (UIUC's measured r/R, c/R, β) at every station the table
/// covers, inboard (r/R < 0.75) and outboard (where most thrust is made) apart, each with its
/// worst station: "twist RMSE 0.21 deg (worst -0.44 at r/R 0.92), chord RMSE 7.9 % (worst -12.6 %
/// at r/R 0.96)". None without a station inside the table.
pub fn reference_check(g: &Geometry, table: &[GeometryRow]) -> Option<String> {
    let mut parts = Vec::new();
    for (name, range) in [("r/R below 0.75", 0.0..0.75), ("r/R 0.75 and beyond", 0.75..1.01)] {
        let (mut db, mut dc, mut no_chord) = (Vec::new(), Vec::new(), Vec::new());
        for s in g.stations.iter().filter(|s| range.contains(&s.r_r)) {
            if let Some((c, b)) = propbet_measure::uiuc::geometry_at(table, s.r_r) {
                db.push((s.r_r, (s.beta - b).to_degrees()));
                // A relative chord error against a chord of 0 (or less) means nothing.
                if c > 0.0 {
                    dc.push((s.r_r, s.chord / g.tip_radius / c - 1.0));
                } else {
                    no_chord.push(format!("{:.2}", s.r_r));
                }
            }
        }
        if db.is_empty() {
            continue;
        }
        let rms = |v: &[(f64, f64)]| (v.iter().map(|x| x.1 * x.1).sum::<f64>() / v.len() as f64).sqrt();
        let worst = |v: &[(f64, f64)]| {
            v.iter()
                .copied()
                .fold((0.0f64, 0.0f64), |a, x| if x.1.abs() > a.1.abs() { x } else { a })
        };
        let (rb, wb) = worst(&db);
        let chord = if dc.is_empty() {
            "no chord error".to_string()
        } else {
            let (rc, wc) = worst(&dc);
            format!(
                "chord RMSE {:.1} % (worst {:+.1} % at r/R {rc:.2})",
                100.0 * rms(&dc),
                100.0 * wc
            )
        };
        let zero = if no_chord.is_empty() {
            String::new()
        } else {
            format!(
                " (the table's chord is 0 at r/R {}: no chord error there)",
                no_chord.join(", ")
            )
        };
        parts.push(format!(
            "{name} ({} stations): twist RMSE {:.2} deg (worst {wb:+.2} at r/R {rb:.2}), {chord}{zero}",
            db.len(),
            rms(&db),
        ));
    }
    (!parts.is_empty()).then(|| format!("against the reference table: {}", parts.join("; ")))
}

/// Every section's points and fits.
pub fn sections_figure(g: &Geometry) -> Figure {
    let panels = g
        .stations
        .iter()
        .map(|s| {
            let step = (s.uw.len() / 300).max(1);
            let pts: Vec<(f64, f64)> = s.uw.iter().step_by(step).map(|&p| s.naca.to_section(p)).collect();
            let mut series = vec![Series::new("points", pts, Mark::Dots, Some(0))];
            if let Some(c) = &s.cst {
                series.push(Series::new("CST fit", c.selig(60), Mark::Line, Some(1)));
            }
            Panel {
                title: format!(
                    "r/R {:.3}: c {:.2} mm, β {:.2}°, NACA {}",
                    s.r_r,
                    1000.0 * s.chord,
                    s.beta.to_degrees(),
                    s.naca.designation()
                ),
                x_label: "x/c".into(),
                y_label: "y/c".into(),
                series,
                zero_line: false,
                y_clip: None,
                equal_aspect: true,
            }
        })
        .collect::<Vec<_>>();
    let rows = panels.len().div_ceil(4).max(1) as u32;
    Figure {
        panels,
        columns: 4,
        width: 1600,
        height: 260 * rows,
    }
}

/// Chord, blade angle, thickness and camber, skew and rake along the radius.
pub fn distributions_figure(g: &Geometry, reference: Option<&[GeometryRow]>) -> Figure {
    let col = |f: &dyn Fn(&propbet_geometry::scan::ScanStation) -> f64| -> Vec<(f64, f64)> {
        g.stations.iter().map(|s| (s.r_r, f(s))).collect()
    };
    let r = g.tip_radius;
    let mut chord = vec![Series::new("scan", col(&|s| s.chord / r), Mark::Line, Some(0))];
    let mut beta = vec![Series::new("scan", col(&|s| s.beta.to_degrees()), Mark::Line, Some(0))];
    if let Some(t) = reference {
        chord.push(Series::new(
            "reference",
            t.iter().map(|x| (x.r_r, x.c_r)).collect(),
            Mark::Dots,
            Some(1),
        ));
        beta.push(Series::new(
            "reference",
            t.iter().map(|x| (x.r_r, x.beta.to_degrees())).collect(),
            Mark::Dots,
            Some(1),
        ));
    }
    let panel = |title: &str, y: &str, series: Vec<Series>| Panel::new(title, "r/R", y, series);
    Figure {
        panels: vec![
            panel("Chord", "c/R", chord),
            panel("Blade angle", "β [deg]", beta),
            panel(
                "Thickness and camber",
                "t/c, camber/c",
                vec![
                    Series::new("t/c", col(&|s| s.t_c), Mark::Line, Some(0)),
                    Series::new("camber", col(&|s| s.camber), Mark::Line, Some(2)),
                ],
            ),
            // An angle and a length: one axis each.
            panel(
                "Skew",
                "skew [deg]",
                vec![Series::new("", col(&|s| s.skew.to_degrees()), Mark::Line, Some(0))],
            ),
            panel(
                "Rake",
                "rake [mm]",
                vec![Series::new("", col(&|s| 1000.0 * s.rake), Mark::Line, Some(2))],
            ),
        ],
        columns: 3,
        width: 1500,
        height: 700,
    }
}

/// The colour filter: the histogram of colour distances with the threshold used.
pub fn colour_figure(c: &ColourReport) -> Figure {
    let pts: Vec<(f64, f64)> = c
        .histogram
        .counts
        .iter()
        .enumerate()
        .map(|(i, &n)| ((i as f64 + 0.5) * c.histogram.width, n as f64))
        .collect();
    let top = pts.iter().map(|p| p.1).fold(1.0, f64::max);
    Figure {
        panels: vec![Panel {
            title: format!(
                "Colour distance to the blade colours: {} of {} points kept (threshold {:.0}, Otsu {:.0})",
                c.kept, c.total, c.threshold, c.suggested
            ),
            x_label: "RGB distance".into(),
            y_label: "points".into(),
            series: vec![
                Series::new("points", pts, Mark::Line, Some(0)),
                Series::new(
                    "threshold",
                    vec![(c.threshold, 0.0), (c.threshold, top)],
                    Mark::Dashed,
                    Some(1),
                ),
            ],
            zero_line: false,
            y_clip: None,
            equal_aspect: false,
        }],
        columns: 1,
        width: 900,
        height: 450,
    }
}
