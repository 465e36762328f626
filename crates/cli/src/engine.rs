//! How polars are made, shared by every command that makes them: the progress bar, where a
//! blade file's sections come from (`DesignArgs`).

use std::path::PathBuf;

use clap::Args;

/// A progress bar on stderr for polar jobs, drawn only when stderr is a terminal, hidden with
/// `quiet`: made at the first job of a batch and cleared when the batch is done (or the bar is
/// dropped), so that no bar is ever left on the terminal; labelled with the engine that makes the
/// polars.
pub struct Bar {
    quiet: bool,
    label: &'static str,
    bar: std::sync::Mutex<Option<indicatif::ProgressBar>>,
}

impl Bar {
    /// A bar for `engine`'s polars; never drawn when `quiet`.
    pub fn new(quiet: bool, engine: propbet_api::polar::Engine) -> Self {
        let label = match engine {
            propbet_api::polar::Engine::NeuralFoil => "NeuralFoil",
            _ => "XFOIL",
        };
        Bar {
            quiet,
            label,
            bar: std::sync::Mutex::new(None),
        }
    }

    /// Clears the bar, drawn or not.
    pub fn clear(&self) {
        if let Some(b) = self.bar.lock().unwrap_or_else(|e| e.into_inner()).take() {
            b.finish_and_clear();
        }
    }

    /// The callback the polar engine calls: `done` of `total` jobs.
    pub fn tick(&self, done: usize, total: usize) {
        if self.quiet || total == 0 {
            return;
        }
        let mut slot = self.bar.lock().unwrap_or_else(|e| e.into_inner());
        if done >= total {
            if let Some(b) = slot.take() {
                b.finish_and_clear();
            }
            return;
        }
        let b = slot.get_or_insert_with(|| {
            let b = indicatif::ProgressBar::new(total as u64);
            if let Ok(style) =
                indicatif::ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} polars, {eta} left")
            {
                b.set_style(style.progress_chars("=> "));
            }
            b.set_prefix(self.label);
            b
        });
        b.set_length(total as u64);
        b.set_position(done as u64);
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        self.clear();
    }
}

/// Where a blade file's sections come from, beside the file itself.
#[derive(Debug, Args, Clone, Default)]
pub struct DesignArgs {
    /// APC's design file (PE0) whose sections a UIUC geometry table or blade table takes:
    /// APC's airfoils blended across its transition and scaled to its thickness at each
    /// station, as `propbet validate` models APC's propellers.
    #[arg(long, value_name = "PE0")]
    pub sections_from: Option<PathBuf>,
    /// A directory of airfoil coordinates (`e63.dat`, ...) looked in before propbet's own.
    #[arg(long, value_name = "DIR")]
    pub airfoils: Option<PathBuf>,
}
