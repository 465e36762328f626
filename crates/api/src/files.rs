//! Writing results, the explicit step after computing them: an output folder claimed and
//! marked incomplete until done, every file written atomically (named only once complete) and
//! never over an input file.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::command_error::refuse;
use crate::{CommandError, CommandResult as Result};

/// The file that marks an output folder as incomplete while a command writes it.
pub const INCOMPLETE: &str = "INCOMPLETE.txt";

/// An output folder this process writes: locked (flock(2) on the folder itself) until the
/// guard drops, so a second propbet writing the same folder stops at once instead of mixing
/// its files with the first's; and marked by [`INCOMPLETE`] until [`FolderLock::finish`], so a
/// command that fails half-way (a full disk, a signal) leaves a folder that says so.
#[must_use = "the folder is locked only while the guard lives"]
pub struct FolderLock {
    _file: Option<std::fs::File>,
    marker: std::path::PathBuf,
}

impl FolderLock {
    /// Every output is written: the marker goes (the lock goes with the guard).
    pub fn finish(self) -> Result<()> {
        std::fs::remove_file(&self.marker)
            .map_err(|e| CommandError::Message(format!("{}: cannot remove: {e}", self.marker.display())))
    }
}

/// Creates `dir` if needed, locks it for this process (an error when another propbet holds
/// it; a file system without locks, some network mounts, is written unlocked) and marks it
/// incomplete, naming `command`.
pub fn claim_folder(dir: &Path, command: &str) -> Result<FolderLock> {
    std::fs::create_dir_all(dir)
        .map_err(|e| CommandError::Message(format!("{}: cannot create: {e}", dir.display())))?;
    let f =
        std::fs::File::open(dir).map_err(|e| CommandError::Message(format!("{}: cannot open: {e}", dir.display())))?;
    let file = match f.try_lock() {
        Ok(()) => Some(f),
        Err(std::fs::TryLockError::WouldBlock) => refuse!(
            "{}: another propbet is writing this folder; wait for it to finish or give another output folder",
            dir.display()
        ),
        Err(std::fs::TryLockError::Error(e)) if e.kind() == std::io::ErrorKind::Unsupported => None,
        Err(std::fs::TryLockError::Error(e)) => refuse!("{}: cannot lock: {e}", dir.display()),
    };
    let marker = dir.join(INCOMPLETE);
    write_atomic(
        &marker,
        &[format!(
            "This folder is incomplete: `{command}` started writing it and has not finished (it failed, was \
             interrupted, or is still running). Its files may be from different runs.\n"
        )],
        &[],
    )?;
    Ok(FolderLock { _file: file, marker })
}

/// Refuses, before a command computes or writes anything, an output directory `out` that holds
/// one of the command's `inputs` (files or directories): a later write could replace it.
/// Nothing is inside a directory that does not exist yet.
pub fn refuse_inputs_inside(out: &Path, inputs: &[&Path]) -> Result<()> {
    refuse_links_inside(out)?;
    refuse_inputs_below(out, inputs)
}

/// The inputs half of [`refuse_inputs_inside`], for a caller that checks the links itself
/// (and words the inputs' error its own way).
pub fn refuse_inputs_below(out: &Path, inputs: &[&Path]) -> Result<()> {
    let Ok(o) = out.canonicalize() else { return Ok(()) };
    for input in inputs {
        if input.canonicalize().is_ok_and(|i| i.starts_with(&o)) {
            refuse!(
                "{}: this input is inside the output directory {}; choose another output directory",
                input.display(),
                out.display()
            );
        }
    }
    Ok(())
}

/// Refuses an output directory that holds a symbolic link (within three levels, the depth of
/// propbet's own folders): a link `OUT/predict -> CASE` would send the outputs over the case's
/// own files, and inputs read through it would be the outputs of the run.
pub fn refuse_links_inside(out: &Path) -> Result<()> {
    fn walk(dir: &Path, depth: usize, seen: &mut usize) -> Result<()> {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return Ok(());
        };
        for e in entries.flatten() {
            *seen += 1;
            if *seen > 20_000 {
                return Ok(());
            }
            let Ok(meta) = std::fs::symlink_metadata(e.path()) else {
                continue;
            };
            if meta.file_type().is_symlink() {
                let to = std::fs::read_link(e.path())
                    .map(|t| t.display().to_string())
                    .unwrap_or_default();
                refuse!(
                    "{}: a symbolic link (to {to}) inside the output directory: propbet writes only into real \
                     folders there, so that no output lands on another file; remove the link or choose another output directory",
                    e.path().display()
                );
            }
            if meta.is_dir() && depth < 3 {
                walk(&e.path(), depth + 1, seen)?;
            }
        }
        Ok(())
    }
    walk(out, 1, &mut 0)
}

/// Refuses, before a command computes or writes anything, output files that are among its
/// `inputs`.
pub fn refuse_outputs_over_inputs(outputs: &[&Path], inputs: &[&Path]) -> Result<()> {
    for out in outputs {
        let Ok(target) = out.canonicalize() else { continue };
        if inputs
            .iter()
            .any(|i| i.canonicalize().ok().as_deref() == Some(target.as_path()))
        {
            refuse!("{}: refusing to overwrite an input file", out.display());
        }
    }
    Ok(())
}

/// Writes `chunks` one after the other to `path` atomically, refusing to replace any of
/// `inputs` (a last guard: commands check their outputs against their inputs before they
/// start, [`refuse_inputs_inside`], [`refuse_outputs_over_inputs`]).
pub fn write_atomic<B: AsRef<[u8]>>(path: &Path, chunks: &[B], inputs: &[&Path]) -> Result<()> {
    refuse_outputs_over_inputs(&[path], inputs)?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    // The bytes go to a file without a name (O_TMPFILE), which gets one only when complete,
    // just before it is renamed into place: a run killed by SIGINT or SIGTERM while writing
    // leaves nothing behind. Where the directory cannot hold unnamed files, a named temporary.
    match unnamed_in(dir, chunks)
        .ok()
        .and_then(|file| link_hidden(&file, dir, path))
    {
        Some(tmp) => std::fs::rename(&tmp, path).map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            CommandError::Message(format!(
                "{}: cannot move the finished file into place: {e}",
                path.display()
            ))
        })?,
        None => {
            let mut tmp = tempfile::NamedTempFile::new_in(dir).map_err(|e| {
                CommandError::io(
                    format!("{}: cannot create a file in {}", path.display(), dir.display()),
                    e,
                )
            })?;
            {
                let mut w = std::io::BufWriter::new(tmp.as_file_mut());
                for c in chunks {
                    w.write_all(c.as_ref())
                        .map_err(|e| CommandError::io(format!("{}: write failed", path.display()), e))?;
                }
                w.flush()
                    .map_err(|e| CommandError::io(format!("{}: write failed", path.display()), e))?;
            }
            // Temporary files are created private (0600); a result is an ordinary file.
            #[cfg(unix)]
            {
                use std::os::unix::fs::PermissionsExt;
                let _ = std::fs::set_permissions(tmp.path(), std::fs::Permissions::from_mode(0o644));
            }
            tmp.persist(path).map_err(|e| {
                CommandError::io(
                    format!("{}: cannot move the finished file into place", path.display()),
                    e.error,
                )
            })?;
        }
    }
    Ok(())
}

/// The chunks in a file of `dir` that has no name yet (Linux O_TMPFILE via `tempfile`).
fn unnamed_in<B: AsRef<[u8]>>(dir: &Path, chunks: &[B]) -> std::io::Result<std::fs::File> {
    let file = tempfile::tempfile_in(dir)?;
    {
        let mut w = std::io::BufWriter::new(&file);
        for c in chunks {
            w.write_all(c.as_ref())?;
        }
        w.flush()?;
    }
    use std::os::unix::fs::PermissionsExt;
    file.set_permissions(std::fs::Permissions::from_mode(0o644))?;
    Ok(file)
}

/// Gives the unnamed `file` a hidden name in `dir` beside `path` (linkat through
/// /proc/self/fd), to be renamed over `path` at once; None where that cannot be done.
fn link_hidden(file: &std::fs::File, dir: &Path, path: &Path) -> Option<std::path::PathBuf> {
    use std::os::fd::AsRawFd;
    static COUNTER: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let name = path
        .file_name()
        .map_or("out".into(), |f| f.to_string_lossy().into_owned());
    let tmp = dir.join(format!(".{name}.propbet-{}-{n}", std::process::id()));
    rustix::fs::linkat(
        rustix::fs::CWD,
        format!("/proc/self/fd/{}", file.as_raw_fd()),
        rustix::fs::CWD,
        &tmp,
        rustix::fs::AtFlags::SYMLINK_FOLLOW,
    )
    .ok()?;
    Some(tmp)
}

/// Writes a figure to `path` as SVG or PNG (by its extension), atomically.
pub fn write_figure(path: &Path, fig: &propbet_plot::Figure, inputs: &[&Path]) -> Result<()> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let bytes = match ext.as_deref() {
        Some("svg") => propbet_plot::svg(fig)?.into_bytes(),
        Some("png") => propbet_plot::png(fig)?,
        _ => refuse!("{}: plots are written as .svg or .png", path.display()),
    };
    write_atomic(path, &[bytes], inputs)
}

/// A command's outputs in memory, in the order it writes them: each file's path under the
/// output folder and its bytes. Made by the computation; [`Outputs::write`] is the separate,
/// explicit step that puts them on disk.
#[derive(Debug, Default)]
pub struct Outputs {
    dirs: Vec<PathBuf>,
    files: Vec<(PathBuf, Vec<u8>)>,
}

impl Outputs {
    /// Adds the file `name` (a path under the output folder).
    pub fn add(&mut self, name: impl Into<PathBuf>, bytes: impl Into<Vec<u8>>) {
        self.files.push((name.into(), bytes.into()));
    }

    /// Adds a folder `name` that is made even when no file goes into it.
    pub fn dir(&mut self, name: impl Into<PathBuf>) {
        self.dirs.push(name.into());
    }

    /// Adds a figure as `name.svg`.
    pub fn svg(&mut self, name: &str, fig: &propbet_plot::Figure) -> Result<()> {
        self.add(format!("{name}.svg"), propbet_plot::svg(fig)?.into_bytes());
        Ok(())
    }

    /// Adds a figure as `name.svg` and `name.png`.
    pub fn figure(&mut self, name: &str, fig: &propbet_plot::Figure) -> Result<()> {
        self.svg(name, fig)?;
        self.add(format!("{name}.png"), propbet_plot::png(fig)?);
        Ok(())
    }

    /// The bytes of the file `name` taken out (empty if there is none).
    pub fn take(&mut self, name: &str) -> Vec<u8> {
        self.files
            .iter_mut()
            .find(|(n, _)| n == Path::new(name))
            .map(|(_, b)| std::mem::take(b))
            .unwrap_or_default()
    }

    /// Writes every file under `out`: the folder claimed for `command` and marked incomplete
    /// until the last is written ([`claim_folder`]), each file atomically and never over one
    /// of `inputs` ([`write_atomic`]).
    pub fn write(&self, out: &Path, command: &str, inputs: &[&Path]) -> Result<()> {
        let lock = claim_folder(out, command)?;
        for d in &self.dirs {
            let dir = out.join(d);
            std::fs::create_dir_all(&dir)
                .map_err(|e| CommandError::io(format!("{}: cannot create the directory", dir.display()), e))?;
        }
        for (name, bytes) in &self.files {
            let path = out.join(name);
            if let Some(dir) = path.parent().filter(|d| !d.exists()) {
                std::fs::create_dir_all(dir)
                    .map_err(|e| CommandError::io(format!("{}: cannot create the directory", dir.display()), e))?;
            }
            write_atomic(&path, &[bytes], inputs)?;
        }
        lock.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_output_has_no_name_until_it_is_complete() {
        let dir = tempfile::tempdir().unwrap();
        let file = unnamed_in(dir.path(), &[b"half of a result".as_slice()]).unwrap();
        // Written, not yet named: a signal now would leave nothing in the directory.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        drop(file);
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        // The whole write leaves exactly the result, readable by others.
        let out = dir.path().join("r.csv");
        write_atomic(&out, &[b"a,b\n".as_slice()], &[]).unwrap();
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("r.csv")]);
        assert_eq!(std::fs::read(&out).unwrap(), b"a,b\n");
        use std::os::unix::fs::PermissionsExt;
        assert_eq!(std::fs::metadata(&out).unwrap().permissions().mode() & 0o777, 0o644);
    }
}
