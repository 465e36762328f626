//! `propbet motor fit`'s motor, in memory: the fit, the QPROP motor file with the fit's
//! numbers in its comments, and the two sentences that say it.

use crate::CommandResult as Result;

use crate::motor::{write_motor, FitKind, MotorFile};

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
    spec: &propbet_settings::spec::MeasuredSpec,
    kv: Option<f64>,
    kind: FitKind,
    name: Option<String>,
) -> Result<Fitted> {
    if let Some(kv) = kv {
        if !(kv > 0.0 && kv.is_finite()) {
            crate::command_error::refuse!("--kv {kv}: Kv is a positive number of rpm per volt");
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
        crate::motor::KvSource::Given => "given".to_string(),
        crate::motor::KvSource::EscDuty(n) => format!("from the ESC duty at {n} steps"),
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

/// `propbet motor fit` in memory (`kq`: a type 2 motor, its Kq fitted on its own): the fit,
/// the motor file's text, and the fitted steps as a table.
pub fn fit(
    spec: &propbet_settings::spec::MeasuredSpec,
    kv: Option<f64>,
    kq: bool,
    name: Option<String>,
) -> Result<(Fitted, propbet_report::table::columns::Table)> {
    let kind = if kq { FitKind::Type2 } else { FitKind::Type1 };
    let f = fitted(spec, kv, kind, name)?;
    let steps = propbet_report::table::motor::steps(&f.fit)?;
    Ok((f, steps))
}
