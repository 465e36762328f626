//! A private X display for XFOIL.
//!
//! Debian's XFOIL 6.99 is built with floating-point traps; with graphics switched off (`PLOP`,
//! `G F`) it divides by zero in its plot set-up and dies of SIGFPE. So every XFOIL run gets an X
//! display: a private `Xvfb` server that the runner starts on first use and kills when the
//! [`PrivateDisplay`] is dropped. Nothing is ever drawn on the user's own screen.

use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use crate::XfoilError;

/// A running private Xvfb server.
#[derive(Debug)]
pub struct PrivateDisplay {
    child: Child,
    number: u32,
}

/// Display numbers tried for the private server (far above the usual :0..:10).
const FIRST_DISPLAY: u32 = 140;
const DISPLAYS_TRIED: u32 = 60;

impl PrivateDisplay {
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
            let child = Command::new(xvfb)
                .arg(format!(":{number}"))
                .args(["-nolisten", "tcp", "-screen", "0", "640x480x24", "-nocursor"])
                .stdin(Stdio::null())
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .map_err(|e| XfoilError::Display(format!("cannot start {}: {e}", xvfb.display())))?;
            let mut display = PrivateDisplay { child, number };
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
                return Err(format!("Xvfb :{} exited at start ({status})", self.number));
            }
            if Path::new(&socket).exists() {
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
}

impl Drop for PrivateDisplay {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
