//! A case's run before it runs: where the case is (the shipped default when none is given) and
//! where it writes, its plan, and the checks that stop it before anything is computed or
//! written (the output folder, missing inputs, inputs outside the case's folder, measurements
//! none of which reads).

use std::path::{Path, PathBuf};

use crate::command_error::refuse;
use crate::{CommandError, CommandResult as Result};
use propbet_pipeline::case::{read_case, RunPlan};
use propbet_settings::spec::XfoilProcessSpec;

/// The shipped default case: `props/apcsp_10x7` under the current directory or beside the
/// executable's repository (`target/release/propbet` → `../../props`).
fn default_case() -> Result<PathBuf> {
    let rel = Path::new("props").join("apcsp_10x7");
    let mut tried = vec![rel.clone()];
    if rel.join("case.toml").is_file() {
        return Ok(rel);
    }
    if let Ok(exe) = std::env::current_exe() {
        for up in exe.ancestors().skip(1).take(4) {
            let c = up.join(&rel);
            if c.join("case.toml").is_file() {
                return Ok(c);
            }
            tried.push(c);
        }
    }
    refuse!(
        "no case directory given and the default case is not at {}",
        tried
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    )
}

/// The plan of a case directory, writing under `out`.
pub fn plan(dir: &Path, out: &Path, xfoil: &XfoilProcessSpec) -> Result<RunPlan> {
    let case = read_case(dir)?;
    Ok(case.plan(dir, out, xfoil)?)
}

/// The case directory (the default case without one) and the output directory (`run_<case>`
/// without `-o`).
pub fn case_and_out(case: Option<&Path>, out: Option<&Path>) -> Result<(PathBuf, PathBuf)> {
    let dir = match case {
        Some(d) => d.to_path_buf(),
        None => default_case()?,
    };
    if !dir.is_dir() {
        refuse!("{}: not a case directory", dir.display());
    }
    let out = match out {
        Some(o) => o.to_path_buf(),
        None => {
            let name = dir
                .canonicalize()
                .ok()
                .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
                .unwrap_or_else(|| "case".into());
            PathBuf::from(format!("run_{name}"))
        }
    };
    Ok((dir, out))
}

/// The case's files exist and none lies where the run writes; the output is not the case.
pub fn check_paths(plan: &RunPlan, dir: &Path, out: &Path, anywhere: bool) -> Result<()> {
    if let (Ok(o), Ok(d)) = (out.canonicalize(), dir.canonicalize()) {
        if o == d || d.starts_with(&o) {
            refuse!(
                "{}: the output directory would hold the case's own files",
                out.display()
            );
        }
    }
    // Every file the case names exists, before anything runs or is written.
    let missing = plan.missing_inputs();
    if !missing.is_empty() {
        let list: Vec<String> = missing.iter().map(|f| f.display().to_string()).collect();
        refuse!(
            "{}: names {} not exist: {} (relative paths are taken from the case directory); nothing was run",
            dir.join("case.toml").display(),
            if list.len() == 1 {
                "a file that does"
            } else {
                "files that do"
            },
            list.join(", ")
        );
    }
    // No input of the case may lie where the run writes (a stage would overwrite it).
    let inputs = plan.inputs();
    let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    // A link in the output folder is refused in its own words, not as an input of the case.
    crate::files::refuse_links_inside(out)?;
    crate::files::refuse_inputs_below(out, &inputs).map_err(|e| {
        e.context(format!(
            "{}: the case reads a file in the output directory",
            dir.join("case.toml").display()
        ))
    })?;
    // A case reads its own files: one outside its folder is named, never read (its contents
    // are not echoed in an error), unless the run allows it.
    let outside = plan.outside_inputs();
    if !anywhere && !outside.is_empty() {
        let list: Vec<String> = outside.iter().map(|f| f.display().to_string()).collect();
        refuse!(
            "{}: names files outside the case's folder: {} (a case reads its own files: copy them in, or give \
             --inputs-anywhere); nothing was run",
            dir.join("case.toml").display(),
            list.join(", ")
        );
    }
    // The measurements are read now, before any stage: a case none of whose files reads stops
    // here, not after its polars and predictions.
    if let Some((c, _)) = &plan.compare {
        propbet_pipeline::stages::load_batch(&c.measured).map_err(|e| {
            CommandError::from(e).context(format!(
                "{}: [measured] files; nothing was run",
                dir.join("case.toml").display()
            ))
        })?;
    }
    Ok(())
}
