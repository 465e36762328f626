//! The files of a validation: the props of a UIUC directory, APC's files by name, the
//! measurements of one prop and the operating points its polars cover.

use std::path::{Path, PathBuf};

use super::ValidateSpec;
use propbet_model::design::first_file;
use propbet_model::{Error, Result};
use propbet_pipeline::stages;
use propbet_settings::spec::MeasuredSpec;

/// The UIUC name of a file of a UIUC directory: `<family>_<D>x<P>` from `<family>_<D>x<P>_*.txt`
/// (`apcsf_10x4.7_static_kt0835.txt` → `apcsf_10x4.7`); None for a file that is not one.
pub fn uiuc_name(file: &str) -> Option<String> {
    let stem = file.strip_suffix(".txt")?;
    let mut parts = stem.splitn(3, '_');
    let (family, size, rest) = (parts.next()?, parts.next()?, parts.next()?);
    let (d, p) = size.split_once('x')?;
    let number = |s: &str| s.parse::<f64>().is_ok_and(|x| x.is_finite() && x > 0.0);
    (!family.is_empty() && number(d) && number(p) && !rest.is_empty()).then(|| format!("{family}_{size}"))
}

/// The props of a UIUC directory: every name with a geometry file (`<prop>_geom.txt`) or a
/// static or J-sweep file, sorted; a prop without a geometry file is still validated (from
/// APC's design blade) or listed with the reason, never dropped.
pub fn uiuc_props(uiuc: &Path) -> Result<Vec<String>> {
    let mut props: Vec<String> = std::fs::read_dir(uiuc)
        .map_err(|reason| Error::Read {
            path: uiuc.to_path_buf(),
            reason,
        })?
        .filter_map(|e| uiuc_name(e.ok()?.file_name().to_str()?))
        .collect();
    props.sort();
    props.dedup();
    Ok(props)
}

/// The file of `dir` named `name` as APC names it, or as it is often saved: in another case, or
/// with the size's decimal point (`10x4.7SF-PERF.PE0`, `10x47sf-perf.pe0` for
/// `10x47SF-PERF.PE0`); the exact name first. None where the directory has none.
pub fn find_apc_file(dir: &Path, name: &str) -> Option<PathBuf> {
    let exact = dir.join(name);
    if exact.is_file() {
        return Some(exact);
    }
    let key = |s: &str| s.to_ascii_uppercase().replace('.', "");
    let want = key(name);
    first_file(dir, |n| key(n) == want).ok().flatten()
}

/// A prop's measured files, and those that do not read.
pub(super) struct MeasuredFiles {
    pub(super) files: Vec<PathBuf>,
    /// (file name, why).
    pub(super) left_out: Vec<(String, String)>,
}

/// The measurements: every file of this prop but the geometry, and those left out (file name,
/// why). A file that does not read is left out with its reason (the row and the table say so,
/// and the command's exit is 1); the prop is validated from its others, if any.
pub(super) fn measured_files(spec: &ValidateSpec, prop: &str) -> Result<MeasuredFiles> {
    let mut measured: Vec<PathBuf> = std::fs::read_dir(&spec.uiuc)
        .map_err(|reason| Error::Read {
            path: spec.uiuc.clone(),
            reason,
        })?
        .filter_map(|e| {
            let n = e.ok()?.file_name().to_str()?.to_string();
            (n.starts_with(&format!("{prop}_")) && n.ends_with(".txt") && !n.ends_with("_geom.txt")).then_some(n)
        })
        .map(|n| spec.uiuc.join(n))
        .collect();
    measured.sort();
    if measured.is_empty() {
        return Err(Error::Nothing("no static or J-sweep file".into()));
    }
    let mut left_out = Vec::new();
    measured.retain(|f| match stages::load_measured(&MeasuredSpec::files(vec![f.clone()])) {
        Ok(_) => true,
        Err(e) => {
            left_out.push((
                f.file_name().unwrap_or_default().to_string_lossy().into_owned(),
                e.to_string(),
            ));
            false
        }
    });
    if measured.is_empty() {
        return Err(Error::Nothing(format!(
            "no file of it reads: {}",
            left_out
                .iter()
                .map(|(_, why)| why.as_str())
                .collect::<Vec<_>>()
                .join("; ")
        )));
    }
    Ok(MeasuredFiles {
        files: measured,
        left_out,
    })
}
