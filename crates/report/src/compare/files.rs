//! The "Measured files" section: a batch table (one row per file, the refused ones with why)
//! and each file's format, rows, points, warnings, notes and dropped rows.

use std::fmt::Write as _;

use propbet_measure::{DropReason, Dropped, MeasuredSet, Refused};

use super::FileEntry;
use crate::page::esc;

/// A file's verdict in the batch table.
fn verdict(s: &MeasuredSet) -> String {
    match (s.faults(), s.warnings.first()) {
        (_, Some(w)) => format!("warning: {w}"),
        (0, None) => "read".into(),
        (n, None) => format!("read; {n} faulty rows"),
    }
}

/// Rows dropped as faults and as expected (idle, not spinning), as "faults / expected".
fn dropped_split(s: &MeasuredSet) -> String {
    format!("{} / {}", s.faults(), s.dropped.len() - s.faults())
}

/// One row of the batch table: a file read, with its format, rows, points, dropped rows and
/// verdict, or a file refused, with why.
enum BatchRow<'a> {
    Read {
        path: &'a str,
        cells: [String; 4],
        verdict: String,
    },
    Refused {
        path: &'a str,
        reason: &'a str,
    },
}

/// The batch table's rows: one per file, the refused ones last; None for a single file read.
fn batch_rows<'a>(files: &'a [FileEntry], refused: &'a [Refused]) -> Option<Vec<BatchRow<'a>>> {
    if files.len() < 2 && refused.is_empty() {
        return None;
    }
    let read = files.iter().map(|f| {
        let s = f.set;
        BatchRow::Read {
            path: &f.path,
            cells: [
                format!("{:?}", s.format),
                s.rows.to_string(),
                s.points.len().to_string(),
                dropped_split(s),
            ],
            verdict: verdict(s),
        }
    });
    let refused = refused.iter().map(|r| BatchRow::Refused {
        path: &r.file,
        reason: &r.reason,
    });
    Some(read.chain(refused).collect())
}

/// The batch table ([`batch_rows`]) in HTML.
fn batch_table_html(files: &[FileEntry], refused: &[Refused]) -> String {
    let Some(rows) = batch_rows(files, refused) else {
        return String::new();
    };
    let mut h = String::from(
        "<table><tr><th>file</th><th>format</th><th>rows</th><th>points</th><th>dropped: faults / expected</th><th>verdict</th></tr>\n",
    );
    for row in rows {
        let _ = match row {
            BatchRow::Read { path, cells, verdict } => writeln!(
                h,
                "<tr><td><code>{}</code></td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                esc(path),
                cells[0],
                cells[1],
                cells[2],
                cells[3],
                esc(&verdict)
            ),
            BatchRow::Refused { path, reason } => writeln!(
                h,
                "<tr><td><code>{}</code></td><td></td><td></td><td>0</td><td></td><td><b>refused</b>: {}</td></tr>",
                esc(path),
                esc(reason)
            ),
        };
    }
    h.push_str("</table>\n");
    h
}

/// The batch table ([`batch_rows`]) in Markdown.
fn batch_table_md(files: &[FileEntry], refused: &[Refused]) -> String {
    let Some(rows) = batch_rows(files, refused) else {
        return String::new();
    };
    let mut md = String::from(
        "| file | format | rows | points | dropped: faults / expected | verdict |\n|---|---|---|---|---|---|\n",
    );
    for row in rows {
        let _ = match row {
            BatchRow::Read { path, cells, verdict } => writeln!(
                md,
                "| `{path}` | {} | {} | {} | {} | {} |",
                cells[0],
                cells[1],
                cells[2],
                cells[3],
                verdict.replace('|', "\\|")
            ),
            BatchRow::Refused { path, reason } => {
                writeln!(md, "| `{path}` | | | 0 | | refused: {} |", reason.replace('|', "\\|"))
            }
        };
    }
    md.push('\n');
    md
}

/// The "Measured files" section of a page: a table of the batch (with the files refused),
/// then each file's format, rows, points, notes, and its dropped rows as line ranges with their
/// reasons.
pub fn measured_files_html(files: &[FileEntry], refused: &[Refused]) -> String {
    let mut h = String::from("<h2>Measured files</h2>\n");
    h.push_str(&batch_table_html(files, refused));
    for (i, f) in files.iter().enumerate() {
        let s = f.set;
        let _ = write!(
            h,
            "<h3>{}. <code>{}</code></h3>\n<p>{:?} file, reduced as {:?}: {} rows → {} points; {}.</p>\n<ul>",
            i + 1,
            esc(&f.path),
            s.format,
            s.reduction,
            s.rows,
            s.points.len(),
            esc(&propbet_measure::summarise_dropped(&s.dropped))
        );
        for w in &s.warnings {
            let _ = write!(h, "<li><b>warning</b>: {}</li>", esc(w));
        }
        for n in &s.notes {
            let _ = write!(h, "<li>{}</li>", esc(n));
        }
        h.push_str("</ul>\n");
        if !s.dropped.is_empty() {
            let _ = writeln!(
                h,
                "<details><summary>{} dropped rows</summary><table><tr><th>lines</th><th>rows</th><th>reason</th><th>detail</th></tr>",
                s.dropped.len()
            );
            for (a, b, n, r, d) in dropped_ranges(&s.dropped) {
                let lines = if a == b { a.to_string() } else { format!("{a}–{b}") };
                let _ = writeln!(
                    h,
                    "<tr><td>{lines}</td><td>{n}</td><td>{}</td><td>{}</td></tr>",
                    r.text(),
                    esc(&d)
                );
            }
            h.push_str("</table></details>\n");
        }
    }
    h
}

/// The "Measured files" section of a Markdown summary.
pub fn measured_files_md(files: &[FileEntry], refused: &[Refused]) -> String {
    let mut md = String::new();
    md.push_str("## Measured files\n\n");
    md.push_str(&batch_table_md(files, refused));
    for (i, f) in files.iter().enumerate() {
        let _ = writeln!(
            md,
            "{}. `{}`: {:?}, {:?}; {} rows → {} points; {}.",
            i + 1,
            f.path,
            f.set.format,
            f.set.reduction,
            f.set.rows,
            f.set.points.len(),
            propbet_measure::summarise_dropped(&f.set.dropped)
        );
        for w in &f.set.warnings {
            let _ = writeln!(md, "   - **warning**: {w}");
        }
        for n in &f.set.notes {
            let _ = writeln!(md, "   - {n}");
        }
    }
    md
}

/// Consecutive dropped rows of one reason, as line ranges.
pub fn dropped_ranges(dropped: &[Dropped]) -> Vec<(usize, usize, usize, DropReason, String)> {
    let mut out: Vec<(usize, usize, usize, DropReason, String)> = Vec::new();
    for d in dropped {
        if let Some(last) = out.last_mut() {
            if last.3 == d.reason && last.1 + 1 == d.line && !d.reason.is_fault() {
                last.1 = d.line;
                last.2 += 1;
                continue;
            }
        }
        out.push((d.line, d.line, 1, d.reason, d.detail.clone()));
    }
    out
}
