//! Measured files as `compare` reads them, as tables: the points (one row per point, every
//! file's in order) and the rows dropped.

use propbet_measure::{DropReason, Format, Loads, MeasuredSet, Refused, Speed};

use super::{csv_rows, Error, Num};

/// A measured point as a row.
#[derive(serde::Serialize)]
struct PointRow<'a> {
    file: &'a str,
    format: Format,
    label: &'a str,
    line_first: usize,
    line_last: usize,
    rpm: Num,
    rpm_sd: Num,
    samples: usize,
    thrust_samples: Option<usize>,
    torque_samples: Option<usize>,
    v_m_s: Num,
    v_sd: Num,
    j: Num,
    thrust_n: Num,
    thrust_sd: Num,
    torque_nm: Num,
    torque_sd: Num,
    ct: Num,
    cp: Num,
    temperature_k: Num,
    pressure_pa: Num,
    humidity: Num,
    transient: usize,
    flags: String,
}

/// The measured points of every file (`names` and `sets` in the same order).
pub fn points(names: &[String], sets: &[MeasuredSet]) -> Result<Vec<u8>, Error> {
    let rpm = propbet_units::omega_to_rpm;
    let rows = names.iter().zip(sets).flat_map(|(file, s)| {
        s.points.iter().map(move |p| {
            let (v, v_sd, j) = match p.speed {
                Speed::Airspeed(v) => (Some(v.mean), v.sd, None),
                Speed::AdvanceRatio(j) => (None, None, Some(j)),
            };
            let (thrust, torque, ct, cp) = match p.loads {
                Loads::Forces { thrust, torque } => (Some(thrust), torque, None, None),
                Loads::Coefficients { ct, cp } => (None, None, Some(ct), Some(cp)),
            };
            PointRow {
                file,
                format: s.format,
                label: &p.label,
                line_first: p.lines.0,
                line_last: p.lines.1,
                rpm: rpm(p.omega.mean).into(),
                rpm_sd: p.omega.sd.map(rpm).into(),
                samples: p.omega.n,
                thrust_samples: thrust.map(|t| t.n),
                torque_samples: torque.map(|t| t.n),
                v_m_s: v.into(),
                v_sd: v_sd.into(),
                j: j.into(),
                thrust_n: thrust.map(|t| t.mean).into(),
                thrust_sd: thrust.and_then(|t| t.sd).into(),
                torque_nm: torque.map(|t| t.mean).into(),
                torque_sd: torque.and_then(|t| t.sd).into(),
                ct: ct.into(),
                cp: cp.into(),
                temperature_k: p.air.temperature.into(),
                pressure_pa: p.air.pressure.into(),
                humidity: p.air.humidity.into(),
                transient: p.transient,
                flags: p.flags.join("; "),
            }
        })
    });
    Ok(csv_rows(rows, true)?)
}

/// A dropped row.
#[derive(serde::Serialize)]
struct DroppedRow<'a> {
    file: &'a str,
    /// Empty for a file refused whole.
    line: Option<usize>,
    /// A [`DropReason`] in snake case, or `file_refused`.
    reason: String,
    detail: &'a str,
}

/// The rows each file dropped, and the files refused whole.
pub fn dropped(names: &[String], sets: &[MeasuredSet], refused: &[Refused]) -> Result<Vec<u8>, Error> {
    let reason = |r: DropReason| {
        serde_json::to_value(r)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default()
    };
    let rows = names.iter().zip(sets).flat_map(|(file, s)| {
        s.dropped.iter().map(move |d| DroppedRow {
            file,
            line: Some(d.line),
            reason: reason(d.reason),
            detail: &d.detail,
        })
    });
    let refused = refused.iter().map(|r| DroppedRow {
        file: &r.file,
        line: None,
        reason: "file_refused".into(),
        detail: &r.reason,
    });
    Ok(csv_rows(rows.chain(refused), true)?)
}
