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
    let panel = |title: &str, y: &str, series: Vec<Series>| Panel {
        title: title.into(),
        x_label: "r/R".into(),
        y_label: y.into(),
        series,
        zero_line: false,
        y_clip: None,
    };
    Figure {
        panels: vec![
            panel("Chord", "c/R", chord),
            panel("Blade angle", "β [deg]", beta),
            panel(
                "Thickness and camber",
                "/ chord",
                vec![
                    Series::new("t/c", col(&|s| s.t_c), Mark::Line, Some(0)),
                    Series::new("camber", col(&|s| s.camber), Mark::Line, Some(2)),
                ],
            ),
            panel(
                "Skew and rake",
                "deg, mm",
                vec![
                    Series::new("skew [deg]", col(&|s| s.skew.to_degrees()), Mark::Line, Some(0)),
                    Series::new("rake [mm]", col(&|s| 1000.0 * s.rake), Mark::Line, Some(2)),
                ],
            ),
        ],
        columns: 2,
        width: 1200,
        height: 800,
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
        }],
        columns: 1,
        width: 900,
        height: 450,
    }
}
