//! Writing results: CSV and JSON tables, written atomically (a temporary file in the target
//! directory, renamed into place) and never over an input file.

use std::io::Write;
use std::path::Path;

use anyhow::{bail, Context, Result};

/// Appends `v` rounded to 10 significant digits (more than the solver's accuracy, fewer than
/// the float noise of unit conversions), in shortest form; an empty cell for `None`.
pub fn push_num(buf: &mut String, v: Option<f64>) {
    if let Some(v) = v {
        let mut b = ryu::Buffer::new();
        buf.push_str(b.format(round_sig(v, 10)));
    }
}

/// `v` rounded to `digits` significant digits.
pub fn round_sig(v: f64, digits: i32) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let mag = v.abs().log10().floor() as i32;
    let scale = 10f64.powi(digits - 1 - mag);
    let r = (v * scale).round() / scale;
    if r.is_finite() {
        r
    } else {
        v
    }
}

/// Writes `bytes` to `path` atomically, refusing to replace any of `inputs`.
pub fn write_atomic(path: &Path, bytes: &[u8], inputs: &[&Path]) -> Result<()> {
    if let Ok(target) = path.canonicalize() {
        for input in inputs {
            if input.canonicalize().ok().as_deref() == Some(target.as_path()) {
                bail!("{}: refusing to overwrite an input file", path.display());
            }
        }
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut tmp = tempfile::NamedTempFile::new_in(dir)
        .with_context(|| format!("{}: cannot create a file in {}", path.display(), dir.display()))?;
    tmp.write_all(bytes)
        .with_context(|| format!("{}: write failed", path.display()))?;
    tmp.persist(path)
        .with_context(|| format!("{}: cannot move the finished file into place", path.display()))?;
    Ok(())
}

/// Writes to `path`, or to standard output when `path` is `None` or `-`.
pub fn emit(path: Option<&Path>, bytes: &[u8], inputs: &[&Path]) -> Result<()> {
    match path {
        Some(p) if p != Path::new("-") => write_atomic(p, bytes, inputs),
        _ => {
            let mut out = std::io::stdout().lock();
            out.write_all(bytes).context("writing to standard output")?;
            out.flush().context("writing to standard output")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ten_significant_digits() {
        let mut s = String::new();
        for v in [6000.000000000001, 0.19999999999999998, 2.0319999976781014, -1.5e-7, 0.0] {
            push_num(&mut s, Some(v));
            s.push(' ');
        }
        push_num(&mut s, None);
        assert_eq!(s, "6000.0 0.2 2.031999998 -1.5e-7 0.0 ");
    }
}
