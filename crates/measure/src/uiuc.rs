//! UIUC Propeller Data Site files (Brandt & Selig; Deters): whitespace tables of coefficients,
//! CT = T/(rho n^2 D^4), CP = P/(rho n^3 D^5).
//!
//! - static: `RPM CT CP`, one row per RPM;
//! - sweep: `J CT CP eta` at the RPM given in the file name (`apcsf_10x4.7_kt0837_5018.txt`) or
//!   in a first line `RPM average ...` (some files carry it there).

use crate::set::{
    limits, DropReason, Dropped, Format, Loads, LoggedAir, MeasuredPoint, MeasuredSet, ReadError, Reduction, Speed,
    Value,
};

/// The RPM in a UIUC file name: the number after the last underscore.
pub fn rpm_from_name(name: &str) -> Option<f64> {
    let base = name.rsplit(['/', '\\']).next()?;
    let stem = base.rsplit_once('.').map_or(base, |(s, _)| s);
    let last = stem.rsplit('_').next()?;
    (last.len() >= 3 && last.bytes().all(|b| b.is_ascii_digit()))
        .then(|| last.parse().ok())
        .flatten()
}

fn last_number(line: &str) -> Option<f64> {
    line.split(|c: char| c.is_whitespace() || c == ':' || c == '=' || c == ',')
        .filter_map(|w| w.parse::<f64>().ok())
        .next_back()
}

/// One data row (file line `line`): a measured point, or why it is dropped. `file_rpm` is the
/// sweep's RPM (None: a static test, whose rows give it).
fn row(line: usize, l: &str, cols: &[String], file_rpm: Option<f64>) -> Result<MeasuredPoint, Dropped> {
    let cells: Vec<&str> = l.split_whitespace().collect();
    let vals: Vec<Option<f64>> = cells
        .iter()
        .map(|c| c.parse::<f64>().ok().filter(|v| v.is_finite()))
        .collect();
    if vals.len() < 3 {
        return Err(Dropped {
            line,
            reason: DropReason::Missing,
            detail: format!("{} values, 3 needed", vals.len()),
        });
    }
    if let Some(k) = vals[..3].iter().position(Option::is_none) {
        return Err(Dropped {
            line,
            reason: DropReason::NotANumber,
            detail: format!(
                "{} = '{}'",
                propbet_units::excerpt(&cols[k]),
                propbet_units::excerpt(cells[k])
            ),
        });
    }
    let (a, ct, cp) = (vals[0].unwrap_or(0.0), vals[1].unwrap_or(0.0), vals[2].unwrap_or(0.0));
    let first = match file_rpm {
        Some(_) => ("J", a, limits::ADVANCE_RATIO),
        None => ("RPM", propbet_units::rpm_to_omega(a), limits::OMEGA),
    };
    let checks = [first, ("CT", ct, limits::COEFFICIENT), ("CP", cp, limits::COEFFICIENT)];
    let slow = match file_rpm {
        Some(_) => None,
        None => limits::too_slow(propbet_units::rpm_to_omega(a)),
    };
    if let Some(detail) = limits::beyond(&checks).or(slow) {
        return Err(Dropped {
            line,
            reason: DropReason::Implausible,
            detail,
        });
    }
    let (rpm, speed) = match file_rpm {
        Some(r) => (r, Speed::AdvanceRatio(a)),
        None => (a, Speed::Airspeed(Value::single(0.0))),
    };
    if rpm <= 0.0 {
        return Err(Dropped {
            line,
            reason: if rpm == 0.0 {
                DropReason::NotSpinning
            } else {
                DropReason::NegativeRpm
            },
            detail: format!("RPM = {rpm}"),
        });
    }
    Ok(MeasuredPoint {
        label: match file_rpm {
            Some(_) => format!("J = {a}"),
            None => format!("{rpm} rpm"),
        },
        lines: (line, line),
        omega: Value::single(propbet_units::rpm_to_omega(rpm)),
        speed,
        loads: Loads::Coefficients { ct, cp },
        air: LoggedAir::default(),
        transient: 0,
        nominal_omega: file_rpm.map(propbet_units::rpm_to_omega),
        flags: Vec::new(),
        electric: None,
    })
}

/// Reads a UIUC file; `name` is the file name (for the sweep RPM).
pub fn read(text: &str, name: Option<&str>) -> Result<MeasuredSet, ReadError> {
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty());
    let mut notes = Vec::new();
    let (mut hline, mut header) = lines.next().ok_or_else(|| ReadError::Empty("empty file".into()))?;
    let mut rpm_line = None;
    if header.to_ascii_lowercase().contains("average") {
        let rpm = last_number(header).ok_or_else(|| ReadError::Line {
            line: hline + 1,
            message: format!(
                "'{}': no RPM value on the 'RPM average' line",
                propbet_units::excerpt(header)
            ),
        })?;
        rpm_line = Some(rpm);
        (hline, header) = lines
            .next()
            .ok_or_else(|| ReadError::Empty("no header after the RPM line".into()))?;
    }
    let cols: Vec<String> = header.split_whitespace().map(str::to_ascii_lowercase).collect();
    let is = |want: &[&str]| cols.len() >= want.len() && cols.iter().zip(want).all(|(a, b)| a == b);
    let sweep = if is(&["j", "ct", "cp"]) {
        true
    } else if is(&["rpm", "ct", "cp"]) {
        false
    } else {
        return Err(ReadError::Line {
            line: hline + 1,
            message: format!(
                "header '{}': expected 'J CT CP eta' (sweep) or 'RPM CT CP' (static), as UIUC files have; \
                 a log or table is read as CSV when its header separates names by commas, semicolons or tabs \
                 (name its columns with --columns map.toml)",
                propbet_units::excerpt(header)
            ),
        });
    };
    let file_rpm = if sweep {
        let r = rpm_line.or_else(|| name.and_then(rpm_from_name)).ok_or_else(|| {
            ReadError::Option(
                "a UIUC J sweep needs its RPM: in the file name (…_5018.txt) or a first line 'RPM average 5018'".into(),
            )
        })?;
        if !(propbet_units::rpm_to_omega(r) >= limits::OMEGA_MIN && propbet_units::rpm_to_omega(r) <= limits::OMEGA) {
            return Err(ReadError::Option(format!(
                "the sweep's RPM {r:.4e} (from the {}) is not a small propeller's",
                if rpm_line.is_some() {
                    "'RPM average' line"
                } else {
                    "file name"
                }
            )));
        }
        notes.push(format!(
            "advance-ratio sweep at {r:.0} rpm (from the {})",
            if rpm_line.is_some() {
                "'RPM average' line"
            } else {
                "file name"
            }
        ));
        Some(r)
    } else {
        notes.push("static test (J = 0)".into());
        None
    };
    let mut points = Vec::new();
    let mut dropped = Vec::new();
    let mut rows = 0;
    for (i, l) in lines {
        rows += 1;
        match row(i + 1, l, &cols, file_rpm) {
            Ok(p) => points.push(p),
            Err(d) => dropped.push(d),
        }
    }
    if points.is_empty() {
        return Err(crate::set::no_points(&dropped, rows, &[]));
    }
    Ok(MeasuredSet {
        format: if sweep { Format::UiucSweep } else { Format::UiucStatic },
        reduction: Reduction::Table,
        points,
        dropped,
        rows,
        has_torque: true,
        rpm_source: None,
        notes,
        series: None,
        warnings: Vec::new(),
        at_rest: None,
    })
}

/// One row of a UIUC geometry file (`<prop>_geom.txt`): blade station, chord and blade angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeometryRow {
    /// Radius over tip radius r/R [-].
    pub r_r: f64,
    /// Chord over tip radius c/R [-].
    pub c_r: f64,
    /// Blade angle β [rad] (the file gives degrees).
    pub beta: f64,
}

/// A UIUC-style geometry table: rows `r/R c/R beta[deg]`; header lines (a first word that is not
/// a number) are skipped. At least two rows.
pub fn read_geometry(text: &str) -> Result<Vec<GeometryRow>, ReadError> {
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let f: Vec<&str> = line.split_whitespace().collect();
        // Header lines before the table; within it every row must be numbers.
        if f.is_empty() || (rows.is_empty() && f[0].parse::<f64>().is_err()) {
            continue;
        }
        let bad = |message: String| ReadError::Line { line: i + 1, message };
        if f.len() < 3 {
            return Err(bad("expected r/R c/R beta".into()));
        }
        let v: Vec<f64> = f[..3]
            .iter()
            .map(|s| s.parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect::<Option<_>>()
            .ok_or_else(|| bad(format!("'{}' is not three numbers", propbet_units::excerpt(line))))?;
        rows.push(GeometryRow {
            r_r: v[0],
            c_r: v[1],
            beta: v[2].to_radians(),
        });
    }
    if rows.len() < 2 {
        return Err(ReadError::Empty("fewer than two rows of r/R c/R beta".into()));
    }
    Ok(rows)
}

/// Linear interpolation of a geometry table at r/R `x`: (c/R, β [rad]); None outside the table.
pub fn geometry_at(table: &[GeometryRow], x: f64) -> Option<(f64, f64)> {
    let i = table.windows(2).position(|w| w[0].r_r <= x && x <= w[1].r_r)?;
    let (a, b) = (table[i], table[i + 1]);
    let f = if b.r_r > a.r_r {
        (x - a.r_r) / (b.r_r - a.r_r)
    } else {
        0.0
    };
    Some((a.c_r + f * (b.c_r - a.c_r), a.beta + f * (b.beta - a.beta)))
}

#[cfg(test)]
mod tests {
    #[test]
    fn absurd_values_are_dropped_as_implausible() {
        let t = "RPM CT CP\n2523 0.0923 0.0397\n2811 1e308 0.0394\n1e20 0.09 0.04\n";
        let s = super::read(t, None).unwrap();
        assert_eq!(s.points.len(), 1);
        assert_eq!(s.dropped.len(), 2);
        assert!(s.dropped.iter().all(|d| d.reason == crate::DropReason::Implausible));
        assert!(s.dropped[0].detail.contains("CT = 1.0000e308"), "{:?}", s.dropped);
        let e = super::read("J CT CP eta\n0.1 0.1 0.05 0.2\n", Some("x_kt0001_99999999.txt")).unwrap_err();
        assert!(e.to_string().contains("not a small propeller's"), "{e}");
    }

    #[test]
    fn geometry_tables_and_bad_rows() {
        let t = super::read_geometry("r/R c/R beta\n0.15 0.12 30\n0.2 0.14 28\n").unwrap();
        assert_eq!(t.len(), 2);
        assert!((t[1].beta - 28f64.to_radians()).abs() < 1e-15);
        let (c, b) = super::geometry_at(&t, 0.175).unwrap();
        assert!((c - 0.13).abs() < 1e-12 && (b - 29f64.to_radians()).abs() < 1e-12);
        assert_eq!(super::geometry_at(&t, 0.3), None);
        let e = super::read_geometry("r/R c/R beta\n0.1 0.2 3\n0.1x 0.135 25.28\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 3") && e.contains("not three numbers"), "{e}");
        let e = super::read_geometry("0.1 0.2\n").unwrap_err().to_string();
        assert!(e.contains("line 1"), "{e}");
        let e = super::read_geometry("0.1 0.2 x\n0.2 0.1 3\n").unwrap_err().to_string();
        assert!(e.contains("line 1") && e.contains("not three numbers"), "{e}");
        assert!(super::read_geometry("0.1 0.2 3\n").is_err());
    }

    use super::*;

    #[test]
    fn names_carry_rpm() {
        assert_eq!(rpm_from_name("apcsf_10x4.7_kt0837_5018.txt"), Some(5018.0));
        assert_eq!(rpm_from_name("/x/y/da4002_9x6.75_1100md_2013.txt"), Some(2013.0));
        assert_eq!(rpm_from_name("apcsf_10x4.7_static_kt0835.txt"), None);
    }

    #[test]
    fn sweep_with_rpm_average_line() {
        let t = "RPM average: 5013.4\nJ       CT       CP       eta\n0.142   0.0994   0.0451   0.312\n0.177 nan 0.0446 0.375\n";
        let set = read(t, Some("whatever.txt")).unwrap();
        assert_eq!(set.format, Format::UiucSweep);
        assert_eq!(set.points.len(), 1);
        assert!((set.points[0].rpm() - 5013.4).abs() < 1e-9);
        assert_eq!(set.dropped[0].line, 4);
        assert_eq!(set.dropped[0].reason, DropReason::NotANumber);
    }

    #[test]
    fn sweep_without_rpm_is_an_error() {
        let e = read("J CT CP eta\n0.1 0.1 0.05 0.2\n", Some("x.txt")).unwrap_err();
        assert!(e.to_string().contains("needs its RPM"));
        let e = read("a b c\n1 2 3\n", None).unwrap_err();
        assert!(e.to_string().contains("line 1"), "{e}");
    }
}
