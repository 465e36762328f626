//! The commands' results in memory, for a program that runs propbet in its own process (the
//! Python package): the same command lines, the same tables as the files the commands write,
//! returned instead of written.

use std::path::Path;

use anyhow::{bail, Result};
use clap::Parser;
use propbet_pipeline::measure::{DropReason, Format, Loads, MeasuredSet, Refused, Speed};
use propbet_pipeline::spec::StageSpec;

use crate::compare::MeasuredArgs;
use crate::output::{csv_rows, Num};
use crate::Command;

/// The command line `argv` (without the program's name) parsed as `propbet`'s.
fn parse(argv: &[String]) -> Result<Command> {
    let cli = crate::parse_args(std::iter::once("propbet".to_string()).chain(argv.iter().cloned()))
        .map_err(crate::clap_error)?;
    Ok(cli.command)
}

/// `propbet predict` with these flags (after `predict`), its tables as columns
/// ([`crate::predict::columns`]): the sweep's, the per-station table's when `stations`, and
/// the count of station solutions that did not converge and of the points they are at.
pub fn predict(
    argv: &[String],
    stations: bool,
) -> Result<(crate::columns::Table, Option<crate::columns::Table>, (usize, usize))> {
    let Command::Predict(a) = parse(argv)? else {
        bail!("not a predict command: {}", argv.join(" "))
    };
    crate::predict::columns(&a.spec()?, stations)
}

/// A number as propbet's tables write it (7 significant digits; empty when it is not finite).
pub fn format_number(v: f64) -> String {
    let mut b = Vec::new();
    crate::output::push_num(&mut b, Some(v));
    String::from_utf8(b).unwrap_or_default()
}

/// The stages `propbet run` would run for a case directory, writing under `out`: each as its
/// command line (without the program's name), in order.
pub fn case_stages(dir: &Path, out: &Path) -> Result<Vec<Vec<String>>> {
    let argv = [
        "run".to_string(),
        dir.display().to_string(),
        "-o".into(),
        out.display().to_string(),
    ];
    let Command::Run(a) = parse(&argv)? else {
        bail!("not a run command")
    };
    let plan = crate::run::plan(dir, out, &a.xfoil)?;
    Ok(plan.stages().iter().map(StageSpec::argv).collect())
}

/// Measured files read with the measurement flags of `compare` (`--measured FILE...`,
/// `--poles`, `--rpm-source`, `--atmosphere`, `--rho`, `--columns`): a table of the points
/// (CSV, one row per point, every file's in order) and one of the rows dropped (CSV).
pub fn measurements(argv: &[String]) -> Result<(Vec<u8>, Vec<u8>)> {
    #[derive(Parser)]
    #[command(name = "read_measurements")]
    struct Flags {
        #[command(flatten)]
        data: MeasuredArgs,
    }
    let flags = Flags::try_parse_from(std::iter::once("read_measurements".to_string()).chain(argv.iter().cloned()))
        .map_err(crate::clap_error)?;
    let spec = flags.data.spec()?;
    // As `compare` reads them: each file on its own, a refused one in the dropped table.
    let batch = propbet_pipeline::stages::load_batch(&spec)?;
    Ok((
        points_csv(&batch.names, &batch.sets)?,
        dropped_csv(&batch.names, &batch.sets, &batch.refused)?,
    ))
}

/// A measured point as a row.
#[derive(serde::Serialize)]
struct PointRow<'a> {
    file: &'a str,
    format: Format,
    label: &'a str,
    line_first: usize,
    line_last: usize,
    rpm: Num,
    rpm_sd: Num,
    samples: usize,
    thrust_samples: Option<usize>,
    torque_samples: Option<usize>,
    v_m_s: Num,
    v_sd: Num,
    j: Num,
    thrust_n: Num,
    thrust_sd: Num,
    torque_nm: Num,
    torque_sd: Num,
    ct: Num,
    cp: Num,
    temperature_k: Num,
    pressure_pa: Num,
    humidity: Num,
    transient: usize,
    flags: String,
}

fn points_csv(names: &[String], sets: &[MeasuredSet]) -> Result<Vec<u8>> {
    let rpm = propbet_pipeline::units::omega_to_rpm;
    let rows = names.iter().zip(sets).flat_map(|(file, s)| {
        s.points.iter().map(move |p| {
            let (v, v_sd, j) = match p.speed {
                Speed::Airspeed(v) => (Some(v.mean), v.sd, None),
                Speed::AdvanceRatio(j) => (None, None, Some(j)),
            };
            let (thrust, torque, ct, cp) = match p.loads {
                Loads::Forces { thrust, torque } => (Some(thrust), torque, None, None),
                Loads::Coefficients { ct, cp } => (None, None, Some(ct), Some(cp)),
            };
            PointRow {
                file,
                format: s.format,
                label: &p.label,
                line_first: p.lines.0,
                line_last: p.lines.1,
                rpm: rpm(p.omega.mean).into(),
                rpm_sd: p.omega.sd.map(rpm).into(),
                samples: p.omega.n,
                thrust_samples: thrust.map(|t| t.n),
                torque_samples: torque.map(|t| t.n),
                v_m_s: v.into(),
                v_sd: v_sd.into(),
                j: j.into(),
                thrust_n: thrust.map(|t| t.mean).into(),
                thrust_sd: thrust.and_then(|t| t.sd).into(),
                torque_nm: torque.map(|t| t.mean).into(),
                torque_sd: torque.and_then(|t| t.sd).into(),
                ct: ct.into(),
                cp: cp.into(),
                temperature_k: p.air.temperature.into(),
                pressure_pa: p.air.pressure.into(),
                humidity: p.air.humidity.into(),
                transient: p.transient,
                flags: p.flags.join("; "),
            }
        })
    });
    csv_rows(rows, true)
}

/// A dropped row.
#[derive(serde::Serialize)]
struct DroppedRow<'a> {
    file: &'a str,
    /// Empty for a file refused whole.
    line: Option<usize>,
    /// A [`DropReason`] in snake case, or `file_refused`.
    reason: String,
    detail: &'a str,
}

fn dropped_csv(names: &[String], sets: &[MeasuredSet], refused: &[Refused]) -> Result<Vec<u8>> {
    let reason = |r: DropReason| {
        serde_json::to_value(r)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default()
    };
    let rows = names.iter().zip(sets).flat_map(|(file, s)| {
        s.dropped.iter().map(move |d| DroppedRow {
            file,
            line: Some(d.line),
            reason: reason(d.reason),
            detail: &d.detail,
        })
    });
    let refused = refused.iter().map(|r| DroppedRow {
        file: &r.file,
        line: None,
        reason: "file_refused".into(),
        detail: &r.reason,
    });
    csv_rows(rows.chain(refused), true)
}

/// A prop file's rows as `propbet prop FILE [--units U] [--qprop-compat]` reads them (flags
/// after `prop`), in SI: radius, chord, blade angle and the ten QPROP section coefficients of
/// each row (a row's own, or the file's global ones), as a table (CSV).
pub fn stations(argv: &[String]) -> Result<Vec<u8>> {
    let Command::Prop(a) = parse(argv)? else {
        bail!("not a prop command: {}", argv.join(" "))
    };
    let model = crate::prop::load(&a)?;
    let file = &model.loaded.file;
    let blade = file.to_blade(propbet_pipeline::qprop::RadiusReading::Documented);
    let rows = (0..blade.r.len()).map(|i| {
        let c = &blade.coeffs[i];
        StationRow {
            r_m: blade.r[i].into(),
            r_over_tip: (blade.r[i] / blade.tip_radius).into(),
            chord_m: blade.chord[i].into(),
            beta_deg: blade.beta[i].to_degrees().into(),
            cl0: c.cl0.into(),
            cl_a_per_rad: c.cl_a.into(),
            cl_min: c.cl_min.into(),
            cl_max: c.cl_max.into(),
            cd0: c.cd0.into(),
            cd2u: c.cd2u.into(),
            cd2l: c.cd2l.into(),
            cl_cd0: c.clcd0.into(),
            re_ref: c.re_ref.into(),
            re_exp: c.re_exp.into(),
        }
    });
    csv_rows(rows, true)
}

/// A prop file's row in SI.
#[derive(serde::Serialize)]
struct StationRow {
    r_m: Num,
    r_over_tip: Num,
    chord_m: Num,
    beta_deg: Num,
    cl0: Num,
    cl_a_per_rad: Num,
    cl_min: Num,
    cl_max: Num,
    cd0: Num,
    cd2u: Num,
    cd2l: Num,
    cl_cd0: Num,
    re_ref: Num,
    re_exp: Num,
}

/// The flags a command takes, each as (name as a keyword: `drag_factor`, kind): `switch` (a
/// flag alone), `number` (one number), `numbers` (one or more, repeated or listed), `text` (one
/// value of any kind). What the Python package checks keyword arguments against at the call.
pub fn flags_of(command: &str) -> Result<Vec<(String, &'static str)>> {
    let cli = crate::command();
    let Some(sub) = cli.get_subcommands().find(|c| c.get_name() == command) else {
        bail!("no command '{command}'");
    };
    Ok(sub
        .get_arguments()
        .filter_map(|a| {
            let long = a.get_long()?;
            let parsed = a.get_value_parser().type_id();
            let number = [
                std::any::TypeId::of::<f64>(),
                std::any::TypeId::of::<u32>(),
                std::any::TypeId::of::<usize>(),
            ]
            .into_iter()
            .any(|t| parsed == t);
            let kind = match a.get_action() {
                clap::ArgAction::SetTrue | clap::ArgAction::SetFalse => "switch",
                clap::ArgAction::Append => "many",
                _ if a.get_num_args().is_some_and(|n| n.max_values() > 1) => "many",
                _ if number => "number",
                _ => "text",
            };
            Some((long.replace('-', "_"), kind))
        })
        .collect())
}
