//! QPROP 1.22's motor files (`qprop.f`, the motor block; `io.f`'s `FREAD`, `IREAD`, `RREAD`).
//!
//! A line whose first character is `#` or `!` is a comment, a blank line is skipped, and
//! everything after a `!` is a label. The first line left is the motor's name, the next its
//! model index, and each line after that one parameter: the line's first number (QPROP reads
//! one value per line: `0.300 0.270 ! Io` is Io = 0.300). At most 10 parameters, as QPROP's
//! `NMPDIM`.

use thiserror::Error;

use crate::model::{Motor, MotorError};

/// QPROP 1.22's largest number of motor parameters (`NMPDIM`).
pub const MAX_PARAMETERS: usize = 10;

/// A motor file: its name, its motor, and the parameters and labels as written.
#[derive(Debug, Clone, PartialEq)]
pub struct MotorFile {
    /// The name line.
    pub name: String,
    /// The motor.
    pub motor: Motor,
    /// The parameters in the file's order.
    pub params: Vec<f64>,
    /// Each parameter's label (the text after its `!`, trimmed; empty where none).
    pub labels: Vec<String>,
}

/// Why a motor file cannot be read.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("line {line}: {kind}")]
pub struct ParseMotorError {
    /// The 1-based line the problem is on (the last line for a file that ends early).
    pub line: usize,
    /// What is wrong.
    pub kind: ParseMotorErrorKind,
}

/// What is wrong with a motor file.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ParseMotorErrorKind {
    /// The file ends before the name or the model index.
    #[error("the file ends before its {0} (a QPROP motor file: a name line, a motor type line, then R, Io, Kv one per line)")]
    Ends(&'static str),
    /// The model line holds no integer.
    #[error("'{0}' is not a motor type (an integer: 1 or 2)")]
    NotAType(String),
    /// A parameter line holds no number.
    #[error("'{0}' is not a number")]
    NotANumber(String),
    /// More parameters than QPROP holds.
    #[error("more than {MAX_PARAMETERS} parameters: QPROP 1.22 stops at this line")]
    TooMany,
    /// The constants are not a motor.
    #[error("{0}")]
    Motor(MotorError),
}

/// The meaningful lines of a QPROP input: (1-based line number, text before any `!`, label).
fn data_lines(text: &str) -> impl Iterator<Item = (usize, &str, &str)> {
    text.lines().enumerate().filter_map(|(k, line)| {
        if line.starts_with(['#', '!']) || line.trim().is_empty() {
            return None;
        }
        let (data, label) = line.split_once('!').unwrap_or((line, ""));
        Some((k + 1, data, label.trim()))
    })
}

/// The first number of a line, as Fortran reads it (`D` exponents too).
fn first_number(data: &str) -> Option<f64> {
    let word = data.split([' ', '\t', ',']).find(|w| !w.is_empty())?;
    word.replace(['d', 'D'], "e").parse().ok()
}

/// Reads a motor file as QPROP 1.22 does, and checks that its constants describe a motor.
pub fn parse_motor(text: &str) -> Result<MotorFile, ParseMotorError> {
    let last = text.lines().count().max(1);
    let mut lines = data_lines(text);
    let ends = |what| ParseMotorError {
        line: last,
        kind: ParseMotorErrorKind::Ends(what),
    };
    let (_, name, _) = lines.next().ok_or_else(|| ends("name"))?;
    let (type_line, data, _) = lines.next().ok_or_else(|| ends("motor type"))?;
    let word = data.split([' ', '\t', ',']).find(|w| !w.is_empty()).unwrap_or("");
    let kind: i64 = word.parse().map_err(|_| ParseMotorError {
        line: type_line,
        kind: ParseMotorErrorKind::NotAType(propbet_units::excerpt(data.trim())),
    })?;
    let (mut params, mut labels, mut at) = (Vec::new(), Vec::new(), Vec::new());
    for (line, data, label) in lines {
        if params.len() == MAX_PARAMETERS {
            return Err(ParseMotorError {
                line,
                kind: ParseMotorErrorKind::TooMany,
            });
        }
        let value = first_number(data).ok_or_else(|| ParseMotorError {
            line,
            kind: ParseMotorErrorKind::NotANumber(propbet_units::excerpt(data.trim())),
        })?;
        params.push(value);
        labels.push(label.to_string());
        at.push(line);
    }
    let motor = Motor::from_params(kind, &params).map_err(|e| {
        let line = match &e {
            MotorError::Parameter { index, .. } => at[*index],
            MotorError::TooFewParameters { .. } => last,
            MotorError::UnknownType(_) => type_line,
        };
        ParseMotorError {
            line,
            kind: ParseMotorErrorKind::Motor(e),
        }
    })?;
    Ok(MotorFile {
        name: name.trim().to_string(),
        motor,
        params,
        labels,
    })
}

/// Writes a motor file QPROP 1.22 reads back to the same motor: `comments` first (each a
/// `#` line), then the name, the type and one parameter per line with its label.
pub fn write_motor(file: &MotorFile, comments: &[String]) -> String {
    let mut out = String::new();
    for c in comments {
        out.push_str(&format!("# {c}\n"));
    }
    out.push_str(&format!("\n {}\n\n", file.name.replace('!', "")));
    out.push_str(&format!(" {}        ! motor type\n\n", file.motor.kind.index()));
    let defaults = file.motor.kind.labels();
    for (i, p) in file.params.iter().enumerate() {
        let label = file
            .labels
            .get(i)
            .filter(|l| !l.is_empty())
            .map(String::as_str)
            .or(defaults.get(i).copied())
            .unwrap_or("");
        out.push_str(&format!(" {:<14} ! {label}\n", p.to_string()));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drelas_files_read_as_qprop_reads_them() {
        let s300 = "\nSpeed-300 7302 (7V) 5.33:1       \n\n 1     ! motor type (brushed DC)\n\n \
                    0.450    ! Rmotor (Ohms) \n 0.300    0.270    ! Io     (Amps) \n 826.0   413.0    2200.0   ! Kv     (rpm/Volt)\n";
        let f = parse_motor(s300).unwrap();
        assert_eq!(f.name, "Speed-300 7302 (7V) 5.33:1");
        assert_eq!(f.params, vec![0.45, 0.3, 826.0], "the first number of each line");
        assert_eq!(f.labels[0], "Rmotor (Ohms)");
        let s280 = "\nSpeed-280 6328 (6V) direct drive\n\n 2     ! motor type (brushed DC)\n\n 0.70 ! R0\n \
                    0.160\n 3800.0\n 3800.0\n 1.0E-5\n 5.7E-5\n 4.0D-8\n 0.012\n";
        let f = parse_motor(s280).unwrap();
        assert_eq!(f.motor.kind, crate::MotorKind::Dc2);
        assert_eq!(f.motor.io2, 4.0e-8);
        // Written and read back, the same motor.
        let back = parse_motor(&write_motor(&f, &["fitted".to_string()])).unwrap();
        assert_eq!(back.motor, f.motor);
        assert_eq!(back.name, f.name);
    }

    #[test]
    fn bad_files_name_their_line() {
        let e = parse_motor("name\n 3\n 0.1\n 1\n 1000\n").unwrap_err();
        assert_eq!(e.line, 2, "{e}");
        assert!(e.to_string().contains("motor type 3"), "{e}");
        let e = parse_motor("name\n 1\n -0.1 ! R\n 1\n 1000\n").unwrap_err();
        assert_eq!(e.line, 3, "{e}");
        assert!(e.to_string().contains("R = -0.1"), "{e}");
        let e = parse_motor("name\n 1\n 0.1\n 1\n 0\n").unwrap_err();
        assert_eq!((e.line, e.to_string().contains("Kv = 0")), (5, true), "{e}");
        let e = parse_motor("name\n one\n").unwrap_err();
        assert!(e.to_string().contains("'one' is not a motor type"), "{e}");
        let e = parse_motor("name\n 1\n 0.1\n fast\n").unwrap_err();
        assert_eq!(e.line, 4, "{e}");
        let e = parse_motor("# only a comment\n").unwrap_err();
        assert!(e.to_string().contains("ends before its name"), "{e}");
        let e = parse_motor("name\n 1\n 0.1\n 1\n").unwrap_err();
        assert!(e.to_string().contains("at least 3"), "{e}");
        let many = format!("name\n 2\n{}", " 1\n".repeat(11));
        assert_eq!(parse_motor(&many).unwrap_err().line, 13);
    }
}
