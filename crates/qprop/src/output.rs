//! QPROP's printed output: header (name, fluid), summary rows and the radial block.
//!
//! Rows are cut at QPROP's fixed column widths (qprop.f formats 2100 and 3100), because wide
//! numbers run into each other (`0.1121-104.2641`). Every number keeps its printed precision
//! ([`Printed::unit`]) so a comparison can be exactly as strict as the print.

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// A printed number and the size of one unit in its last printed digit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Printed {
    /// The value.
    pub value: f64,
    /// One unit of the last printed digit (0.001 for `2.386`, 1e1 for `0.1200E+05`).
    pub unit: f64,
}

impl Printed {
    fn parse(field: &str) -> Option<Printed> {
        let t = field.trim();
        if t.is_empty() {
            return None;
        }
        let value: f64 = t.parse().ok()?;
        let (mantissa, exp) = match t.find(['E', 'e']) {
            Some(k) => (&t[..k], t[k + 1..].parse::<i32>().ok()?),
            None => (t, 0),
        };
        let decimals = mantissa.find('.').map_or(0, |k| mantissa.len() - k - 1) as i32;
        Some(Printed {
            value,
            unit: 10f64.powi(exp - decimals),
        })
    }

    /// True when `x` rounds to this print: |x - value| <= unit/2, with `slack` extra units for
    /// values that sit on a rounding boundary.
    pub fn matches(&self, x: f64, slack: f64) -> bool {
        (x - self.value).abs() <= self.unit * (0.5 + slack)
    }
}

/// Column names of a summary row, in order.
pub const SUMMARY_COLUMNS: [&str; 19] = [
    "V", "rpm", "Dbeta", "T", "Q", "Pshaft", "Volts", "Amps", "effmot", "effprop", "adv", "CT", "CP", "DV", "eff",
    "Pelec", "Pprop", "cl_avg", "cd_avg",
];
/// Field widths of a summary row after the one-character marker (format 2100).
const SUMMARY_WIDTHS: [usize; 19] = [8, 12, 7, 12, 12, 12, 8, 10, 9, 9, 10, 12, 12, 9, 9, 12, 12, 9, 12];
/// Column names of a radial row.
pub const RADIAL_COLUMNS: [&str; 12] = [
    "radius", "chord", "beta", "Cl", "Cd", "Re", "Mach", "effi", "effp", "Wa", "Aswirl", "adv_wake",
];
/// Field widths of a radial row after the leading blank (format 3100).
const RADIAL_WIDTHS: [usize; 12] = [8, 8, 8, 9, 9, 9, 7, 9, 9, 12, 12, 12];

/// A QPROP output file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QpropOutput {
    /// Prop name from the header.
    pub name: String,
    /// Density [kg/m^3].
    pub rho: f64,
    /// Viscosity [kg/(m s)].
    pub mu: f64,
    /// Speed of sound [m/s].
    pub a: f64,
    /// Summary rows, each [`SUMMARY_COLUMNS`].
    pub summary: Vec<[Printed; 19]>,
    /// Radial rows of a single-point run, each [`RADIAL_COLUMNS`].
    pub radial: Vec<[Printed; 12]>,
}

/// Why a QPROP output could not be read.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ParseOutputError {
    /// A header value is missing.
    #[error("no '{0}' line in the header: is this a QPROP 1.22 output file?")]
    MissingHeader(&'static str),
    /// A data row is malformed.
    #[error("line {line}: {message}")]
    BadRow {
        /// Line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
}

fn fields<const N: usize>(line: usize, rest: &str, widths: &[usize; N]) -> Result<[Printed; N], ParseOutputError> {
    let chars: Vec<char> = rest.chars().collect();
    let mut out = [Printed { value: 0.0, unit: 0.0 }; N];
    let mut pos = 0;
    for (k, w) in widths.iter().enumerate() {
        let end = (pos + w).min(chars.len());
        let field: String = chars[pos.min(end)..end].iter().collect();
        out[k] = Printed::parse(&field).ok_or_else(|| ParseOutputError::BadRow {
            line,
            message: format!("field {} ('{}') is not a number", k + 1, field.trim()),
        })?;
        pos = end;
    }
    Ok(out)
}

fn header_value(text: &str, key: &'static str) -> Result<f64, ParseOutputError> {
    text.lines()
        .find_map(|l| l.strip_prefix(key))
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|t| t.parse().ok())
        .ok_or(ParseOutputError::MissingHeader(key))
}

/// Parses a QPROP 1.22 output file.
pub fn parse_output(text: &str) -> Result<QpropOutput, ParseOutputError> {
    let rho = header_value(text, "#   rho =")?;
    let mu = header_value(text, "#   mu  =")?;
    let a = header_value(text, "#   a   =")?;
    let lines: Vec<&str> = text.lines().collect();
    let version = lines
        .iter()
        .position(|l| l.starts_with("# QPROP Version"))
        .ok_or(ParseOutputError::MissingHeader("# QPROP Version"))?;
    let name = lines
        .get(version + 2)
        .and_then(|l| l.strip_prefix("# "))
        .unwrap_or("")
        .trim()
        .to_string();
    let mut summary = Vec::new();
    let mut radial = Vec::new();
    let mut in_summary = false;
    let mut in_radial = false;
    for (i, l) in lines.iter().enumerate() {
        let lineno = i + 1;
        if l.starts_with("#  V(m/s)") {
            in_summary = true;
            continue;
        }
        if l.starts_with("#  radius") {
            in_summary = false;
            in_radial = true;
            continue;
        }
        if in_summary {
            // Data rows start with a blank, or with '#' in a single-point run; a '#' line with
            // nothing numeric is a separator.
            let Some(first) = l.chars().next() else { continue };
            let rest = &l[first.len_utf8()..];
            if rest.trim().is_empty() || !(first == ' ' || first == '#') {
                continue;
            }
            summary.push(fields(lineno, rest, &SUMMARY_WIDTHS)?);
        } else if in_radial {
            let Some(rest) = l.strip_prefix(' ') else { continue };
            if rest.trim().is_empty() {
                continue;
            }
            radial.push(fields(lineno, rest, &RADIAL_WIDTHS)?);
        }
    }
    Ok(QpropOutput {
        name,
        rho,
        mu,
        a,
        summary,
        radial,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn printed_units() {
        let check = |s: &str, v: f64, u: f64| {
            let p = Printed::parse(s).unwrap();
            assert_eq!(p.value, v);
            assert!((p.unit - u).abs() <= u * 1e-12, "{s}: {}", p.unit);
        };
        check("2.386", 2.386, 1e-3);
        check("0.1200E+05", 12000.0, 10.0);
        check("-0.2333E-03", -0.2333e-3, 1e-7);
        check("28547", 28547.0, 1.0);
        check("8000.", 8000.0, 1.0);
    }

    #[test]
    fn glued_fields_are_split_by_width() {
        let text = include_str!("../../../tests/reference/qprop/cam6x3_Vsweep_rpm16000.out");
        let out = parse_output(text).unwrap();
        assert_eq!(out.summary.len(), 31);
        let last = out.summary[30];
        assert_eq!(last[8].value, 0.1121);
        assert_eq!(last[9].value, -104.2641);
        assert_eq!(out.rho, 1.225);
        assert_eq!(out.name, "Graupner CAM 6x3 folder");
    }

    #[test]
    fn single_point_with_radial_block() {
        let text = include_str!("../../../tests/reference/qprop/cam6x3_point_V0_rpm12000.out");
        let out = parse_output(text).unwrap();
        assert_eq!(out.summary.len(), 1);
        assert_eq!(out.radial.len(), 25);
        assert_eq!(out.radial[0][5].value, 28547.0);
        assert_eq!(out.summary[0][3].value, 2.386);
    }

    #[test]
    fn not_an_output() {
        assert_eq!(
            parse_output("hello").unwrap_err(),
            ParseOutputError::MissingHeader("#   rho =")
        );
    }
}
