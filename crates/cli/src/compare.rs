//! `propbet compare`: measured files against the model's prediction; writes the report
//! directory (report.html, metrics.json, summary.md, points.csv, plots/*.svg and *.png).

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use clap::{Args, ValueEnum};
use propbet_atmosphere::AirState;
use propbet_compare::report::{self, FileEntry, ReportInput};
use propbet_compare::{compare, metrics::metrics, AirChoice, ComparedPoint, Setup};
use propbet_measure::{MeasuredSet, ReadOptions, RpmSource};

use crate::output::{push_num, write_atomic, write_figure};
use crate::predict::ModelArgs;
use crate::values::{parse_humidity, parse_pressure, parse_temperature};

/// Which RPM column of a thrust-stand log to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum RpmSourceArg {
    /// The optical (once-per-revolution) sensor.
    Optical,
    /// The ESC's electrical speed.
    Electrical,
}

/// Arguments of `propbet compare`.
#[derive(Debug, Args)]
pub struct CompareArgs {
    /// The propeller model.
    #[command(flatten)]
    pub model: ModelArgs,
    /// The measurements.
    #[command(flatten)]
    pub data: MeasuredArgs,
    /// Output directory (created if missing).
    #[arg(long, short)]
    pub out: PathBuf,
}

/// Measured files and how to read them (shared by `compare` and `diagnose`).
#[derive(Debug, Args)]
pub struct MeasuredArgs {
    /// Measured files: RCbenchmark/Tyto CSV, UIUC .txt, or generic CSV.
    #[arg(long, required = true, num_args = 1..)]
    pub measured: Vec<PathBuf>,
    /// Motor poles: electrical RPM readings are multiplied by 2/N.
    #[arg(long)]
    pub poles: Option<u32>,
    /// RPM column of thrust-stand logs (default: optical when it reads, else electrical).
    #[arg(long, value_enum)]
    pub rpm_source: Option<RpmSourceArg>,
    /// Air state T,P,RH overriding what the files log: temperature (°C unless suffixed K or F),
    /// pressure (Pa unless suffixed hPa, mbar, kPa, inHg, psi), relative humidity (%). Example:
    /// 22,1009hPa,40.
    #[arg(long)]
    pub atmosphere: Option<String>,
    /// Air density [kg/m^3], overriding the one from any air state (to reproduce a study).
    #[arg(long, allow_negative_numbers = true)]
    pub rho: Option<f64>,
    /// Column map (TOML) for generic CSV files.
    #[arg(long)]
    pub columns: Option<PathBuf>,
}

impl MeasuredArgs {
    /// The air choice and the measured sets, read and checked.
    pub fn load(&self) -> Result<(AirChoice, Vec<MeasuredSet>)> {
        if let Some(p) = self.poles {
            if p < 2 || p % 2 != 0 {
                bail!("--poles {p}: a motor has an even number of poles, at least 2");
            }
        }
        if let Some(r) = self.rho {
            if !(r.is_finite() && r > 0.0 && r < 20.0) {
                bail!("--rho {r}: not a plausible air density in kg/m^3");
            }
        }
        let air = AirChoice {
            given: self.atmosphere.as_deref().map(parse_atmosphere).transpose()?,
            rho: self.rho,
        };
        let column_map = self
            .columns
            .as_ref()
            .map(|p| std::fs::read_to_string(p).with_context(|| format!("{}: cannot read the column map", p.display())))
            .transpose()?;
        let opts = ReadOptions {
            poles: self.poles,
            rpm_source: self.rpm_source.map(|s| match s {
                RpmSourceArg::Optical => RpmSource::Optical,
                RpmSourceArg::Electrical => RpmSource::Electrical,
            }),
            column_map,
            ..Default::default()
        };
        let sets: Vec<MeasuredSet> = self
            .measured
            .iter()
            .map(|p| read_measured(p, &opts))
            .collect::<Result<_>>()?;
        Ok((air, sets))
    }

    /// The files read (never to be overwritten).
    pub fn inputs(&self) -> Vec<&Path> {
        self.measured
            .iter()
            .map(PathBuf::as_path)
            .chain(self.columns.as_deref())
            .collect()
    }

    /// One line per file: rows, points and what was dropped.
    pub fn print_summary(&self, sets: &[MeasuredSet]) {
        for (p, s) in self.measured.iter().zip(sets) {
            eprintln!(
                "propbet: {}: {} rows -> {} points; {}",
                p.display(),
                s.rows,
                s.points.len(),
                propbet_measure::summarise_dropped(&s.dropped)
            );
        }
    }
}

/// `T,P,RH` split into its three parts, a bare temperature given its unit (°C).
pub fn split_atmosphere(text: &str) -> Result<[String; 3]> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        bail!("--atmosphere '{text}': give temperature, pressure and humidity, for example 22,1009hPa,40");
    }
    let t = if parts[0].parse::<f64>().is_ok() {
        format!("{}C", parts[0])
    } else {
        parts[0].to_string()
    };
    Ok([t, parts[1].to_string(), parts[2].to_string()])
}

/// `T,P,RH` with optional units.
pub fn parse_atmosphere(text: &str) -> Result<AirState> {
    let [t, p, rh] = split_atmosphere(text)?;
    let state = AirState::new(parse_temperature(&t)?, parse_pressure(&p)?, parse_humidity(&rh)?)
        .map_err(|e| anyhow::anyhow!("--atmosphere '{text}': {e}"))?;
    Ok(state)
}

fn read_measured(path: &Path, opts: &ReadOptions) -> Result<MeasuredSet> {
    let bytes = std::fs::read(path).with_context(|| format!("{}: cannot read", path.display()))?;
    let text = String::from_utf8(bytes).map_err(|e| {
        anyhow::anyhow!(
            "{}: not UTF-8 text (byte {}); export the log as CSV",
            path.display(),
            e.utf8_error().valid_up_to()
        )
    })?;
    let opts = ReadOptions {
        name: path.file_name().map(|n| n.to_string_lossy().into_owned()),
        ..opts.clone()
    };
    propbet_measure::read(&text, &opts).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
}

const POINTS_HEADER: &str = "file,label,line_first,line_last,rpm,rpm_sd,v_m_s,j,rho,thrust_n,thrust_sd,thrust_pred,torque_nm,torque_sd,torque_pred,power_w,power_pred,ct,ct_sd,ct_pred,cp,cp_sd,cp_pred,eta,eta_pred,re75,mach_tip,scored";

fn points_csv(files: &[PathBuf], pts: &[ComparedPoint]) -> Vec<u8> {
    let mut s = format!("{POINTS_HEADER}\n").into_bytes();
    for p in pts {
        let name = files[p.file].display().to_string().replace(',', ";");
        s.extend_from_slice(format!("{name},{},{},{},", p.label.replace(',', ";"), p.lines.0, p.lines.1).as_bytes());
        let cells = [
            Some(p.rpm),
            p.rpm_sd,
            Some(p.v),
            Some(p.j),
            Some(p.air.fluid.rho),
            p.measured.thrust,
            p.measured_sd.thrust,
            p.predicted.thrust,
            p.measured.torque,
            p.measured_sd.torque,
            p.predicted.torque,
            p.measured.power,
            p.predicted.power,
            p.measured.ct,
            p.measured_sd.ct,
            p.predicted.ct,
            p.measured.cp,
            p.measured_sd.cp,
            p.predicted.cp,
            p.measured.eta,
            p.predicted.eta,
            Some(p.re75),
            Some(p.mach_tip),
        ];
        for c in cells {
            push_num(&mut s, c);
            s.push(b',');
        }
        s.extend_from_slice(if p.scored() { b"1\n" } else { b"0\n" });
    }
    s
}

/// Runs `propbet compare`; returns false when rows were dropped as faulty or the solver did
/// not converge somewhere (all reported).
pub fn run(args: &CompareArgs) -> Result<bool> {
    let model = args.model.build(false)?;
    let (air, sets) = args.data.load()?;
    let setup = Setup {
        rotor: &model.rotor,
        diameter: model.diameter,
        opts: model.opts,
        air,
        effects: model.effects.clone(),
    };
    let points = compare(&setup, &sets)?;
    let m = metrics(&points);
    let mut prop_notes = model.loaded.warnings.clone();
    if args.model.qprop_compat {
        prop_notes.push(format!(
            "read as QPROP 1.22 does (--qprop-compat): tip-loss radius {} m",
            model.rotor.tip_radius
        ));
    }
    if !model.effects.is_empty() {
        prop_notes.push(format!("model with effects: {}", model.effects.describe()));
    }
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let rep = report::build(&ReportInput {
        prop: args.model.prop.display().to_string(),
        prop_notes,
        files: args
            .data
            .measured
            .iter()
            .zip(&sets)
            .map(|(p, set)| FileEntry {
                path: p.display().to_string(),
                set,
            })
            .collect(),
        points: &points,
        metrics: &m,
        setup: &setup,
        command,
    })?;

    let mut inputs = args.model.inputs();
    inputs.extend(args.data.inputs());
    let plots = args.out.join("plots");
    std::fs::create_dir_all(&plots).with_context(|| format!("{}: cannot create the directory", plots.display()))?;
    for (name, fig) in &rep.figures {
        for ext in ["svg", "png"] {
            write_figure(&plots.join(format!("{name}.{ext}")), fig, &inputs)?;
        }
    }
    let mut json = serde_json::to_vec_pretty(&rep.json)?;
    json.push(b'\n');
    write_atomic(&args.out.join("metrics.json"), &[json], &inputs)?;
    write_atomic(&args.out.join("summary.md"), &[rep.markdown.as_bytes()], &inputs)?;
    write_atomic(
        &args.out.join("points.csv"),
        &[points_csv(&args.data.measured, &points)],
        &inputs,
    )?;
    write_atomic(&args.out.join("report.html"), &[rep.html.as_bytes()], &inputs)?;

    // A short summary on the terminal.
    args.data.print_summary(&sets);
    for q in ["thrust", "torque", "power", "eta"] {
        if let Some(x) = m.overall.metrics.get(q) {
            println!(
                "{q:>7}: n {:>3}  mean error {:+6.1} %  mean |error| {:5.1} %  worst {:+6.1} % ({})",
                x.n,
                100.0 * x.mean_rel,
                100.0 * x.mean_abs_rel,
                100.0 * x.max_rel,
                x.max_rel_at
            );
        }
    }
    if m.overall.points == 0 {
        let mut reasons: Vec<&str> = points.iter().flat_map(|p| p.flags.iter().map(String::as_str)).collect();
        reasons.sort_unstable();
        reasons.dedup();
        println!(
            "no point could be scored: all {} points are flagged ({})",
            points.len(),
            reasons.join("; ")
        );
    }
    println!("report: {}", args.out.join("report.html").display());
    let faults: usize = sets.iter().map(MeasuredSet::faults).sum();
    let unconverged: usize = points.iter().map(|p| p.not_converged).sum();
    if faults > 0 {
        eprintln!("propbet: {faults} rows were dropped as faulty; they are listed in the report");
    }
    if unconverged > 0 {
        eprintln!("propbet: {unconverged} station solutions did not converge");
    }
    Ok(faults == 0 && unconverged == 0)
}
