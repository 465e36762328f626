//! validate's tables: validation.csv (one row per prop) and each prop's band_sources.csv.

use propbet_compare::ComparedPoint;
use propbet_validate::{Row, Validated};

use super::{bytes, csv_rows, Error, Num};

/// validation.csv: one row per prop.
pub fn csv(rows: &[Row]) -> Result<Vec<u8>, Error> {
    // Rows are structs: the header comes from the same fields as the values.
    let rows = rows.iter().map(|r| CsvRow {
        prop: &r.prop,
        points: r.points,
        ct_median: Num::from(Some(r.ct.before.median)),
        ct_p90: Num::from(Some(r.ct.before.p90)),
        cp_median: Num::from(Some(r.cp.before.median)),
        cp_p90: Num::from(Some(r.cp.before.p90)),
        ct_median_after: Num::from(Some(r.ct.after.median)),
        ct_p90_after: Num::from(Some(r.ct.after.p90)),
        cp_median_after: Num::from(Some(r.cp.after.median)),
        cp_p90_after: Num::from(Some(r.cp.after.p90)),
        implausible_points: r.implausible,
        stations_beyond_polars: r.beyond_polars.0,
        station_solves: r.beyond_polars.1,
        apc_points: r.per3.as_ref().map(|p| p.points),
        apc_ct_median: Num::from(r.per3.as_ref().map(|p| p.ct.median)),
        apc_ct_p90: Num::from(r.per3.as_ref().map(|p| p.ct.p90)),
        apc_cp_median: Num::from(r.per3.as_ref().map(|p| p.cp.median)),
        apc_cp_p90: Num::from(r.per3.as_ref().map(|p| p.cp.p90)),
        twist_gap_deg: Num::from(Some(r.twist_gap)),
        uiuc_geometry: r.uiuc_geometry,
        assumed_section: r.assumed_section.as_deref(),
        files_left_out: r.left_out.len(),
        static_fm_error: Num::from(Some(r.static_fm)),
        static_ct_error: Num::from(Some(r.regimes.static_points.ct)),
        static_cp_error: Num::from(Some(r.regimes.static_points.cp)),
        low_j_ct_error: Num::from(Some(r.regimes.low_j.ct)),
        low_j_cp_error: Num::from(Some(r.regimes.low_j.cp)),
        high_j_ct_error: Num::from(Some(r.regimes.high_j.ct)),
        high_j_cp_error: Num::from(Some(r.regimes.high_j.cp)),
        static_ct_rise_measured: Num::from(r.static_rise.map(|s| s.measured)),
        static_ct_rise_predicted: Num::from(r.static_rise.map(|s| s.predicted)),
        forward_ct_error_rpm_change: Num::from(r.forward_rpm_trend.map(|t| t.change)),
        zero_thrust_j_change_measured: Num::from(r.zero_thrust_shift.map(|z| z.measured_change())),
        zero_thrust_j_change_predicted: Num::from(r.zero_thrust_shift.and_then(|z| z.predicted_change())),
        ladder: &r.ladder,
        held_out_ladders: r.held_out_ladders.join(" / "),
        repeatability: Num::from(r.repeatability),
        outlier_reason: crate::validate::outlier_reason(r).unwrap_or_default(),
        band_ct_coverage: Num::from(r.band[0].map(|c| c.inside)),
        band_ct_half_width: Num::from(r.band[0].map(|c| c.half_width)),
        band_cp_coverage: Num::from(r.band[1].map(|c| c.inside)),
        band_cp_half_width: Num::from(r.band[1].map(|c| c.half_width)),
    });
    Ok(csv_rows(rows, true)?)
}

/// A row of validation.csv.
#[derive(serde::Serialize)]
struct CsvRow<'a> {
    prop: &'a str,
    points: usize,
    ct_median: Num,
    ct_p90: Num,
    cp_median: Num,
    cp_p90: Num,
    ct_median_after: Num,
    ct_p90_after: Num,
    cp_median_after: Num,
    cp_p90_after: Num,
    implausible_points: usize,
    /// Station solves beyond their polars' Reynolds-number range, of `station_solves`.
    stations_beyond_polars: usize,
    station_solves: usize,
    apc_points: Option<usize>,
    apc_ct_median: Num,
    apc_ct_p90: Num,
    apc_cp_median: Num,
    apc_cp_p90: Num,
    twist_gap_deg: Num,
    uiuc_geometry: bool,
    assumed_section: Option<&'a str>,
    files_left_out: usize,
    static_fm_error: Num,
    static_ct_error: Num,
    static_cp_error: Num,
    low_j_ct_error: Num,
    low_j_cp_error: Num,
    high_j_ct_error: Num,
    high_j_cp_error: Num,
    static_ct_rise_measured: Num,
    static_ct_rise_predicted: Num,
    forward_ct_error_rpm_change: Num,
    /// The J sweeps' zero-thrust J from the lowest to the highest sweep RPM, measured, relative
    /// (`ZeroThrustShift`); empty without two sweeps reaching zero thrust.
    zero_thrust_j_change_measured: Num,
    /// The same, predicted.
    zero_thrust_j_change_predicted: Num,
    ladder: &'a str,
    held_out_ladders: String,
    /// The relative deviation of one repeated point (the diagnosis' repeatability).
    repeatability: Num,
    /// Why the prop is an outlier (CT or CP median above 15 %); empty otherwise.
    outlier_reason: String,
    /// The share of the scored points whose measured CT lies inside the uncertainty band.
    band_ct_coverage: Num,
    /// The band's median half-width relative to the predicted CT.
    band_ct_half_width: Num,
    /// The same for CP.
    band_cp_coverage: Num,
    /// The same for CP.
    band_cp_half_width: Num,
}

/// The band's makings at every compared point (validate's `compare/band_sources.csv`, in
/// `points.csv`'s order): the point, whether validate scores it, the measured and predicted CT and CP, and CT and
/// CP at each source's two ends, so that another band can be made from the same solves.
pub fn band_sources(v: &Validated) -> Result<Vec<u8>, Error> {
    let points = &v.compared.0.points;
    let scored = propbet_compare::metrics::in_window(points, propbet_compare::metrics::VALIDATION_J_WINDOW);
    let mut header: Vec<String> = [
        "file",
        "line_first",
        "rpm",
        "j",
        "scored",
        "ct",
        "ct_pred",
        "cp",
        "cp_pred",
    ]
    .map(String::from)
    .to_vec();
    for (name, _) in &v.band_sources {
        let slug = name.replace([' ', '\''], "_");
        for q in ["ct_lo", "ct_hi", "cp_lo", "cp_hi"] {
            header.push(format!("{slug}_{q}"));
        }
    }
    let mut csv = csv::Writer::from_writer(Vec::new());
    csv.write_record(&header)?;
    const QS: [fn(&ComparedPoint) -> Option<f64>; 2] = [|p| p.predicted.ct, |p| p.predicted.cp];
    let num = |x: Option<f64>| {
        x.filter(|v| v.is_finite())
            .map(|v| format!("{v:.7}"))
            .unwrap_or_default()
    };
    for (i, p) in points.iter().enumerate() {
        let mut r = vec![
            p.file.to_string(),
            p.lines.0.to_string(),
            format!("{:.1}", p.rpm),
            format!("{:.5}", p.j),
            u8::from(scored[i]).to_string(),
            num(p.measured.ct),
            num(p.predicted.ct),
            num(p.measured.cp),
            num(p.predicted.cp),
        ];
        for (_, ends) in &v.band_sources {
            for q in QS {
                for end in ends {
                    r.push(num(end.get(i).and_then(q)));
                }
            }
        }
        csv.write_record(&r)?;
    }
    Ok(bytes(csv)?)
}
