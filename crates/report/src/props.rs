//! The side-by-side page (`propbet compare-props`): which propeller for this motor and
//! battery, answered first, then the ranked table and the figures over airspeed.

use std::fmt::Write as _;

use propbet_pipeline::stages::{overall_efficiency, FullRange, SideProp};
use propbet_plot::{Figure, Mark, Panel, PlotError, Series};

use crate::page::{esc, page, sig};

/// What the page is about.
pub struct Setup<'a> {
    /// The motor's name.
    pub motor: &'a str,
    /// The battery as given (`3S,2200mAh`).
    pub battery: &'a str,
    /// The hover thrust [N].
    pub hover_thrust: f64,
    /// The command that made it.
    pub command: &'a str,
}

/// The answer in sentences: the best g/W at hover, the most thrust at full throttle, and the
/// current at hover of the best.
pub fn answer(props: &[SideProp], s: &Setup) -> Vec<String> {
    let g = propbet_units::STANDARD_GRAVITY;
    let mut out = Vec::new();
    if let Some(best) = props.first().filter(|p| p.hover_g_per_w().is_some()) {
        if let Ok((m, _, b)) = &best.hover {
            out.push(format!(
                "Most grams per watt at hover ({:.0} g): {} with {:.2} g/W, {:.1} A from the battery ({:.1} A in the motor) at {:.0} % throttle and {:.0} rpm{}.",
                s.hover_thrust / g * 1000.0,
                best.name,
                best.hover_g_per_w().unwrap_or(0.0),
                b.battery_amps,
                m.amps,
                100.0 * b.throttle,
                propbet_units::omega_to_rpm(m.omega),
                b.endurance
                    .map_or(String::new(), |t| format!(", {:.1} minutes on the battery", propbet_units::seconds_to_minutes(t)))
            ));
        }
    }
    let full_static = |p: &SideProp| {
        p.full
            .first()
            .and_then(|(_, r)| r.as_ref().ok())
            .map(|(m, _, b)| (m.loads.thrust, b.battery_amps))
    };
    if let Some((p, (t, a))) = props
        .iter()
        .filter_map(|p| full_static(p).map(|f| (p, f)))
        .max_by(|x, y| x.1 .0.total_cmp(&y.1 .0))
    {
        out.push(format!(
            "Most static thrust at full throttle: {} with {:.0} g ({:.2} N) at {:.1} A.",
            p.name,
            t / g * 1000.0,
            t,
            a
        ));
    }
    if let [a, b, ..] = props {
        if let (Some(x), Some(y)) = (a.hover_band, b.hover_band) {
            out.push(if x.0 <= y.1 {
                format!(
                    "Within the predictions' uncertainty bands, {} ({:.2}-{:.2} g/W) and {} ({:.2}-{:.2} g/W) are not told apart at hover.",
                    a.name, x.0, x.1, b.name, y.0, y.1
                )
            } else {
                format!(
                    "{} is ahead of {} at hover beyond the predictions' uncertainty bands ({:.2}-{:.2} against {:.2}-{:.2} g/W).",
                    a.name, b.name, x.0, x.1, y.0, y.1
                )
            });
        }
    }
    let cannot: Vec<String> = props
        .iter()
        .filter_map(|p| p.hover.as_ref().err().map(|why| format!("{}: {why}", p.name)))
        .collect();
    if !cannot.is_empty() {
        out.push(format!("Cannot hover at that thrust: {}.", cannot.join("; ")));
    }
    out
}

/// The figure: full-throttle thrust, overall efficiency and battery current over airspeed, one
/// line per prop, each shaded over its prediction's uncertainty band.
pub fn figure(props: &[SideProp]) -> Figure {
    type Full = (
        propbet_motor::Powered,
        propbet_bemt::PointResult,
        propbet_motor::SupplyPoint,
    );
    let series = |value: &dyn Fn(f64, &Full) -> f64, range: &dyn Fn(&FullRange) -> (f64, f64)| {
        let mut out = Vec::new();
        for (k, p) in props.iter().enumerate() {
            // The band first, so that the lines are drawn over it.
            let ranged: Vec<(f64, (f64, f64))> = p
                .full
                .iter()
                .zip(&p.full_band)
                .filter_map(|((v, _), b)| b.as_ref().map(|b| (*v, range(b))))
                .collect();
            if ranged.len() > 1 {
                let outline = ranged
                    .iter()
                    .map(|(v, r)| (*v, r.0))
                    .chain(ranged.iter().rev().map(|(v, r)| (*v, r.1)))
                    .collect();
                out.push(Series::new("", outline, Mark::Area, Some(k)));
            }
            let pts = p
                .full
                .iter()
                .filter_map(|(v, r)| r.as_ref().ok().map(|x| (*v, value(*v, x))))
                .collect();
            out.push(Series::new(&p.name, pts, Mark::Line, Some(k)));
        }
        out
    };
    let panel = |title: &str, y: &str, series: Vec<Series>| Panel::new(title, "airspeed [m/s]", y, series);
    Figure {
        panels: vec![
            panel(
                "thrust at full throttle",
                "thrust [N]",
                series(&|_, x| x.0.loads.thrust, &|b| b.thrust),
            ),
            panel(
                "overall efficiency at full throttle (thrust power / battery power)",
                "efficiency [-]",
                series(
                    &|v, x| overall_efficiency(x.0.loads.thrust, v, x.2.battery_power),
                    &|b| b.efficiency,
                ),
            ),
            panel(
                "battery current at full throttle",
                "current [A]",
                series(&|_, x| x.2.battery_amps, &|b| b.battery_amps),
            ),
        ],
        columns: 3,
        width: 1500,
        height: 480,
    }
}

/// The page: the answer, the ranked table, the figure.
pub fn html(props: &[SideProp], s: &Setup, fig: &Figure) -> Result<String, PlotError> {
    let mut h = String::new();
    let _ = writeln!(
        h,
        "<h1>Propellers side by side on {} and {}</h1>",
        esc(s.motor),
        esc(s.battery)
    );
    for a in answer(props, s) {
        let _ = writeln!(h, "<p><strong>{}</strong></p>", esc(&a));
    }
    h.push_str("<table><tr><th>rank</th><th>propeller</th><th>D [m]</th><th>hover g/W</th><th>band</th><th>hover throttle</th><th>hover battery A</th><th>hover motor A</th><th>endurance [min]</th><th>full-throttle thrust [N]</th><th>full-throttle battery A</th><th>full-throttle rpm</th></tr>\n");
    for (k, p) in props.iter().enumerate() {
        let hover = p.hover.as_ref().ok();
        let full = p.full.first().and_then(|(_, r)| r.as_ref().ok());
        let opt = |x: Option<f64>| x.map_or("–".to_string(), sig);
        let band = p.full_band.first().copied().flatten();
        let ranged = |x: Option<f64>, r: Option<(f64, f64)>| match r {
            Some((lo, hi)) => format!("{} ({}–{})", opt(x), sig(lo), sig(hi)),
            None => opt(x),
        };
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            k + 1,
            esc(&p.name),
            sig(p.diameter),
            opt(p.hover_g_per_w()),
            p.hover_band.map_or("–".to_string(), |(lo, hi)| format!("{lo:.2}-{hi:.2}")),
            opt(hover.map(|x| x.2.throttle)),
            opt(hover.map(|x| x.2.battery_amps)),
            opt(hover.map(|x| x.0.amps)),
            opt(hover.and_then(|x| x.2.endurance).map(propbet_units::seconds_to_minutes)),
            ranged(full.map(|x| x.0.loads.thrust), band.map(|b| b.thrust)),
            ranged(full.map(|x| x.2.battery_amps), band.map(|b| b.battery_amps)),
            opt(full.map(|x| propbet_units::omega_to_rpm(x.0.omega))),
        );
    }
    h.push_str("</table>\n");
    let _ = writeln!(
        h,
        "<figure id=\"fig-props\">{}</figure>",
        propbet_plot::svg_inline(fig)?
    );
    let _ = writeln!(
        h,
        "<p class=\"note\">Each propeller's prediction (its model as `propbet predict` makes it) on QPROP's motor model and a battery of cells behind their resistance through an ESC taken as an ideal switch with a resistance (docs: commands, `--battery`). Hover: static, at the thrust given. Ranked by g/W at hover (thrust over the battery's power). The band: the g/W at hover at the ends of each prediction's uncertainty band (its CT and CP, as `predict --band` gives them; at a fixed thrust the power goes as CP/CT^1.5, the motor's efficiency held, the corners taken apart). At full throttle (the table's static range and the figure's shading): the propeller's thrust and torque scaled by its band's ends of CT and CP at each point (low CT with high CP, high CT with low CP) and the motor's and battery's operating point found again for each, so that a propeller taking more torque turns slower and draws more. command: <code>{}</code></p>",
        esc(s.command)
    );
    Ok(page("propbet: propellers side by side", "", &h))
}
