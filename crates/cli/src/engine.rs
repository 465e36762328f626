//! How polars are made, shared by every command that makes them: the engine, XFOIL and its
//! cache (`XfoilProcess`), the progress bar, where a blade file's sections come from
//! (`DesignArgs`).

use std::path::PathBuf;

use clap::Args;
use propbet_api::spec::XfoilProcessSpec;

/// The XFOIL executable, the polar cache and the progress bar (shared by every command that
/// runs XFOIL, and passed on by `run` and `validate` to their `polars` stages).
// Fields without a doc comment are documented by their declared setting's help (`settings`).
#[allow(missing_docs)]
#[derive(Debug, Args)]
pub struct XfoilProcess {
    /// XFOIL executable (default: `xfoil` on PATH).
    #[arg(long)]
    pub xfoil: Option<PathBuf>,
    /// Polar cache directory (default: $PROPBET_CACHE_DIR, $XDG_CACHE_HOME/propbet/polars or
    /// ~/.cache/propbet/polars).
    #[arg(long, conflicts_with = "no_cache")]
    pub cache: Option<PathBuf>,
    /// Compute every polar afresh and store nothing.
    #[arg(long)]
    pub no_cache: bool,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    #[arg(long = propbet_api::settings::XFOIL_BUDGET.flag, help = propbet_api::settings::XFOIL_BUDGET.help, value_name = "SECONDS")]
    pub xfoil_budget: Option<f64>,
    #[arg(
        long = propbet_api::settings::ENGINE.flag,
        help = propbet_api::settings::ENGINE.help,
        value_parser = clap::builder::PossibleValuesParser::new(propbet_api::settings::ENGINE.names().iter().copied()),
        default_value = propbet_api::settings::ENGINE.default,
    )]
    pub engine: String,
    #[arg(
        long = propbet_api::settings::NEURALFOIL_SIZE.flag,
        help = propbet_api::settings::NEURALFOIL_SIZE.help,
        value_parser = clap::builder::PossibleValuesParser::new(propbet_api::settings::NEURALFOIL_SIZE.names().iter().copied()),
    )]
    pub neuralfoil_size: Option<String>,
}

impl XfoilProcess {
    /// What the flags ask for.
    pub fn request(&self) -> propbet_api::ProcessRequest {
        propbet_api::ProcessRequest {
            engine: Some(self.engine.clone()),
            neuralfoil_size: self.neuralfoil_size.clone(),
            xfoil: self.xfoil.clone(),
            cache: self.cache.clone(),
            no_cache: self.no_cache,
            quiet: self.quiet,
            budget: self.xfoil_budget,
        }
    }

    /// The same settings as a spec.
    pub fn spec(&self) -> anyhow::Result<XfoilProcessSpec> {
        Ok(self.request().spec()?)
    }
}

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
