//! What a propbet process has running or on disk while XFOIL works (XFOIL's process groups,
//! its temporary folders) is removed when propbet is interrupted (SIGINT, SIGTERM, SIGHUP):
//! XFOIL leads its own process group, so without this a hung XFOIL outlives an interrupted
//! propbet for ever. [`install`] once, early in `main`; the runner tracks what it starts.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

static GROUPS: Mutex<Vec<i32>> = Mutex::new(Vec::new());
static DIRS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Handles SIGINT, SIGTERM and SIGHUP on a thread of its own: kills every tracked XFOIL
/// process group, removes every tracked temporary folder, and exits with 128 + the signal,
/// as the default action would have.
pub fn install() -> std::io::Result<()> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
    std::thread::Builder::new()
        .name("propbet-interrupt".into())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                clean_up();
                std::process::exit(128 + signal);
            }
        })?;
    Ok(())
}

/// Kills the tracked process groups and removes the tracked folders.
fn clean_up() {
    if let Ok(groups) = GROUPS.lock() {
        for &pid in groups.iter() {
            if let Some(pid) = rustix::process::Pid::from_raw(pid) {
                let _ = rustix::process::kill_process_group(pid, rustix::process::Signal::KILL);
            }
        }
    }
    if let Ok(dirs) = DIRS.lock() {
        for d in dirs.iter() {
            let _ = std::fs::remove_dir_all(d);
        }
    }
}

/// A started XFOIL (its process group) and its temporary folder, tracked while it lives.
pub(crate) struct Tracked {
    group: i32,
    dir: PathBuf,
}

impl Tracked {
    pub(crate) fn new(group: u32, dir: &Path) -> Self {
        let group = i32::try_from(group).unwrap_or(0);
        if let Ok(mut g) = GROUPS.lock() {
            g.push(group);
        }
        if let Ok(mut d) = DIRS.lock() {
            d.push(dir.to_path_buf());
        }
        Tracked {
            group,
            dir: dir.to_path_buf(),
        }
    }
}

impl Drop for Tracked {
    fn drop(&mut self) {
        if let Ok(mut g) = GROUPS.lock() {
            g.retain(|&x| x != self.group);
        }
        if let Ok(mut d) = DIRS.lock() {
            d.retain(|x| *x != self.dir);
        }
    }
}
