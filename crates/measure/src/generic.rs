//! Generic CSV: one row per point (or a log, when a time column is mapped), columns named by a
//! small TOML column map or by self-describing headers.
//!
//! Column map (every key optional except `rpm` and `thrust`):
//! ```toml
//! rpm = { column = "Motor speed", unit = "rpm" }
//! thrust = { column = "Thrust", unit = "kgf" }
//! torque = "Torque (N·m)"            # unit taken from the header
//! airspeed = { column = "V", unit = "km/h" }
//! temperature = { column = "T", unit = "C" }
//! pressure = { column = "p", unit = "hPa" }
//! humidity = { column = "RH", unit = "%" }
//! time = { column = "t", unit = "s" }  # the rows are a log: steps or RPM bins
//! ```
//! Without a map, headers name themselves: `name (unit)`, `name [unit]` or `name_unit`
//! (`rpm, airspeed_m_s, thrust_N, torque_Nm, air_temp_C, pressure_Pa`).

use std::collections::BTreeMap;

use serde::Deserialize;

use crate::options::ReadOptions;
use crate::reduce::reduce_log;
use crate::set::{Format, MeasuredSet, ReadError};
use crate::table::{read_csv, samples, split_header, Column, Columns, CsvTable};
use crate::units::{conversion, Quantity};

#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum Entry {
    Name(String),
    Full { column: String, unit: Option<String> },
}

const KEYS: [(&str, Quantity); 11] = [
    ("time", Quantity::Time),
    ("esc", Quantity::Esc),
    ("rpm", Quantity::Rotation),
    ("thrust", Quantity::Thrust),
    ("torque", Quantity::Torque),
    ("airspeed", Quantity::Airspeed),
    ("temperature", Quantity::Temperature),
    ("pressure", Quantity::Pressure),
    ("humidity", Quantity::Humidity),
    ("voltage", Quantity::Voltage),
    ("current", Quantity::Current),
];

/// Header names that mean a quantity, longest first within each.
const ALIASES: [(Quantity, &[&str]); 11] = [
    (Quantity::Time, &["time", "t"]),
    (Quantity::Esc, &["esc_signal", "throttle", "esc"]),
    (Quantity::Rotation, &["rotation_speed", "speed_rpm", "rpm", "omega"]),
    (Quantity::Thrust, &["thrust"]),
    (Quantity::Torque, &["torque"]),
    (
        Quantity::Airspeed,
        &[
            "freestream",
            "wind_speed",
            "air_speed",
            "airspeed",
            "velocity",
            "vinf",
            "v",
        ],
    ),
    (
        Quantity::Temperature,
        &["air_temperature", "temperature", "air_temp", "t_air", "temp"],
    ),
    (Quantity::Pressure, &["air_pressure", "pressure", "baro", "p"]),
    (Quantity::Humidity, &["relative_humidity", "humidity", "rh"]),
    (Quantity::Voltage, &["voltage", "volts"]),
    (Quantity::Current, &["current", "amps"]),
];

fn slot(cols: &mut Columns, q: Quantity) -> &mut Option<Column> {
    match q {
        Quantity::Time => &mut cols.time,
        Quantity::Esc => &mut cols.esc,
        Quantity::Rotation => &mut cols.rotation,
        Quantity::Thrust => &mut cols.thrust,
        Quantity::Torque => &mut cols.torque,
        Quantity::Airspeed => &mut cols.airspeed,
        Quantity::Temperature => &mut cols.temperature,
        Quantity::Pressure => &mut cols.pressure,
        Quantity::Humidity => &mut cols.humidity,
        Quantity::Voltage => &mut cols.voltage,
        Quantity::Current => &mut cols.current,
    }
}

/// Columns from a TOML column map.
fn mapped(table: &CsvTable, map: &str) -> Result<Columns, ReadError> {
    let entries: BTreeMap<String, Entry> = toml::from_str(map).map_err(|e| {
        let at = e
            .span()
            .map_or_else(String::new, |s| format!("{}: ", propbet_units::place(map, s.start)));
        ReadError::Map(format!("{at}{}", propbet_units::excerpt(e.message())))
    })?;
    let mut cols = Columns::default();
    let mut taken: BTreeMap<usize, Vec<String>> = BTreeMap::new();
    for (key, entry) in entries {
        let Some(&(_, q)) = KEYS.iter().find(|(k, _)| *k == key) else {
            let known: Vec<&str> = KEYS.iter().map(|k| k.0).collect();
            return Err(ReadError::Map(format!(
                "unknown key '{key}' (known: {})",
                known.join(", ")
            )));
        };
        let (name, unit) = match entry {
            Entry::Name(n) => (n, None),
            Entry::Full { column, unit } => (column, unit),
        };
        let index = table.headers.iter().position(|h| *h == name).ok_or_else(|| {
            ReadError::Map(format!(
                "{key}: no column '{}' (columns: {})",
                propbet_units::excerpt(&name),
                table.header_list()
            ))
        })?;
        let unit = unit.or_else(|| split_header(&name).1);
        *slot(&mut cols, q) = Some(Column::new(q, index, &name, unit.as_deref())?);
        taken.entry(index).or_default().push(key);
    }
    // One column cannot hold two quantities: a copied line of the map, not a measurement.
    if let Some((index, keys)) = taken.iter().find(|(_, k)| k.len() > 1) {
        return Err(ReadError::Map(format!(
            "{} all name column '{}': each quantity needs its own column",
            keys.join(", "),
            propbet_units::excerpt(&table.headers[*index])
        )));
    }
    Ok(cols)
}

/// Columns from self-describing headers.
fn automatic(table: &CsvTable) -> Result<Columns, ReadError> {
    let mut cols = Columns::default();
    for (index, header) in table.headers.iter().enumerate() {
        let (name, unit) = split_header(header);
        let name = name.trim().to_ascii_lowercase().replace([' ', '-'], "_");
        'quantities: for (q, aliases) in ALIASES {
            for alias in aliases {
                let unit = if name == *alias {
                    unit.clone()
                } else if let Some(rest) = name.strip_prefix(alias).and_then(|r| r.strip_prefix('_')) {
                    if unit.is_some() {
                        continue;
                    }
                    if conversion(q, rest).is_none() {
                        if matches!(q, Quantity::Thrust | Quantity::Torque | Quantity::Airspeed) {
                            // `thrust_furlong`: the quantity is plain, the unit unknown.
                            return Err(ReadError::UnknownUnit {
                                column: header.clone(),
                                unit: rest.to_string(),
                                quantity: q.name(),
                                known: q.known_units(),
                            });
                        }
                        continue;
                    }
                    Some(rest.to_string())
                } else {
                    continue;
                };
                let s = slot(&mut cols, q);
                if s.is_none() {
                    *s = Some(Column::new(q, index, header, unit.as_deref())?);
                }
                break 'quantities;
            }
        }
    }
    Ok(cols)
}

/// Reads a generic CSV.
pub fn read(text: &str, opts: &ReadOptions) -> Result<MeasuredSet, ReadError> {
    let table = read_csv(text)?;
    let cols = match &opts.column_map {
        Some(map) => mapped(&table, map)?,
        None => automatic(&table)?,
    };
    let all = table.header_list();
    for (what, c) in [("rpm", &cols.rotation), ("thrust", &cols.thrust)] {
        if c.is_none() {
            return Err(ReadError::MissingColumn {
                what,
                columns: format!("{all}; name the columns with a column map"),
            });
        }
    }
    let mut notes: Vec<String> = table.dialect.iter().map(|d| format!("{d}: read as such")).collect();
    let mut used: Vec<String> = [
        &cols.time,
        &cols.rotation,
        &cols.airspeed,
        &cols.thrust,
        &cols.torque,
        &cols.temperature,
        &cols.pressure,
        &cols.humidity,
    ]
    .iter()
    .filter_map(|c| c.as_ref().map(|c| format!("'{}'", c.header)))
    .collect();
    used.dedup();
    notes.push(format!("columns used: {}", used.join(", ")));
    if cols.torque.is_none() {
        notes.push("no torque column: thrust-only comparison".into());
    }
    let mut dropped = Vec::new();
    let s = samples(&table, &cols, false, &mut dropped, &mut notes);
    let rows = table.rows.len();
    let at_rest = cols.time.is_some().then(|| crate::rest::at_rest(&s)).flatten();
    let (reduction, points) = reduce_log(s, cols.time.is_none(), &mut dropped, &mut notes, &opts.reduce);
    dropped.sort_by_key(|d| d.line);
    if points.is_empty() {
        return Err(crate::set::no_points(&dropped, rows, &notes));
    }
    Ok(MeasuredSet {
        format: Format::Generic,
        reduction,
        points,
        dropped,
        rows,
        has_torque: cols.torque.is_some(),
        rpm_source: None,
        notes,
        series: None,
        warnings: Vec::new(),
        at_rest,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Loads, Speed};
    use approx::assert_relative_eq;

    const HIDDEN: &str = "rpm,airspeed_m_s,thrust_N,torque_Nm,air_temp_C,pressure_Pa\n\
        6000.0,0.0000,0.58769,0.006685,15.00,101325\n6000.0,0.8310,0.54371,0.006395,15.00,101325\n";

    #[test]
    fn self_describing_headers() {
        let set = read(HIDDEN, &ReadOptions::default()).unwrap();
        assert_eq!(set.points.len(), 2);
        let p = &set.points[1];
        assert_relative_eq!(p.rpm(), 6000.0, epsilon = 1e-9);
        let Speed::Airspeed(v) = p.speed else { panic!() };
        assert_relative_eq!(v.mean, 0.831);
        assert_relative_eq!(p.air.temperature.unwrap(), 288.15);
        assert_relative_eq!(p.air.pressure.unwrap(), 101325.0);
        let Loads::Forces { thrust, torque } = p.loads else {
            panic!()
        };
        assert_relative_eq!(thrust.mean, 0.54371);
        assert_relative_eq!(torque.unwrap().mean, 0.006395);
    }

    #[test]
    fn column_map_with_units() {
        let csv = "Motor speed,Pull,V\n5000,0.1,36\n6000,0.2,0\n";
        let map = "rpm = \"Motor speed\"\nthrust = { column = \"Pull\", unit = \"kgf\" }\nairspeed = { column = \"V\", unit = \"km/h\" }\n";
        let opts = ReadOptions {
            column_map: Some(map.into()),
            ..Default::default()
        };
        let set = read(csv, &opts).unwrap();
        assert!(!set.has_torque);
        let Speed::Airspeed(v) = set.points[0].speed else {
            panic!()
        };
        assert_relative_eq!(v.mean, 10.0);
        let Loads::Forces { thrust, .. } = set.points[1].loads else {
            panic!()
        };
        assert_relative_eq!(thrust.mean, 0.2 * 9.80665);
    }

    #[test]
    fn semicolons_and_decimal_commas_read_as_the_comma_file_and_said() {
        let semi = HIDDEN.replace(',', ";").replace('.', ",");
        let a = read(HIDDEN, &ReadOptions::default()).unwrap();
        let b = read(&semi, &ReadOptions::default()).unwrap();
        assert_eq!(a.points, b.points);
        assert!(
            b.notes[0].starts_with("semicolon-separated values, with decimal commas"),
            "{:?}",
            b.notes
        );
        let tabbed = "Rotation speed (rpm)\tThrust (N)\n5000\t0,1\n6000\t0,2\n";
        let t = read(tabbed, &ReadOptions::default()).unwrap();
        assert_eq!(t.points.len(), 2);
        assert!(
            t.notes[0].starts_with("tab-separated values, with decimal commas"),
            "{:?}",
            t.notes
        );
    }

    #[test]
    fn a_time_column_over_rows_of_distinct_points_keeps_every_row() {
        let mut csv = String::from("t,rpm,thrust_N\n");
        for k in 0..12 {
            csv.push_str(&format!(
                "{},{},{}\n",
                k as f64 * 0.5,
                3000 + 500 * k,
                0.1 + 0.05 * k as f64
            ));
        }
        let map = "time = \"t\"\nrpm = \"rpm\"\nthrust = \"thrust_N\"\n";
        let set = read(
            &csv,
            &ReadOptions {
                column_map: Some(map.into()),
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(set.points.len(), 12);
        assert!(
            set.notes.iter().any(|n| n.contains("each row is used as a point")),
            "{:?}",
            set.notes
        );
        let e = read("rpm,thrust_N\n", &ReadOptions::default()).unwrap_err().to_string();
        assert!(e.contains("a header and no data rows"), "{e}");
    }

    #[test]
    fn map_errors_name_the_problem() {
        let csv = "a,b\n1,2\n";
        let e = |map: &str| {
            let opts = ReadOptions {
                column_map: Some(map.into()),
                ..Default::default()
            };
            read(csv, &opts).unwrap_err().to_string()
        };
        assert!(e("rpm = \"x\"").contains("no column 'x'"), "{}", e("rpm = \"x\""));
        assert!(e("speed = \"a\"").contains("unknown key 'speed'"));
        assert!(e("rpm = \"a\"\nthrust = { column = \"b\", unit = \"stone\" }").contains("unknown unit 'stone'"));
        assert!(e("rpm = \"a\"").contains("no thrust column"));
        assert!(e("rpm = [").contains("column map"));
        let auto = read("rpm,thrust_furlong\n1,2\n", &ReadOptions::default())
            .unwrap_err()
            .to_string();
        assert!(auto.contains("unknown unit 'furlong'"), "{auto}");
    }
}
