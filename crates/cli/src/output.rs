//! The terminal: the console the commands below the binary tell (standard output, standard
//! error, the progress bar of polars, the equivalent command lines), its long sentences
//! wrapped for a person.

use std::io::Write;

use propbet_api::diagnose::Diagnosis;
use propbet_api::spec::{PredictSpec, StageSpec, XfoilProcessSpec};

use crate::engine::Bar;

/// The terminal as a command's [`Console`](propbet_api::console::Console): lines printed,
/// tables written to standard output, one progress bar for a batch of polars.
#[derive(Default)]
pub struct Terminal {
    bar: std::sync::Mutex<Option<Bar>>,
}

impl propbet_api::console::Console for Terminal {
    fn out(&self, text: &str) {
        println!("{text}");
    }

    fn err(&self, text: &str) {
        eprintln!("{text}");
    }

    fn data(&self, bytes: &[u8]) -> std::io::Result<()> {
        let mut out = std::io::stdout().lock();
        out.write_all(bytes)?;
        out.flush()
    }

    fn progress(&self, process: &XfoilProcessSpec, done: usize, total: usize) {
        let mut slot = self.bar.lock().unwrap_or_else(|e| e.into_inner());
        slot.get_or_insert_with(|| Bar::new(process.quiet, process.engine))
            .tick(done, total);
    }

    fn progress_done(&self) {
        self.bar.lock().unwrap_or_else(|e| e.into_inner()).take();
    }

    fn command(&self, stage: &StageSpec) -> String {
        crate::argv::command(stage)
    }

    fn export_command(&self, spec: &PredictSpec, out: &std::path::Path) -> String {
        crate::argv::export_command(spec, out)
    }

    fn effect_args(&self, diagnosis: &Diagnosis) -> Vec<String> {
        crate::argv::effect_args(diagnosis)
    }

    fn is_terminal(&self, stdout: bool) -> bool {
        use std::io::IsTerminal;
        if stdout {
            std::io::stdout().is_terminal()
        } else {
            std::io::stderr().is_terminal()
        }
    }
}

/// `text` as the stream gets it: on a `terminal`, each line longer than 160 characters wrapped
/// at [`TERM_WIDTH`](propbet_api::console::TERM_WIDTH) (its continuation indented by two spaces
/// more than it), unless it is a table row (CSV, or Markdown's `|`), which is data, or an
/// error or a warning, which is read whole; into a pipe or a file, as it is (a script reads
/// each message as one line).
pub fn for_terminal(text: &str, terminal: bool) -> String {
    if !terminal || text.lines().all(|l| l.chars().count() <= 160) {
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
            propbet_api::console::wrapped(l.trim_start(), &indent, &format!("{indent}  "))
        })
        .collect::<Vec<_>>()
        .join("\n")
        + if text.ends_with('\n') { "\n" } else { "" }
}
