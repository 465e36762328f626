//! Polars of a whole blade: one set per input station, at the Reynolds and Mach numbers that
//! station sees at an operating point, with the QPROP fit of each. Written by `propbet polars`
//! as JSON and read back by `propbet predict --polars` for the tabulated section model.

use std::sync::Arc;

use propbet_bemt::SectionAero;
use serde::{Deserialize, Serialize};

use crate::reduce::QpropFit;
use crate::table::Polar;
use crate::tabulated::TabulatedAero;

/// Section models placed at radii [m], ascending.
pub type StationModels = (Vec<f64>, Vec<Arc<dyn SectionAero>>);

/// Format tag of the JSON file.
pub const FORMAT: &str = "propbet-blade-polars-1";

/// Polars of every input station of a blade.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BladePolars {
    /// Always [`FORMAT`].
    pub format: String,
    /// Where the geometry came from.
    pub geometry: String,
    /// The section used (name).
    pub airfoil: String,
    /// Operating point the Reynolds numbers were taken at: rotation speed [rpm].
    pub rpm: f64,
    /// Operating point: axial speed [m/s].
    pub v: f64,
    /// Air density [kg/m^3], viscosity [Pa s], speed of sound [m/s] used.
    pub air: [f64; 3],
    /// The stations, ascending in radius.
    pub stations: Vec<StationPolars>,
}

/// One input station.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StationPolars {
    /// Radius [m].
    pub r: f64,
    /// Chord [m].
    pub chord: f64,
    /// Reynolds number at the operating point [-].
    pub re: f64,
    /// Mach number at the operating point [-].
    pub mach: f64,
    /// Angle of attack at the operating point [deg].
    pub alpha_deg: f64,
    /// Polars computed (the station's Re and its neighbours).
    pub polars: Vec<Polar>,
    /// QPROP fit, when the polars allowed one.
    pub fit: Option<QpropFit>,
    /// What went wrong at this station, if anything.
    pub problem: Option<String>,
}

impl BladePolars {
    /// Reads and checks the JSON text.
    pub fn from_json(text: &str) -> Result<Self, String> {
        let b: BladePolars = serde_json::from_str(text).map_err(|e| format!("not a blade-polars file: {e}"))?;
        if b.format != FORMAT {
            return Err(format!("format {:?}, expected {FORMAT:?}", b.format));
        }
        if b.stations.windows(2).any(|w| w[1].r <= w[0].r) {
            return Err("station radii are not ascending".into());
        }
        for (i, s) in b.stations.iter().enumerate() {
            if !(s.r.is_finite() && s.r > 0.0 && s.chord.is_finite() && s.chord >= 0.0) {
                return Err(format!(
                    "station {} (r = {}): radius or chord not a positive number",
                    i + 1,
                    s.r
                ));
            }
            for p in &s.polars {
                check_polar(p).map_err(|e| format!("station {} (r = {:.4} m), Re {:.0}: {e}", i + 1, s.r, p.re))?;
            }
        }
        Ok(b)
    }

    /// Tabulated section models at the stations that have polars: their radii and models.
    pub fn models(&self) -> Result<StationModels, String> {
        let mut r = Vec::new();
        let mut m: Vec<Arc<dyn SectionAero>> = Vec::new();
        for s in &self.stations {
            if let Some(t) = TabulatedAero::new(&s.polars) {
                r.push(s.r);
                m.push(Arc::new(t));
            }
        }
        if m.is_empty() {
            return Err("no station has a usable polar".into());
        }
        Ok((r, m))
    }
}

/// How XFOIL is asked for a blade's polars: transition, angles, panels, iterations.
#[derive(Debug, Clone, PartialEq)]
pub struct XfoilSettings {
    /// Transition amplification ratio Ncrit [-].
    pub ncrit: f64,
    /// Angles of attack [deg], ascending, no duplicates (XFOIL's unit).
    pub alphas_deg: Vec<f64>,
    /// Panel nodes.
    pub panels: u32,
    /// Viscous iteration limit per angle.
    pub max_iter: u32,
}

/// A polar as the tabulated model needs it: a positive Re, and points of finite, plausible
/// coefficients in strictly ascending alpha.
fn check_polar(p: &Polar) -> Result<(), String> {
    if !(p.re.is_finite() && p.re > 0.0) {
        return Err("Reynolds number not a positive number".into());
    }
    for (k, q) in p.points.iter().enumerate() {
        if !(q.alpha_deg.is_finite() && q.cl.is_finite() && q.cd.is_finite()) {
            return Err(format!("point {}: not a finite number", k + 1));
        }
        if q.cl.abs() > 5.0 || !(q.cd > 0.0 && q.cd < 5.0) {
            return Err(format!(
                "point {} (alpha {} deg): cl {} or cd {} is not a section's",
                k + 1,
                q.alpha_deg,
                q.cl,
                q.cd
            ));
        }
    }
    if let Some(w) = p.points.windows(2).find(|w| w[1].alpha_deg <= w[0].alpha_deg) {
        return Err(format!(
            "angles not ascending ({} deg then {} deg)",
            w[0].alpha_deg, w[1].alpha_deg
        ));
    }
    Ok(())
}

/// Panels for a blade's polars: 1.9x faster than XFOIL's 160, and close to it (NACA 4412 at
/// 4 deg, Debian XFOIL 6.99: Re 1e5 cl 0.8896 vs 0.8880, cd 0.0196 vs 0.01965; Re 5e4 cl 0.6062
/// vs 0.6108, cd 0.04977 vs 0.04952 — at Re 5e4 XFOIL itself moves by 3 % between 100 and 160).
pub const BLADE_PANELS: u32 = 120;

/// What [`compute_blade`] needs.
pub struct BladeJob<'a> {
    /// The blade (radii, chords, twists; its coefficients give the first inflow estimate).
    pub blade: &'a propbet_bemt::QpropBlade,
    /// Where it came from (recorded in [`BladePolars::geometry`]).
    pub geometry: String,
    /// One section for every station, or one per input station.
    pub foils: &'a [crate::Airfoil],
    /// Operating point: rotation speed [rad/s].
    pub omega: f64,
    /// Operating point: axial speed [m/s].
    pub v: f64,
    /// Further multiples of each station's Re (for REexp).
    pub factors: &'a [f64],
    /// Air.
    pub fluid: propbet_bemt::Fluid,
    /// Angles, panels, iterations, Ncrit.
    pub settings: &'a XfoilSettings,
}

/// Why a blade's polars could not be computed at all.
#[derive(Debug, thiserror::Error)]
pub enum BladeError {
    /// The blade cannot be discretised.
    #[error(transparent)]
    Rotor(#[from] propbet_bemt::RotorError),
    /// No section was given.
    #[error("no section given")]
    NoSection,
}

/// Polars of every input station at its Re and Mach at the operating point, each fitted to
/// QPROP's coefficients around the angle of attack the station works at. A station whose
/// polars or fit failed keeps `fit: None` and says why in `problem`; the batch goes on.
///
/// Each station's inflow comes from the solver on the blade's own coefficients at the
/// operating point; Re = ρ W c / μ, Mach = W / a (capped at 0.85, XFOIL's limit of sense).
pub fn compute_blade(
    job: &BladeJob,
    engine: &crate::PolarEngine,
    progress: &crate::Progress<'_>,
) -> Result<BladePolars, BladeError> {
    use propbet_bemt::{OperatingPoint, Solver, SolverOptions, StationResult};
    let blade = job.blade;
    let rotor = blade.to_rotor(propbet_bemt::Discretization::default())?;
    let fluid = job.fluid;
    if job.foils.is_empty() {
        return Err(BladeError::NoSection);
    }
    let opts = SolverOptions {
        keep_stations: true,
        ..SolverOptions::default()
    };
    let point = Solver::new(&rotor, &fluid, &opts).solve(OperatingPoint {
        v: job.v,
        omega: job.omega,
    });
    let st = &point.stations;
    let at = |r: f64, f: &dyn Fn(&StationResult) -> f64| -> f64 {
        let i = st.partition_point(|s| s.r <= r).clamp(1, st.len() - 1);
        let (a, b) = (&st[i - 1], &st[i]);
        let t = ((r - a.r) / (b.r - a.r)).clamp(-0.5, 1.5);
        f(a) + t * (f(b) - f(a))
    };
    let mut jobs = Vec::new();
    let mut stations = Vec::new();
    for (i, &r) in blade.r.iter().enumerate() {
        let w = at(r, &|s| s.w);
        let chord = blade.chord[i];
        let re = fluid.rho * w * chord / fluid.mu;
        let mach = (w / fluid.a).min(0.85);
        let alpha_deg = at(r, &|s| s.alpha).to_degrees();
        let first = jobs.len();
        if re > 0.0 && chord > 0.0 {
            let foil = &job.foils[i.min(job.foils.len() - 1)];
            for f in std::iter::once(1.0).chain(job.factors.iter().copied()) {
                jobs.push(crate::PolarJob {
                    panels: job.settings.panels,
                    max_iter: job.settings.max_iter,
                    ..crate::PolarJob::new(
                        foil.clone(),
                        re * f,
                        mach,
                        job.settings.ncrit,
                        job.settings.alphas_deg.clone(),
                    )
                });
            }
        }
        stations.push((r, chord, re, mach, alpha_deg, first..jobs.len()));
    }
    let mut results: Vec<Option<Result<Polar, String>>> = engine
        .compute_all(&jobs, progress)
        .into_iter()
        .map(|r| Some(r.map(|(p, _)| p).map_err(|e| e.to_string())))
        .collect();
    let mut out = Vec::new();
    for (r, chord, re, mach, alpha_deg, range) in stations {
        let mut polars = Vec::new();
        let mut problems = Vec::new();
        for k in range {
            match results[k].take() {
                Some(Ok(p)) => polars.push(p),
                Some(Err(e)) => problems.push(e),
                None => {}
            }
        }
        let weights = crate::AlphaWeights::Around {
            alphas_deg: vec![alpha_deg],
            sigma_deg: 3.0,
        };
        let fit = if polars.is_empty() {
            problems.push(format!("no polar at r = {r:.4} m (Re {re:.0})"));
            None
        } else {
            match crate::fit_qprop(&polars, re, &weights, -0.5) {
                Ok(f) => Some(f),
                Err(e) => {
                    problems.push(e.to_string());
                    None
                }
            }
        };
        out.push(StationPolars {
            r,
            chord,
            re,
            mach,
            alpha_deg,
            polars,
            fit,
            problem: (!problems.is_empty()).then(|| problems.join("; ")),
        });
    }
    let names: Vec<&str> = job.foils.iter().map(|f| f.name.as_str()).collect();
    Ok(BladePolars {
        format: FORMAT.into(),
        geometry: job.geometry.clone(),
        airfoil: if names.len() == 1 {
            names[0].to_string()
        } else {
            format!("{} sections, {} ... {}", names.len(), names[0], names[names.len() - 1])
        },
        rpm: propbet_bemt::units::omega_to_rpm(job.omega),
        v: job.v,
        air: [fluid.rho, fluid.mu, fluid.a],
        stations: out,
    })
}
