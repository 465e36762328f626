//! Figures of section polars: XFOIL's points and the QPROP fit over its linear range.

use propbet_pipeline::stages::Polars;
use propbet_plot::{Mark, Panel, Series};
use propbet_polar::{Makers, Polar, QpropFit};

/// Lift and drag polars from XFOIL with their QPROP fits (`propbet polar --plot`).
pub fn panels(name: &str, polars: &[Polar], fits: &[QpropFit]) -> Vec<Panel> {
    let mut lift = Vec::new();
    let mut drag = Vec::new();
    for (k, p) in polars.iter().enumerate() {
        let label = format!("XFOIL Re {:.0}", p.re);
        lift.push(Series::new(
            label.clone(),
            p.points.iter().map(|q| (q.alpha_deg, q.cl)).collect(),
            Mark::Dots,
            Some(k),
        ));
        drag.push(Series::new(
            label,
            p.points.iter().map(|q| (q.cd, q.cl)).collect(),
            Mark::Dots,
            Some(k),
        ));
    }
    for f in fits {
        let k = polars.iter().position(|p| p.re == f.coeffs.re_ref);
        let label = format!("QPROP fit Re {:.0}", f.coeffs.re_ref);
        let lin: Vec<_> = f.residuals.iter().filter(|r| r.linear).collect();
        lift.push(Series::new(
            label.clone(),
            lin.iter().map(|r| (r.alpha_deg, r.cl_fit)).collect(),
            Mark::Line,
            k,
        ));
        drag.push(Series::new(
            label,
            lin.iter().map(|r| (r.cd_fit, r.cl_xfoil)).collect(),
            Mark::Line,
            k,
        ));
    }
    vec![
        Panel::new(format!("{name}: lift"), "angle of attack [deg]", "cl", lift),
        Panel::new(format!("{name}: drag polar"), "cd", "cl", drag),
    ]
}

/// The polars stage in two short lines (the terminal of `propbet run`): what XFOIL or
/// NeuralFoil made and how often XFOIL failed (the tables interpolate across), and how far the
/// exported QPROP file's law is from the tables the prediction uses; every station's detail is
/// in the report.
pub fn brief(p: &Polars) -> Vec<String> {
    let stations = &p.blade.stations;
    let makers = Makers::of(stations.iter().flat_map(|s| &s.polars));
    let unconverged: usize = stations
        .iter()
        .map(|s| s.polars.iter().filter(|pol| !pol.unconverged_deg.is_empty()).count())
        .sum();
    let faults: usize = stations
        .iter()
        .map(|s| s.polars.iter().map(|pol| pol.faults.len()).sum::<usize>())
        .sum();
    let without = stations.iter().filter(|s| s.polars.is_empty()).count();
    let mut out = vec![format!(
        "{} stations, {} used as tables{}",
        stations.len(),
        makers.words(),
        if without > 0 {
            format!(", {without} stations without a polar")
        } else {
            String::new()
        }
    )];
    if let Some(d) = makers.doubts() {
        out.push(d);
    }
    if unconverged + faults > 0 {
        out.push(format!(
            "XFOIL missed some angles in {unconverged} polars and failed {faults} times: the tables interpolate across the gaps"
        ));
    }
    if let Some(e) = &p.export {
        out.push(format!(
            "the exported QPROP file's law differs from these tables by {:.1} % in CT, {:.1} % in CP (median)",
            100.0 * e.ct.median,
            100.0 * e.cp.median
        ));
    }
    out
}
