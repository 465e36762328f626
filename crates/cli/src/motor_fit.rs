//! `propbet motor fit`: a QPROP motor file (type 1: R, Io, Kv; with `--kq` type 2: R, Io, Kv,
//! Kq) fitted to thrust-stand logs that carry speed, torque, voltage and current, with the
//! fit's numbers in its comments.

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, Subcommand};
use propbet_api::motor::{write_motor, FitKind, MotorFile};

use crate::compare::MeasuredArgs;
use crate::output::emit;

/// `propbet motor`'s subcommands.
#[derive(Debug, Subcommand)]
pub enum MotorCommand {
    /// Fit R, Io and Kv to stand logs' speed, torque, voltage and current; write a QPROP motor
    /// file.
    Fit(FitArgs),
}

/// Arguments of `propbet motor fit`.
#[derive(Debug, Args)]
pub struct FitArgs {
    /// The logs.
    #[command(flatten)]
    pub measured: MeasuredArgs,
    /// The maker's Kv [rpm/V]: R and Io are fitted for it (without it Kv is found from the
    /// ESC command's duty).
    #[arg(long)]
    pub kv: Option<f64>,
    /// Fit the torque constant Kq on its own (a QPROP type 2 motor: R, Io, Kv, Kq): Kq and Io
    /// from the motor's current at the ESC's duty, R and Kv from the supply power. Needs the
    /// ESC command.
    #[arg(long)]
    pub kq: bool,
    /// The motor's name in the file (default: the first log's name).
    #[arg(long)]
    pub name: Option<String>,
    /// The motor file to write (default: standard output).
    #[arg(long, short)]
    pub out: Option<PathBuf>,
}

/// Runs `propbet motor ...`.
pub fn run(command: &MotorCommand) -> Result<bool> {
    match command {
        MotorCommand::Fit(a) => fit(a),
    }
}

/// A motor fitted to stand logs, with what the file's comments and the terminal say of it.
pub struct Fitted {
    /// The fit: the constants with their intervals, the held-out errors, the notes.
    pub fit: propbet_pipeline::stages::FittedMotor,
    /// The motor as a file.
    pub file: MotorFile,
    /// The QPROP motor file, its comments included.
    pub text: String,
    /// The constants and the current's errors, in two sentences.
    pub lines: [String; 2],
}

/// Fits a motor of `kind` to the logs of `spec` (`kv` [rpm/V] the maker's, or None: from the
/// ESC command's duty); `name` the motor's (None: the first log's name).
pub fn fitted(
    spec: &propbet_pipeline::spec::MeasuredSpec,
    kv: Option<f64>,
    kind: FitKind,
    name: Option<String>,
) -> Result<Fitted> {
    if let Some(kv) = kv {
        if !(kv > 0.0 && kv.is_finite()) {
            anyhow::bail!("--kv {kv}: Kv is a positive number of rpm per volt");
        }
    }
    let f = propbet_pipeline::stages::fit_motor(spec, kv, kind)?;
    let m = &f.fit;
    let name = name.unwrap_or_else(|| {
        let first = spec
            .files
            .first()
            .and_then(|p| p.file_stem())
            .map(|s| s.to_string_lossy().into_owned());
        format!("{} (fitted)", first.unwrap_or_else(|| "motor".into()))
    });
    let kv_words = match m.kv_source {
        propbet_api::motor::KvSource::Given => "given".to_string(),
        propbet_api::motor::KvSource::EscDuty(n) => format!("from the ESC duty at {n} steps"),
    };
    let held = f
        .held_out_median
        .map_or("n/a".to_string(), |h| format!("{:.1} %", 100.0 * h));
    let lines = [
        format!(
            "R  = {:.4} ± {:.4} ohm, Io = {:.3} ± {:.3} A, Kv = {:.0} ± {:.0} rpm/V ({kv_words}){}; 95 % intervals",
            m.r.value,
            m.r.plus_minus,
            m.io.value,
            m.io.plus_minus,
            m.kv_rpm.value,
            m.kv_rpm.plus_minus,
            m.kq_rpm
                .map_or(String::new(), |k| format!(", Kq = {:.0} ± {:.0} rpm/V", k.value, k.plus_minus))
        ),
        format!(
            "supply current over {} steps: RMS error {:.1} %; each step left out of the fit and predicted: median {held}",
            m.points,
            100.0 * m.rms_current
        ),
    ];
    let mut comments = vec![format!(
        "fitted by propbet {} (propbet motor fit) from {}",
        env!("CARGO_PKG_VERSION"),
        spec.files
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    )];
    comments.extend(lines.iter().cloned());
    comments.extend(f.notes.iter().cloned());
    comments.extend(f.misses.iter().map(|m| format!("where it misses: {m}")));
    let file = MotorFile {
        name,
        motor: m.motor,
        params: match kind {
            FitKind::Type1 => vec![m.motor.r0, m.motor.io0, m.motor.kv_rpm],
            FitKind::Type2 => vec![
                m.motor.r0,
                m.motor.io0,
                m.motor.kv_rpm,
                m.motor.kq_rpm,
                0.0,
                0.0,
                0.0,
                0.0,
            ],
        },
        labels: Vec::new(),
    };
    // Comment lines a person reads in an editor or a terminal: at most 100 characters.
    let comments: Vec<String> = comments
        .iter()
        .flat_map(|c| {
            textwrap::wrap(c, 98)
                .into_iter()
                .map(|l| l.into_owned())
                .collect::<Vec<_>>()
        })
        .collect();
    let text = write_motor(&file, &comments);
    Ok(Fitted {
        fit: f,
        file,
        text,
        lines,
    })
}

fn fit(args: &FitArgs) -> Result<bool> {
    let spec = args.measured.spec()?;
    let Fitted {
        fit: f, text, lines, ..
    } = fitted(
        &spec,
        args.kv,
        if args.kq { FitKind::Type2 } else { FitKind::Type1 },
        args.name.clone(),
    )?;
    let inputs: Vec<&std::path::Path> = spec.files.iter().map(PathBuf::as_path).collect();
    emit(args.out.as_deref(), &[text.as_bytes()], &inputs)?;
    for l in &lines {
        eprintln!("propbet motor fit: {l}");
    }
    for n in &f.notes {
        eprintln!("{}", crate::output::wrapped(&format!("propbet: note: {n}"), "", "  "));
    }
    if let Some(w) = &f.misses {
        eprintln!(
            "{}",
            crate::output::wrapped(&format!("propbet: where the motor model misses: {w}"), "", "  ")
        );
    }
    if let Some(out) = &args.out {
        eprintln!("propbet motor fit: -> {}", out.display());
    }
    Ok(true)
}

/// A fitted step as a row.
#[derive(serde::Serialize)]
struct StepRow<'a> {
    step: &'a str,
    rpm: propbet_report::table::Num,
    torque_nm: propbet_report::table::Num,
    volts: propbet_report::table::Num,
    amps: propbet_report::table::Num,
    esc_us: propbet_report::table::Num,
    amps_held_out: propbet_report::table::Num,
}

/// The fitted steps: speed, torque, voltage, current, ESC command and the current predicted
/// with the step left out.
pub fn steps(f: &propbet_pipeline::stages::FittedMotor) -> Result<propbet_report::table::columns::Table> {
    let rows = f.points.iter().map(|(step, p, held)| StepRow {
        step,
        rpm: propbet_api::units::omega_to_rpm(p.omega).into(),
        torque_nm: p.torque.into(),
        volts: p.volts.into(),
        amps: p.amps.into(),
        esc_us: p.esc.into(),
        amps_held_out: (*held).into(),
    });
    Ok(propbet_report::table::columns::table(rows)?)
}
