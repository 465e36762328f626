//! Where a command's words go, and how its stages read as commands: the door that runs it
//! (the binary's terminal, the Python package's streams) says. A command below the binary
//! tells its answer and its problems here, line by line, as it has them.

use crate::diagnose::Diagnosis;
use propbet_settings::spec::{PredictSpec, StageSpec, XfoilProcessSpec};

/// A door's terminal and command lines, as a command running below it uses them.
pub trait Console: Sync {
    /// A line of the answer (standard output).
    fn out(&self, text: &str);
    /// A line on how it went: a warning, a note, a stage's status (standard error).
    fn err(&self, text: &str);
    /// A table as it is, bytes on standard output (no file given for it), in the chunks it was
    /// made in.
    fn data(&self, bytes: &[u8]) -> std::io::Result<()>;
    /// `done` of `total` polars made by `process`'s engine (a progress bar).
    fn progress(&self, process: &XfoilProcessSpec, done: usize, total: usize);
    /// The polars are done: the progress is cleared.
    fn progress_done(&self);
    /// The command line that does what `stage` does (the binary's one formatter).
    fn command(&self, stage: &StageSpec) -> String;
    /// The command line that exports `spec`'s prediction for every simulator into `out`.
    fn export_command(&self, spec: &PredictSpec, out: &std::path::Path) -> String;
    /// A diagnosis's final model as the `--effect` arguments that add it to a model.
    fn effect_args(&self, diagnosis: &Diagnosis) -> Vec<String>;
    /// Whether standard output (`stdout`) or standard error is a terminal a person reads: long
    /// sentences are wrapped there, and only there (a script or a log file reads each message
    /// as one line).
    fn is_terminal(&self, _stdout: bool) -> bool {
        false
    }
    /// A sentence on standard output: wrapped at [`TERM_WIDTH`] after the indents `first` and
    /// `rest` on a terminal, one line after `first` otherwise.
    fn out_sentence(&self, text: &str, first: &str, rest: &str) {
        self.out(&sentence(text, first, rest, self.is_terminal(true)));
    }
    /// The same on standard error.
    fn err_sentence(&self, text: &str, first: &str, rest: &str) {
        self.err(&sentence(text, first, rest, self.is_terminal(false)));
    }
}

/// `text` after `first`, wrapped ([`wrapped`]) when `terminal`.
fn sentence(text: &str, first: &str, rest: &str, terminal: bool) -> String {
    if terminal {
        wrapped(text, first, rest)
    } else {
        format!("{first}{text}")
    }
}

/// The terminal's width for propbet's sentences.
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

/// A Markdown page line by line on standard output: its tables as they are (data), its
/// sentences wrapped on a terminal.
pub fn print_page(console: &dyn Console, md: &str) {
    for line in md.lines() {
        if line.starts_with('|') {
            console.out(line);
        } else {
            console.out_sentence(line, "", "");
        }
    }
}

/// Writes `chunks` to `path`, or to standard output when `path` is `None` or `-`.
pub fn emit<B: AsRef<[u8]>>(
    console: &dyn Console,
    path: Option<&std::path::Path>,
    chunks: &[B],
    inputs: &[&std::path::Path],
) -> crate::CommandResult<()> {
    match path {
        Some(p) if p != std::path::Path::new("-") => crate::files::write_atomic(p, chunks, inputs),
        _ => chunks
            .iter()
            .try_for_each(|c| console.data(c.as_ref()))
            .map_err(|e| crate::CommandError::io("writing to standard output", e)),
    }
}
