//! The propeller on its motor in a run's report: the operating points as a table (the
//! propeller's band beside its thrust), and the terminal's short lines.

use std::fmt::Write as _;

use propbet_pipeline::stages::{PoweredPoint, PoweredTable};
use propbet_settings::spec::PoweredSpec;

use crate::page::{esc, sig};

/// Grams of thrust per newton.
fn grams(newtons: f64) -> f64 {
    newtons / propbet_units::STANDARD_GRAVITY * 1000.0
}

/// The terminal's lines: how many points, and the one of most thrust.
pub fn brief(t: &PoweredTable, spec: &PoweredSpec) -> Vec<String> {
    let solved = t.points.iter().filter(|p| p.problem().is_none()).count();
    let mut v = vec![format!(
        "{} operating points on {}, {solved} with an operating point{}",
        t.points.len(),
        t.motor.name,
        spec.out
            .as_ref()
            .map_or(String::new(), |o| format!(" -> {}", o.display()))
    )];
    let strongest = t
        .points
        .iter()
        .filter(|p| p.problem().is_none())
        .filter_map(|p| Some((p, p.outcome.as_ref().ok()?)))
        .max_by(|a, b| a.1 .0.loads.thrust.total_cmp(&b.1 .0.loads.thrust));
    if let Some((p, (s, _))) = strongest {
        v.push(format!(
            "most thrust: {} at {} m/s: {:.0} rpm, {} N ({:.0} g), {} A, {} W, {} g/W",
            p.drive.describe(),
            p.v,
            propbet_units::omega_to_rpm(s.omega),
            sig(s.loads.thrust),
            grams(s.loads.thrust),
            sig(s.amps),
            sig(s.electrical_power()),
            sig(s.grams_per_watt())
        ));
    }
    v
}

/// The run report's section (a body whose h1 the run's page nests): the motor, the battery,
/// and a row per point.
pub fn section(t: &PoweredTable, spec: &PoweredSpec) -> String {
    let mut h = String::new();
    let _ = writeln!(h, "<h1>On its motor</h1>");
    let battery = spec.supply.as_ref().map_or(String::new(), |s| {
        format!(
            ", on a battery of {} cells ({} V open-circuit per cell, {} ohm each{}) through an ESC of {} ohm",
            s.battery.cells,
            s.battery.cell_volts,
            s.battery.cell_ohms,
            if s.battery.capacity_ah > 0.0 {
                format!(", {} Ah", s.battery.capacity_ah)
            } else {
                String::new()
            },
            s.esc_ohms
        )
    });
    let _ = writeln!(
        h,
        "<p>The propeller on the motor {} ({}){battery}: where the motor's torque meets the propeller's, as QPROP \
         solves it. The thrust's range is the propeller's band (its CT's) at that speed. Every column: <code>{}</code>.</p>",
        esc(&t.motor.name),
        esc(&spec
            .motor
            .file_name()
            .map_or(String::new(), |n| n.to_string_lossy().into_owned())),
        esc(&spec
            .out
            .as_ref()
            .map_or(String::new(), |o| o.display().to_string()))
    );
    let supply = spec.supply.is_some();
    h.push_str("<table><tr><th>driver</th><th>V [m/s]</th><th>rpm</th><th>thrust [N]</th><th>thrust [g]</th><th>current [A]</th><th>electrical [W]</th><th>g/W</th><th>motor η</th><th>overall η</th>");
    if supply {
        h.push_str("<th>throttle</th><th>battery [A]</th><th>minutes</th>");
    }
    h.push_str("</tr>\n");
    for (i, p) in t.points.iter().enumerate() {
        let band = t.band.as_ref().and_then(|b| b[i]);
        row(&mut h, p, band, supply);
    }
    h.push_str("</table>\n");
    h
}

fn row(h: &mut String, p: &PoweredPoint, band: Option<propbet_compare::band::PointBand>, supply: bool) {
    let _ = write!(h, "<tr><td>{}</td><td>{}</td>", esc(&p.drive.describe()), sig(p.v));
    let Ok((s, r)) = &p.outcome else {
        let _ = writeln!(
            h,
            "<td colspan=\"{}\">{}</td></tr>",
            if supply { 11 } else { 8 },
            esc(p.problem().unwrap_or_default())
        );
        return;
    };
    let thrust = s.loads.thrust;
    let range = match (band, r.ct) {
        (Some(b), Some(ct)) if ct.abs() > 0.0 => {
            format!(" ({}–{})", sig(thrust * b.ct.lo / ct), sig(thrust * b.ct.hi / ct))
        }
        _ => String::new(),
    };
    let _ = write!(
        h,
        "<td>{:.0}</td><td>{}{range}</td><td>{:.0}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>",
        propbet_units::omega_to_rpm(s.omega),
        sig(thrust),
        grams(thrust),
        sig(s.amps),
        sig(s.electrical_power()),
        sig(s.grams_per_watt()),
        sig(s.motor_efficiency()),
        sig(s.motor_efficiency() * r.eta)
    );
    if supply {
        match p.supply.as_ref() {
            Some(Ok(b)) => {
                let _ = write!(
                    h,
                    "<td>{:.0} %</td><td>{}</td><td>{}</td>",
                    100.0 * b.throttle,
                    sig(b.battery_amps),
                    b.endurance
                        .map_or("".to_string(), |e| sig(propbet_units::seconds_to_minutes(e)))
                );
            }
            Some(Err(why)) => {
                let _ = write!(h, "<td colspan=\"3\">{}</td>", esc(why));
            }
            None => h.push_str("<td></td><td></td><td></td>"),
        }
    }
    h.push_str("</tr>\n");
}
