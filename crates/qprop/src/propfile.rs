//! QPROP prop files.
//!
//! Format (QPROP 1.22 `qprop.f`, `io.f`): comment lines start with `#` or `!`, text after `!`
//! is ignored, numbers are separated by blanks, tabs or commas.
//!
//! 1. name
//! 2. `Nblades [R]`
//! 3. `CL0 CL_a`, 4. `CLmin CLmax`, 5. `CD0 CD2u CD2l CLCD0`, 6. `REref REexp`
//! 7. `Rfac Cfac Bfac`, 8. `Radd Cadd Badd`
//! 9. rows `r chord beta [CL0 CL_a CLmin CLmax CD0 CD2u CD2l CLCD0 REref REexp]`; per-station
//!    columns fill from the left, missing ones take the global values.
//!
//! r = r_in Rfac + Radd, c = c_in Cfac + Cadd, beta[deg] = beta_in Bfac + Badd.

use propbet_bemt::{QpropBlade, QpropCoefficients};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// QPROP's line buffer (`CHARACTER*128 LINE`): longer lines are cut.
pub const QPROP_LINE_MAX: usize = 128;
/// QPROP's maximum number of radial rows (`IRDIM`).
pub const QPROP_MAX_ROWS: usize = 81;

/// One radial row as written in the file (file units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PropRow {
    /// Radius (file units).
    pub r: f64,
    /// Chord (file units).
    pub chord: f64,
    /// Blade angle (file units, degrees after scaling).
    pub beta: f64,
    /// Per-station coefficients given on this row, filled from the left (0 to 10 values).
    pub coeffs: Vec<f64>,
}

/// A parsed prop file, values as written.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PropFile {
    /// Propeller name (line 1).
    pub name: String,
    /// Number of blades.
    pub blades: f64,
    /// Tip radius as written on line 2, if given.
    pub radius: Option<f64>,
    /// Global coefficients, prop-file order (CL0 ... REexp).
    pub global: [f64; 10],
    /// Rfac, Cfac, Bfac.
    pub scale: [f64; 3],
    /// Radd, Cadd, Badd.
    pub offset: [f64; 3],
    /// Radial rows.
    pub rows: Vec<PropRow>,
    /// R on line 2 is in metres, as QPROP 1.22 reads it, because in the units of the r column
    /// (Rfac, Radd) it would lie inside the blade.
    #[serde(default)]
    pub radius_in_metres: bool,
    /// How well the geometry is known, where the file says (a scan's, on its
    /// [`accuracy::ACCURACY_PREFIX`] comment line).
    #[serde(default)]
    pub accuracy: Option<GeometryAccuracy>,
    /// 1-based line number of line 2 (Nblades, R) in the source, 0 when not read from a file
    /// (not part of equality).
    #[serde(skip)]
    pub radius_line: usize,
    /// 1-based line number of each row in the source (not part of equality).
    #[serde(skip)]
    pub row_lines: Vec<usize>,
}

impl PartialEq for PropFile {
    fn eq(&self, o: &Self) -> bool {
        self.name == o.name
            && self.blades == o.blades
            && self.radius == o.radius
            && self.radius_in_metres == o.radius_in_metres
            && self.global == o.global
            && self.scale == o.scale
            && self.offset == o.offset
            && self.rows == o.rows
            && self.accuracy == o.accuracy
    }
}

/// Something QPROP 1.22 would do differently from what the file means, or a doubtful value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Warning {
    /// 1-based line number (0: the file as a whole).
    pub line: usize,
    /// What to know.
    pub message: String,
}

/// Why a prop file could not be read.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ParsePropError {
    /// The file ended before a required line.
    #[error("line {line}: file ends before the {expected} line")]
    Truncated {
        /// Line number after the last line.
        line: usize,
        /// What was expected.
        expected: &'static str,
    },
    /// A token is not a number.
    #[error("line {line}: '{token}' is not a number ({expected})")]
    NotANumber {
        /// Line number.
        line: usize,
        /// The token.
        token: String,
        /// What the line should hold.
        expected: &'static str,
    },
    /// A number is NaN or infinite.
    #[error("line {line}: '{token}' is not a finite number ({expected})")]
    NotFinite {
        /// Line number.
        line: usize,
        /// The token.
        token: String,
        /// What the line should hold.
        expected: &'static str,
    },
    /// Too few numbers on a line.
    #[error("line {line}: expected {needed} numbers ({expected}), found {found}")]
    TooFewValues {
        /// Line number.
        line: usize,
        /// Numbers needed.
        needed: usize,
        /// Numbers found.
        found: usize,
        /// What the line should hold.
        expected: &'static str,
    },
    /// A semantic problem with a value.
    #[error("line {line}: {message}")]
    Invalid {
        /// Line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The file is not text.
    #[error("the file is not UTF-8 text (is it a QPROP prop file?)")]
    NotText,
}

/// How to read the tip radius R given on line 2.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum RadiusReading {
    /// As QPROP's documentation means it: in the units of the r column
    /// (R_SI = R Rfac + Radd).
    Documented,
    /// As QPROP 1.22 does: unscaled, in metres (a defect: with inches, R is 39x too large and
    /// the tip loss vanishes).
    Qprop122,
}

struct Lines<'a> {
    iter: std::iter::Enumerate<std::str::Lines<'a>>,
    last: usize,
    warnings: Vec<Warning>,
    /// The accuracy comment lines passed (line number, text).
    accuracy: Vec<(usize, &'a str)>,
}

impl<'a> Lines<'a> {
    /// Next non-comment, non-blank line: (1-based number, text before `!`).
    fn next_data(&mut self) -> Option<(usize, &'a str)> {
        for (i, raw) in self.iter.by_ref() {
            let line = i + 1;
            self.last = line;
            let raw = raw.strip_suffix('\r').unwrap_or(raw);
            let raw = if line == 1 {
                raw.trim_start_matches('\u{feff}')
            } else {
                raw
            };
            let t = raw.trim_start();
            if t.is_empty() || t.starts_with('#') || t.starts_with('!') {
                if accuracy::is_accuracy_line(t) {
                    self.accuracy.push((line, t));
                }
                continue;
            }
            if raw.chars().count() > QPROP_LINE_MAX {
                self.warnings.push(Warning {
                    line,
                    message: format!(
                        "line is {} characters long; QPROP 1.22 reads only the first {QPROP_LINE_MAX}",
                        raw.chars().count()
                    ),
                });
            }
            let data = raw.split('!').next().unwrap_or("");
            return Some((line, data));
        }
        None
    }

    fn numbers(&mut self, expected: &'static str) -> Result<(usize, Vec<f64>), ParsePropError> {
        let (line, text) = self.next_data().ok_or(ParsePropError::Truncated {
            line: self.last + 1,
            expected,
        })?;
        Ok((line, parse_numbers(line, text, expected)?))
    }
}

fn parse_numbers(line: usize, text: &str, expected: &'static str) -> Result<Vec<f64>, ParsePropError> {
    text.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(|tok| {
            // Fortran list-directed input also accepts D exponents.
            let v: f64 = tok
                .replace(['d', 'D'], "e")
                .parse()
                .map_err(|_| ParsePropError::NotANumber {
                    line,
                    token: propbet_bemt::units::excerpt(tok),
                    expected,
                })?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(ParsePropError::NotFinite {
                    line,
                    token: propbet_bemt::units::excerpt(tok),
                    expected,
                })
            }
        })
        .collect()
}

fn need(line: usize, v: &[f64], n: usize, expected: &'static str) -> Result<(), ParsePropError> {
    if v.len() < n {
        return Err(ParsePropError::TooFewValues {
            line,
            needed: n,
            found: v.len(),
            expected,
        });
    }
    Ok(())
}

/// The radial rows after line 8 (at least two; more than QPROP takes is a warning), with their
/// line numbers.
fn radial_rows(lines: &mut Lines) -> Result<(Vec<PropRow>, Vec<usize>), ParsePropError> {
    const ROW: &str = "r chord beta [CL0 CL_a CLmin CLmax CD0 CD2u CD2l CLCD0 REref REexp]";
    let mut rows = Vec::new();
    let mut row_lines = Vec::new();
    while let Some((l, text)) = lines.next_data() {
        let v = parse_numbers(l, text, ROW)?;
        need(l, &v, 3, ROW)?;
        if v.len() > 13 {
            lines.warnings.push(Warning {
                line: l,
                message: format!("{} numbers on a radial row; only the first 13 are used", v.len()),
            });
        }
        rows.push(PropRow {
            r: v[0],
            chord: v[1],
            beta: v[2],
            coeffs: v[3..v.len().min(13)].to_vec(),
        });
        row_lines.push(l);
    }
    if rows.len() < 2 {
        return Err(ParsePropError::Invalid {
            line: lines.last,
            message: format!("a prop file needs at least two radial rows, found {}", rows.len()),
        });
    }
    if rows.len() > QPROP_MAX_ROWS {
        lines.warnings.push(Warning {
            line: 0,
            message: format!(
                "{} radial rows; QPROP 1.22 accepts at most {QPROP_MAX_ROWS}",
                rows.len()
            ),
        });
    }
    Ok((rows, row_lines))
}

/// Parses a prop file. Returns the file and the warnings a user should see.
pub fn parse_prop(text: &str) -> Result<(PropFile, Vec<Warning>), ParsePropError> {
    let mut lines = Lines {
        iter: text.lines().enumerate(),
        last: 0,
        warnings: Vec::new(),
        accuracy: Vec::new(),
    };
    let (_, name) = lines.next_data().ok_or(ParsePropError::Truncated {
        line: 1,
        expected: "name",
    })?;
    let name = propbet_units::printable(name);

    const L2: &str = "Nblades [R]";
    // A file whose first numbers are not numbers is not a prop file: said without quoting it
    // (a file of another kind, `/etc/passwd` say, is never echoed).
    let (l, v) = lines.numbers(L2).map_err(|e| match e {
        ParsePropError::NotANumber { line, .. } => ParsePropError::Invalid {
            line,
            message: "not a QPROP prop file: the first line after its name must be the blade count (and R), in numbers"
                .into(),
        },
        e => e,
    })?;
    need(l, &v, 1, L2)?;
    let radius_line = l;
    let blades = v[0];
    if blades <= 0.0 {
        return Err(ParsePropError::Invalid {
            line: l,
            message: format!("blade count must be positive, found {blades}"),
        });
    }
    if blades.fract() != 0.0 {
        lines.warnings.push(Warning {
            line: l,
            message: format!("blade count {blades} is not a whole number"),
        });
    }
    let radius = v.get(1).copied();
    if let Some(r) = radius {
        if r <= 0.0 {
            return Err(ParsePropError::Invalid {
                line: l,
                message: format!("tip radius R must be positive, found {r}"),
            });
        }
    }

    let mut global = [0.0; 10];
    for (slot, n, what) in [
        (0usize, 2usize, "CL0 CL_a"),
        (2, 2, "CLmin CLmax"),
        (4, 4, "CD0 CD2u CD2l CLCD0"),
        (8, 2, "REref REexp"),
    ] {
        let (l, v) = lines.numbers(what)?;
        need(l, &v, n, what)?;
        global[slot..slot + n].copy_from_slice(&v[..n]);
    }
    let mut scale = [0.0; 3];
    let mut offset = [0.0; 3];
    for (dst, what) in [(&mut scale, "Rfac Cfac Bfac"), (&mut offset, "Radd Cadd Badd")] {
        let (l, v) = lines.numbers(what)?;
        need(l, &v, 3, what)?;
        dst.copy_from_slice(&v[..3]);
    }

    let (rows, row_lines) = radial_rows(&mut lines)?;
    let mut file = PropFile {
        name,
        blades,
        radius,
        radius_in_metres: false,
        radius_line,
        global,
        scale,
        offset,
        rows,
        row_lines,
        accuracy: accuracy::parse(&lines.accuracy)?,
    };
    // QPROP 1.22 takes R unscaled, in metres; propbet reads it in the r column's units. Where
    // that would put the tip inside the blade and metres do not, the file was written for
    // QPROP's reading (several of QPROP's own examples are): read it so, and say so.
    if let (Some(rad), Some(last)) = (radius, file.rows.last()) {
        let last = last.r * scale[0] + offset[0];
        let documented = rad * scale[0] + offset[0];
        if documented < last && rad >= last * (1.0 - 1e-9) && (scale[0] != 1.0 || offset[0] != 0.0) {
            file.radius_in_metres = true;
            lines.warnings.push(Warning {
                line: radius_line,
                message: format!(
                    "R = {rad} would lie inside the blade in the r column's units ({documented} m); \
                     read in metres, as QPROP 1.22 reads it"
                ),
            });
        }
    }
    file.check_rows()?;
    let mut warnings = lines.warnings;
    warnings.extend(file.qprop_differences());
    Ok((file, warnings))
}

impl PropFile {
    /// A prop file in metres (Rfac = Cfac = Bfac = 1) with the tip radius on line 2 and
    /// [`crate::GENERIC`] as the global coefficients: what propbet writes for a blade it has
    /// measured (a scan, a validation geometry) before its polars are fitted.
    pub fn metric(name: String, blades: f64, tip_radius: f64, rows: Vec<PropRow>) -> PropFile {
        PropFile {
            name,
            blades,
            radius: Some(tip_radius),
            radius_in_metres: false,
            radius_line: 0,
            global: crate::GENERIC.to_array(),
            scale: [1.0, 1.0, 1.0],
            offset: [0.0, 0.0, 0.0],
            rows,
            row_lines: Vec::new(),
            accuracy: None,
        }
    }

    fn row_line(&self, i: usize) -> usize {
        self.row_lines.get(i).copied().unwrap_or(0)
    }

    /// Radius, chord and angle of each row after scaling, checked.
    fn check_rows(&self) -> Result<(), ParsePropError> {
        let mut prev: Option<f64> = None;
        for (i, row) in self.rows.iter().enumerate() {
            let line = self.row_line(i);
            let r = row.r * self.scale[0] + self.offset[0];
            let c = row.chord * self.scale[1] + self.offset[1];
            if r < 0.0 {
                return Err(ParsePropError::Invalid {
                    line,
                    message: format!(
                        "radius {} gives r = {r} m after scaling; radii must not be negative",
                        row.r
                    ),
                });
            }
            if let Some(p) = prev {
                if r <= p {
                    return Err(ParsePropError::Invalid {
                        line,
                        message: format!(
                            "radius {} (r = {r} m) does not increase from the previous row (r = {p} m)",
                            row.r
                        ),
                    });
                }
            }
            if c < 0.0 {
                return Err(ParsePropError::Invalid {
                    line,
                    message: format!(
                        "chord {} gives c = {c} m after scaling; chords must not be negative",
                        row.chord
                    ),
                });
            }
            let k = self.coeffs_at(i);
            if k.re_ref <= 0.0 {
                return Err(ParsePropError::Invalid {
                    line,
                    message: format!("REref must be positive, found {}", k.re_ref),
                });
            }
            if k.cl_a <= 0.0 {
                return Err(ParsePropError::Invalid {
                    line,
                    message: format!("CL_a must be positive, found {}", k.cl_a),
                });
            }
            prev = Some(r);
        }
        if let Some(rad) = self.radius {
            let last = self.rows.last().map(|r| r.r).unwrap_or(0.0);
            if self.tip_radius(RadiusReading::Documented) < last * self.scale[0] + self.offset[0] {
                return Err(ParsePropError::Invalid {
                    line: self.radius_line,
                    message: format!("tip radius R = {rad} on line 2 is less than the last radius {last}"),
                });
            }
        }
        Ok(())
    }

    /// Where QPROP 1.22 reads this file differently from what it means (also among the
    /// warnings of [`parse_prop`]).
    pub fn qprop_differences(&self) -> Vec<Warning> {
        let mut w = Vec::new();
        if let Some(rad) = self.radius.filter(|_| !self.radius_in_metres) {
            if self.scale[0] != 1.0 || self.offset[0] != 0.0 {
                let si = rad * self.scale[0] + self.offset[0];
                w.push(Warning {
                    line: self.radius_line,
                    message: format!(
                        "line 2 gives R = {rad}: QPROP 1.22 takes it unscaled as {rad} m, propbet reads it in the \
                         units of the r column as {si} m"
                    ),
                });
            }
        }
        let rerefs: Vec<f64> = (0..self.rows.len()).map(|i| self.coeffs_at(i).re_ref).collect();
        if rerefs.iter().any(|&r| r != rerefs[0]) {
            w.push(Warning {
                line: 0,
                message: "REref varies along the blade: QPROP 1.22 uses the value at its first station for all \
                          stations, propbet uses each station's own"
                    .to_string(),
            });
        }
        w
    }

    /// The same blade written so that QPROP 1.22 reads what propbet reads: radii, chords and
    /// angles in metres and degrees with no scaling (QPROP takes R on line 2 unscaled), R the
    /// documented tip radius, and every row with all ten coefficients on the first row's REref
    /// (QPROP 1.22 uses the first station's everywhere): CD0, CD2u and CD2l times
    /// (REref / REref_i)^REexp_i, which leaves each row's drag law unchanged.
    pub fn as_qprop_reads(&self) -> PropFile {
        // A whole number, so that every row writes it alike however its line is shortened.
        let re_ref = self.coeffs_at(0).re_ref.round().max(1.0);
        let rows = (0..self.rows.len())
            .map(|i| {
                let row = &self.rows[i];
                let mut c = self.coeffs_at(i);
                let f = (re_ref / c.re_ref).powf(c.re_exp);
                c.cd0 *= f;
                c.cd2u *= f;
                c.cd2l *= f;
                c.re_ref = re_ref;
                PropRow {
                    r: row.r * self.scale[0] + self.offset[0],
                    chord: row.chord * self.scale[1] + self.offset[1],
                    beta: row.beta * self.scale[2] + self.offset[2],
                    coeffs: c.to_array().to_vec(),
                }
            })
            .collect();
        let mut global = self.coeffs_at(0).to_array();
        global[8] = re_ref;
        PropFile {
            global,
            accuracy: self.accuracy,
            ..PropFile::metric(
                self.name.clone(),
                self.blades,
                self.tip_radius(RadiusReading::Documented),
                rows,
            )
        }
    }

    /// The ten coefficients of row `i`: the row's own, filled from the left, the rest global.
    pub fn coeffs_at(&self, i: usize) -> QpropCoefficients {
        let mut k = self.global;
        for (slot, v) in k.iter_mut().zip(&self.rows[i].coeffs) {
            *slot = *v;
        }
        QpropCoefficients::from_array(k)
    }

    /// Gives row `i` all ten coefficients of its own (CL_a per radian, as QPROP reads it).
    pub fn set_station_coeffs(&mut self, i: usize, c: &QpropCoefficients) {
        self.rows[i].coeffs = c.to_array().to_vec();
    }

    /// Tip radius [m] under the given reading of line 2 (last station radius when absent).
    pub fn tip_radius(&self, reading: RadiusReading) -> f64 {
        let last = self
            .rows
            .last()
            .map(|r| r.r * self.scale[0] + self.offset[0])
            .unwrap_or(0.0);
        let documented = |r: f64| {
            // A tip radius that equals the last station's but for rounding (a file written
            // from inches, say) is that station's radius: r / R must not exceed 1.
            if r < last && within_rounding(r, last) {
                last
            } else {
                r
            }
        };
        match (self.radius, reading) {
            (None, _) => last,
            (Some(r), RadiusReading::Documented) if self.radius_in_metres => documented(r),
            (Some(r), RadiusReading::Documented) => documented(r * self.scale[0] + self.offset[0]),
            (Some(r), RadiusReading::Qprop122) => r,
        }
    }

    /// The blade in SI units.
    pub fn to_blade(&self, reading: RadiusReading) -> QpropBlade {
        let deg = std::f64::consts::PI / 180.0;
        QpropBlade {
            blades: self.blades,
            tip_radius: self.tip_radius(reading),
            r: self.rows.iter().map(|r| r.r * self.scale[0] + self.offset[0]).collect(),
            chord: self
                .rows
                .iter()
                .map(|r| r.chord * self.scale[1] + self.offset[1])
                .collect(),
            beta: self
                .rows
                .iter()
                .map(|r| (r.beta * self.scale[2] + self.offset[2]) * deg)
                .collect(),
            coeffs: (0..self.rows.len()).map(|i| self.coeffs_at(i)).collect(),
        }
    }

    /// A prop file for a blade given in SI units (metres, degrees).
    pub fn from_blade(name: &str, blade: &QpropBlade) -> Self {
        let deg = 180.0 / std::f64::consts::PI;
        let global = blade.coeffs[0].to_array();
        let rows = (0..blade.r.len())
            .map(|i| {
                let k = blade.coeffs[i].to_array();
                // Write only as many columns as needed to express the differences from global.
                let used = (0..10).rev().find(|&j| k[j] != global[j]).map_or(0, |j| j + 1);
                PropRow {
                    r: blade.r[i],
                    chord: blade.chord[i],
                    beta: blade.beta[i] * deg,
                    coeffs: k[..used].to_vec(),
                }
            })
            .collect();
        PropFile {
            name: name.to_string(),
            blades: blade.blades,
            radius: Some(blade.tip_radius),
            radius_in_metres: false,
            radius_line: 0,
            global,
            scale: [1.0, 1.0, 1.0],
            offset: [0.0, 0.0, 0.0],
            rows,
            row_lines: Vec::new(),
            accuracy: None,
        }
    }
}

/// Writes a prop file that QPROP 1.22 reads as `file` means it: every number in its shortest
/// exact form, a blank before every `!`, and no line longer than QPROP's 128-character buffer
/// (a row that would be longer is written with the most significant digits, 9 down to 4, that
/// fit: thirteen numbers share 126 characters).
///
/// Two lengths that differ only by the rounding of a decimal written and read back
/// (0.1524 and 0.15239999999999998), relative to their size.
fn within_rounding(a: f64, b: f64) -> bool {
    propbet_units::same_radius(a, b)
}

mod accuracy;
mod write;

pub use accuracy::{GeometryAccuracy, ACCURACY_PREFIX};
pub use write::write_prop;

#[cfg(test)]
mod tests;
