//! Figures of section polars: XFOIL's points and the QPROP fit over its linear range.

use propbet_plot::{Mark, Panel, Series};
use propbet_polar::{Polar, QpropFit};

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
