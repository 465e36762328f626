//! The comparison page's electrical section (`compare --motor`): the log's supply current and
//! electrical power against what the motor draws, in a sentence, a figure and a table.

use std::fmt::Write as _;

use propbet_compare::electric::Electric;
use propbet_plot::{Figure, Mark, Panel, Series};

use crate::page::{esc, sig};

/// The figure: supply current and electrical power over RPM, measured and predicted.
pub(super) fn figure(e: &Electric) -> Figure {
    let series = |f: &dyn Fn(&propbet_compare::electric::ElectricPoint) -> Option<f64>| {
        let mut v: Vec<(f64, f64)> = e.points.iter().filter_map(|p| Some((p.rpm, f(p)?))).collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        v
    };
    let panel =
        |title: &str, y: &str, measured: Vec<(f64, f64)>, predicted: Vec<(f64, f64)>, alone: Vec<(f64, f64)>| {
            let mut s = vec![
                Series::new("measured", measured, Mark::Dots, Some(0)),
                Series::new("predicted (propeller + motor)", predicted, Mark::Line, Some(1)),
            ];
            if !alone.is_empty() {
                s.push(Series::new(
                    "motor alone (measured torque)",
                    alone,
                    Mark::Dashed,
                    Some(2),
                ));
            }
            Panel::new(title, "RPM", y, s)
        };
    let mut panels = vec![
        panel(
            "supply current vs RPM",
            "current [A]",
            series(&|p| Some(p.amps)),
            series(&|p| Some(p.amps_predicted)),
            series(&|p| p.amps_motor_only),
        ),
        panel(
            "electrical power vs RPM",
            "power [W]",
            series(&|p| Some(p.power)),
            series(&|p| Some(p.power_predicted)),
            Vec::new(),
        ),
        panel(
            "motor efficiency (shaft / electrical power) vs RPM",
            "efficiency [-]",
            series(&|p| p.eta_motor),
            series(&|p| Some(p.eta_motor_predicted).filter(|x| x.is_finite())),
            Vec::new(),
        ),
    ];
    let at_volts = series(&|p| p.rpm_at_volts);
    if !at_volts.is_empty() {
        // Measured on the diagonal; the chain's speed at the same throttle beside it.
        let measured = series(&|p| p.rpm_at_volts.map(|_| p.rpm));
        panels.push(Panel::new(
            "speed at the log's throttle (the motor at the ESC's voltage)",
            "measured RPM",
            "RPM",
            vec![
                Series::new("measured", measured, Mark::Dots, Some(0)),
                Series::new("predicted (propeller + motor)", at_volts, Mark::Dots, Some(1)),
            ],
        ));
    }
    let rows = panels.len().div_ceil(2);
    Figure {
        panels,
        columns: 2,
        width: 1200,
        height: 440 * rows as u32,
    }
}

/// The sentence that answers how well the current is predicted.
pub fn sentence(e: &Electric) -> String {
    let alone = e.motor_only_median_abs.map_or(String::new(), |m| {
        format!("; the motor model alone (with the measured torque) {:.1} %", 100.0 * m)
    });
    let speed = e.rpm_median.map_or(String::new(), |m| {
        format!(
            "; speed at the log's throttle (the motor at the ESC's voltage turning the predicted propeller) {:+.1} % over {} points",
            100.0 * m,
            e.points.iter().filter(|p| p.rpm_at_volts.is_some()).count()
        )
    });
    format!(
        "Supply current on {}: median error {:+.1} % (median |error| {:.1} %) over {} points, from the predicted torque{alone}; electrical power {:+.1} %{speed}.",
        e.motor,
        100.0 * e.current_median,
        100.0 * e.current_median_abs,
        e.points.len(),
        100.0 * e.power_median
    )
}

/// The section's HTML (the figure inline).
pub(super) fn html(h: &mut String, e: &Electric, fig: &Figure) -> Result<(), propbet_plot::PlotError> {
    let _ = writeln!(h, "<h2>Electrical: current and power on {}</h2>", esc(&e.motor));
    let _ = writeln!(h, "<p>{}</p>", esc(&sentence(e)));
    h.push_str(
        "<p class=\"note\">The log's voltage and current are the supply's, before the ESC; the ESC is taken as lossless, so the predicted current is the motor's electrical power (QPROP's motor model at the measured speed and the torque) over the measured voltage. The speed at the log's throttle: at the points of half throttle and above with the ESC command logged, the motor at the voltage the ESC gives it (the command read as a linear ESC calibrated to 1000-2000 µs, times the supply's voltage) turning the predicted propeller.</p>\n",
    );
    let _ = writeln!(
        h,
        "<figure id=\"fig-electric\">{}</figure>",
        propbet_plot::svg_inline(fig)?
    );
    let _ = write!(
        h,
        "<details><summary>{} points: open the table</summary>\n<table><tr><th>point</th><th>RPM</th><th>V</th><th>A measured</th><th>A predicted</th><th>error</th><th>W measured</th><th>W predicted</th><th>g/W measured</th><th>g/W predicted</th><th>motor η measured</th><th>motor η predicted</th><th>RPM at the ESC's voltage</th></tr>\n",
        e.points.len()
    );
    let opt = |x: Option<f64>| x.map_or("–".to_string(), sig);
    for p in &e.points {
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{:.0}</td><td>{}</td><td>{}</td><td>{}</td><td>{:+.1} %</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            esc(&p.label),
            p.rpm,
            sig(p.volts),
            sig(p.amps),
            sig(p.amps_predicted),
            100.0 * (p.amps_predicted / p.amps - 1.0),
            sig(p.power),
            sig(p.power_predicted),
            opt(p.g_per_w),
            opt(p.g_per_w_predicted),
            opt(p.eta_motor),
            opt(Some(p.eta_motor_predicted).filter(|x| x.is_finite())),
            p.rpm_at_volts.map_or("–".to_string(), |r| format!("{r:.0}"))
        );
    }
    h.push_str("</table></details>\n");
    Ok(())
}
