//! Polars from XFOIL: one job per (airfoil, Re, Mach, Ncrit, alpha grid), run in parallel
//! (rayon) reporting progress through a callback, through a content-addressed cache.
//!
//! The cache key is the SHA-256 of everything that decides XFOIL's answer: the coordinates as
//! sent (shortest round-trip decimal of each f64), Re, Mach, Ncrit, the angles, the iteration
//! limit and panel count, the XFOIL executable's own SHA-256 (its version) and the runner's
//! script version. Entries are JSON files written atomically (temporary file + rename) that
//! repeat their key; an entry that does not parse or names another key is corrupt, and is
//! recomputed and replaced.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use thiserror::Error;
use xfoil_runner::{SectionSettings, SweepRequest, Xfoil, XfoilError};

use crate::airfoil::{Airfoil, AirfoilError};
pub use crate::engine::Engine;
use crate::table::Polar;

/// Bumped whenever the XFOIL script or the meaning of a cached polar changes.
const SCRIPT_VERSION: &str = "propbet-xfoil-script-2";

/// One polar to compute.
#[derive(Debug, Clone, PartialEq)]
pub struct PolarJob {
    /// The section (any position and size; sent to XFOIL normalised).
    pub airfoil: Airfoil,
    /// Chord Reynolds number [-].
    pub re: f64,
    /// Mach number [-].
    pub mach: f64,
    /// The transition, the angles, XFOIL's panels and iterations.
    pub section: SectionSettings,
}

impl PolarJob {
    /// A job with the runner's defaults ([`SectionSettings::new`]) at `ncrit`.
    pub fn new(airfoil: Airfoil, re: f64, mach: f64, ncrit: f64, alphas_deg: Vec<f64>) -> Self {
        PolarJob {
            airfoil,
            re,
            mach,
            section: SectionSettings {
                ncrit,
                ..SectionSettings::new(alphas_deg)
            },
        }
    }

    fn request(&self) -> Result<SweepRequest, PolarError> {
        self.airfoil.check(&self.airfoil.name)?;
        let mut a = self.airfoil.clone();
        a.normalise();
        Ok(SweepRequest {
            coordinates: a.points,
            reynolds: self.re,
            mach: self.mach,
            section: self.section.clone(),
        })
    }
}

/// Why a polar could not be had.
#[derive(Debug, Error)]
pub enum PolarError {
    /// The airfoil is unusable.
    #[error(transparent)]
    Airfoil(#[from] AirfoilError),
    /// XFOIL failed (with its output).
    #[error("{airfoil} at Re {}: {source}", propbet_units::show(re.round()))]
    Xfoil {
        /// Airfoil name.
        airfoil: String,
        /// Reynolds number.
        re: f64,
        /// The runner's error.
        source: XfoilError,
    },
    /// The command's XFOIL time budget ran out before this polar was started.
    #[error("{airfoil} at Re {}: not computed, the XFOIL time budget ({seconds:.0} s) ran out", propbet_units::show(re.round()))]
    Budget {
        /// Airfoil name.
        airfoil: String,
        /// Reynolds number.
        re: f64,
        /// The budget [s].
        seconds: f64,
    },
    /// NeuralFoil's Kulfan fit of the section failed.
    #[error("{airfoil}: NeuralFoil cannot take this section: {reason}")]
    Kulfan {
        /// Airfoil name.
        airfoil: String,
        /// Why.
        reason: String,
    },
    /// The cache directory cannot be used.
    #[error("polar cache {path}: {source}")]
    Cache {
        /// The path.
        path: PathBuf,
        /// The error.
        source: std::io::Error,
    },
}

/// Where a polar came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// Read from the cache.
    Cache,
    /// Computed by XFOIL now.
    Xfoil,
    /// The cache entry was corrupt; computed again and replaced.
    RecomputedCorrupt,
    /// Made by NeuralFoil's networks (in whole: the `neuralfoil` engine, or `auto` where XFOIL
    /// gave no polar).
    NeuralFoil,
}

#[derive(Serialize, Deserialize)]
struct Entry {
    key: String,
    polar: Polar,
}

/// A directory of cached polars.
#[derive(Debug, Clone)]
pub struct PolarCache {
    dir: PathBuf,
}

impl PolarCache {
    /// Uses (and creates) `dir`.
    pub fn open(dir: &Path) -> Result<Self, PolarError> {
        std::fs::create_dir_all(dir).map_err(|source| PolarError::Cache {
            path: dir.to_path_buf(),
            source,
        })?;
        Ok(PolarCache { dir: dir.to_path_buf() })
    }

    /// The default location: `$PROPBET_CACHE_DIR`, else `$XDG_CACHE_HOME/propbet/polars`, else
    /// `~/.cache/propbet/polars`.
    pub fn default_dir() -> Option<PathBuf> {
        if let Some(d) = std::env::var_os("PROPBET_CACHE_DIR") {
            return Some(PathBuf::from(d));
        }
        if let Some(d) = std::env::var_os("XDG_CACHE_HOME") {
            return Some(PathBuf::from(d).join("propbet/polars"));
        }
        std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache/propbet/polars"))
    }

    fn path(&self, key: &str) -> PathBuf {
        self.dir.join(&key[..2]).join(format!("{key}.json"))
    }

    /// `Ok(None)` when absent, `Err(())` when present but corrupt.
    fn get(&self, key: &str) -> Result<Option<Polar>, ()> {
        let Ok(bytes) = std::fs::read(self.path(key)) else {
            return Ok(None);
        };
        match serde_json::from_slice::<Entry>(&bytes) {
            Ok(e) if e.key == key => Ok(Some(e.polar)),
            _ => Err(()),
        }
    }

    fn put(&self, key: &str, polar: &Polar) -> Result<(), PolarError> {
        let path = self.path(key);
        let dir = path.parent().unwrap_or(&self.dir).to_path_buf();
        let err = |source| PolarError::Cache {
            path: path.clone(),
            source,
        };
        std::fs::create_dir_all(&dir).map_err(err)?;
        let json = serde_json::to_vec(&Entry {
            key: key.to_string(),
            polar: polar.clone(),
        })
        .map_err(|e| err(e.into()))?;
        let mut tmp = tempfile::NamedTempFile::new_in(&dir).map_err(err)?;
        std::io::Write::write_all(&mut tmp, &json).map_err(err)?;
        tmp.persist(&path).map_err(|e| err(e.error))?;
        Ok(())
    }
}

/// The programs an engine runs.
#[derive(Debug)]
enum Programs {
    /// XFOIL alone.
    Xfoil(Xfoil),
    /// NeuralFoil's network alone.
    NeuralFoil(propbet_neuralfoil::Network),
    /// XFOIL, NeuralFoil filling what it leaves out.
    Auto(Xfoil, propbet_neuralfoil::Network),
}

/// XFOIL and/or NeuralFoil, plus an optional cache of XFOIL's polars.
#[derive(Debug)]
pub struct PolarEngine {
    programs: Programs,
    cache: Option<PolarCache>,
    identity: OnceLock<String>,
    /// The command's budget: (deadline, its length [s]).
    deadline: Option<(std::time::Instant, f64)>,
    /// The first polar the cache could not store (read-only, full): the polar is used all the
    /// same, and the caller says so once.
    cache_error: std::sync::Mutex<Option<String>>,
}

impl PolarEngine {
    fn of(programs: Programs, cache: Option<PolarCache>) -> Self {
        PolarEngine {
            programs,
            cache,
            identity: OnceLock::new(),
            deadline: None,
            cache_error: std::sync::Mutex::new(None),
        }
    }

    /// An engine; `cache` None computes everything afresh.
    pub fn new(xfoil: Xfoil, cache: Option<PolarCache>) -> Self {
        PolarEngine::of(Programs::Xfoil(xfoil), cache)
    }

    /// An engine of NeuralFoil's network alone (no XFOIL, no cache: a polar takes
    /// milliseconds).
    pub fn neuralfoil(net: propbet_neuralfoil::Network) -> Self {
        PolarEngine::of(Programs::NeuralFoil(net), None)
    }

    /// This XFOIL engine with NeuralFoil's network filling what XFOIL leaves out (`auto`).
    pub fn with_neuralfoil(self, net: propbet_neuralfoil::Network) -> Self {
        let programs = match self.programs {
            Programs::Xfoil(x) | Programs::Auto(x, _) => Programs::Auto(x, net),
            Programs::NeuralFoil(_) => Programs::NeuralFoil(net),
        };
        PolarEngine { programs, ..self }
    }

    /// Which program makes the polars.
    pub fn engine(&self) -> Engine {
        match self.programs {
            Programs::Xfoil(_) => Engine::Xfoil,
            Programs::NeuralFoil(_) => Engine::NeuralFoil,
            Programs::Auto(..) => Engine::Auto,
        }
    }

    /// Why the cache could not store a polar XFOIL computed (the first such error), if it
    /// could not: a warning for the caller; the polar itself was used.
    pub fn cache_error(&self) -> Option<String> {
        self.cache_error.lock().ok().and_then(|e| e.clone())
    }

    /// The engine with a total XFOIL time budget from now [s]: polars not started by then are
    /// errors ([`PolarError::Budget`]), a polar running then gives up its remaining angles.
    pub fn with_budget(mut self, seconds: f64) -> Self {
        let d = std::time::Duration::from_secs_f64(seconds.clamp(0.0, 1e9));
        self.deadline = Some((std::time::Instant::now() + d, seconds));
        self
    }

    /// The total XFOIL time budget [s], None without one.
    pub fn budget(&self) -> Option<f64> {
        self.deadline.map(|d| d.1)
    }

    /// SHA-256 of the XFOIL executable and the script version.
    fn identity(&self) -> &str {
        self.identity.get_or_init(|| {
            let (Programs::Xfoil(xfoil) | Programs::Auto(xfoil, _)) = &self.programs else {
                return String::new();
            };
            let exe = &xfoil.config().executable;
            let mut h = Sha256::new();
            h.update(SCRIPT_VERSION);
            match std::fs::read(exe) {
                Ok(bytes) => h.update(&bytes),
                Err(_) => h.update(exe.to_string_lossy().as_bytes()),
            }
            hex(&h.finalize())
        })
    }

    fn key(&self, req: &SweepRequest) -> String {
        let mut h = Sha256::new();
        h.update(self.identity());
        let mut text = String::with_capacity(40 * req.coordinates.len());
        for p in &req.coordinates {
            text.push_str(&format!("{} {}\n", p[0], p[1]));
        }
        text.push_str(&format!(
            "re {} mach {} ncrit {} iter {} panels {}\nalpha",
            req.reynolds,
            req.mach,
            req.section.ncrit,
            req.section.max_iter,
            req.section.panel_count()
        ));
        // Free transition keeps the key it always had (caches stay valid).
        if let Some(x) = req.section.trip {
            text.push_str(&format!(" trip {x}"));
        }
        for a in &req.section.alphas_deg {
            text.push_str(&format!(" {a}"));
        }
        h.update(text.as_bytes());
        hex(&h.finalize())
    }

    /// One polar: XFOIL's (from the cache when it holds it), NeuralFoil's, or XFOIL's with
    /// NeuralFoil filling its gaps, as the engine is.
    pub fn compute(&self, job: &PolarJob) -> Result<(Polar, Source), PolarError> {
        let section = crate::neural::Section {
            airfoil: &job.airfoil,
            re: job.re,
            ncrit: job.section.ncrit,
            trip: job.section.trip,
        };
        let kulfan = |e: crate::neural::NeuralError| PolarError::Kulfan {
            airfoil: job.airfoil.name.clone(),
            reason: e.0,
        };
        let whole = |net: &propbet_neuralfoil::Network| {
            crate::neural::polar(&section, &job.section.alphas_deg, net)
                .map(|p| (p, Source::NeuralFoil))
                .map_err(kulfan)
        };
        match &self.programs {
            Programs::NeuralFoil(net) => whole(net),
            Programs::Auto(x, net) => match self.xfoil_polar(x, job) {
                Ok((p, s)) => Ok((crate::neural::fill(p, &section, net), s)),
                // No polar from XFOIL (a crash, the budget): NeuralFoil's, or XFOIL's failure
                // where NeuralFoil cannot take the section either.
                Err(e @ (PolarError::Xfoil { .. } | PolarError::Budget { .. })) => whole(net).or(Err(e)),
                Err(e) => Err(e),
            },
            Programs::Xfoil(x) => self.xfoil_polar(x, job),
        }
    }

    /// XFOIL's polar, from the cache when it holds it.
    fn xfoil_polar(&self, xfoil: &Xfoil, job: &PolarJob) -> Result<(Polar, Source), PolarError> {
        let req = job.request()?;
        let key = self.key(&req);
        let mut source = Source::Xfoil;
        if let Some(c) = &self.cache {
            match c.get(&key) {
                Ok(Some(p)) => return Ok((p, Source::Cache)),
                Ok(None) => {}
                Err(()) => source = Source::RecomputedCorrupt,
            }
        }
        let out = match self.deadline {
            None => xfoil.sweep(&req),
            Some((deadline, seconds)) => {
                if std::time::Instant::now() >= deadline {
                    return Err(PolarError::Budget {
                        airfoil: job.airfoil.name.clone(),
                        re: job.re,
                        seconds,
                    });
                }
                xfoil.sweep_until(&req, deadline)
            }
        }
        .map_err(|source| PolarError::Xfoil {
            airfoil: job.airfoil.name.clone(),
            re: job.re,
            source,
        })?;
        let polar = Polar {
            re: job.re,
            mach: job.mach,
            ncrit: job.section.ncrit,
            trip: job.section.trip,
            points: out.points,
            unconverged_deg: out.unconverged_deg,
            hysteresis: out.hysteresis,
            faults: out.faults,
            neuralfoil: Vec::new(),
            not_filled: None,
        };
        // A hang or a budget run out may be the machine's load, not XFOIL's answer (the limits
        // are wall time): a polar with one is not cached, so the next run asks XFOIL again.
        let transient = polar.faults.iter().any(|f| {
            matches!(
                f.kind,
                xfoil_runner::FaultKind::Hang { .. } | xfoil_runner::FaultKind::OverBudget { .. }
            )
        });
        if let (Some(c), false) = (&self.cache, transient) {
            // A cache that cannot be written (read-only, full) costs the next run its time,
            // not this run its polar.
            if let Err(e) = c.put(&key, &polar) {
                if let Ok(mut first) = self.cache_error.lock() {
                    first.get_or_insert_with(|| e.to_string());
                }
            }
        }
        Ok((polar, source))
    }

    /// Every job, in parallel on rayon's pool; `progress(done, total)` is called after each
    /// job (from any thread). Results come back in job order.
    pub fn compute_all(&self, jobs: &[PolarJob], progress: &Progress<'_>) -> Vec<Result<(Polar, Source), PolarError>> {
        let done = std::sync::atomic::AtomicUsize::new(0);
        jobs.par_iter()
            .map(|j| {
                let r = self.compute(j);
                let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                progress(n, jobs.len());
                r
            })
            .collect()
    }
}

/// A progress callback: `(jobs done, jobs in all)`, called from worker threads.
pub type Progress<'a> = dyn Fn(usize, usize) + Sync + 'a;

/// A progress callback that does nothing.
pub fn no_progress(_: usize, _: usize) {}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}
