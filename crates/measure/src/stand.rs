//! Thrust-stand logs: RCbenchmark's and Tyto Robotics' older app (Series 1520, 1580, 1585,
//! 1780), Tyto's Flight Stand software and Tyto's online test database, read by column name in
//! any subset and order.
//!
//! Names, compared in lower case with the unit in the last parentheses apart:
//! - time: `Time (s)`;
//! - ESC command: `ESC signal (µs)`, `ESC (µs)`, `ESC throttle (μs)`, `Throttle (µs)`, a DShot
//!   column without a unit (a label: any unit is kept as written);
//! - thrust: `Thrust (gf|kgf|N|lbf)`, Flight Stand's `force Fz (thrust) (N)`; not the load
//!   cells' millivolts, not an efficiency;
//! - torque: `Torque (N·m)`, `torque MZ (torque) (N⋅m)`;
//! - rotation: `Motor Electrical Speed (RPM)`, `Motor Optical Speed (RPM)`, `rotation speed
//!   (rpm|rad/s)`;
//! - air: a temperature whose name says air or ambient (the Series 1780's `4N76 Temp (ºC)` is
//!   a probe on the motor), pressure, humidity, airspeed.
//!
//! Several propulsion units in one file are several series: Flight Stand's `Powertrain 2 -
//! ...` prefixes, the Series 1780's B side (`Thrust B (N)`). Everything else (voltage, current,
//! accelerometers, script columns after `App message`) is not read.
//!
//! The app writes `Motor Electrical Speed` already divided by the pole pairs entered in it (its
//! `Mechanical Power` column is torque times that speed); `poles` rescales it by 2/poles for logs
//! recorded with the app's pole count at 2.

use crate::options::ReadOptions;
use crate::reduce::reduce_log;
use crate::set::{Format, MeasuredSet, ReadError, RpmSource};
use crate::table::{read_csv, samples, split_header, Column, Columns, CsvTable};
use crate::units::{Conversion, Quantity};

/// A header as the reader sees it.
#[derive(Debug, Clone)]
struct Named {
    index: usize,
    header: String,
    /// Lower case, without the series' prefix or suffix and the unit.
    name: String,
    unit: Option<String>,
    /// `Powertrain 2`, `B`; None for the first (or only) unit.
    series: Option<String>,
}

fn named(index: usize, header: &str) -> Named {
    let (name, unit) = split_header(header);
    let mut name = name.to_lowercase().split_whitespace().collect::<Vec<_>>().join(" ");
    let mut series = None;
    if let Some(rest) = name.strip_prefix("powertrain ") {
        if let Some((id, quantity)) = rest.split_once(" - ") {
            series = Some(format!("Powertrain {id}"));
            name = quantity.to_string();
        }
    }
    // The Series 1780's second side: `Thrust B (N)`, `Motor Optical Speed B (RPM)`.
    for side in [" a", " b"] {
        if let Some(stem) = name.strip_suffix(side) {
            if series.is_none() && is_load_or_speed(stem) {
                series = (side == " b").then(|| "B".to_string());
                name = stem.to_string();
            }
        }
    }
    Named {
        index,
        header: header.to_string(),
        name,
        unit,
        series,
    }
}

fn is_load_or_speed(n: &str) -> bool {
    thrust_name(n) || torque_name(n) || speed_name(n).is_some() || esc_name(n)
}

fn not_a_reading(n: &str) -> bool {
    [
        "efficien",
        "load cell",
        "target",
        "(mv)",
        "mv)",
        "power",
        "temp",
        "volt",
        "current",
    ]
    .iter()
    .any(|w| n.contains(w))
}

fn thrust_name(n: &str) -> bool {
    n.contains("thrust") && !not_a_reading(n)
}

fn torque_name(n: &str) -> bool {
    n.contains("torque") && !not_a_reading(n)
}

fn esc_name(n: &str) -> bool {
    (n.starts_with("esc") || n.starts_with("throttle") || n.starts_with("dshot")) && !not_a_reading(n)
}

/// Which sensor a rotation column names, or None.
fn speed_name(n: &str) -> Option<Option<RpmSource>> {
    if not_a_reading(n) {
        return None;
    }
    if n.contains("electrical speed") {
        Some(Some(RpmSource::Electrical))
    } else if n.contains("optical speed") {
        Some(Some(RpmSource::Optical))
    } else if n.contains("rotation speed") || n == "motor speed" || n == "rpm" {
        Some(None)
    } else {
        None
    }
}

/// True when a header (its cells) is a thrust stand's: RCbenchmark's time and ESC columns, or
/// a rotation speed named as the stands name it beside a thrust column with its unit.
pub fn looks_like(headers: &[String]) -> bool {
    let names: Vec<Named> = headers.iter().enumerate().map(|(i, h)| named(i, h)).collect();
    let has = |f: &dyn Fn(&Named) -> bool| names.iter().any(f);
    let time = |n: &Named| n.name == "time" && n.unit.as_deref() == Some("s");
    let classic = has(&time) && has(&|n| esc_name(&n.name));
    let speed = has(&|n| {
        speed_name(&n.name).is_some_and(|s| s.is_some()) || (n.name.contains("rotation speed") && n.series.is_some())
    });
    let tyto = has(&time) && has(&|n| n.name.contains("rotation speed"));
    let thrust = has(&|n| thrust_name(&n.name) && n.unit.is_some());
    classic || (thrust && (speed || tyto))
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

/// Cells of a column that hold anything.
fn filled(table: &CsvTable, index: usize) -> usize {
    table
        .rows
        .iter()
        .filter(|r| r.cells.get(index).is_some_and(|c| !c.is_empty()))
        .count()
}

/// One series' columns, by name.
struct Series {
    name: Option<String>,
    cols: Vec<Named>,
}

impl Series {
    fn find(&self, pred: impl Fn(&str) -> bool) -> Option<&Named> {
        self.cols.iter().find(|n| pred(&n.name))
    }

    fn column(&self, q: Quantity, pred: impl Fn(&str) -> bool) -> Result<Option<Column>, ReadError> {
        self.find(pred)
            .map(|n| Column::new(q, n.index, &n.header, n.unit.as_deref()))
            .transpose()
    }
}

/// The series of a header: the columns without a series belong to every series (time, air);
/// the shared columns make a series of their own only with a thrust column among them, or when
/// the file names no series (then the search for a thrust column reports what is missing).
fn series(table: &CsvTable) -> Vec<Series> {
    let names: Vec<Named> = table.headers.iter().enumerate().map(|(i, h)| named(i, h)).collect();
    let mut ids: Vec<Option<String>> = vec![None];
    for n in &names {
        if n.series.is_some() && !ids.contains(&n.series) {
            ids.push(n.series.clone());
        }
    }
    let named_series = ids.len() > 1;
    ids.into_iter()
        .map(|id| {
            // A series' own columns first: they are found before a shared one of the same name.
            let (mut cols, shared): (Vec<Named>, Vec<Named>) = names
                .iter()
                .filter(|n| n.series.is_none() || n.series == id)
                .cloned()
                .partition(|n| n.series.is_some());
            cols.extend(shared);
            Series { name: id, cols }
        })
        .filter(|s| s.name.is_some() || !named_series || s.cols.iter().any(|n| thrust_name(&n.name)))
        .collect()
}

/// The RPM column (optical or electrical, as asked or as logged; scaled by the pole count) and
/// the other one, with what was chosen in `notes`.
fn rotation(
    table: &CsvTable,
    s: &Series,
    opts: &ReadOptions,
    notes: &mut Vec<String>,
) -> Result<(RpmSource, Column, Option<Column>), ReadError> {
    let logged = |c: Option<Column>| c.filter(|c| filled(table, c.index) > 0);
    let electrical = logged(s.column(Quantity::Rotation, |n| {
        speed_name(n) == Some(Some(RpmSource::Electrical))
    })?);
    let optical = logged(s.column(Quantity::Rotation, |n| speed_name(n) == Some(Some(RpmSource::Optical)))?);
    let plain = logged(s.column(Quantity::Rotation, |n| speed_name(n) == Some(None))?);
    if let Some(p) = plain.filter(|_| optical.is_none() && electrical.is_none()) {
        notes.push(format!("RPM from '{}', as the stand reports it", p.header));
        return Ok((RpmSource::Optical, p, None));
    }
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
                what: "RPM (Motor Optical Speed, Motor Electrical Speed or rotation speed, with a reading)",
                columns: table.header_list(),
            })
        }
    };
    if readings(table, &rot) == 0 {
        return Err(ReadError::NoUsableRows(format!(
            "'{}' is zero in every row: the propeller never turned",
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

/// The format a header's names belong to.
fn format_of(table: &CsvTable) -> Format {
    let names: Vec<Named> = table.headers.iter().enumerate().map(|(i, h)| named(i, h)).collect();
    if names.iter().any(|n| n.header.to_lowercase().starts_with("powertrain")) {
        Format::FlightStand
    } else if names.iter().any(|n| n.name.contains("rotation speed")) {
        Format::TytoDatabase
    } else {
        Format::RcBenchmark
    }
}

/// Reads a log: one set per series (the first is the file's only one, mostly).
pub fn read(text: &str, opts: &ReadOptions) -> Result<Vec<MeasuredSet>, ReadError> {
    let table = read_csv(text)?;
    let format = format_of(&table);
    let all = series(&table);
    let many = all.len() > 1;
    let mut sets = Vec::new();
    let mut refused = Vec::new();
    for s in &all {
        match read_series(&table, s, format, opts) {
            Ok(set) => sets.push(set),
            Err(e) if many => refused.push(format!("{}: {e}", s.name.as_deref().unwrap_or("the first series"))),
            Err(e) => return Err(e),
        }
    }
    if sets.is_empty() {
        return Err(ReadError::NoUsableRows(refused.join("; ")));
    }
    for r in refused {
        sets[0].notes.push(format!("series not read: {r}"));
    }
    Ok(sets)
}

fn read_series(table: &CsvTable, s: &Series, format: Format, opts: &ReadOptions) -> Result<MeasuredSet, ReadError> {
    let missing = |what| ReadError::MissingColumn {
        what,
        columns: table.header_list(),
    };
    let mut notes: Vec<String> = table.dialect.iter().map(|d| format!("{d}: read as such")).collect();
    if let Some(name) = &s.name {
        notes.push(format!("series '{name}' of a file of several"));
    }
    // A column the log never wrote (an ESC column of a DShot run) is no column.
    let logged = |c: Option<Column>, notes: &mut Vec<String>| match c {
        Some(c) if filled(table, c.index) == 0 => {
            notes.push(format!("column '{}' is empty in every row: not used", c.header));
            None
        }
        c => c,
    };
    let esc = s.find(esc_name).map(|n| Column {
        index: n.index,
        header: n.header.clone(),
        conv: Conversion {
            scale: 1.0,
            offset: 0.0,
        },
    });
    let mut cols = Columns {
        time: s.column(Quantity::Time, |n| n == "time")?,
        esc: logged(esc, &mut notes),
        thrust: s.column(Quantity::Thrust, thrust_name)?,
        torque: logged(s.column(Quantity::Torque, torque_name)?, &mut notes),
        airspeed: s.column(Quantity::Airspeed, |n| {
            n.contains("airspeed") || n.contains("air speed") || n.contains("wind speed")
        })?,
        temperature: s.column(Quantity::Temperature, |n| {
            (n.contains("air") || n.contains("ambient")) && n.contains("temp")
        })?,
        pressure: s.column(Quantity::Pressure, |n| n.contains("pressure") || n.contains("baro"))?,
        humidity: s.column(Quantity::Humidity, |n| n.contains("humidity"))?,
        voltage: s.column(Quantity::Voltage, |n| n == "voltage")?,
        current: s.column(Quantity::Current, |n| n == "current")?,
        rotation: None,
        rotation_other: None,
    };
    let Some(thrust) = &cols.thrust else {
        return Err(missing("thrust"));
    };
    if filled(table, thrust.index) == 0 {
        return Err(ReadError::NoUsableRows(format!(
            "'{}' is empty in every row: no thrust was logged",
            thrust.header
        )));
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
    for n in &s.cols {
        if n.name.contains("temp") && !n.name.contains("air") && !n.name.contains("ambient") {
            notes.push(format!(
                "column '{}' is a probe temperature, not air temperature: not used for density",
                n.header
            ));
        }
    }
    let (source, rot, other) = rotation(table, s, opts, &mut notes)?;
    cols.rotation_other = other;
    cols.rotation = Some(rot);
    let mut dropped = Vec::new();
    let samples = samples(table, &cols, true, &mut dropped, &mut notes);
    if !table.long_rows.is_empty() {
        notes.push(format!(
            "{} rows have more values than the header has names (extra values ignored): lines {}",
            table.long_rows.len(),
            list_lines(&table.long_rows)
        ));
    }
    let rows = table.rows.len();
    let at_rest = crate::rest::at_rest(&samples);
    let (reduction, points) = reduce_log(samples, false, &mut dropped, &mut notes, &opts.reduce);
    dropped.sort_by_key(|d| d.line);
    if points.is_empty() {
        return Err(crate::set::no_points(&dropped, rows, &notes));
    }
    let mut set = MeasuredSet {
        format,
        reduction,
        points,
        dropped,
        rows,
        has_torque: cols.torque.is_some(),
        rpm_source: Some(source),
        notes,
        series: s.name.clone(),
        warnings: Vec::new(),
        at_rest,
    };
    set.warnings = crate::plausible::warnings(&set);
    Ok(set)
}

/// "3, 7, 12" (at most 10, then "and N more").
pub fn list_lines(lines: &[usize]) -> String {
    let mut s: Vec<String> = lines.iter().take(10).map(usize::to_string).collect();
    if lines.len() > 10 {
        s.push(format!("and {} more", lines.len() - 10));
    }
    s.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_of_every_spelling_and_series() {
        let n = named(3, "Powertrain 2 - force Fz (thrust) (N)");
        assert_eq!(
            (n.series.as_deref(), n.name.as_str(), n.unit.as_deref()),
            (Some("Powertrain 2"), "force fz (thrust)", Some("N"))
        );
        assert!(thrust_name(&n.name));
        let n = named(0, "Thrust B (N)");
        assert_eq!((n.series.as_deref(), n.name.as_str()), (Some("B"), "thrust"));
        let n = named(0, "Motor Optical Speed A (RPM)");
        assert_eq!((n.series, n.name.as_str()), (None, "motor optical speed"));
        assert!(!thrust_name("propeller efficiency (thrust)"));
        assert!(!thrust_name("thrust load cell"));
        assert_eq!(speed_name("rotation speed"), Some(None));
        assert!(esc_name("esc throttle") && esc_name("dshot") && !esc_name("esc temperature"));
        let h = |s: &str| s.split(',').map(str::to_string).collect::<Vec<_>>();
        assert!(looks_like(&h("Torque (N·m),Thrust (N),Motor Electrical Speed (RPM)")));
        assert!(looks_like(&h(
            "Time (s),Powertrain 1 - force Fz (thrust) (kgf),Powertrain 1 - rotation speed (rpm)"
        )));
        assert!(looks_like(&h(
            "Time (s),Throttle (µs),Rotation speed (rpm),Thrust (kgf)"
        )));
        assert!(!looks_like(&h("rpm,thrust_N")));
        assert!(!looks_like(&h("time,esc,rpm,thrust_N")));
    }

    /// The Series 1780's two sides as two series, a DShot ESC column without a unit, a speed in
    /// rad/s.
    #[test]
    fn a_dual_stand_gives_one_set_per_side() {
        let mut text = String::from(
            "Time (s),DShot,Thrust (N),Torque (N·m),Motor Optical Speed (rad/s),Thrust B (N),Torque B (N·m),Motor Optical Speed B (rad/s)\n",
        );
        for (k, w) in [300.0, 500.0, 700.0].iter().enumerate() {
            for i in 0..10 {
                let t = 1e-4 * w * w;
                text.push_str(&format!(
                    "{},{},{t},{},{w},{},{},{}\n",
                    10 * k + i,
                    100 * k,
                    t / 60.0,
                    t / 2.0,
                    t / 120.0,
                    w / 2.0
                ));
            }
        }
        let sets = read(&text, &ReadOptions::default()).unwrap();
        assert_eq!(sets.len(), 2);
        assert_eq!(
            (sets[0].series.as_deref(), sets[1].series.as_deref()),
            (None, Some("B"))
        );
        assert_eq!(sets[0].points.len(), 3);
        assert!(
            (sets[0].points[2].omega.mean - 700.0).abs() < 1e-9,
            "rad/s read as such"
        );
        assert!((sets[1].points[2].omega.mean - 350.0).abs() < 1e-9);
        assert_eq!(
            sets[0].reduction,
            crate::Reduction::Steps,
            "the DShot column makes the steps"
        );
    }
}
