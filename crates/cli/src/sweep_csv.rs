//! The sweep table's CSV written directly, without serde and the csv crate: the same bytes as
//! `csv_rows` of the sweep's rows (a test holds it), for the streamed sweep, where the generic
//! path spent as long formatting a 20,000-point table as the solver took to compute it.

use propbet_api::bemt::PointResult;

use crate::output::push_num;

/// The sweep table's columns, in `SweepRow`'s order.
pub const HEADER: &str = "rpm,v_m_s,j,thrust_n,torque_nm,power_w,ct,cp,cq,eta,ct_qprop,cp_qprop,adv_qprop,dv_m_s,\
cl_avg,cd_avg,not_converged,flags,rho_kg_m3,air";

/// Where the air came from as the sweep table's `air` cell: no comma in it, so that the table
/// stays splittable on commas.
pub fn air_cell(air: &str) -> String {
    air.replace(',', ";")
}

/// Appends `text` as one CSV field, quoted (its quotes doubled) where it holds a comma, a quote
/// or a line break, as the csv crate's necessary quoting does.
fn push_field(out: &mut Vec<u8>, text: &str) {
    if text.bytes().any(|b| matches!(b, b',' | b'"' | b'\n' | b'\r')) {
        out.push(b'"');
        for b in text.bytes() {
            if b == b'"' {
                out.push(b'"');
            }
            out.push(b);
        }
        out.push(b'"');
    } else {
        out.extend_from_slice(text.as_bytes());
    }
}

/// The rows of `results` (with the header line first when `header`): the air's density `rho`,
/// where the air came from (`air`, as [`air_cell`] writes it) and the tip radius for the
/// flags of [`propbet_api::bemt::check::implausible`].
pub fn rows(results: &[PointResult], header: bool, rho: f64, air: &str, tip_radius: f64) -> Vec<u8> {
    let mut out = Vec::with_capacity(results.len() * 256 + HEADER.len() + 1);
    if header {
        out.extend_from_slice(HEADER.as_bytes());
        out.push(b'\n');
    }
    // The two cells every row shares, formatted once.
    let mut tail = vec![b','];
    push_num(&mut tail, Some(rho));
    tail.push(b',');
    push_field(&mut tail, &air_cell(air));
    tail.push(b'\n');
    for p in results {
        let numbers = [
            Some(p.rpm),
            Some(p.v),
            p.j,
            Some(p.thrust),
            Some(p.torque),
            Some(p.power),
            p.ct,
            p.cp,
            p.cq,
            Some(p.eta),
            p.ct_qprop,
            p.cp_qprop,
            p.adv_qprop,
            Some(p.dv),
            Some(p.cl_avg),
            Some(p.cd_avg),
        ];
        for v in numbers {
            push_num(&mut out, v);
            out.push(b',');
        }
        out.extend_from_slice(p.not_converged.to_string().as_bytes());
        out.push(b',');
        push_field(
            &mut out,
            &propbet_api::bemt::check::implausible(p, rho, tip_radius).join("; "),
        );
        out.extend_from_slice(&tail);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point as the solver returns it: a static one (no J, no efficiency), a forward one,
    /// and one whose loads are implausible (flags with their own separators).
    fn points() -> Vec<PointResult> {
        let point = |v: f64, rpm: f64, thrust: f64, j: Option<f64>, not_converged: usize| {
            serde_json::from_value(serde_json::json!({
                "v": v, "omega": propbet_api::units::rpm_to_omega(rpm), "rpm": rpm,
                "thrust": thrust, "torque": 0.0123456789, "power": 12.3456789e-3 * rpm,
                "j": j, "ct": Some(0.1234567890123), "cp": None::<f64>, "cq": Some(1.5e-7),
                "eta": 0.0, "adv_qprop": j.map(|j| j / 3.0), "ct_qprop": Some(-2.5e-12),
                "cp_qprop": Some(123456789.0), "dv": 1.0 / 3.0, "cl_avg": -0.25, "cd_avg": 1e20,
                "not_converged": not_converged, "stations": []
            }))
            .unwrap()
        };
        vec![
            point(0.0, 2000.0, 0.064, None, 0),
            point(12.5, 18181.818181, 3.25, Some(0.41), 2),
            point(40.0, 500.0, 900.0, Some(2.0), 0),
        ]
    }

    #[test]
    fn the_direct_rows_are_the_csv_crates_bytes() {
        let pts = points();
        for (air, header) in [
            ("QPROP defaults (standard air; not measured)", true),
            ("given, \"lab\"\nair", false),
        ] {
            let via_csv =
                crate::output::csv_rows(pts.iter().map(|p| crate::predict::sweep_row(p, 1.2, air, 0.1)), header)
                    .unwrap();
            let direct = rows(&pts, header, 1.2, air, 0.1);
            assert_eq!(String::from_utf8(direct).unwrap(), String::from_utf8(via_csv).unwrap());
        }
        // The implausible point carries flags: the case the quoting rule is for.
        assert!(!propbet_api::bemt::check::implausible(&pts[2], 1.2, 0.1).is_empty());
    }
}
