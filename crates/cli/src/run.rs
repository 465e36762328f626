//! `propbet run CASE_DIR`: the main job. A case directory's `case.toml` names a scan (or a
//! prop file), the sections, the operating points, the measurements and the air; the run
//! chains scan → XFOIL or NeuralFoil polars at each station's Reynolds number → BEMT sweeps → comparison →
//! diagnosis in memory (`propbet_api::commands::run`), each stage the documented command
//! it is equivalent to, then writes every stage's outputs and one HTML report that holds them.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;

/// Arguments of `propbet run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// Case directory holding `case.toml` (default: the shipped `props/apcsp_10x7`, APC's 10x7 Sport
    /// from its design file against UIUC's measurements).
    pub case: Option<PathBuf>,
    /// Output directory (default: `run_<case directory name>` in the current directory).
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// XFOIL executable, polar cache, progress bars (passed on to the polars stage).
    #[command(flatten)]
    pub xfoil: propbet_api::ProcessRequest,
    /// Print every stage's full terminal output (each station's polar fit, the measured files
    /// again for the diagnosis), as the stages' own commands do; by default a summary per stage.
    #[arg(long)]
    pub verbose: bool,
    /// Read files the case names outside its folder (by default every file a case names lies
    /// in it, links followed).
    #[arg(long)]
    pub inputs_anywhere: bool,
}

/// Runs `propbet run`.
pub fn run(a: &RunArgs) -> Result<bool> {
    let request = propbet_api::commands::run::RunRequest {
        case: a.case.clone(),
        out: a.out.clone(),
        xfoil: a.xfoil.spec()?,
        verbose: a.verbose,
        inputs_anywhere: a.inputs_anywhere,
    };
    Ok(propbet_api::commands::run::run(&request, &crate::output::Terminal::default())?.0)
}
