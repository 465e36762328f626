//! Polars of a whole blade: one set per input station, at Reynolds numbers that cover what that
//! station sees over a set of operating points (the sweep), with the QPROP fit of each. Written
//! by `propbet polars` as JSON and read back by `propbet predict --polars` for the tabulated
//! section model.
//!
//! Reynolds numbers are taken from a fixed ladder of five per decade (10^(k/5): 10,000, 15,849,
//! 25,119, 39,811, 63,096, 100,000, ...), the rungs just below and above the station's lowest and
//! highest Re over the points and every rung between: neighbouring polars differ by a factor
//! 1.58 in Re, and the same rung recurs from one sweep to the next (the cache serves it). Each
//! rung is computed at the Mach number that goes with it at that station (M = Re mu/(rho c a)).

use serde::{Deserialize, Serialize};

use xfoil_runner::SectionSettings;

use crate::reduce::QpropFit;
use crate::table::Polar;
use crate::tabulated::TabulatedAero;

/// Section models placed at radii [m], ascending.
pub type StationModels = (Vec<f64>, Vec<TabulatedAero>);

/// Format tag of the JSON file.
pub const FORMAT: &str = "propbet-blade-polars-2";

/// Rungs of the Reynolds-number ladder per decade.
pub const RE_PER_DECADE: f64 = 5.0;
/// Most rungs per station (a station whose Re spans more than this many is given the lowest
/// rungs' and highest rungs' ends and the rungs between thinned; in practice a sweep spans 2-5).
pub const MAX_RUNGS: usize = 10;

/// Polars of every input station of a blade.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BladePolars {
    /// Always [`FORMAT`].
    pub format: String,
    /// Where the geometry came from.
    pub geometry: String,
    /// The section used (name).
    pub airfoil: String,
    /// Rotation speeds the polars cover (lowest, highest) [rpm].
    pub rpm: [f64; 2],
    /// Axial speeds they cover (lowest, highest) [m/s].
    pub v: [f64; 2],
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
    /// Reynolds number the QPROP fit is centred on: the geometric mean of the lowest and
    /// highest over the operating points [-].
    pub re: f64,
    /// Lowest and highest Reynolds number over the operating points [-].
    pub re_range: [f64; 2],
    /// Mach number at `re` [-].
    pub mach: f64,
    /// Median angle of attack over the operating points [deg].
    pub alpha_deg: f64,
    /// Lowest and highest angle of attack over the operating points [deg].
    pub alpha_range_deg: [f64; 2],
    /// Polars computed (the rungs of the Re ladder covering `re_range`).
    pub polars: Vec<Polar>,
    /// The same rungs at other Ncrit values (each polar carries its own), for the `transition`
    /// effect that fits Ncrit between them; empty unless asked for (`--ncrit-effect`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub other_ncrit: Vec<Polar>,
    /// The same rungs at the uncertainty band's two ends ([`BAND_ENDS`], keyed by their Ncrit):
    /// each polar the station's own moved by NeuralFoil's difference between that end and the
    /// polar's own transition (the band's section-model source; never a diagnosis candidate). Empty where NeuralFoil
    /// cannot take the section.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub band: Vec<Polar>,
    /// QPROP fit, when the polars allowed one.
    pub fit: Option<QpropFit>,
    /// What went wrong at this station, if anything.
    pub problem: Option<String>,
}

impl BladePolars {
    /// Reads and checks the JSON text.
    pub fn from_json(text: &str) -> Result<Self, String> {
        // The format first: a file of another version says so, not which field it lacks.
        let v: serde_json::Value = serde_json::from_str(text).map_err(|e| format!("not a blade-polars file: {e}"))?;
        match v.get("format").and_then(|f| f.as_str()) {
            Some(FORMAT) => {}
            Some(f) if f.starts_with("propbet-blade-polars-") => {
                return Err(format!(
                    "format {f:?}, written by another version of propbet (this one reads {FORMAT:?}): run `propbet polars` again"
                ))
            }
            _ => return Err(format!("not a blade-polars file (no \"format\": {FORMAT:?})")),
        }
        let b: BladePolars = serde_json::from_value(v).map_err(|e| format!("not a blade-polars file: {e}"))?;
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
        let mut m = Vec::new();
        for s in &self.stations {
            if let Some(t) = TabulatedAero::new(&s.polars) {
                r.push(s.r);
                m.push(t);
            }
        }
        if m.is_empty() {
            return Err("no station has a usable polar".into());
        }
        Ok((r, m))
    }

    /// Ncrit values of the stations' [`StationPolars::other_ncrit`] polars, ascending.
    pub fn other_ncrits(&self) -> Vec<f64> {
        let mut n: Vec<f64> = self
            .stations
            .iter()
            .flat_map(|s| s.other_ncrit.iter().map(|p| p.ncrit))
            .collect();
        n.sort_by(f64::total_cmp);
        n.dedup();
        n
    }

    /// Tabulated section models at Ncrit `ncrit` from the stations' other-Ncrit polars: radii
    /// and models of the stations that have one.
    pub fn models_at_ncrit(&self, ncrit: f64) -> StationModels {
        self.models_of(ncrit, |s| &s.other_ncrit)
    }

    /// Tabulated section models of the uncertainty band's end keyed `ncrit` ([`BAND_NCRIT`], from
    /// the stations' [`StationPolars::band`] polars): radii and models of the stations that
    /// have one.
    pub fn band_models(&self, ncrit: f64) -> StationModels {
        self.models_of(ncrit, |s| &s.band)
    }

    fn models_of(&self, ncrit: f64, polars: impl Fn(&StationPolars) -> &Vec<Polar>) -> StationModels {
        let mut r = Vec::new();
        let mut m = Vec::new();
        for s in &self.stations {
            let at: Vec<Polar> = polars(s).iter().filter(|p| p.ncrit == ncrit).cloned().collect();
            if let Some(t) = TabulatedAero::new(&at) {
                r.push(s.r);
                m.push(t);
            }
        }
        (r, m)
    }
}

/// The two ends of the uncertainty band's section-model source, each an Ncrit and a forced
/// transition x/c: early transition (Ncrit 3 and a trip at mid-chord: a turbulent tunnel, a
/// rough blade; the tripped model the cross-validation weighed against free transition) and
/// late (Ncrit 7 free: a quiet one), about the model's Ncrit 5 free. Each end's tables are
/// keyed by its Ncrit.
pub const BAND_ENDS: [(f64, Option<f64>); 2] = [(3.0, Some(0.5)), (7.0, None)];

/// The Ncrit values the band's two ends are keyed by ([`BAND_ENDS`]).
pub const BAND_NCRIT: [f64; 2] = [BAND_ENDS[0].0, BAND_ENDS[1].0];

/// A station's polars at the band's two ends ([`BAND_ENDS`]): each polar moved, angle by
/// angle, by NeuralFoil's difference between that end and the polar's own Ncrit and transition
/// on the same section and Re (so an XFOIL table keeps its own shape and takes NeuralFoil's
/// sensitivity; an end's trip never later than the polar's own). Empty where NeuralFoil
/// cannot take the section.
fn band_polars(foil: &crate::Airfoil, polars: &[Polar], net: &propbet_neuralfoil::Network) -> Vec<Polar> {
    let mut out = Vec::new();
    for p in polars {
        let alphas: Vec<f64> = p.points.iter().map(|q| q.alpha_deg).collect();
        if alphas.is_empty() {
            continue;
        }
        let at = |ncrit: f64, trip: Option<f64>| {
            let job = crate::neural::Section {
                airfoil: foil,
                re: p.re,
                ncrit,
                trip,
            };
            crate::neural::polar(&job, &alphas, net).ok()
        };
        let Some(own) = at(p.ncrit, p.trip) else { continue };
        for (n, trip) in BAND_ENDS {
            let trip = match (trip, p.trip) {
                (Some(a), Some(b)) => Some(a.min(b)),
                (a, b) => a.or(b),
            };
            let Some(other) = at(n, trip) else { continue };
            let mut moved = Polar {
                ncrit: n,
                points: p.points.clone(),
                ..Polar::from_law(p.re, 0, 0, |_| (0.0, 0.0))
            };
            moved.mach = p.mach;
            moved.trip = p.trip;
            for ((q, a), b) in moved.points.iter_mut().zip(&own.points).zip(&other.points) {
                q.cl += b.cl - a.cl;
                // Drag stays positive: at most halved by the move.
                q.cd = (q.cd + b.cd - a.cd).max(0.5 * q.cd);
            }
            out.push(moved);
        }
    }
    out
}

/// How XFOIL is asked for a blade's polars: transition, angles, panels, iterations.
#[derive(Debug, Clone, PartialEq)]
pub struct XfoilSettings {
    /// Transition, angles (ascending, no duplicates), panels and iterations of every polar.
    pub section: SectionSettings,
    /// More Ncrit values at which every rung is also computed (for the `transition` effect;
    /// no QPROP fit): [`StationPolars::other_ncrit`].
    pub ncrit_effect: Vec<f64>,
}

/// A polar as the tabulated model needs it: a positive Re, and points of finite, plausible
/// coefficients in strictly ascending alpha.
fn check_polar(p: &Polar) -> Result<(), String> {
    if !(p.re.is_finite() && p.re > 0.0) {
        return Err("Reynolds number not a positive number".into());
    }
    // Prandtl-Glauert divides by sqrt(1 - M^2): a polar's Mach is subsonic.
    if !(p.mach.is_finite() && (0.0..1.0).contains(&p.mach)) {
        return Err(format!("Mach number {} is not in [0, 1)", p.mach));
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
    /// Operating points whose Reynolds numbers the polars cover (at least one).
    pub points: &'a [propbet_bemt::OperatingPoint],
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
    /// No operating point was given.
    #[error("no operating point to cover")]
    NoPoint,
}

/// The rungs of the Re ladder that cover `lo..=hi`: the one at or below `lo`, the one at or
/// above `hi`, those between; at least two (REexp needs two), at most [`MAX_RUNGS`].
pub fn re_rungs(lo: f64, hi: f64) -> Vec<f64> {
    let k = |re: f64| RE_PER_DECADE * re.log10();
    // A hair of tolerance, so that a Re on a rung is not bracketed by the rung below it.
    let k_lo = (k(lo) + 1e-9).floor() as i64;
    let k_hi = ((k(hi) - 1e-9).ceil() as i64).max(k_lo + 1);
    let n = (k_hi - k_lo + 1) as usize;
    let step = n.div_ceil(MAX_RUNGS).max(1);
    let mut ks: Vec<i64> = (k_lo..=k_hi).step_by(step).collect();
    if ks.last() != Some(&k_hi) {
        ks.push(k_hi);
    }
    ks.into_iter().map(|k| 10f64.powf(k as f64 / RE_PER_DECADE)).collect()
}

/// The smallest and largest of `v`.
fn span(v: &[f64]) -> [f64; 2] {
    [
        v.iter().copied().fold(f64::INFINITY, f64::min),
        v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    ]
}

/// What a station's polars are planned from: its radius, chord, the Reynolds numbers and Mach
/// number it sees over the operating points, the angles it works at, and its jobs.
struct Planned {
    r: f64,
    chord: f64,
    re: f64,
    re_range: [f64; 2],
    mach: f64,
    alphas: Vec<f64>,
    jobs: std::ops::Range<usize>,
}

/// The polar jobs of every station (the Reynolds ladder at the default Ncrit, then each other
/// Ncrit's), from the stations' flow at each operating point (`solved`).
fn plan(job: &BladeJob, solved: &[Vec<propbet_bemt::StationResult>]) -> (Vec<crate::PolarJob>, Vec<Planned>) {
    use propbet_bemt::StationResult;
    let blade = job.blade;
    let fluid = job.fluid;
    let at = |st: &[StationResult], r: f64, f: &dyn Fn(&StationResult) -> f64| -> f64 {
        let i = st.partition_point(|s| s.r <= r).clamp(1, st.len() - 1);
        let (a, b) = (&st[i - 1], &st[i]);
        let t = ((r - a.r) / (b.r - a.r)).clamp(-0.5, 1.5);
        f(a) + t * (f(b) - f(a))
    };
    let mut jobs = Vec::new();
    let mut stations = Vec::new();
    for (i, &r) in blade.r.iter().enumerate() {
        let chord = blade.chord[i];
        let ws: Vec<f64> = solved.iter().map(|st| at(st, r, &|s| s.w)).collect();
        let mut alphas: Vec<f64> = solved.iter().map(|st| at(st, r, &|s| s.alpha).to_degrees()).collect();
        alphas.sort_by(f64::total_cmp);
        let per_re = fluid.mu / (fluid.rho * chord);
        let re_range = span(&ws).map(|w| w / per_re);
        let re = (re_range[0] * re_range[1]).sqrt();
        let mach_at = |re: f64| (re * per_re / fluid.a).min(0.85);
        let first = jobs.len();
        if re > 0.0 && chord > 0.0 && re.is_finite() {
            let foil = &job.foils[i.min(job.foils.len() - 1)];
            let rungs = re_rungs(re_range[0], re_range[1]);
            // The default Ncrit's rungs first (they make the fit), then each other Ncrit's.
            for &ncrit in std::iter::once(&job.settings.section.ncrit).chain(&job.settings.ncrit_effect) {
                for &rung in &rungs {
                    jobs.push(crate::PolarJob {
                        airfoil: foil.clone(),
                        re: rung,
                        mach: mach_at(rung),
                        section: SectionSettings {
                            ncrit,
                            ..job.settings.section.clone()
                        },
                    });
                }
            }
        }
        stations.push(Planned {
            r,
            chord,
            re,
            re_range,
            mach: mach_at(re),
            alphas,
            jobs: first..jobs.len(),
        });
    }
    (jobs, stations)
}

/// One station's polars from the engine's `results` (taken), its QPROP fit at its working
/// angles, and what went wrong.
fn station_polars(
    job: &BladeJob,
    planned: Planned,
    jobs: &[crate::PolarJob],
    results: &mut [Option<Result<Polar, String>>],
) -> StationPolars {
    let Planned {
        r,
        chord,
        re,
        re_range,
        mach,
        alphas,
        jobs: range_k,
    } = planned;
    let mut polars = Vec::new();
    let mut other_ncrit = Vec::new();
    let mut problems = Vec::new();
    for k in range_k {
        match results[k].take() {
            Some(Ok(p)) if jobs[k].section.ncrit == job.settings.section.ncrit => polars.push(p),
            Some(Ok(p)) => other_ncrit.push(p),
            Some(Err(e)) if jobs[k].section.ncrit == job.settings.section.ncrit => problems.push(e),
            Some(Err(e)) => problems.push(format!("at Ncrit {} (transition effect): {e}", jobs[k].section.ncrit)),
            None => {}
        }
    }
    let alpha_deg = alphas[alphas.len() / 2];
    let alpha_range_deg = [alphas[0], alphas[alphas.len() - 1]];
    let weights = crate::AlphaWeights::Around {
        alphas_deg: alphas,
        sigma_deg: 3.0,
    };
    let fit = if polars.is_empty() {
        problems.push(format!(
            "no polar at r = {r:.4} m (Re {:.0}-{:.0})",
            re_range[0], re_range[1]
        ));
        None
    } else {
        match crate::fit_qprop(&polars, re, &weights, crate::DEFAULT_RE_EXP) {
            Ok(f) => Some(f),
            Err(e) => {
                problems.push(e.to_string());
                None
            }
        }
    };
    StationPolars {
        r,
        chord,
        re,
        re_range,
        mach,
        alpha_deg,
        alpha_range_deg,
        polars,
        other_ncrit,
        band: Vec::new(),
        fit,
        problem: (!problems.is_empty()).then(|| problems.join("; ")),
    }
}

/// Polars of every input station on the rungs of the Re ladder covering what it sees over the
/// operating points, each fitted to QPROP's coefficients over the angles of attack the station
/// works at. A station whose polars or fit failed keeps `fit: None` and says why in `problem`;
/// the batch goes on.
///
/// Each station's inflow comes from the solver on the blade's own coefficients at every
/// point; Re = ρ W c / μ, Mach = W / a (capped at 0.85, XFOIL's limit of sense).
pub fn compute_blade(
    job: &BladeJob,
    engine: &crate::PolarEngine,
    progress: &crate::Progress<'_>,
) -> Result<BladePolars, BladeError> {
    use propbet_bemt::{Solver, SolverOptions, StationResult};
    let blade = job.blade;
    let rotor = blade.to_rotor(propbet_bemt::Discretization::default())?;
    let fluid = job.fluid;
    if job.foils.is_empty() {
        return Err(BladeError::NoSection);
    }
    if job.points.is_empty() {
        return Err(BladeError::NoPoint);
    }
    let opts = SolverOptions {
        keep_stations: true,
        ..SolverOptions::default()
    };
    let solver = Solver::new(&rotor, &fluid, &opts);
    let solved: Vec<Vec<StationResult>> = job.points.iter().map(|&op| solver.solve(op).stations).collect();
    let (jobs, stations) = plan(job, &solved);
    let mut results: Vec<Option<Result<Polar, String>>> = engine
        .compute_all(&jobs, progress)
        .into_iter()
        .map(|r| Some(r.map(|(p, _)| p).map_err(|e| e.to_string())))
        .collect();
    let mut out: Vec<StationPolars> = stations
        .into_iter()
        .map(|st| station_polars(job, st, &jobs, &mut results))
        .collect();
    // The band's section-model source: NeuralFoil's networks are built in, so this costs
    // milliseconds whatever made the polars.
    if let Ok(net) = propbet_neuralfoil::Network::shipped(propbet_neuralfoil::DEFAULT_SIZE) {
        use rayon::prelude::*;
        out.par_iter_mut().enumerate().for_each(|(i, st)| {
            st.band = band_polars(&job.foils[i.min(job.foils.len() - 1)], &st.polars, &net);
        });
    }
    let names: Vec<&str> = job.foils.iter().map(|f| f.name.as_str()).collect();
    let rpms: Vec<f64> = job
        .points
        .iter()
        .map(|p| propbet_bemt::units::omega_to_rpm(p.omega))
        .collect();
    let vs: Vec<f64> = job.points.iter().map(|p| p.v).collect();
    Ok(BladePolars {
        format: FORMAT.into(),
        geometry: job.geometry.clone(),
        airfoil: if names.len() == 1 {
            names[0].to_string()
        } else {
            format!("{} sections, {} ... {}", names.len(), names[0], names[names.len() - 1])
        },
        rpm: span(&rpms),
        v: span(&vs),
        air: [fluid.rho, fluid.mu, fluid.a],
        stations: out,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_polar_at_sonic_mach_is_refused() {
        let mut p = Polar::from_law(1e5, -2, 4, |a| (0.4 + 0.1 * a, 0.012));
        assert!(check_polar(&p).is_ok());
        p.mach = 1.2;
        assert!(check_polar(&p).unwrap_err().contains("Mach number 1.2"));
        p.mach = f64::NAN;
        assert!(check_polar(&p).is_err());
    }

    /// The band's two ends move a polar, angle by angle, by NeuralFoil's difference between
    /// that end (Ncrit 3 tripped at mid-chord; Ncrit 7) and the polar's own transition; the
    /// angles, the Reynolds number and the rest of the polar's own shape stay.
    #[test]
    fn the_bands_ends_move_a_polar_by_neuralfoils_difference() {
        let foil = crate::naca4_from_name("naca4412").unwrap().unwrap();
        let net = propbet_neuralfoil::Network::shipped(propbet_neuralfoil::DEFAULT_SIZE).unwrap();
        // An XFOIL-like polar of its own (any shape: only the difference is NeuralFoil's).
        let mut base = Polar::from_law(6e4, -2, 8, |a| (0.45 + 0.1 * a, 0.015 + 0.0005 * a * a));
        base.ncrit = 5.0;
        let ends = band_polars(&foil, std::slice::from_ref(&base), &net);
        assert_eq!(ends.iter().map(|p| p.ncrit).collect::<Vec<_>>(), BAND_NCRIT);
        let alphas: Vec<f64> = base.points.iter().map(|q| q.alpha_deg).collect();
        let nf = |ncrit: f64, trip: Option<f64>| {
            let job = crate::neural::Section {
                airfoil: &foil,
                re: 6e4,
                ncrit,
                trip,
            };
            crate::neural::polar(&job, &alphas, &net).unwrap()
        };
        let own = nf(5.0, None);
        for (e, (ncrit, trip)) in ends.iter().zip(BAND_ENDS) {
            assert_eq!((e.re, e.trip, e.points.len()), (base.re, base.trip, base.points.len()));
            let other = nf(ncrit, trip);
            let mut moved = 0.0_f64;
            for (((q, b), o), x) in e.points.iter().zip(&base.points).zip(&own.points).zip(&other.points) {
                assert_eq!(q.alpha_deg, b.alpha_deg);
                assert!((q.cl - (b.cl + x.cl - o.cl)).abs() < 1e-12, "{ncrit}: {q:?}");
                assert!(q.cd > 0.0 && (q.cd - (b.cd + x.cd - o.cd).max(0.5 * b.cd)).abs() < 1e-12);
                moved = moved.max((q.cl - b.cl).abs());
            }
            // The transition moves this section's lift at Re 60,000 visibly.
            assert!(moved > 0.01, "{ncrit}: largest lift move {moved}");
        }
    }

    #[test]
    fn rungs_bracket_the_range_five_per_decade() {
        let r = re_rungs(30_000.0, 70_000.0);
        let want = [25_118.864, 39_810.717, 63_095.734, 100_000.0];
        assert_eq!(r.len(), want.len(), "{r:?}");
        for (a, b) in r.iter().zip(want) {
            assert!((a / b - 1.0).abs() < 1e-6, "{r:?}");
        }
        // A Re on a rung is its own lower end; one Re still gets two rungs.
        let one = re_rungs(100_000.0, 100_000.0);
        assert_eq!(one.len(), 2);
        assert!((one[0] - 1e5).abs() < 1e-6 && (one[1] / 158_489.32 - 1.0).abs() < 1e-6);
        // Absurd spans are thinned, ends kept.
        let wide = re_rungs(1e3, 1e8);
        assert!(wide.len() <= MAX_RUNGS + 1 && wide[0] <= 1e3 * 1.0001 && *wide.last().unwrap() >= 1e8 * 0.9999);
    }
}
