//! `propbet predict`: performance of a QPROP prop file over RPM x (J or V).

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use clap::{Args, ValueEnum};
use propbet_atmosphere::AirState;
use propbet_bemt::{grid_rpm_j, grid_rpm_v, Discretization, Fluid, PointResult, Rotor, Solver, SolverOptions};
use propbet_effects::spec::Registry;
use propbet_effects::{parse_spec, Stack};
use propbet_qprop::{parse_prop, PropFile, RadiusReading};
use serde::Serialize;

use crate::output::{emit, push_num};
use crate::values::{parse_humidity, parse_length_unit, parse_list, parse_pressure, parse_temperature};

/// Output format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// One row per operating point.
    Csv,
    /// All results, with the inputs, as one JSON document.
    Json,
}

/// Arguments of `propbet predict`.
#[derive(Debug, Args)]
pub struct PredictArgs {
    /// The propeller model.
    #[command(flatten)]
    pub model: ModelArgs,
    /// Rotation speeds [rpm]: a list, `start:stop:step` or `start:stop/N`.
    #[arg(long, allow_hyphen_values = true)]
    pub rpm: String,
    /// Advance ratios J = V/(nD), same syntax.
    #[arg(long, conflicts_with = "v", allow_hyphen_values = true)]
    pub j: Option<String>,
    /// Axial speeds [m/s], same syntax (default: 0, static).
    #[arg(long, allow_hyphen_values = true)]
    pub v: Option<String>,
    /// Air properties.
    #[command(flatten)]
    pub air: FluidArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Csv)]
    pub format: Format,
    /// Output file (default: standard output).
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Also write the per-station table (CSV) to this file; with --format json the stations
    /// are included in the JSON as well.
    #[arg(long)]
    pub stations: Option<PathBuf>,
}

/// The propeller model: a prop file, how to read it, and what to change in it.
#[derive(Debug, Args)]
pub struct ModelArgs {
    /// QPROP prop file.
    #[arg(long)]
    pub prop: PathBuf,
    /// Collective blade-angle change [deg].
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub dbeta: f64,
    /// Length unit of the prop file's radii and chords (overrides its Rfac and Cfac): m, cm, mm, in.
    #[arg(long)]
    pub units: Option<String>,
    /// Reproduce QPROP 1.22 exactly: R on line 2 unscaled, REref of the first station everywhere.
    #[arg(long)]
    pub qprop_compat: bool,
    /// Switch the tip-loss factor off.
    #[arg(long)]
    pub no_tip_loss: bool,
    /// Use the tabulated XFOIL polars of this file (from `propbet polars --out-polars`) as the
    /// section model, instead of the prop file's QPROP coefficients.
    #[arg(long)]
    pub polars: Option<PathBuf>,
    /// Add a physical effect to the model: `id` or `id:param=value[,param=value]`, for
    /// example `pitch-offset:deg=1.2` or `torque-tare:q0=0.002,q1=2e-6` (repeatable; see
    /// `propbet effects` for the list). Parameters not given take their neutral value.
    #[arg(long = "effect", value_name = "SPEC")]
    pub effect: Vec<String>,
    /// TOML file of user-defined effects (formulas on a hook), usable by `--effect`.
    #[arg(long)]
    pub user_effects: Option<PathBuf>,
}

/// A model ready to solve.
pub struct Model {
    /// The prop file as read.
    pub loaded: LoadedProp,
    /// The rotor the solver sees.
    pub rotor: Rotor,
    /// Solver options from the flags.
    pub opts: SolverOptions,
    /// Propeller diameter of the blade as documented (2 x its last station radius, or line 2's R
    /// in the table's units) [m]: the D of the coefficients even when `--qprop-compat` gives
    /// the tip-loss factor QPROP's unscaled R.
    pub diameter: f64,
    /// The effects known (built-in and user-defined).
    pub registry: Registry,
    /// The effects added with `--effect`.
    pub effects: Stack,
}

impl ModelArgs {
    /// Reads the prop file (and polars) and builds the rotor.
    pub fn build(&self, keep_stations: bool) -> Result<Model> {
        let (loaded, mut rotor) = load_rotor(&self.prop, self.units.as_deref(), self.qprop_compat)?;
        if let Some(path) = &self.polars {
            apply_polars(&mut rotor, path)?;
        }
        if !self.dbeta.is_finite() {
            bail!("--dbeta: not a finite number");
        }
        let opts = SolverOptions {
            tip_loss: !self.no_tip_loss,
            dbeta: self.dbeta.to_radians(),
            keep_stations,
            ..SolverOptions::default()
        };
        let diameter = 2.0 * loaded.file.tip_radius(RadiusReading::Documented);
        let registry = match &self.user_effects {
            Some(path) => {
                let text = std::fs::read_to_string(path).with_context(|| format!("{}: cannot read", path.display()))?;
                let user = propbet_effects::user::parse(&text, &path.display().to_string())?;
                Registry::with_user(user)?
            }
            None => Registry::default(),
        };
        let active = self
            .effect
            .iter()
            .map(|s| registry.resolve(&parse_spec(s)?))
            .collect::<Result<Vec<_>, _>>()
            .context("--effect")?;
        Ok(Model {
            loaded,
            rotor,
            opts,
            diameter,
            registry,
            effects: Stack { active },
        })
    }

    /// The files the model reads (never to be overwritten).
    pub fn inputs(&self) -> Vec<&Path> {
        std::iter::once(self.prop.as_path())
            .chain(self.polars.as_deref())
            .chain(self.user_effects.as_deref())
            .collect()
    }
}

/// Replaces the rotor's section models by the tabulated polars of a `propbet polars` file.
fn apply_polars(rotor: &mut Rotor, path: &Path) -> Result<()> {
    let text = std::fs::read_to_string(path).with_context(|| format!("{}: cannot read", path.display()))?;
    let blade = propbet_polar::BladePolars::from_json(&text).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let (r, models) = blade.models().map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let (lo, hi) = (rotor.stations[0].r, rotor.stations[rotor.stations.len() - 1].r);
    if r[0] > hi || r[r.len() - 1] < lo {
        bail!(
            "{}: its stations (r = {:.4}..{:.4} m) do not overlap the blade (r = {lo:.4}..{hi:.4} m)",
            path.display(),
            r[0],
            r[r.len() - 1]
        );
    }
    propbet_polar::tabulated::apply_to_rotor(rotor, &r, &models);
    Ok(())
}

/// Air properties from flags: --rho/--mu/--a (QPROP's defaults), or --temp/--pressure
/// [--humidity] through the atmosphere model.
#[derive(Debug, Args)]
pub struct FluidArgs {
    /// Air density [kg/m^3] (default 1.225, QPROP's).
    #[arg(long, conflicts_with_all = ["temp", "pressure"], allow_negative_numbers = true)]
    pub rho: Option<f64>,
    /// Dynamic viscosity [Pa s] (default 1.78e-5, QPROP's).
    #[arg(long, allow_negative_numbers = true)]
    pub mu: Option<f64>,
    /// Speed of sound [m/s] (default 340, QPROP's).
    #[arg(long, allow_negative_numbers = true)]
    pub a: Option<f64>,
    /// Air temperature with unit (20C, 293.15K, 68F); sets rho, mu and a.
    #[arg(long, requires = "pressure")]
    pub temp: Option<String>,
    /// Air pressure (Pa unless suffixed: hPa, mbar, kPa, inHg, psi).
    #[arg(long, requires = "temp")]
    pub pressure: Option<String>,
    /// Relative humidity in percent (with --temp and --pressure).
    #[arg(long, requires = "temp")]
    pub humidity: Option<String>,
}

/// A prop file read and checked, with its warnings printed.
pub struct LoadedProp {
    /// The file as written.
    pub file: PropFile,
    /// Warnings for the user.
    pub warnings: Vec<String>,
}

/// Reads a prop file, naming the file in every error.
pub fn load_prop(path: &Path, units: Option<&str>) -> Result<LoadedProp> {
    let bytes = std::fs::read(path).with_context(|| format!("{}: cannot read", path.display()))?;
    let text = String::from_utf8(bytes)
        .map_err(|_| anyhow::anyhow!("{}: not UTF-8 text (is it a QPROP prop file?)", path.display()))?;
    let (mut file, warnings) = parse_prop(&text).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let mut warnings: Vec<String> = warnings
        .into_iter()
        .map(|w| match w.line {
            0 => format!("{}: {}", path.display(), w.message),
            l => format!("{}: line {l}: {}", path.display(), w.message),
        })
        .collect();
    if let Some(u) = units {
        let f = parse_length_unit(u)?;
        warnings.push(format!(
            "{}: --units {u} replaces the file's Rfac = {} and Cfac = {} with {f}",
            path.display(),
            file.scale[0],
            file.scale[1]
        ));
        file.scale[0] = f;
        file.scale[1] = f;
    }
    Ok(LoadedProp { file, warnings })
}

/// Reads a prop file, prints its warnings and discretises it as QPROP does (or exactly as
/// QPROP 1.22 reads it, with `qprop_compat`).
pub fn load_rotor(path: &Path, units: Option<&str>, qprop_compat: bool) -> Result<(LoadedProp, Rotor)> {
    let mut loaded = load_prop(path, units)?;
    let differences: Vec<String> = loaded.file.qprop_differences().into_iter().map(|w| w.message).collect();
    for w in &mut loaded.warnings {
        if differences.iter().any(|d| w.ends_with(d.as_str())) {
            w.push_str(if qprop_compat {
                " (reproduced as QPROP reads it: --qprop-compat)"
            } else {
                " (--qprop-compat reproduces QPROP)"
            });
        }
    }
    for w in &loaded.warnings {
        eprintln!("propbet: warning: {w}");
    }
    let reading = if qprop_compat {
        RadiusReading::Qprop122
    } else {
        RadiusReading::Documented
    };
    let rotor = loaded
        .file
        .to_blade(reading)
        .to_rotor(Discretization {
            stations: 25,
            qprop_reref_quirk: qprop_compat,
        })
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    Ok((loaded, rotor))
}

impl FluidArgs {
    /// The fluid, and a note of where it came from.
    pub fn fluid(&self) -> Result<(Fluid, String)> {
        fluid(self)
    }
}

fn fluid(args: &FluidArgs) -> Result<(Fluid, String)> {
    if let (Some(t), Some(p)) = (&args.temp, &args.pressure) {
        let rh = args.humidity.as_deref().map(parse_humidity).transpose()?.unwrap_or(0.0);
        let state = AirState::new(parse_temperature(t)?, parse_pressure(p)?, rh)?;
        let mut f = state.fluid();
        if let Some(mu) = args.mu {
            f.mu = mu;
        }
        if let Some(a) = args.a {
            f.a = a;
        }
        return Ok((f, format!("from T = {t}, p = {p}, RH = {:.0} %", rh * 100.0)));
    }
    let d = Fluid::QPROP_DEFAULT;
    let f = Fluid {
        rho: args.rho.unwrap_or(d.rho),
        mu: args.mu.unwrap_or(d.mu),
        a: args.a.unwrap_or(d.a),
    };
    f.validate().map_err(|e| anyhow::anyhow!("air: {e}"))?;
    let source = if args.rho.is_none() && args.mu.is_none() && args.a.is_none() {
        "QPROP defaults (standard air, not measured)".to_string()
    } else {
        "given".to_string()
    };
    Ok((f, source))
}

#[derive(Serialize)]
struct JsonOut<'a> {
    prop: &'a str,
    name: &'a str,
    blades: f64,
    tip_radius_m: f64,
    fluid: Fluid,
    fluid_source: &'a str,
    qprop_compat: bool,
    tip_loss: bool,
    dbeta_deg: f64,
    warnings: &'a [String],
    points: &'a [PointResult],
}

/// Runs `propbet predict`; returns whether every station of every point converged.
pub fn run(args: &PredictArgs) -> Result<bool> {
    let Model {
        loaded,
        rotor,
        opts,
        diameter,
        effects,
        ..
    } = args.model.build(args.stations.is_some())?;
    let (fluid, fluid_source) = args.air.fluid()?;
    let rpms = parse_list("--rpm", &args.rpm)?;
    if let Some(bad) = rpms.iter().find(|&&r| r < 0.0) {
        bail!("--rpm: rotation speed must not be negative, found {bad}");
    }
    let points = match (&args.j, &args.v) {
        (Some(j), _) => {
            if rpms.contains(&0.0) {
                bail!("--j needs a non-zero --rpm (J = V/(nD) is undefined at 0 rpm)");
            }
            grid_rpm_j(&rpms, &parse_list("--j", j)?, rotor.tip_radius)
        }
        (None, Some(v)) => grid_rpm_v(&rpms, &parse_list("--v", v)?),
        (None, None) => grid_rpm_v(&rpms, &[0.0]),
    };
    // Solve and format chunk by chunk in the same parallel task, so the table is written
    // while the data is still in cache; the results themselves are kept only when the output
    // needs them (JSON, the station table).
    let solver = Solver::new(&rotor, &fluid, &opts);
    let csv = args.format == Format::Csv;
    let keep_results = !csv || args.stations.is_some();
    struct Chunk {
        results: Vec<PointResult>,
        text: Vec<u8>,
        failed: usize,
        failed_points: usize,
    }
    let chunks: Vec<Chunk> = {
        use rayon::prelude::*;
        points
            .par_chunks(128)
            .map(|c| {
                let r: Vec<PointResult> = if effects.is_empty() {
                    solver.solve_many(c)
                } else {
                    c.iter()
                        .map(|&op| {
                            let p = effects.predict(&rotor, &opts, &fluid, diameter, op)?;
                            Ok(p.result.with_loads(
                                p.loads.thrust,
                                p.loads.torque,
                                op.omega,
                                fluid.rho,
                                rotor.tip_radius,
                            ))
                        })
                        .collect::<Result<_, propbet_effects::EffectError>>()?
                };
                Ok(Chunk {
                    text: if csv { summary_rows(&r) } else { Vec::new() },
                    failed: r.iter().map(|p| p.not_converged).sum(),
                    failed_points: r.iter().filter(|p| p.not_converged > 0).count(),
                    results: if keep_results { r } else { Vec::new() },
                })
            })
            .collect::<Result<_, propbet_effects::EffectError>>()?
    };
    let failed: usize = chunks.iter().map(|c| c.failed).sum();
    let failed_points: usize = chunks.iter().map(|c| c.failed_points).sum();
    let mut results = Vec::with_capacity(if keep_results { points.len() } else { 0 });
    let mut body = vec![format!("{SUMMARY_HEADER}\n").into_bytes()];
    for c in chunks {
        results.extend(c.results);
        body.push(c.text);
    }
    let inputs = args.model.inputs();
    if !csv {
        let doc = JsonOut {
            prop: &args.model.prop.to_string_lossy(),
            name: &loaded.file.name,
            blades: rotor.blades,
            tip_radius_m: rotor.tip_radius,
            fluid,
            fluid_source: &fluid_source,
            qprop_compat: args.model.qprop_compat,
            tip_loss: opts.tip_loss,
            dbeta_deg: args.model.dbeta,
            warnings: &loaded.warnings,
            points: &results,
        };
        let mut s = serde_json::to_vec_pretty(&doc)?;
        s.push(b'\n');
        body = vec![s];
    }
    emit(args.out.as_deref(), &body, &inputs)?;
    if let Some(path) = &args.stations {
        emit(Some(path), &[stations_csv(&results)], &inputs)?;
    }
    if failed > 0 {
        eprintln!(
            "propbet: {failed} station solutions at {failed_points} operating points did not converge; \
             they are flagged in the per-station table"
        );
    }
    Ok(failed == 0)
}

/// Column header of the summary CSV.
pub const SUMMARY_HEADER: &str = "rpm,v_m_s,j,thrust_n,torque_nm,power_w,ct,cp,cq,eta,ct_qprop,cp_qprop,adv_qprop,dv_m_s,cl_avg,cd_avg,not_converged";

fn summary_rows(results: &[PointResult]) -> Vec<u8> {
    let mut s = Vec::with_capacity(200 * results.len());
    for p in results {
        let cells = [
            Some(p.rpm),
            Some(p.v),
            p.j,
            Some(p.thrust),
            Some(p.torque),
            Some(p.power),
            p.ct,
            p.cp,
            p.cq,
            Some(p.eta),
            p.ct_qprop,
            p.cp_qprop,
            p.adv_qprop,
            Some(p.dv),
            Some(p.cl_avg),
            Some(p.cd_avg),
        ];
        for c in cells {
            push_num(&mut s, c);
            s.push(b',');
        }
        s.extend_from_slice(p.not_converged.to_string().as_bytes());
        s.push(b'\n');
    }
    s
}

fn stations_csv(results: &[PointResult]) -> Vec<u8> {
    let mut s = b"rpm,v_m_s,r_m,chord_m,beta_deg,alpha_deg,cl,cd,re,mach,w_m_s,wa_m_s,wt_m_s,va_m_s,vt_m_s,f_tip,\
dt_dr_n_m,dq_dr_n,stalled,convergence\n"
        .to_vec();
    for p in results {
        for st in &p.stations {
            for v in [
                p.rpm,
                p.v,
                st.r,
                st.chord,
                st.beta.to_degrees(),
                st.alpha.to_degrees(),
                st.cl,
                st.cd,
                st.re,
                st.mach,
                st.w,
                st.wa,
                st.wt,
                st.va,
                st.vt,
                st.f_tip,
                st.dt_dr,
                st.dq_dr,
            ] {
                push_num(&mut s, Some(v));
                s.push(b',');
            }
            let conv = match st.convergence {
                propbet_bemt::Convergence::Newton { .. } => "newton",
                propbet_bemt::Convergence::Bracketed { .. } => "bracketed",
                propbet_bemt::Convergence::NotConverged => "not_converged",
                propbet_bemt::Convergence::NoFlow => "no_flow",
                propbet_bemt::Convergence::NoRotation => "no_rotation",
                propbet_bemt::Convergence::ZeroChord => "zero_chord",
            };
            s.extend_from_slice(if st.stalled { b"true," } else { b"false," });
            s.extend_from_slice(conv.as_bytes());
            s.push(b'\n');
        }
    }
    s
}
