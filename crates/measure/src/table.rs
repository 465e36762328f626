//! CSV text to header and cells, and cells to samples in SI: the part RCbenchmark logs and
//! generic CSV share.

use crate::set::{limits, DropReason, Dropped, ReadError};
use crate::units::{conversion, Conversion, Quantity};

/// A CSV file's header and rows, as text.
#[derive(Debug, Clone)]
pub struct CsvTable {
    /// Header cells, trimmed, without the empty one a trailing comma leaves.
    pub headers: Vec<String>,
    /// Data rows.
    pub rows: Vec<CsvRow>,
    /// Rows with more cells than the header has names.
    pub long_rows: Vec<usize>,
    /// How the file differs from plain CSV ("semicolon-separated values, with decimal
    /// commas"), for the notes.
    pub dialect: Option<String>,
}

impl CsvTable {
    /// The header's names for a message: each as an excerpt, at most 40 of them.
    pub fn header_list(&self) -> String {
        const SHOWN: usize = 40;
        let mut list: Vec<String> = self
            .headers
            .iter()
            .take(SHOWN)
            .map(|h| propbet_units::excerpt(h))
            .collect();
        if self.headers.len() > SHOWN {
            list.push(format!("and {} more", self.headers.len() - SHOWN));
        }
        list.join(", ")
    }
}

/// One data row.
#[derive(Debug, Clone)]
pub struct CsvRow {
    /// Line (1-based).
    pub line: usize,
    /// Cells, trimmed.
    pub cells: Vec<String>,
}

/// Splits a header into name and unit: `Thrust (gf)`, `speed [m/s]` → (`Thrust`, `gf`).
pub fn split_header(h: &str) -> (String, Option<String>) {
    let h = h.trim();
    for (open, close) in [('(', ')'), ('[', ']')] {
        if h.ends_with(close) {
            if let Some(i) = h.rfind(open) {
                let unit = h[i + open.len_utf8()..h.len() - close.len_utf8()].trim().to_string();
                return (h[..i].trim().to_string(), Some(unit));
            }
        }
    }
    (h.to_string(), None)
}

/// Most fields a CSV row may have: RCbenchmark's logs have about 40 columns, a generic log a
/// few; a row of thousands is not a measurement table (and would cost memory per field).
pub const MAX_FIELDS: usize = 1000;

/// The field separator of a CSV whose first line is `header`: a semicolon (spreadsheets in
/// locales with a decimal comma) or a tab when the header holds more of them than commas, else a
/// comma.
pub fn delimiter(header: &str) -> u8 {
    let count = |c: char| header.matches(c).count();
    let commas = count(',');
    if count(';') > commas {
        b';'
    } else if count('\t') > commas && header.split('\t').any(|f| f.trim().contains(' ')) {
        // Tab-separated with names of several words ("Thrust (N)"); a UIUC file's header is
        // separated by whitespace of any kind and has one-word names.
        b'\t'
    } else {
        b','
    }
}

/// The cells of a header line, split at its [`delimiter`] (quotes removed, trimmed).
pub fn header_cells(line: &str) -> Vec<String> {
    let mut rdr = csv::ReaderBuilder::new()
        .delimiter(delimiter(line))
        .has_headers(false)
        .flexible(true)
        .trim(csv::Trim::All)
        .from_reader(line.as_bytes());
    rdr.records()
        .next()
        .and_then(Result::ok)
        .map(|r| r.iter().map(str::to_string).collect())
        .unwrap_or_default()
}

/// "1,25" or "-0,5e-3" as "1.25", "-0.5e-3": a decimal comma in a file whose separator is not
/// a comma. None when the cell is not such a number.
fn decimal_comma(cell: &str) -> Option<String> {
    if cell.matches(',').count() != 1 || cell.contains('.') {
        return None;
    }
    let dotted = cell.replacen(',', ".", 1);
    dotted.parse::<f64>().is_ok().then_some(dotted)
}

/// Reads CSV text (BOM, trailing commas and rows longer than the header allowed); the
/// separator is found from the header ([`delimiter`]), and with a semicolon or a tab, decimal
/// commas are read as decimal points. [`CsvTable::dialect`] says which when it is not plain CSV.
pub fn read_csv(text: &str) -> Result<CsvTable, ReadError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let first = text.lines().find(|l| !l.trim().is_empty()).unwrap_or("");
    let sep = delimiter(first);
    let mut commas = 0usize;
    let mut rdr = csv::ReaderBuilder::new()
        .delimiter(sep)
        .has_headers(false)
        .flexible(true)
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let mut headers: Option<Vec<String>> = None;
    let mut rows = Vec::new();
    let mut long_rows = Vec::new();
    for rec in rdr.records() {
        let rec = rec.map_err(|e| ReadError::Line {
            line: e.position().map_or(0, |p| p.line() as usize),
            message: format!("not CSV: {e}"),
        })?;
        let line = rec.position().map_or(0, |p| p.line() as usize);
        if rec.len() > MAX_FIELDS {
            return Err(ReadError::Line {
                line,
                message: format!(
                    "{} fields in one row: at most {MAX_FIELDS} (a thrust-stand log has tens of columns)",
                    rec.len()
                ),
            });
        }
        if rec.iter().all(|c| c.is_empty()) {
            continue;
        }
        match &headers {
            None => {
                let mut h: Vec<String> = rec.iter().map(str::to_string).collect();
                while h.last().is_some_and(|c| c.is_empty()) {
                    h.pop();
                }
                // Two columns of one name: no reader can tell which holds what.
                for (j, name) in h.iter().enumerate().filter(|(_, n)| !n.is_empty()) {
                    if let Some(k) = h[..j].iter().position(|x| x == name) {
                        return Err(ReadError::Line {
                            line,
                            message: format!(
                                "column '{name}' appears twice (columns {} and {}): rename one so that each quantity has one column",
                                k + 1,
                                j + 1
                            ),
                        });
                    }
                }
                headers = Some(h);
            }
            Some(h) => {
                let mut cells: Vec<String> = rec
                    .iter()
                    .map(|c| match decimal_comma(c).filter(|_| sep != b',') {
                        Some(d) => {
                            commas += 1;
                            d
                        }
                        None => c.to_string(),
                    })
                    .collect();
                if cells.len() > h.len() {
                    if cells[h.len()..].iter().any(|c| !c.is_empty()) {
                        long_rows.push(line);
                    }
                    cells.truncate(h.len());
                }
                rows.push(CsvRow { line, cells });
            }
        }
    }
    let headers = headers.ok_or_else(|| ReadError::Empty("no header line".into()))?;
    if rows.is_empty() {
        return Err(ReadError::Empty("a header and no data rows".into()));
    }
    let dialect = match (sep, commas > 0) {
        (b',', _) => None,
        (sep, comma) => Some(format!(
            "{}-separated values{}",
            if sep == b';' { "semicolon" } else { "tab" },
            if comma { ", with decimal commas" } else { "" }
        )),
    };
    Ok(CsvTable {
        headers,
        rows,
        long_rows,
        dialect,
    })
}

/// A column chosen for a quantity, with its conversion to SI.
#[derive(Debug, Clone)]
pub struct Column {
    /// Index in the row.
    pub index: usize,
    /// Header as written.
    pub header: String,
    /// To SI.
    pub conv: Conversion,
}

impl Column {
    /// The column at `index`, its unit `unit` (or the quantity's default) checked.
    pub fn new(q: Quantity, index: usize, header: &str, unit: Option<&str>) -> Result<Self, ReadError> {
        let unit = unit.unwrap_or(q.default_unit());
        let conv = conversion(q, unit).ok_or_else(|| ReadError::UnknownUnit {
            column: header.to_string(),
            unit: unit.to_string(),
            quantity: q.name(),
            known: q.known_units(),
        })?;
        Ok(Self {
            index,
            header: header.to_string(),
            conv,
        })
    }
}

/// The columns a log is read through.
#[derive(Debug, Clone, Default)]
pub struct Columns {
    /// Time.
    pub time: Option<Column>,
    /// ESC command.
    pub esc: Option<Column>,
    /// Rotation.
    pub rotation: Option<Column>,
    /// A second rotation sensor (the electrical speed beside the optical one), read to fill the
    /// first's dropouts.
    pub rotation_other: Option<Column>,
    /// Thrust.
    pub thrust: Option<Column>,
    /// Torque.
    pub torque: Option<Column>,
    /// Airspeed.
    pub airspeed: Option<Column>,
    /// Air temperature.
    pub temperature: Option<Column>,
    /// Air pressure.
    pub pressure: Option<Column>,
    /// Relative humidity.
    pub humidity: Option<Column>,
    /// The supply's voltage.
    pub voltage: Option<Column>,
    /// The supply's current.
    pub current: Option<Column>,
}

/// One row in SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Line (1-based).
    pub line: usize,
    /// Time [s].
    pub time: Option<f64>,
    /// ESC command [µs].
    pub esc: Option<f64>,
    /// Rotation rate [rad/s].
    pub omega: f64,
    /// The second rotation sensor's reading [rad/s], as logged, where the log has one.
    pub omega_other: Option<f64>,
    /// Thrust [N] (as logged; oriented later).
    pub thrust: f64,
    /// Torque [N m] (as logged; oriented later).
    pub torque: Option<f64>,
    /// Airspeed [m/s] (0 without a column).
    pub airspeed: f64,
    /// Air temperature [K].
    pub temperature: Option<f64>,
    /// Pressure [Pa].
    pub pressure: Option<f64>,
    /// Relative humidity [0..1].
    pub humidity: Option<f64>,
    /// The supply's voltage [V].
    pub volts: Option<f64>,
    /// The supply's current [A].
    pub amps: Option<f64>,
    /// Which of the row's readings are its own, not a sparse log's latest earlier value.
    pub fresh: Fresh,
}

/// Which readings of a row were logged on it (a thrust stand writes each sensor at its own
/// rate: the other cells of a row are empty, and take the sensor's latest reading).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fresh {
    /// The rotation reading.
    pub omega: bool,
    /// The thrust reading.
    pub thrust: bool,
    /// The torque reading.
    pub torque: bool,
}

impl Fresh {
    /// Every reading the row's own.
    pub const ALL: Fresh = Fresh {
        omega: true,
        thrust: true,
        torque: true,
    };
}

/// A sparse log's empty cells filled with each column's latest reading (the columns of
/// `cols`, time excepted): the rows filled, which cells of each were filled (rotation, thrust,
/// torque), the rows before a needed sensor's first reading, and how many cells were filled.
struct Filled {
    rows: Vec<CsvRow>,
    fresh: Vec<Fresh>,
    before_first: Vec<bool>,
    cells: usize,
}

fn fill_sparse(table: &CsvTable, cols: &Columns) -> Filled {
    let fill: Vec<usize> = [
        &cols.esc,
        &cols.rotation,
        &cols.rotation_other,
        &cols.thrust,
        &cols.torque,
        &cols.airspeed,
        &cols.temperature,
        &cols.pressure,
        &cols.humidity,
        &cols.voltage,
        &cols.current,
    ]
    .into_iter()
    .flatten()
    .map(|c| c.index)
    .collect();
    let needed: Vec<usize> = [&cols.rotation, &cols.thrust, &cols.torque]
        .into_iter()
        .flatten()
        .map(|c| c.index)
        .collect();
    let index = |c: &Option<Column>| c.as_ref().map(|c| c.index);
    let (rot, thr, tor) = (index(&cols.rotation), index(&cols.thrust), index(&cols.torque));
    let mut latest: Vec<Option<String>> = vec![None; table.headers.len()];
    let mut out = Filled {
        rows: Vec::with_capacity(table.rows.len()),
        fresh: Vec::with_capacity(table.rows.len()),
        before_first: Vec::with_capacity(table.rows.len()),
        cells: 0,
    };
    for row in &table.rows {
        let mut row = row.clone();
        if row.cells.len() < table.headers.len() {
            row.cells.resize(table.headers.len(), String::new());
        }
        let own = |i: Option<usize>, row: &CsvRow| i.is_none_or(|i| !row.cells[i].is_empty());
        out.fresh.push(Fresh {
            omega: own(rot, &row),
            thrust: own(thr, &row),
            torque: own(tor, &row),
        });
        let mut waiting = false;
        for &i in &fill {
            if row.cells[i].is_empty() {
                match &latest[i] {
                    Some(v) => {
                        row.cells[i] = v.clone();
                        out.cells += 1;
                    }
                    None => waiting |= needed.contains(&i),
                }
            } else {
                latest[i] = Some(row.cells[i].clone());
            }
        }
        out.before_first.push(waiting);
        out.rows.push(row);
    }
    out
}

fn cell(row: &CsvRow, col: &Column) -> Result<f64, (DropReason, String)> {
    let text = row.cells.get(col.index).map(String::as_str).unwrap_or("");
    if text.is_empty() {
        return Err((
            DropReason::Missing,
            format!("{} is empty", propbet_units::excerpt(&col.header)),
        ));
    }
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(col.conv.apply(v)),
        _ => Err((
            DropReason::NotANumber,
            format!(
                "{} = '{}'",
                propbet_units::excerpt(&col.header),
                propbet_units::excerpt(text)
            ),
        )),
    }
}

/// Converts rows to samples; rows with an unusable needed cell are dropped with the reason.
/// `rotation` and `thrust` must be set. `sparse`: a thrust stand's log, whose empty cells take
/// their column's latest reading (rows before a needed sensor's first reading are left out as
/// such), said in `notes`.
pub fn samples(
    table: &CsvTable,
    cols: &Columns,
    sparse: bool,
    dropped: &mut Vec<Dropped>,
    notes: &mut Vec<String>,
) -> Vec<Sample> {
    let rot = cols.rotation.as_ref().expect("rotation column chosen");
    let thr = cols.thrust.as_ref().expect("thrust column chosen");
    let optional = |row: &CsvRow, c: &Option<Column>| c.as_ref().and_then(|c| cell(row, c).ok());
    let mut out = Vec::with_capacity(table.rows.len());
    // A row shorter than the header in a table whose rows are otherwise full lost a cell:
    // every value after it would be read from its neighbour's column.
    let width = table.headers.len();
    let short = table.rows.iter().filter(|r| r.cells.len() < width).count();
    let short_is_fault = short * 10 < table.rows.len();
    let filled = sparse.then(|| fill_sparse(table, cols));
    if let Some(f) = filled.as_ref().filter(|f| f.cells > 0) {
        let own = |pick: fn(&Fresh) -> bool| f.fresh.iter().filter(|x| pick(x)).count();
        let torque = if cols.torque.is_some() {
            format!(", torque on {}", own(|x| x.torque))
        } else {
            String::new()
        };
        notes.push(format!(
            "sparse log (each sensor written at its own rate): {} empty cells took their column's latest reading; \
             of {} rows, RPM is logged on {}, thrust on {}{torque}; each point's thrust and torque are the mean \
             of the readings logged within it",
            f.cells,
            table.rows.len(),
            own(|x| x.omega),
            own(|x| x.thrust),
        ));
    }
    let rows = filled.as_ref().map_or(&table.rows, |f| &f.rows);
    for (k, row) in rows.iter().enumerate() {
        if filled.as_ref().is_some_and(|f| f.before_first[k]) {
            dropped.push(Dropped {
                line: row.line,
                reason: DropReason::BeforeFirstReading,
                detail: "a needed sensor has not logged its first reading yet".into(),
            });
            continue;
        }
        let row_short = table.rows[k].cells.len() < width;
        if short_is_fault && row_short {
            dropped.push(Dropped {
                line: row.line,
                reason: DropReason::Missing,
                detail: format!(
                    "{} values where the header and the other rows have {width}: a cell is missing, the values after it would be read from the wrong columns",
                    table.rows[k].cells.len()
                ),
            });
            continue;
        }
        let other = optional(row, &cols.rotation_other);
        let needed = (|| {
            // An empty reading of one sensor is a dropout when the other reads.
            let omega = match cell(row, rot) {
                Err(_) if other.is_some_and(|o| o > 0.0) => 0.0,
                read => read?,
            };
            let thrust = cell(row, thr)?;
            let torque = cols.torque.as_ref().map(|c| cell(row, c)).transpose()?;
            let airspeed = cols.airspeed.as_ref().map(|c| cell(row, c)).transpose()?.unwrap_or(0.0);
            let time = cols.time.as_ref().map(|c| cell(row, c)).transpose()?;
            let checks = [
                ("rotation rate [rad/s]", omega, limits::OMEGA),
                ("thrust [N]", thrust, limits::THRUST),
                ("torque [N m]", torque.unwrap_or(0.0), limits::TORQUE),
                ("airspeed [m/s]", airspeed, limits::AIRSPEED),
            ];
            let air = limits::air(
                optional(row, &cols.temperature),
                optional(row, &cols.pressure),
                optional(row, &cols.humidity),
            );
            if let Some(detail) = limits::beyond(&checks).or_else(|| limits::too_slow(omega)).or(air) {
                return Err((DropReason::Implausible, detail));
            }
            Ok::<_, (DropReason, String)>((omega, thrust, torque, airspeed, time))
        })();
        match needed {
            Ok((omega, thrust, torque, airspeed, time)) => out.push(Sample {
                line: row.line,
                time,
                esc: optional(row, &cols.esc),
                omega,
                omega_other: other,
                thrust,
                torque,
                airspeed,
                temperature: optional(row, &cols.temperature),
                pressure: optional(row, &cols.pressure),
                humidity: optional(row, &cols.humidity),
                volts: optional(row, &cols.voltage),
                amps: optional(row, &cols.current),
                fresh: filled.as_ref().map_or(Fresh::ALL, |f| f.fresh[k]),
            }),
            Err((reason, detail)) => dropped.push(Dropped {
                line: row.line,
                reason,
                detail,
            }),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_of_too_many_fields_are_refused_by_count() {
        let mut text = String::from("rpm,thrust_N\n");
        text.push_str(&vec!["1"; 5000].join(","));
        let e = read_csv(&text).unwrap_err().to_string();
        assert!(e.contains("5000 fields in one row: at most 1000"), "{e}");
        assert!(e.len() < 200, "the message does not echo the row: {} bytes", e.len());
        let header = (0..3000).map(|k| format!("c{k}")).collect::<Vec<_>>().join(",");
        let e = read_csv(&format!("{header}\n1\n")).unwrap_err().to_string();
        assert!(e.contains("3000 fields") && e.len() < 200, "{e}");
    }

    #[test]
    fn headers_and_units() {
        assert_eq!(split_header("Thrust (gf)"), ("Thrust".into(), Some("gf".into())));
        assert_eq!(split_header("Torque (N·m)"), ("Torque".into(), Some("N·m".into())));
        assert_eq!(split_header(" v [m/s] "), ("v".into(), Some("m/s".into())));
        assert_eq!(split_header("App message"), ("App message".into(), None));
    }

    #[test]
    fn bom_trailing_comma_and_long_rows() {
        let t = read_csv("\u{feff}a (s),b (N),\n1,2,\n3,4,,5,6\n\n").unwrap();
        assert_eq!(t.headers, vec!["a (s)", "b (N)"]);
        assert_eq!(t.rows.len(), 2);
        assert_eq!(t.rows[1].cells, vec!["3", "4"]);
        assert_eq!(t.rows[1].line, 3);
        assert_eq!(t.long_rows, vec![3]);
    }

    #[test]
    fn empty_files_are_errors() {
        assert!(matches!(read_csv(""), Err(ReadError::Empty(_))));
        assert!(matches!(read_csv("a,b\n"), Err(ReadError::Empty(_))));
    }
}
