//! Blade files other than QPROP's, read as they are: APC's design file (PE0), UIUC's geometry
//! table (`r/R c/R beta`), and a plain table (CSV of radius, chord and blade angle, optionally
//! thickness and airfoil per station). Each becomes the stations of a prop file (QPROP's generic
//! coefficients, which the polars replace) and, where the file or the user says them, the
//! section at each station, as `propbet validate` models APC's propellers: APC's two airfoils
//! blended across its transition and scaled to the PE0 thickness ratio at each station.

use std::path::{Path, PathBuf};

use propbet_polar::{naca4_from_name, Airfoil};
use propbet_qprop::apc::{read_pe0, Pe0};
use propbet_qprop::{PropFile, PropRow};

use crate::{as_written, LoadedProp};
use crate::{Error, Result};
use table::{read_table, table_columns};

/// What a blade file is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BladeFormat {
    /// A QPROP prop file (read by [`crate::load_prop`]).
    Qprop,
    /// APC's design file (`*-PERF.PE0`).
    Pe0,
    /// UIUC's geometry table (`*_geom.txt`: r/R, c/R, beta in degrees).
    UiucTable,
    /// A plain table: CSV with a header naming radius, chord and blade angle.
    Table,
}

impl BladeFormat {
    /// The format of a blade file's text: PE0 by its airfoil lines, UIUC's table by its
    /// `r/R` header, a table by a comma-separated header naming a radius; QPROP otherwise.
    pub(crate) fn of(text: &str) -> BladeFormat {
        if text.lines().any(|l| l.trim_start().starts_with("AIRFOIL1:")) && text.contains("AIRFOIL SUMMARY DATA") {
            return BladeFormat::Pe0;
        }
        let first = text
            .lines()
            .map(str::trim)
            .find(|l| !l.is_empty() && !l.starts_with('#'));
        let Some(first) = first else { return BladeFormat::Qprop };
        let lower = first.to_ascii_lowercase();
        if lower.split_whitespace().next() == Some("r/r") {
            return BladeFormat::UiucTable;
        }
        if first.contains(',') && table_columns(first).is_ok() {
            return BladeFormat::Table;
        }
        BladeFormat::Qprop
    }

    /// How the format is named to the user.
    pub fn name(self) -> &'static str {
        match self {
            BladeFormat::Qprop => "QPROP prop file",
            BladeFormat::Pe0 => "APC design file (PE0)",
            BladeFormat::UiucTable => "UIUC geometry table",
            BladeFormat::Table => "blade table (CSV)",
        }
    }
}

/// The format of the blade file at `path` (QPROP's when it cannot be read: its reader then
/// says why).
pub fn format_of_file(path: &Path) -> BladeFormat {
    match crate::read_text(path) {
        Ok(t) => BladeFormat::of(&t),
        Err(_) => BladeFormat::Qprop,
    }
}

/// Sections named by the user: one airfoil everywhere (`e63`), or airfoils at radii with a
/// linear blend between them (`E63@0.25,APC12@0.45`: E63 to r/R 0.25, blended into APC12 by
/// r/R 0.45, APC12 beyond), each a coordinate file, a NACA 4-digit name, `APC12` or a
/// name of propbet's airfoil library ([`LIBRARY`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SectionPlan {
    /// (r/R, airfoil) ascending in r/R; one entry: that airfoil everywhere.
    pub anchors: Vec<(f64, String)>,
}

impl SectionPlan {
    /// Reads `e63` or `E63@0.25,APC12@0.45`; `what` names the flag or key in errors.
    pub fn parse(text: &str, what: &str) -> Result<SectionPlan> {
        let parts: Vec<&str> = text.split(',').map(str::trim).collect();
        if parts.len() == 1 && !parts[0].contains('@') {
            if parts[0].is_empty() {
                return Err(Error::value(what, text, "no airfoil named"));
            }
            return Ok(SectionPlan {
                anchors: vec![(0.0, parts[0].to_string())],
            });
        }
        let mut anchors = Vec::new();
        for p in parts {
            let Some((name, at)) = p.rsplit_once('@') else {
                return Err(Error::value(
                    what,
                    text,
                    format!(
                        "'{p}' has no '@r/R': write each airfoil with the r/R it starts at, as E63@0.25,APC12@0.45"
                    ),
                ));
            };
            let x: f64 = at
                .trim()
                .parse()
                .ok()
                .filter(|x: &f64| (0.0..=1.0).contains(x))
                .ok_or_else(|| Error::value(what, text, format!("'{at}' is not an r/R between 0 and 1")))?;
            if let Some((last, _)) = anchors.last() {
                if x <= *last {
                    return Err(Error::value(what, text, "the r/R of the airfoils must increase"));
                }
            }
            if name.trim().is_empty() {
                return Err(Error::value(what, text, format!("'{p}' names no airfoil")));
            }
            anchors.push((x, name.trim().to_string()));
        }
        Ok(SectionPlan { anchors })
    }
}

/// propbet's airfoil library: the coordinates of `props/airfoils` (UIUC's coordinate database;
/// provenance in its PROVENANCE.md), built in so that APC's sections need no file.
pub(crate) const LIBRARY: [(&str, &str); 6] = [
    ("e63", include_str!("../../../props/airfoils/e63.dat")),
    ("clarky", include_str!("../../../props/airfoils/clarky.dat")),
    ("sd7037", include_str!("../../../props/airfoils/sd7037.dat")),
    ("e387", include_str!("../../../props/airfoils/e387.dat")),
    ("s1223", include_str!("../../../props/airfoils/s1223.dat")),
    ("naca4412", include_str!("../../../props/airfoils/naca4412.dat")),
];

/// An airfoil name as the library and a directory's files are keyed: letters and digits,
/// lower case (`CLARK-Y` → `clarky`).
fn key(s: &str) -> String {
    s.chars()
        .filter(|c| c.is_ascii_alphanumeric())
        .map(|c| c.to_ascii_lowercase())
        .collect()
}

/// A section by name: `APC12` is NACA 4412 (APC's note), a NACA 4-digit name is generated, a
/// name is looked for in `dir` (a `.dat` file whose stem is the name without case, spaces,
/// hyphens or underscores: `CLARK-Y` → `clarky.dat`), then in the [`LIBRARY`]; any other text is
/// a coordinate file's path.
pub fn airfoil_by_name(name: &str, dir: Option<&Path>) -> Result<Airfoil> {
    let k = key(name);
    let naca = if k == "apc12" {
        "naca4412".to_string()
    } else {
        k.clone()
    };
    if let Some(foil) = naca4_from_name(&naca) {
        return Ok(foil?);
    }
    if let Some(dir) = dir {
        if let Some(file) = first_dat(dir, &k)? {
            return Ok(read_airfoil(&file)?.0);
        }
    }
    if let Some((n, text)) = LIBRARY.iter().find(|(n, _)| *n == k) {
        return Ok(parse_airfoil(text, Path::new(&format!("{n}.dat")))?.0);
    }
    let path = Path::new(name);
    if path.is_file() {
        return Ok(read_airfoil(path)?.0);
    }
    let names: Vec<&str> = LIBRARY.iter().map(|(n, _)| *n).collect();
    Err(Error::Nothing(format!(
        "airfoil {name:?}: not a coordinate file, a NACA 4-digit name, APC12, or one of propbet's ({}){}",
        names.join(", "),
        dir.map_or_else(String::new, |d| format!(", and no {k}.dat in {}", d.display()))
    )))
}

/// A section of the [`LIBRARY`] by name (`e63`, `Clark-Y`), with what reading its coordinates
/// notes, as the file's own would be read; None for a name it does not hold.
pub fn library_airfoil(name: &str) -> Option<Result<(Airfoil, Vec<String>)>> {
    let k = key(name);
    LIBRARY
        .iter()
        .find(|(n, _)| *n == k)
        .map(|(n, text)| parse_airfoil(text, Path::new(&format!("{n}.dat"))))
}

/// Whether `name` is an airfoil propbet knows without a file: APC12, a NACA 4-digit name or a
/// name of the [`LIBRARY`].
pub(crate) fn is_known_name(name: &str) -> bool {
    let k = key(name);
    k == "apc12" || naca4_from_name(&k).is_some() || LIBRARY.iter().any(|(n, _)| *n == k)
}

/// A section text (`--airfoil`, a case's `airfoil`) with each name that is a file of `dir`
/// written as that file's path (a case's files are relative to it), the others as they are;
/// and the files it names (each a file of `dir`, or neither a known name nor found there).
pub fn resolve_in(text: &str, dir: &Path) -> (String, Vec<PathBuf>) {
    let mut files = Vec::new();
    let mut resolve = |name: &str| -> String {
        let n = name.trim();
        if is_known_name(n) && !dir.join(n).is_file() {
            return n.to_string();
        }
        let p = dir.join(n);
        files.push(p.clone());
        p.display().to_string()
    };
    let out = if text.contains('@') {
        text.split(',')
            .map(|part| match part.rsplit_once('@') {
                Some((n, at)) => format!("{}@{}", resolve(n), at.trim()),
                None => resolve(part),
            })
            .collect::<Vec<_>>()
            .join(",")
    } else {
        resolve(text)
    };
    (out, files)
}

/// The first `.dat` file of `dir` (by name) whose stem keys as `k`.
fn first_dat(dir: &Path, k: &str) -> Result<Option<PathBuf>> {
    first_file(dir, |n| {
        let p = Path::new(n);
        p.extension().is_some_and(|x| x.eq_ignore_ascii_case("dat"))
            && p.file_stem().and_then(|s| s.to_str()).is_some_and(|s| key(s) == k)
    })
}

/// The first (by name) file of `dir` whose name passes `wanted`.
pub fn first_file(dir: &Path, wanted: impl Fn(&str) -> bool) -> Result<Option<PathBuf>> {
    let mut found: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|reason| Error::Read {
            path: dir.to_path_buf(),
            reason,
        })?
        .filter_map(|e| {
            let e = e.ok()?;
            (wanted(e.file_name().to_str()?) && e.path().is_file()).then(|| e.path())
        })
        .collect();
    found.sort();
    Ok(found.into_iter().next())
}

/// UIUC's stations (r/R 0.15 to 1 in steps of 0.05, as its geometry files give them), in
/// hundredths: the stations at which a PE0 blade is predicted.
pub(crate) const UIUC_STATIONS: (u32, u32, u32) = (15, 5, 18);

/// APC's design blade (PE0 chord and twist) at UIUC's stations, as a UIUC geometry table: the
/// stations from one step inboard of APC's first (whose chord and twist are held there) to
/// the tip.
pub fn pe0_table(pe0: &Pe0, big_r: f64) -> Vec<propbet_measure::uiuc::GeometryRow> {
    let (start, step, n) = UIUC_STATIONS;
    let first = pe0.chord.first().map_or(0.0, |c| c.0 / big_r);
    (0..n)
        .map(|k| f64::from(start + step * k) / 100.0)
        .filter(|&x| x > first - f64::from(step) / 100.0 - 1e-9)
        .map(|x| propbet_measure::uiuc::GeometryRow {
            r_r: x,
            c_r: pe0.chord_at(x * big_r) / big_r,
            beta: pe0.twist_at(x * big_r).to_radians(),
        })
        .collect()
}

/// The diameter a PE0 file's first line names (`10x4.7SF`, `4.2x4`: inches before the `x`)
/// [m].
pub(crate) fn pe0_diameter(text: &str) -> Option<f64> {
    propbet_qprop::apc::diameter_before_x(text.lines().next()?.split_whitespace().next()?)
}

/// APC's section at radius `r` [m] of a PE0 blade: its two airfoils (`f1`, `f2`) blended across
/// the transition, scaled to the thickness ratio there as APC scales them
/// ([`Airfoil::scale_as_apc`]; docs/studies/section-scaling.md), named with its t/c.
pub fn pe0_section(pe0: &Pe0, f1: &Airfoil, f2: &Airfoil, r: f64) -> Result<Airfoil> {
    let frac = pe0.blend_at(r);
    let base = if frac <= 0.0 {
        f1.clone()
    } else if frac >= 1.0 {
        f2.clone()
    } else {
        f1.blend(f2, frac, 80)?
    };
    let tc = pe0.thickness_at(r);
    let mut foil = base.scale_as_apc(tc)?;
    foil.name = format!("{} t/c {:.3}", base.name, tc);
    Ok(foil)
}

/// A blade read from a design file: its stations as a prop file (as written and read back) and
/// the section of each station, where known.
#[derive(Debug, Clone)]
pub struct DesignBlade {
    /// The stations (QPROP's generic coefficients until the polars replace them).
    pub geometry: LoadedProp,
    /// Each station's section (Selig text, as a file written and read back would give it);
    /// None where the file names none (the user's airfoil is then needed).
    pub sections: Option<Vec<String>>,
    /// What the blade is, for the prop file's name and the report.
    pub description: String,
    /// The file's format.
    pub format: BladeFormat,
}

/// What a design file needs beside itself.
#[derive(Debug, Clone, Default)]
pub struct DesignOptions {
    /// Length unit of a table's radius and chord columns without a unit [m per unit].
    pub units: Option<f64>,
    /// Blade count (default 2).
    pub blades: Option<f64>,
    /// The sections the user names (`--airfoil`), replacing the file's.
    pub sections: Option<SectionPlan>,
    /// Thickness ratio the user's sections are scaled to at every station (`--thickness`).
    pub thickness: Option<f64>,
    /// APC's design file whose sections (airfoils, blend, thickness) a measured blade takes
    /// (`--sections-from`; UIUC's table of an APC prop, as `validate` models it).
    pub sections_from: Option<PathBuf>,
    /// A directory of airfoil coordinates looked in before the library (`--airfoils`).
    pub airfoils: Option<PathBuf>,
}

/// Reads a blade file other than QPROP's; None for a QPROP prop file.
pub fn read_design(path: &Path, opts: &DesignOptions) -> Result<Option<DesignBlade>> {
    let text = crate::read_text(path)?;
    let format = BladeFormat::of(&text);
    let at = |e: String| Error::input(path, e);
    let Some((big_r, stations, own)) = stations_of(format, &text, path, opts)? else {
        return Ok(None);
    };
    let dir = opts.airfoils.as_deref();
    let rows: Vec<PropRow> = stations
        .iter()
        .map(|&(r, chord, beta)| PropRow {
            r,
            chord,
            beta,
            coeffs: Vec::new(),
        })
        .collect();
    // The sections: the user's plan, else a PE0 named for them, else the file's own.
    let from = match &opts.sections_from {
        Some(p) => {
            let t = crate::read_text(p)?;
            if BladeFormat::of(&t) != BladeFormat::Pe0 {
                return Err(Error::input(
                    p,
                    "not an APC design file (PE0): no AIRFOIL1 / AIRFOIL2 lines",
                ));
            }
            Some(read_pe0(&t, &p.display().to_string()).map_err(|e| Error::input(p, e.to_string()))?)
        }
        None => None,
    };
    let radii: Vec<f64> = rows.iter().map(|r| r.r).collect();
    let (from, own) = match (from, own) {
        (Some(p), own) => (Some(p), own),
        (None, Own::Pe0(p)) => (Some(*p), Own::None),
        (None, own) => (None, own),
    };
    let (sections, said): (Option<Vec<Airfoil>>, String) = match (&opts.sections, from, own) {
        (Some(plan), from, own) => {
            let tcs = match (own, from) {
                _ if opts.thickness.is_some() => vec![opts.thickness; radii.len()],
                (Own::Thickness(t) | Own::PerStation(_, t), _) => t,
                (_, Some(pe0)) => radii.iter().map(|&r| Some(pe0.thickness_at(r))).collect(),
                _ => vec![None; radii.len()],
            };
            let foils = plan_sections(plan, &radii, big_r, &tcs, dir)?;
            (Some(foils), format!("sections {}", plan_text(plan)))
        }
        (None, Some(pe0), _) => {
            let f1 = airfoil_by_name(&pe0.airfoils[0].1, dir)?;
            let f2 = airfoil_by_name(&pe0.airfoils[1].1, dir)?;
            let foils = radii
                .iter()
                .map(|&r| pe0_section(&pe0, &f1, &f2, r))
                .collect::<Result<Vec<_>>>()?;
            let text = format!("APC sections {} to {}", pe0.airfoils[0].1, pe0.airfoils[1].1);
            (Some(foils), text)
        }
        (None, None, Own::PerStation(names, tcs)) => {
            let mut foils = Vec::new();
            for (i, name) in names.iter().enumerate() {
                let Some(name) = name else {
                    return Err(at(format!(
                        "station {} has no airfoil while others do: name one on every row",
                        i + 1
                    )));
                };
                let f = airfoil_by_name(name, dir)?;
                foils.push(match tcs[i] {
                    Some(t) => f.scale_thickness(t)?,
                    None => f,
                });
            }
            (Some(foils), "the table's sections".into())
        }
        (None, None, _) => (None, "no sections named".into()),
    };
    let description = format!("{} ({said})", format.name());
    // The prop's name: APC's for its design file (`APC 10x7`), else the file's stem.
    let label = match format {
        BladeFormat::Pe0 => text
            .split_whitespace()
            .next()
            .map_or_else(String::new, |n| format!("APC {}", propbet_units::printable(n))),
        _ => path
            .file_stem()
            .and_then(|n| n.to_str())
            .map(|s| propbet_units::printable(s.trim_end_matches("_geom")))
            .unwrap_or_default(),
    };
    let file = PropFile::metric(
        format!("{label} ({description})"),
        opts.blades.unwrap_or(2.0),
        big_r,
        rows,
    );
    let geometry = as_written(&file, path)?;
    // Each section as a Selig file written and read back gives it (as validate's files do).
    let sections = sections.map(|foils| foils.iter().map(|f| f.to_selig()).collect::<Vec<String>>());
    Ok(Some(DesignBlade {
        geometry,
        sections,
        description,
        format,
    }))
}

/// A blade file's stations (r [m], chord [m], beta [deg]), its tip radius [m] and the sections
/// it says itself; None for a QPROP prop file.
#[allow(clippy::type_complexity)]
fn stations_of(
    format: BladeFormat,
    text: &str,
    path: &Path,
    opts: &DesignOptions,
) -> Result<Option<(f64, Vec<(f64, f64, f64)>, Own)>> {
    let at = |e: String| Error::input(path, e);
    Ok(Some(match format {
        BladeFormat::Qprop => return Ok(None),
        BladeFormat::Pe0 => {
            let pe0 = read_pe0(text, &path.display().to_string()).map_err(|e| at(e.to_string()))?;
            let d = pe0_diameter(text).ok_or_else(|| {
                at("line 1: no diameter (APC's `10x7`, inches before the x) to place the stations".into())
            })?;
            let big_r = 0.5 * d;
            let rows = pe0_table(&pe0, big_r);
            if rows.len() < 2 {
                return Err(at(
                    "the PE0 blade covers fewer than two stations of r/R 0.15 to 1".into()
                ));
            }
            let st = rows
                .iter()
                .map(|g| (g.r_r * big_r, g.c_r * big_r, g.beta.to_degrees()))
                .collect();
            (big_r, st, Own::Pe0(Box::new(pe0)))
        }
        BladeFormat::UiucTable => {
            let rows = propbet_measure::uiuc::read_geometry(text).map_err(|e| at(e.to_string()))?;
            let name = path.file_name().and_then(|n| n.to_str()).unwrap_or_default();
            let d = propbet_qprop::apc::uiuc_diameter(name).ok_or_else(|| {
                at("no diameter in the file's name: UIUC's tables name it (apce_10x7_geom.txt: 10 inches)".into())
            })?;
            let big_r = 0.5 * d;
            let st = rows
                .iter()
                .map(|g| (g.r_r * big_r, g.c_r * big_r, g.beta.to_degrees()))
                .collect();
            (big_r, st, Own::None)
        }
        BladeFormat::Table => {
            let t = read_table(text, opts.units).map_err(at)?;
            let big_r = t.rows.last().map_or(0.0, |r| r.0);
            let own = if t.airfoils.iter().any(Option::is_some) {
                Own::PerStation(t.airfoils, t.thickness)
            } else if t.thickness.iter().any(Option::is_some) {
                Own::Thickness(t.thickness)
            } else {
                Own::None
            };
            (big_r, t.rows, own)
        }
    }))
}

/// The sections of a plan at each station: an airfoil, or two blended, scaled to the station's
/// thickness ratio where the table gives one.
pub fn plan_sections(
    plan: &SectionPlan,
    radii: &[f64],
    big_r: f64,
    tcs: &[Option<f64>],
    dir: Option<&Path>,
) -> Result<Vec<Airfoil>> {
    let foils = plan
        .anchors
        .iter()
        .map(|(_, n)| airfoil_by_name(n, dir))
        .collect::<Result<Vec<_>>>()?;
    radii
        .iter()
        .zip(tcs)
        .map(|(&r, tc)| {
            let x = r / big_r;
            let a = &plan.anchors;
            let k = a.iter().rposition(|(at, _)| *at <= x);
            let base = match k {
                None => foils[0].clone(),
                Some(k) if k + 1 == a.len() => foils[k].clone(),
                Some(k) => {
                    // Blended from this anchor's airfoil into the next one's.
                    let f = (x - a[k].0) / (a[k + 1].0 - a[k].0);
                    if f <= 0.0 {
                        foils[k].clone()
                    } else {
                        foils[k].blend(&foils[k + 1], f, 80)?
                    }
                }
            };
            Ok(match tc {
                Some(t) => base.scale_thickness(*t)?,
                None => base,
            })
        })
        .collect()
}

/// A plan as the user wrote it.
fn plan_text(plan: &SectionPlan) -> String {
    match plan.anchors.as_slice() {
        [(_, n)] => n.clone(),
        a => a.iter().map(|(x, n)| format!("{n}@{x}")).collect::<Vec<_>>().join(","),
    }
}

/// The sections a blade file says itself.
enum Own {
    None,
    Pe0(Box<Pe0>),
    /// A thickness ratio per station.
    Thickness(Vec<Option<f64>>),
    /// An airfoil (and a thickness ratio) per station.
    PerStation(Vec<Option<String>>, Vec<Option<f64>>),
}

/// An airfoil file, parsed and normalised, with what was repaired in it.
pub fn read_airfoil(path: &Path) -> Result<(Airfoil, Vec<String>)> {
    let text = crate::error::read_titled_text(path)?;
    parse_airfoil(&text, path)
}

/// An airfoil file's text, parsed and normalised, with what was repaired in it.
pub fn parse_airfoil(text: &str, path: &Path) -> Result<(Airfoil, Vec<String>)> {
    let (mut foil, repairs) = Airfoil::parse(text, &path.display().to_string())?;
    foil.normalise();
    Ok((
        foil,
        repairs
            .into_iter()
            .map(|r| format!("{}: {}", path.display(), r.0))
            .collect(),
    ))
}

mod table;

#[cfg(test)]
mod tests;
