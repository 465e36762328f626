//! A private X display for XFOIL.
//!
//! Debian's XFOIL 6.99 is built with floating-point traps; with graphics switched off (`PLOP`,
//! `G F`) it divides by zero in its plot set-up and dies of SIGFPE. So every XFOIL run gets an X
//! display: a private `Xvfb` server that the runner starts on first use and kills when the
//! [`PrivateDisplay`] is dropped. Nothing is ever drawn on the user's own screen.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex, Weak};
use std::time::{Duration, Instant};

use crate::XfoilError;

/// A running private Xvfb server.
#[derive(Debug)]
pub struct PrivateDisplay {
    child: Child,
    number: u32,
    /// Process id of the Xvfb server itself (the watcher shell's child).
    server_pid: u32,
}

/// The display shared by every runner of this process while any of them holds it.
static SHARED: Mutex<Weak<PrivateDisplay>> = Mutex::new(Weak::new());

/// `sh -c WATCHER propbet-xvfb XVFB :N PARENT_PID`: runs Xvfb until the parent dies (a
/// zombie counts as dead: `kill -0` would still succeed on it), Xvfb dies, or the shell gets
/// SIGTERM.
const WATCHER: &str = r#"
"$1" "$2" -nolisten tcp -screen 0 640x480x24 -nocursor >/dev/null 2>&1 &
x=$!
echo $x
trap 'kill $x 2>/dev/null; wait $x; exit 0' TERM INT HUP
alive() { s=$(cat /proc/$1/stat 2>/dev/null) || return 1; case "$s" in *") Z "*) return 1;; esac; }
while kill -0 $x 2>/dev/null && alive "$3"; do sleep 0.2; done
kill $x 2>/dev/null; wait $x
exit 1
"#;

/// Display numbers tried for the private server (far above the usual :0..:10).
const FIRST_DISPLAY: u32 = 140;
const DISPLAYS_TRIED: u32 = 60;

impl PrivateDisplay {
    /// The process's private display: the running one if any runner holds it, else a new one.
    /// Starting is serialised, so that threads never race for a display number.
    pub fn shared(xvfb: &Path) -> Result<Arc<Self>, XfoilError> {
        let mut guard = SHARED.lock().unwrap_or_else(|p| p.into_inner());
        if let Some(d) = guard.upgrade().filter(|d| d.is_alive()) {
            return Ok(d);
        }
        let d = Arc::new(PrivateDisplay::start(xvfb, Duration::from_secs(10))?);
        *guard = Arc::downgrade(&d);
        Ok(d)
    }

    /// Starts `Xvfb` on the first free display number at or above 140, waiting up to `timeout`
    /// for its socket to appear.
    pub fn start(xvfb: &Path, timeout: Duration) -> Result<Self, XfoilError> {
        // Spread concurrent propbet processes over the range so that they rarely race.
        let offset = std::process::id() % DISPLAYS_TRIED;
        let mut last_error = String::from("no display number was free");
        for k in 0..DISPLAYS_TRIED {
            let number = FIRST_DISPLAY + (offset + k) % DISPLAYS_TRIED;
            if Path::new(&format!("/tmp/.X{number}-lock")).exists()
                || Path::new(&format!("/tmp/.X11-unix/X{number}")).exists()
            {
                continue;
            }
            // A small shell keeps watch: it stops Xvfb when this process goes away without
            // dropping the display (killed), and when asked to (SIGTERM from Drop).
            let mut child = Command::new("sh")
                .args(["-c", WATCHER, "propbet-xvfb"])
                .arg(xvfb)
                .arg(format!(":{number}"))
                .arg(std::process::id().to_string())
                .stdin(Stdio::null())
                .stdout(Stdio::piped())
                .stderr(Stdio::null())
                .spawn()
                .map_err(|e| XfoilError::Display(format!("cannot start {}: {e}", xvfb.display())))?;
            let mut line = String::new();
            if let Some(out) = child.stdout.take() {
                let _ = BufReader::new(out).read_line(&mut line);
            }
            let server_pid = line.trim().parse().unwrap_or(0);
            let mut display = PrivateDisplay {
                child,
                number,
                server_pid,
            };
            match display.wait_ready(timeout) {
                Ok(()) => return Ok(display),
                Err(e) => last_error = e,
            }
            // Dropping `display` kills the failed server before the next number is tried.
        }
        Err(XfoilError::Display(format!(
            "could not start a private Xvfb server on displays :{FIRST_DISPLAY}..:{}: {last_error}",
            FIRST_DISPLAY + DISPLAYS_TRIED - 1
        )))
    }

    fn wait_ready(&mut self, timeout: Duration) -> Result<(), String> {
        let socket = format!("/tmp/.X11-unix/X{}", self.number);
        let start = Instant::now();
        loop {
            if let Ok(Some(status)) = self.child.try_wait() {
                return Err(format!(
                    "Xvfb :{} exited at start ({status}); display in use?",
                    self.number
                ));
            }
            // Ready when the lock file names our server (not another process's on this number).
            let lock = std::fs::read_to_string(format!("/tmp/.X{}-lock", self.number)).unwrap_or_default();
            if Path::new(&socket).exists() && lock.trim().parse::<u32>().ok() == Some(self.server_pid) {
                return Ok(());
            }
            if start.elapsed() > timeout {
                return Err(format!(
                    "Xvfb :{} did not open {socket} within {timeout:?}",
                    self.number
                ));
            }
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// The value for `DISPLAY`.
    pub fn name(&self) -> String {
        format!(":{}", self.number)
    }

    /// Whether the server still runs and owns its display (its lock file names it, its socket
    /// is there).
    pub fn is_alive(&self) -> bool {
        let lock = std::fs::read_to_string(format!("/tmp/.X{}-lock", self.number)).unwrap_or_default();
        // The state follows the command name's closing parenthesis: Z is a zombie.
        let running = std::fs::read_to_string(format!("/proc/{}/stat", self.server_pid))
            .ok()
            .and_then(|s| s.rsplit_once(')').map(|(_, rest)| !rest.trim_start().starts_with('Z')))
            .unwrap_or(false);
        running
            && lock.trim().parse::<u32>().ok() == Some(self.server_pid)
            && Path::new(&format!("/tmp/.X11-unix/X{}", self.number)).exists()
    }
}

impl Drop for PrivateDisplay {
    /// Stops the server politely (SIGTERM, so that it removes its lock file and socket), then
    /// by force after a second; removes what a forced stop leaves behind.
    fn drop(&mut self) {
        let pid = self.child.id().to_string();
        let polite = Command::new("kill")
            .args(["-TERM", &pid])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        let deadline = Instant::now() + Duration::from_secs(2);
        while polite && Instant::now() < deadline {
            if let Ok(Some(_)) = self.child.try_wait() {
                break;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
        if !matches!(self.child.try_wait(), Ok(Some(_))) {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
        // Remove only what our own server left (the lock file names its owner).
        let lock_path = format!("/tmp/.X{}-lock", self.number);
        let lock = std::fs::read_to_string(&lock_path).unwrap_or_default();
        if lock.trim().parse::<u32>().ok() == Some(self.server_pid) {
            let _ = std::fs::remove_file(&lock_path);
            let _ = std::fs::remove_file(format!("/tmp/.X11-unix/X{}", self.number));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn starts_and_cleans_up() {
        let xvfb = crate::find::find_on_path("Xvfb", std::env::var_os("PATH").as_deref())
            .expect("Xvfb must be installed (scripts/setup.sh)");
        let d = PrivateDisplay::start(&xvfb, Duration::from_secs(10)).unwrap();
        let n = d.number;
        assert!(Path::new(&format!("/tmp/.X11-unix/X{n}")).exists());
        assert!(d.is_alive());
        drop(d);
        assert!(!Path::new(&format!("/tmp/.X11-unix/X{n}")).exists());
        assert!(!Path::new(&format!("/tmp/.X{n}-lock")).exists());
    }

    #[test]
    fn a_dead_server_is_seen_and_replaced() {
        let xvfb = crate::find::find_on_path("Xvfb", std::env::var_os("PATH").as_deref())
            .expect("Xvfb must be installed (scripts/setup.sh)");
        let first = PrivateDisplay::shared(&xvfb).unwrap();
        assert!(first.is_alive());
        // The server dies under the runner (killed, crashed): the shared display is not
        // handed out again, a new server is.
        let status = Command::new("kill")
            .args(["-KILL", &first.server_pid.to_string()])
            .status()
            .unwrap();
        assert!(status.success());
        let deadline = Instant::now() + Duration::from_secs(5);
        while first.is_alive() && Instant::now() < deadline {
            std::thread::sleep(Duration::from_millis(10));
        }
        assert!(!first.is_alive(), "a killed server is not alive");
        let second = PrivateDisplay::shared(&xvfb).unwrap();
        assert!(second.is_alive());
        assert_ne!(second.server_pid, first.server_pid);
    }
}
