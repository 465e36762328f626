//! One XFOIL process at a time: the script written, the process in its own group under a
//! watchdog, its output read back, restarts and the retry pass; kept bounded (log head and
//! tail) and sanitised.

use super::*;

impl Xfoil {
    /// Checks that the executable exists; the display starts on the first run.
    pub fn new(config: XfoilConfig) -> Result<Self, XfoilError> {
        crate::find_xfoil(Some(&config.executable), None)?;
        Ok(Xfoil {
            config,
            display: Mutex::new(None),
        })
    }

    /// The configuration.
    pub fn config(&self) -> &XfoilConfig {
        &self.config
    }

    fn display_name(&self) -> Result<Option<String>, XfoilError> {
        match &self.config.display {
            DisplayChoice::Headless => Ok(None),
            DisplayChoice::Existing(d) => Ok(Some(d.clone())),
            DisplayChoice::PrivateXvfb { xvfb } => {
                let mut guard = self.display.lock().unwrap_or_else(|p| p.into_inner());
                if guard.is_none() {
                    *guard = Some(PrivateDisplay::shared(xvfb)?);
                }
                Ok(guard.as_ref().map(|d| d.name()))
            }
        }
    }

    /// Runs a viscous sweep: from the requested angle nearest zero upward, and from there
    /// downward, each direction one XFOIL process restarted beyond any angle where it crashed or
    /// hung, each direction returning at its end over the last angles it came through
    /// ([`UPPER_RETURN_DEG`], [`LOWER_RETURN_DEG`]) so that a hysteresis loop (stall and laminar
    /// bubbles at low Re) shows as a second solution, of which the lower-drag one is kept
    /// ([`SweepOutcome::hysteresis`] has both) and angles the outward sweep missed are filled;
    /// then the angles that failed, each from a fresh boundary layer.
    /// Converged points come back with the angles that failed; an error only when the request
    /// is invalid, XFOIL cannot be started, it writes unreadable output, or every run faulted
    /// before converging anything.
    pub fn sweep(&self, req: &SweepRequest) -> Result<SweepOutcome, XfoilError> {
        self.sweep_until(req, Instant::now() + self.config.sweep_budget)
    }

    /// [`Xfoil::sweep`] that gives up what is left at `deadline` (the earlier of it and the
    /// sweep's own budget).
    pub fn sweep_until(&self, req: &SweepRequest, deadline: Instant) -> Result<SweepOutcome, XfoilError> {
        req.validate()?;
        let start = Instant::now();
        let deadline = deadline.min(start + self.config.sweep_budget);
        let settings = RunSettings {
            reynolds: req.reynolds,
            mach: req.mach,
            section: req.section.clone(),
        };
        let airfoil = script::airfoil_file(&req.coordinates);
        let a = &req.section.alphas_deg;
        let i0 = (0..a.len())
            .min_by(|&i, &j| a[i].abs().total_cmp(&a[j].abs()))
            .unwrap_or(0);
        // One process: up from the angle nearest zero and back over the last angles, then
        // from a fresh boundary layer at it down and back. Then the angles that failed, each
        // from a fresh boundary layer.
        let n = a.len();
        let mut steps = Step::list(&a[i0..], false, false);
        let top = a[n - 1];
        steps.extend(returning(
            (i0 + 1..n.saturating_sub(1))
                .rev()
                .map(|k| a[k])
                .filter(|&x| x >= top - UPPER_RETURN_DEG),
        ));
        let down: Vec<f64> = a[..=i0].iter().rev().copied().collect();
        if down.len() > 1 {
            steps.extend(Step::list(&down, true, false));
            let bottom = a[0];
            steps.extend(returning(
                (1..i0).map(|k| a[k]).filter(|&x| x <= bottom + LOWER_RETURN_DEG),
            ));
        }
        let mut out = SweepOutcome::default();
        let mut last_tail = String::new();
        let clock = (start, deadline);
        let failed = self.branch(&airfoil, &settings, &steps, &mut out, &mut last_tail, clock)?;
        // (An angle the return converged is not retried.)
        let mut retry: Vec<f64> = failed
            .into_iter()
            .filter(|&x| !has_angle(&out.points, x) && !has_angle(&out.returned, x))
            .collect();
        retry.dedup();
        if !retry.is_empty() {
            // A fresh boundary layer converges within RETRY_ITER iterations or, in practice, not
            // at all; failing angles cost the whole limit, so the retry pass caps it.
            let retry_settings = RunSettings {
                section: crate::SectionSettings {
                    max_iter: settings.section.max_iter.min(RETRY_ITER),
                    ..settings.section.clone()
                },
                ..settings.clone()
            };
            self.branch(
                &airfoil,
                &retry_settings,
                &Step::list(&retry, false, true),
                &mut out,
                &mut last_tail,
                clock,
            )?;
        }
        // A drag below 80 % of laminar flat-plate friction on both sides (2 x 1.328 / sqrt(Re))
        // is a spurious XFOIL solution, not a polar point.
        let floor = 0.8 * 2.0 * 1.328 / req.reynolds.sqrt();
        // Nor are values no section has (|cl| above 5, cd above 5): taken as not converged.
        let plausible = |p: &XfoilPoint| p.cd >= floor && p.cd <= 5.0 && p.cl.abs() <= 5.0 && p.cm.abs() <= 5.0;
        out.points.retain(plausible);
        // The points of the returns, against the outward ones at the same angle (the first of
        // a repeated one, which the sort below keeps).
        let mut back = std::mem::take(&mut out.returned);
        back.retain(plausible);
        for p in back {
            match out.points.iter_mut().find(|q| same_angle(q.alpha_deg, p.alpha_deg)) {
                Some(q) if (q.cl - p.cl).abs() > HYSTERESIS_CL => {
                    let (kept, other) = if p.cd < q.cd { (p, *q) } else { (*q, p) };
                    *q = kept;
                    out.hysteresis.push(Branches { kept, other });
                }
                Some(_) => {}
                None => out.points.push(p),
            }
        }
        out.hysteresis
            .sort_by(|x, y| x.kept.alpha_deg.total_cmp(&y.kept.alpha_deg));
        out.hysteresis
            .dedup_by(|x, y| same_angle(x.kept.alpha_deg, y.kept.alpha_deg));
        out.unconverged_deg = a.iter().copied().filter(|&x| !has_angle(&out.points, x)).collect();
        if out.points.is_empty() && !out.faults.is_empty() {
            let summary: Vec<String> = out.faults.iter().map(|f| f.to_string()).collect();
            return Err(XfoilError::NoPoints {
                summary: summary.join("\n"),
                output_tail: last_tail,
            });
        }
        out.points.sort_by(|p, q| p.alpha_deg.total_cmp(&q.alpha_deg));
        out.points.dedup_by(|p, q| same_angle(p.alpha_deg, q.alpha_deg));
        Ok(out)
    }

    /// One pass over `steps` in order: runs until every angle is converged, failed or given
    /// up, restarting beyond crashes (with a warm-up at the last converged angle). Returns the
    /// angles that did not converge.
    fn branch(
        &self,
        airfoil: &str,
        settings: &RunSettings,
        steps: &[Step],
        out: &mut SweepOutcome,
        last_tail: &mut String,
        (start, deadline): (Instant, Instant),
    ) -> Result<Vec<f64>, XfoilError> {
        let mut warm_up: Option<f64> = None;
        let mut failed = Vec::new();
        // What is left to solve; after a fault, without the returns through the angle that
        // faulted (XFOIL would fault there again).
        let mut left: Vec<Step> = steps.to_vec();
        let mut restarts = 0;
        while !left.is_empty() {
            let todo_steps = &left[..];
            let todo: Vec<f64> = todo_steps.iter().map(|s| s.alpha_deg).collect();
            let now = Instant::now();
            if now >= deadline {
                out.faults.push(Fault {
                    kind: FaultKind::OverBudget {
                        seconds: (now - start).as_secs_f64(),
                    },
                    alpha_deg: todo[0],
                    output_tail: last_tail.clone(),
                });
                failed.extend(todo);
                return Ok(failed);
            }
            let run = self.with_display_retries(deadline - now, |left| {
                self.run_process(airfoil, settings, warm_up, todo_steps, left)
            })?;
            out.runs += 1;
            // Match saved points to requested angles; anything else is garbage.
            let mut last_done: Option<usize> = None;
            for p in &run.points {
                // Points come in solving order; an angle may come twice (the return to the
                // start before the downward branch), so match from the last one on.
                let from = last_done.map_or(0, |d| d + 1);
                let k = todo[from..]
                    .iter()
                    .position(|&a| same_angle(a, p.alpha_deg))
                    .map(|k| k + from)
                    .ok_or_else(|| XfoilError::Garbage {
                        detail: format!(
                            "XFOIL saved a point at alpha {} deg, which was not requested",
                            p.alpha_deg
                        ),
                        output_tail: run.output_tail.clone(),
                    })?;
                last_done = Some(k);
                if todo_steps[k].returning {
                    out.returned.push(*p);
                } else {
                    out.points.push(*p);
                }
            }
            let converged = |a: f64| has_angle(&run.points, a);
            *last_tail = run.output_tail.clone();
            let Some(kind) = run.ending.fault() else {
                failed.extend(todo.iter().copied().filter(|&a| !converged(a)));
                return Ok(failed);
            };
            if !run.reached_sweep {
                if let Some(w) = warm_up.take() {
                    // The warm-up angle itself failed: note it, go on without one.
                    out.faults.push(Fault {
                        kind,
                        alpha_deg: w,
                        output_tail: run.output_tail,
                    });
                    restarts += 1;
                    continue;
                }
                return Err(XfoilError::Startup {
                    status: match kind {
                        FaultKind::Crash { status } => status,
                        FaultKind::Hang { .. } => "hung".into(),
                        FaultKind::OverBudget { .. } => "over its time budget".into(),
                    },
                    output_tail: run.output_tail,
                });
            }
            // The angle given up: the first after the last one saved.
            let failed_at = last_done.map_or(0, |d| d + 1).min(todo.len() - 1);
            out.faults.push(Fault {
                kind,
                alpha_deg: todo[failed_at],
                output_tail: run.output_tail,
            });
            failed.extend(todo[..=failed_at].iter().copied().filter(|&a| !converged(a)));
            if let Some(d) = last_done {
                warm_up = Some(todo[d]);
            }
            let at = todo[failed_at];
            left = left[failed_at + 1..]
                .iter()
                .filter(|s| !(s.returning && same_angle(s.alpha_deg, at)))
                .copied()
                .collect();
            restarts += 1;
            if restarts > self.config.max_restarts {
                failed.extend(left.iter().map(|s| s.alpha_deg));
                return Ok(failed);
            }
        }
        Ok(failed)
    }

    /// One XFOIL process (`run`, given the time left: [`Xfoil::run_process`]), started again
    /// when XFOIL could not open its X display: a transient refusal (seen a few times in a
    /// validate run, at random rungs) would otherwise lose a whole polar and make the results
    /// depend on the machine's luck. A private display whose server has died is replaced before
    /// the next attempt; after [`DISPLAY_ATTEMPTS`] refusals it is an error naming the display.
    fn with_display_retries(
        &self,
        left: Duration,
        run: impl Fn(Duration) -> Result<RunOutput, XfoilError>,
    ) -> Result<RunOutput, XfoilError> {
        let start = Instant::now();
        let mut pause = DISPLAY_RETRY_PAUSE;
        let mut attempt = 1;
        loop {
            let run = run(left.saturating_sub(start.elapsed()))?;
            if !run.display_refused {
                return Ok(run);
            }
            if attempt == DISPLAY_ATTEMPTS || start.elapsed() + pause >= left {
                let name = self.display_name()?.unwrap_or_else(|| "(none: DISPLAY unset)".into());
                return Err(XfoilError::Display(format!(
                    "XFOIL could not open the X display {name} ({attempt} attempts)\n--- end of XFOIL's output ---\n{}",
                    run.output_tail
                )));
            }
            self.forget_dead_display();
            std::thread::sleep(pause);
            pause *= 2;
            attempt += 1;
        }
    }

    /// Drops this runner's private display if its server has died, so that the next run
    /// starts (or shares) a live one.
    fn forget_dead_display(&self) {
        let mut guard = self.display.lock().unwrap_or_else(|p| p.into_inner());
        if guard.as_ref().is_some_and(|d| !d.is_alive()) {
            *guard = None;
        }
    }

    /// Starts XFOIL once over `steps` and waits for it (the watchdog's budget at most `left`).
    fn run_process(
        &self,
        airfoil: &str,
        settings: &RunSettings,
        warm_up: Option<f64>,
        steps: &[Step],
        left: Duration,
    ) -> Result<RunOutput, XfoilError> {
        let dir = tempfile::Builder::new()
            .prefix("propbet-xfoil-")
            .tempdir()
            .map_err(|e| XfoilError::io("cannot create a temporary directory for XFOIL", e))?;
        let path = dir.path();
        std::fs::write(path.join(script::AIRFOIL_FILE), airfoil)
            .map_err(|e| XfoilError::io("cannot write the airfoil file for XFOIL", e))?;
        let log_path = path.join("xfoil.log");
        let log = File::create(&log_path).map_err(|e| XfoilError::io("cannot create XFOIL's log file", e))?;
        let log2 = log
            .try_clone()
            .map_err(|e| XfoilError::io("cannot create XFOIL's log file", e))?;
        let mut cmd = Command::new(&self.config.executable);
        // Its own process group: a hang kills XFOIL and whatever it started (a wrapper script's
        // children), not only the direct child.
        std::os::unix::process::CommandExt::process_group(&mut cmd, 0);
        cmd.current_dir(path)
            .stdin(Stdio::piped())
            .stdout(Stdio::from(log))
            .stderr(Stdio::from(log2))
            // Unbuffered Fortran output: the log shows how far XFOIL got before a crash.
            .env("GFORTRAN_UNBUFFERED_PRECONNECTED", "y");
        match self.display_name()? {
            Some(d) => cmd.env("DISPLAY", d),
            None => cmd.env_remove("DISPLAY"),
        };
        let mut child = spawn_when_not_busy(&mut cmd)
            .map_err(|e| XfoilError::io(format!("cannot start XFOIL ({})", self.config.executable.display()), e))?;
        let tracked = crate::interrupt::Tracked::new(child.id(), path);
        let text = script::sweep_script(settings, warm_up, steps);
        if let Some(mut stdin) = child.stdin.take() {
            // XFOIL may die before reading everything; the watchdog below reports that.
            let _ = stdin.write_all(text.as_bytes());
        }
        let budget = (self.config.startup_timeout + self.config.point_timeout * (steps.len() as u32 + 1)).min(left);
        let ending = watch(&mut child, &log_path, self.config.stall_timeout, budget)?;
        // Whatever XFOIL (or a wrapper given as --xfoil) left running in its group goes too.
        kill_group(&mut child);
        drop(tracked);
        // The log's head (where XFOIL says it accumulates the polar, or that the display
        // refused it) and tail (where it stopped): never the whole of a babbling log.
        let output = head_and_tail(&log_path);
        let output_tail = tail(&output);
        let display_refused = !matches!(ending, Ending::Finished) && contains(&output, DISPLAY_REFUSED);
        if display_refused {
            return Ok(RunOutput {
                ending,
                reached_sweep: false,
                points: Vec::new(),
                output_tail,
                display_refused,
            });
        }
        let polar = match std::fs::read(path.join(script::POLAR_FILE)) {
            Ok(b) => String::from_utf8_lossy(&b).into_owned(),
            Err(_) => String::new(),
        };
        let points = parse_polar_file(&polar, &output_tail)?;
        if matches!(ending, Ending::Finished) && polar.is_empty() {
            return Err(XfoilError::Garbage {
                detail: "XFOIL finished without writing its polar file".into(),
                output_tail,
            });
        }
        Ok(RunOutput {
            ending,
            reached_sweep: contains(&output, b"Polar accumulation enabled"),
            points,
            output_tail,
            display_refused,
        })
    }
}

/// Waits for `child`, killing it when its log stops growing for `stall` or the whole run
/// exceeds `budget`.
fn watch(child: &mut std::process::Child, log: &Path, stall: Duration, budget: Duration) -> Result<Ending, XfoilError> {
    let start = Instant::now();
    let mut last_len = 0;
    let mut last_change = start;
    let mut nap = Duration::from_millis(1);
    loop {
        match child.try_wait() {
            Ok(Some(status)) if status.success() => return Ok(Ending::Finished),
            Ok(Some(status)) => return Ok(Ending::Crashed(status)),
            Ok(None) => {}
            Err(e) => return Err(XfoilError::io("cannot wait for XFOIL", e)),
        }
        let len = std::fs::metadata(log).map(|m| m.len()).unwrap_or(0);
        let now = Instant::now();
        if len != last_len {
            last_len = len;
            last_change = now;
        }
        if now - last_change > stall || now - start > budget || len > LOG_LIMIT {
            kill_group(child);
            let _ = child.wait();
            return Ok(Ending::Hung(now - start));
        }
        std::thread::sleep(nap);
        nap = (nap * 2).min(Duration::from_millis(10));
    }
}

/// Most bytes of XFOIL's log a run keeps (its head and its tail): a babbling executable
/// costs its log's disk, not the memory of propbet.
const LOG_KEPT: u64 = 1 << 20;

/// A log larger than this ends the run as a hang: nothing useful is that long.
const LOG_LIMIT: u64 = 256 << 20;

/// The first and last [`LOG_KEPT`] / 2 bytes of the log (all of it when shorter).
fn head_and_tail(log: &Path) -> Vec<u8> {
    use std::io::{Read, Seek, SeekFrom};
    let Ok(mut f) = File::open(log) else { return Vec::new() };
    let len = f.metadata().map(|m| m.len()).unwrap_or(0);
    let mut out = Vec::new();
    if len <= LOG_KEPT {
        let _ = f.read_to_end(&mut out);
        return out;
    }
    let half = LOG_KEPT / 2;
    let _ = (&mut f).take(half).read_to_end(&mut out);
    out.push(b'\n');
    if f.seek(SeekFrom::Start(len - half)).is_ok() {
        let _ = f.take(half).read_to_end(&mut out);
    }
    out
}

/// Kills `child`'s process group (it leads its own: `process_group(0)` at spawn), then the child
/// itself in case the group is already gone.
fn kill_group(child: &mut std::process::Child) {
    if let Some(pid) = i32::try_from(child.id()).ok().and_then(rustix::process::Pid::from_raw) {
        let _ = rustix::process::kill_process_group(pid, rustix::process::Signal::KILL);
    }
    let _ = child.kill();
}

/// The end of XFOIL's output, as text safe to print anywhere (terminal, JSON, HTML after
/// escaping): control bytes other than newline and tab removed, so no escape sequence or bell
/// from a misbehaving executable reaches the user's terminal.
pub(super) fn tail(bytes: &[u8]) -> String {
    let start = bytes.len().saturating_sub(TAIL_BYTES);
    let text = String::from_utf8_lossy(&bytes[start..]);
    let text = match text.find('\n') {
        Some(i) if start > 0 => &text[i + 1..],
        _ => &text[..],
    };
    text.chars()
        .filter(|&c| !c.is_control() || c == '\n' || c == '\t')
        .collect()
}

/// Starts `cmd`, again a few times while its executable is busy (ETXTBSY): an executable
/// written a moment ago (a wrapper script, a test's fake XFOIL) is held open for writing by
/// any process another thread forked in the meantime, until that process execs.
fn spawn_when_not_busy(cmd: &mut Command) -> std::io::Result<std::process::Child> {
    let busy = rustix::io::Errno::TXTBSY.raw_os_error();
    let mut wait = std::time::Duration::from_millis(5);
    for _ in 0..8 {
        match cmd.spawn() {
            Err(e) if e.raw_os_error() == Some(busy) => {
                std::thread::sleep(wait);
                wait *= 2;
            }
            started => return started,
        }
    }
    cmd.spawn()
}
