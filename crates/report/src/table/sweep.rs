//! A prediction's tables: the sweep (one row per operating point, with the uncertainty band's
//! columns when asked), the per-station table, and the JSON document of every result. The
//! sweep's CSV is also written directly ([`rows`]), without serde and the csv crate, the same
//! bytes as [`csv_rows`] of its rows (a test holds it), for the streamed sweep, where the
//! generic path spent as long formatting a 20,000-point table as the solver took to compute it.

use propbet_bemt::{Fluid, PointResult};
use propbet_compare::band::PointBand;
use propbet_model::Model;
use propbet_settings::spec::PredictSpec;
use serde::Serialize;

use super::columns::{table, Table};
use super::number::{csv_rows, push_num, Num};

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
/// flags of [`propbet_bemt::check::implausible`].
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
            &propbet_bemt::check::implausible(p, rho, tip_radius).join("; "),
        );
        out.extend_from_slice(&tail);
    }
    out
}

/// A row of the sweep table.
#[derive(serde::Serialize)]
pub struct SweepRow {
    rpm: Num,
    v_m_s: Num,
    j: Num,
    thrust_n: Num,
    torque_nm: Num,
    power_w: Num,
    ct: Num,
    cp: Num,
    cq: Num,
    eta: Num,
    ct_qprop: Num,
    cp_qprop: Num,
    adv_qprop: Num,
    dv_m_s: Num,
    cl_avg: Num,
    cd_avg: Num,
    not_converged: usize,
    /// What is physically implausible at the point ([`propbet_bemt::check::implausible`]).
    flags: String,
    /// Air density used [kg/m^3].
    rho_kg_m3: Num,
    /// Where the air came from: given, from T, P, RH, or QPROP's defaults (assumed).
    air: String,
}

/// The band's columns of a sweep row.
#[derive(serde::Serialize)]
pub struct BandColumns {
    /// CT at the band's low end.
    pub ct_lo: Num,
    /// CT at its high end.
    pub ct_hi: Num,
    /// CP at the band's low end.
    pub cp_lo: Num,
    /// CP at its high end.
    pub cp_hi: Num,
    /// Efficiency at the band's low end.
    pub eta_lo: Num,
    /// Efficiency at its high end.
    pub eta_hi: Num,
}

/// The sweep table with the band's columns after the others (`band` in the points' order).
pub fn band_rows(
    results: &[PointResult],
    band: &[PointBand],
    rho: f64,
    air: &str,
    tip_radius: f64,
) -> Result<Vec<u8>, csv::Error> {
    csv_rows(with_band(results, band, rho, air, tip_radius), true)
}

/// The sweep's rows with the band's columns after the others.
pub fn with_band<'a>(
    results: &'a [PointResult],
    band: &'a [PointBand],
    rho: f64,
    air: &'a str,
    tip_radius: f64,
) -> impl Iterator<Item = (SweepRow, BandColumns)> + 'a {
    results.iter().zip(band).map(move |(p, b)| {
        (
            sweep_row(p, rho, air, tip_radius),
            BandColumns {
                ct_lo: b.ct.lo.into(),
                ct_hi: b.ct.hi.into(),
                cp_lo: b.cp.lo.into(),
                cp_hi: b.cp.hi.into(),
                eta_lo: b.eta.lo.into(),
                eta_hi: b.eta.hi.into(),
            },
        )
    })
}

/// One point as a row of the sweep table.
pub fn sweep_row(p: &PointResult, rho: f64, air: &str, tip_radius: f64) -> SweepRow {
    SweepRow {
        rpm: p.rpm.into(),
        v_m_s: p.v.into(),
        j: p.j.into(),
        thrust_n: p.thrust.into(),
        torque_nm: p.torque.into(),
        power_w: p.power.into(),
        ct: p.ct.into(),
        cp: p.cp.into(),
        cq: p.cq.into(),
        eta: p.eta.into(),
        ct_qprop: p.ct_qprop.into(),
        cp_qprop: p.cp_qprop.into(),
        adv_qprop: p.adv_qprop.into(),
        dv_m_s: p.dv.into(),
        cl_avg: p.cl_avg.into(),
        cd_avg: p.cd_avg.into(),
        not_converged: p.not_converged,
        flags: propbet_bemt::check::implausible(p, rho, tip_radius).join("; "),
        rho_kg_m3: rho.into(),
        air: air_cell(air),
    }
}

/// A row of the per-station table.
#[derive(serde::Serialize)]
struct StationRow {
    rpm: Num,
    v_m_s: Num,
    r_m: Num,
    chord_m: Num,
    beta_deg: Num,
    alpha_deg: Num,
    cl: Num,
    cd: Num,
    re: Num,
    mach: Num,
    w_m_s: Num,
    wa_m_s: Num,
    wt_m_s: Num,
    va_m_s: Num,
    vt_m_s: Num,
    f_tip: Num,
    dt_dr_n_m: Num,
    dq_dr_n: Num,
    stalled: bool,
    convergence: &'static str,
}

/// The per-station table of `results` as CSV.
pub fn stations_csv(results: &[PointResult]) -> Result<Vec<u8>, csv::Error> {
    csv_rows(station_rows(results), true)
}

/// The per-station table of `results` as columns.
pub fn stations_table(results: &[PointResult]) -> Result<Table, super::columns::Error> {
    table(station_rows(results))
}

fn station_rows(results: &[PointResult]) -> impl Iterator<Item = StationRow> + '_ {
    results.iter().flat_map(|p| {
        p.stations.iter().map(move |st| StationRow {
            rpm: p.rpm.into(),
            v_m_s: p.v.into(),
            r_m: st.r.into(),
            chord_m: st.chord.into(),
            beta_deg: st.beta.to_degrees().into(),
            alpha_deg: st.alpha.to_degrees().into(),
            cl: st.cl.into(),
            cd: st.cd.into(),
            re: st.re.into(),
            mach: st.mach.into(),
            w_m_s: st.w.into(),
            wa_m_s: st.wa.into(),
            wt_m_s: st.wt.into(),
            va_m_s: st.va.into(),
            vt_m_s: st.vt.into(),
            f_tip: st.f_tip.into(),
            dt_dr_n_m: st.dt_dr.into(),
            dq_dr_n: st.dq_dr.into(),
            stalled: st.stalled,
            convergence: match st.convergence {
                propbet_bemt::Convergence::Newton { .. } => "newton",
                propbet_bemt::Convergence::Bracketed { .. } => "bracketed",
                propbet_bemt::Convergence::NotConverged => "not_converged",
                propbet_bemt::Convergence::NoFlow => "no_flow",
                propbet_bemt::Convergence::NoRotation => "no_rotation",
                propbet_bemt::Convergence::ZeroChord => "zero_chord",
            },
        })
    })
}

#[derive(Serialize)]
struct JsonOut<'a> {
    prop: &'a str,
    name: &'a str,
    blades: f64,
    tip_radius_m: f64,
    fluid: Fluid,
    fluid_source: &'a str,
    qprop_compat: bool,
    tip_loss: bool,
    dbeta_deg: f64,
    warnings: &'a [String],
    points: &'a [PointResult],
    /// The uncertainty band at each point (`--band`), in the points' order.
    #[serde(skip_serializing_if = "Option::is_none")]
    band: Option<&'a [PointBand]>,
}

/// Every result of a prediction, with its inputs, as one JSON document (`--format json`).
pub fn json_doc(
    spec: &PredictSpec,
    model: &Model,
    fluid: &Fluid,
    source: &str,
    results: &[PointResult],
    band: Option<&[PointBand]>,
) -> serde_json::Result<Vec<u8>> {
    let doc = JsonOut {
        prop: &spec.model.prop.to_string_lossy(),
        name: &model.loaded.file.name,
        blades: model.rotor.blades,
        tip_radius_m: model.rotor.tip_radius,
        fluid: *fluid,
        fluid_source: source,
        qprop_compat: spec.model.qprop_compat,
        tip_loss: model.opts.tip_loss,
        dbeta_deg: spec.model.dbeta.to_degrees(),
        warnings: &model.loaded.warnings,
        points: results,
        band,
    };
    let mut s = serde_json::to_vec_pretty(&doc)?;
    s.push(b'\n');
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point as the solver returns it: a static one (no J, no efficiency), a forward one,
    /// and one whose loads are implausible (flags with their own separators).
    fn points() -> Vec<PointResult> {
        let point = |v: f64, rpm: f64, thrust: f64, j: Option<f64>, not_converged: usize| {
            serde_json::from_value(serde_json::json!({
                "v": v, "omega": propbet_units::rpm_to_omega(rpm), "rpm": rpm,
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
            let via_csv = csv_rows(pts.iter().map(|p| sweep_row(p, 1.2, air, 0.1)), header).unwrap();
            let direct = rows(&pts, header, 1.2, air, 0.1);
            assert_eq!(String::from_utf8(direct).unwrap(), String::from_utf8(via_csv).unwrap());
        }
        // The implausible point carries flags: the case the quoting rule is for.
        assert!(!propbet_bemt::check::implausible(&pts[2], 1.2, 0.1).is_empty());
    }
}
