//! The terminal: sentences wrapped for a person, Markdown pages printed, and a table sent to
//! standard output or to its file.

use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result};

/// Writes `chunks` to `path`, or to standard output when `path` is `None` or `-`.
pub fn emit<B: AsRef<[u8]>>(path: Option<&Path>, chunks: &[B], inputs: &[&Path]) -> Result<()> {
    match path {
        Some(p) if p != Path::new("-") => Ok(propbet_api::files::write_atomic(p, chunks, inputs)?),
        _ => {
            let mut out = std::io::stdout().lock();
            for c in chunks {
                out.write_all(c.as_ref()).context("writing to standard output")?;
            }
            out.flush().context("writing to standard output")
        }
    }
}

/// `text` as the terminal gets it: each line longer than 160 characters wrapped at
/// [`TERM_WIDTH`] (its continuation indented by two spaces more than it), unless it is a table
/// row (CSV, or Markdown's `|`), which is data, or an error or a warning, which is read whole.
pub fn for_terminal(text: &str) -> String {
    if text.lines().all(|l| l.chars().count() <= 160) {
        return text.to_string();
    }
    text.lines()
        .map(|l| {
            let table_row = l.matches(',').count() >= 4 || l.trim_start().starts_with('|');
            // An error or a warning stays one line: scripts and the Python package read it so.
            let message = l.starts_with("propbet: error") || l.starts_with("propbet: warning");
            if l.chars().count() <= 160 || table_row || message {
                return l.to_string();
            }
            let indent: String = l.chars().take_while(|c| *c == ' ').collect();
            wrapped(l.trim_start(), &indent, &format!("{indent}  "))
        })
        .collect::<Vec<_>>()
        .join("\n")
        + if text.ends_with('\n') { "\n" } else { "" }
}

/// The terminal's width for propbet's sentences (and clap's help: `max_term_width`).
pub const TERM_WIDTH: usize = 100;

/// `text` wrapped at [`TERM_WIDTH`] columns, its first line after `first`, the others after
/// `rest` (each an indent): a long sentence a person reads on a terminal.
pub fn wrapped(text: &str, first: &str, rest: &str) -> String {
    let opts = textwrap::Options::new(TERM_WIDTH)
        .initial_indent(first)
        .subsequent_indent(rest)
        .break_words(false)
        .word_splitter(textwrap::WordSplitter::NoHyphenation);
    textwrap::fill(text, opts)
}

/// A Markdown page on the terminal: its tables as they are (data), its sentences wrapped.
pub(crate) fn print_page(md: &str) {
    for line in md.lines() {
        if line.starts_with('|') {
            println!("{line}");
        } else {
            println!("{}", wrapped(line, "", ""));
        }
    }
}
