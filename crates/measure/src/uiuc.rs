//! UIUC Propeller Data Site files (Brandt & Selig; Deters): whitespace tables of coefficients,
//! CT = T/(rho n^2 D^4), CP = P/(rho n^3 D^5).
//!
//! - static: `RPM CT CP`, one row per RPM;
//! - sweep: `J CT CP eta` at the RPM given in the file name (`apcsf_10x4.7_kt0837_5018.txt`) or
//!   in a first line `RPM average ...` (some files carry it there).

use crate::reduce::Reduction;
use crate::{DropReason, Dropped, Format, Loads, LoggedAir, MeasuredPoint, MeasuredSet, ReadError, Speed, Value};

const RPM: f64 = std::f64::consts::PI / 30.0;

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

/// Reads a UIUC file; `name` is the file name (for the sweep RPM).
pub fn read(text: &str, name: Option<&str>) -> Result<MeasuredSet, ReadError> {
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty());
    let mut notes = Vec::new();
    let (mut hline, mut header) = lines.next().ok_or_else(|| ReadError::Empty("empty file".into()))?;
    let mut rpm_line = None;
    if header.to_ascii_lowercase().contains("average") {
        let rpm = last_number(header).ok_or_else(|| ReadError::Line {
            line: hline + 1,
            message: format!("'{}': no RPM value on the 'RPM average' line", header.trim()),
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
                "header '{}': expected 'J CT CP eta' (sweep) or 'RPM CT CP' (static), as UIUC files have",
                header.trim()
            ),
        });
    };
    let file_rpm = if sweep {
        let r = rpm_line.or_else(|| name.and_then(rpm_from_name)).ok_or_else(|| {
            ReadError::Option(
                "a UIUC J sweep needs its RPM: in the file name (…_5018.txt) or a first line 'RPM average 5018'".into(),
            )
        })?;
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
        let line = i + 1;
        let cells: Vec<&str> = l.split_whitespace().collect();
        let vals: Vec<Option<f64>> = cells
            .iter()
            .map(|c| c.parse::<f64>().ok().filter(|v| v.is_finite()))
            .collect();
        if vals.len() < 3 {
            dropped.push(Dropped {
                line,
                reason: DropReason::Missing,
                detail: format!("{} values, 3 needed", vals.len()),
            });
            continue;
        }
        if let Some(k) = vals[..3].iter().position(Option::is_none) {
            dropped.push(Dropped {
                line,
                reason: DropReason::NotANumber,
                detail: format!("{} = '{}'", cols[k], cells[k]),
            });
            continue;
        }
        let (a, ct, cp) = (vals[0].unwrap_or(0.0), vals[1].unwrap_or(0.0), vals[2].unwrap_or(0.0));
        let (rpm, speed) = match file_rpm {
            Some(r) => (r, Speed::AdvanceRatio(a)),
            None => (a, Speed::Airspeed(Value::single(0.0))),
        };
        if rpm <= 0.0 {
            dropped.push(Dropped {
                line,
                reason: if rpm == 0.0 {
                    DropReason::NotSpinning
                } else {
                    DropReason::NegativeRpm
                },
                detail: format!("RPM = {rpm}"),
            });
            continue;
        }
        points.push(MeasuredPoint {
            label: match file_rpm {
                Some(_) => format!("J = {a}"),
                None => format!("{rpm} rpm"),
            },
            lines: (line, line),
            omega: Value::single(rpm * RPM),
            speed,
            loads: Loads::Coefficients { ct, cp },
            air: LoggedAir::default(),
            transient: 0,
            nominal_omega: file_rpm.map(|r| r * RPM),
            flags: Vec::new(),
        });
    }
    if points.is_empty() {
        return Err(ReadError::NoUsableRows(crate::summarise_dropped(&dropped)));
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
    })
}

#[cfg(test)]
mod tests {
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
