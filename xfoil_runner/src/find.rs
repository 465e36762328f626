//! Locating the XFOIL executable.

use std::path::{Path, PathBuf};

use thiserror::Error;

/// XFOIL could not be found.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
pub enum FindXfoilError {
    /// Not on the PATH (or the given path is not a file).
    #[error(
        "XFOIL was not found ({searched}); install it with `apt-get install xfoil xvfb` (Debian package xfoil 6.99)"
    )]
    NotFound {
        /// Where it was looked for.
        searched: String,
    },
}

/// Finds the XFOIL executable: `explicit` when given, else `xfoil` on `path_var` (a PATH-style
/// list of directories).
pub fn find_xfoil(explicit: Option<&Path>, path_var: Option<&std::ffi::OsStr>) -> Result<PathBuf, FindXfoilError> {
    if let Some(p) = explicit {
        return if p.is_file() {
            // Absolute: XFOIL runs in a temporary folder, where `./fake.sh` is not.
            Ok(std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf()))
        } else {
            Err(FindXfoilError::NotFound {
                searched: p.display().to_string(),
            })
        };
    }
    find_on_path("xfoil", path_var).ok_or_else(|| FindXfoilError::NotFound {
        searched: format!(
            "xfoil on PATH ({} directories)",
            path_var.map_or(0, |v| std::env::split_paths(v).count())
        ),
    })
}

/// The first file called `name` in the directories of `path_var` (a PATH-style list).
pub(crate) fn find_on_path(name: &str, path_var: Option<&std::ffi::OsStr>) -> Option<PathBuf> {
    let dirs: Vec<PathBuf> = path_var.map(|v| std::env::split_paths(v).collect()).unwrap_or_default();
    dirs.iter().map(|d| d.join(name)).find(|c| c.is_file())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_xfoil_says_how_to_install() {
        let dir = std::env::temp_dir().join("propbet-no-xfoil-here");
        let e = find_xfoil(None, Some(dir.as_os_str())).unwrap_err();
        assert!(e.to_string().contains("apt-get install xfoil"), "{e}");
        let e = find_xfoil(Some(&dir.join("xfoil")), None).unwrap_err();
        assert!(e.to_string().contains("propbet-no-xfoil-here"), "{e}");
    }

    #[test]
    fn finds_an_executable_on_the_path() {
        let dir = std::env::temp_dir().join(format!("propbet-xfoil-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("xfoil"), b"#!/bin/sh\n").unwrap();
        let found = find_xfoil(None, Some(dir.as_os_str())).unwrap();
        assert_eq!(found, dir.join("xfoil"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
