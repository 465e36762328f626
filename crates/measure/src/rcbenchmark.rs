//! RCbenchmark / Tyto Robotics thrust-stand CSV exports.
//!
//! Columns are found by name (`Time (s)`, `ESC signal (µs)` or `ESC (µs)`, `Thrust (gf|kgf|N|lbf)`,
//! `Torque (N·m)`, `Motor Electrical Speed (RPM)`, `Motor Optical Speed (RPM)`); everything else
//! (accelerometers, load-cell millivolts, script columns such as `TargetRPM`) is ignored. A
//! temperature column counts as air temperature only when its name says air or ambient: the
//! Series 1780's `4N76 Temp (ºC)` is a probe on the motor.
//!
//! The app writes `Motor Electrical Speed` already divided by the pole pairs entered in it (its
//! `Mechanical Power` column is torque times that speed); `poles` rescales it by 2/poles for logs
//! recorded with the app's pole count at 2.

use crate::options::ReadOptions;
use crate::reduce::reduce_log;
use crate::set::{Format, MeasuredSet, ReadError, RpmSource};
use crate::table::{read_csv, samples, split_header, Column, Columns, CsvTable};
use crate::units::Quantity;

/// True when a header line looks like an RCbenchmark export.
pub fn looks_like(header: &str) -> bool {
    let h = header.to_ascii_lowercase();
    h.contains("time (s)") && h.contains("esc")
}

fn find(table: &CsvTable, pred: impl Fn(&str) -> bool) -> Option<(usize, String, Option<String>)> {
    table.headers.iter().enumerate().find_map(|(i, h)| {
        let (name, unit) = split_header(h);
        pred(&name.to_ascii_lowercase()).then(|| (i, h.clone(), unit))
    })
}

fn column(table: &CsvTable, q: Quantity, pred: impl Fn(&str) -> bool) -> Result<Option<Column>, ReadError> {
    find(table, pred)
        .map(|(i, h, unit)| Column::new(q, i, &h, unit.as_deref()))
        .transpose()
}

/// Non-zero readings of a column.
fn readings(table: &CsvTable, c: &Column) -> usize {
    table
        .rows
        .iter()
        .filter(|r| {
            r.cells
                .get(c.index)
                .and_then(|s| s.parse::<f64>().ok())
                .is_some_and(|v| v != 0.0 && v.is_finite())
        })
        .count()
}

/// The RPM column (optical or electrical, as asked or as logged; scaled by the pole count) and
/// the other one, with what was chosen in `notes`.
fn rotation(
    table: &CsvTable,
    opts: &ReadOptions,
    notes: &mut Vec<String>,
) -> Result<(RpmSource, Column, Option<Column>), ReadError> {
    let electrical = column(table, Quantity::Rotation, |n| n.contains("electrical speed"))?;
    let optical = column(table, Quantity::Rotation, |n| n.contains("optical speed"))?;
    let (source, mut rot) = match (opts.rpm_source, optical.clone(), electrical.clone()) {
        (Some(RpmSource::Optical), Some(o), _) => (RpmSource::Optical, o),
        (Some(RpmSource::Optical), None, _) => {
            return Err(ReadError::Option(
                "--rpm-source optical: the log has no 'Motor Optical Speed' column".into(),
            ))
        }
        (Some(RpmSource::Electrical), _, Some(e)) => (RpmSource::Electrical, e),
        (Some(RpmSource::Electrical), _, None) => {
            return Err(ReadError::Option(
                "--rpm-source electrical: the log has no 'Motor Electrical Speed' column".into(),
            ))
        }
        (None, Some(o), Some(e)) => {
            if readings(table, &o) * 2 >= readings(table, &e) && readings(table, &o) > 0 {
                (RpmSource::Optical, o)
            } else {
                notes.push("the optical RPM column reads zero: RPM from the electrical speed".into());
                (RpmSource::Electrical, e)
            }
        }
        (None, Some(o), None) => (RpmSource::Optical, o),
        (None, None, Some(e)) => (RpmSource::Electrical, e),
        (None, None, None) => {
            return Err(ReadError::MissingColumn {
                what: "RPM (Motor Optical Speed or Motor Electrical Speed)",
                columns: table.header_list(),
            })
        }
    };
    if readings(table, &rot) == 0 {
        return Err(ReadError::NoUsableRows(format!(
            "'{}' is zero in every row",
            rot.header
        )));
    }
    match (source, opts.poles) {
        (RpmSource::Electrical, Some(p)) => {
            rot.conv.scale *= 2.0 / p as f64;
            notes.push(format!(
                "RPM from '{}' multiplied by 2/{p} ({p} motor poles)",
                rot.header
            ));
        }
        (RpmSource::Electrical, None) => notes.push(format!(
            "RPM from '{}' as logged (the app divides by the pole pairs entered in it; give the pole count if it was left at 2)",
            rot.header
        )),
        (RpmSource::Optical, Some(_)) => notes.push("pole count ignored: RPM from the optical sensor".into()),
        (RpmSource::Optical, None) => notes.push(format!("RPM from the optical sensor ('{}')", rot.header)),
    }
    let other = match source {
        RpmSource::Optical => electrical,
        RpmSource::Electrical => optical,
    };
    Ok((source, rot, other))
}

/// Reads an export and reduces it to points.
pub fn read(text: &str, opts: &ReadOptions) -> Result<MeasuredSet, ReadError> {
    let table = read_csv(text)?;
    let all = table.header_list();
    let missing = |what| ReadError::MissingColumn {
        what,
        columns: all.clone(),
    };
    let mut notes: Vec<String> = table.dialect.iter().map(|d| format!("{d}: read as such")).collect();
    let mut cols = Columns {
        time: column(&table, Quantity::Time, |n| n == "time")?,
        esc: column(&table, Quantity::Esc, |n| n.starts_with("esc"))?,
        thrust: column(&table, Quantity::Thrust, |n| {
            n.starts_with("thrust") && !n.contains("load cell")
        })?,
        torque: column(&table, Quantity::Torque, |n| n.starts_with("torque"))?,
        airspeed: column(&table, Quantity::Airspeed, |n| {
            n.contains("airspeed") || n.contains("air speed") || n.contains("wind speed")
        })?,
        temperature: column(&table, Quantity::Temperature, |n| {
            (n.contains("air") || n.contains("ambient")) && n.contains("temp")
        })?,
        pressure: column(&table, Quantity::Pressure, |n| {
            n.contains("pressure") || n.contains("baro")
        })?,
        humidity: column(&table, Quantity::Humidity, |n| n.contains("humidity"))?,
        rotation: None,
        rotation_other: None,
    };
    if cols.thrust.is_none() {
        return Err(missing("thrust"));
    }
    // The app writes every load's unit in its header; a bare `Thrust` has lost it (a
    // renamed column), and gf read as N is 100 times off.
    for c in [&cols.thrust, &cols.torque].into_iter().flatten() {
        if split_header(&c.header).1.is_none() {
            return Err(ReadError::Option(format!(
                "column '{}' has no unit: thrust-stand exports write it, as in 'Thrust (gf)', 'Thrust (N)' or \
                 'Torque (N·m)'; put it back in the header, or name the columns and units with --columns map.toml",
                propbet_units::excerpt(&c.header)
            )));
        }
    }
    if cols.torque.is_none() {
        notes.push("no torque column: thrust-only comparison".into());
    }
    for h in &table.headers {
        let n = split_header(h).0.to_ascii_lowercase();
        if n.contains("temp") && !n.contains("air") && !n.contains("ambient") {
            notes.push(format!(
                "column '{h}' is a probe temperature, not air temperature: not used for density"
            ));
        }
    }
    let (source, rot, other) = rotation(&table, opts, &mut notes)?;
    cols.rotation_other = other;
    cols.rotation = Some(rot);
    let mut dropped = Vec::new();
    let s = samples(&table, &cols, &mut dropped);
    if !table.long_rows.is_empty() {
        notes.push(format!(
            "{} rows have more values than the header has names (extra values ignored): lines {}",
            table.long_rows.len(),
            list_lines(&table.long_rows)
        ));
    }
    let rows = table.rows.len();
    let (reduction, points) = reduce_log(s, false, &mut dropped, &mut notes, &opts.reduce);
    dropped.sort_by_key(|d| d.line);
    if points.is_empty() {
        return Err(crate::set::no_points(&dropped, rows, &notes));
    }
    Ok(MeasuredSet {
        format: Format::RcBenchmark,
        reduction,
        points,
        dropped,
        rows,
        has_torque: cols.torque.is_some(),
        rpm_source: Some(source),
        notes,
    })
}

/// "3, 7, 12" (at most 10, then "and N more").
pub fn list_lines(lines: &[usize]) -> String {
    let mut s: Vec<String> = lines.iter().take(10).map(usize::to_string).collect();
    if lines.len() > 10 {
        s.push(format!("and {} more", lines.len() - 10));
    }
    s.join(", ")
}
