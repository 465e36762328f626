//! The blade validate predicts: UIUC's measured stations or APC's design at them, and each
//! station's section from the PE0 file (blended across APC's transition, scaled to its
//! thickness ratio) or the one assumed for another maker's prop.

use std::path::Path;

use propbet_polar::{naca4_from_name, Airfoil};
use propbet_qprop::apc::{read_pe0, uiuc_diameter, Pe0};
use propbet_qprop::PropRow;

use super::files::first_file;
use super::{GeometrySource, Sections, ValidateSpec};
use crate::stages;
use crate::{read_text, Error, Result};

/// UIUC's stations (r/R 0.15 to 1 in steps of 0.05, as its geometry files give them), in
/// hundredths (k / 100 is the double a file's "0.35" reads as): where a prop has no UIUC
/// geometry file, the blade validate predicts is APC's design chord and twist there.
pub(super) const UIUC_STATIONS: (u32, u32, u32) = (15, 5, 18);

/// APC's design blade (PE0 chord and twist) at UIUC's stations, as a UIUC geometry table: the
/// stations from one step inboard of APC's first (whose chord and twist are held there, as
/// `--geometry pe0` holds them) to the tip.
pub fn pe0_table(pe0: &propbet_qprop::apc::Pe0, big_r: f64) -> Vec<propbet_measure::uiuc::GeometryRow> {
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

/// APC's airfoil name → a section: `APC12` is NACA 4412 (APC's note), a NACA 4-digit name is
/// generated, and any other name is looked for in the directory as coordinates whose file
/// stem is the name without case, spaces, hyphens or underscores (`CLARK-Y` → `clarky.dat`,
/// `E63` → `e63.dat`, `SD7037` → `sd7037.dat`).
pub(super) fn apc_airfoil(name: &str, dir: &Path) -> Result<Airfoil> {
    let key = |s: &str| -> String {
        s.chars()
            .filter(|c| c.is_ascii_alphanumeric())
            .map(|c| c.to_ascii_lowercase())
            .collect()
    };
    let k = key(name);
    let naca = if k == "apc12" {
        "naca4412".to_string()
    } else {
        k.clone()
    };
    if let Some(foil) = naca4_from_name(&naca) {
        return Ok(foil?);
    }
    let coordinates = first_file(dir, |n| {
        let p = Path::new(n);
        p.extension().is_some_and(|x| x.eq_ignore_ascii_case("dat"))
            && p.file_stem().and_then(|s| s.to_str()).is_some_and(|s| key(s) == k)
    })?;
    match coordinates {
        Some(file) => Ok(stages::read_airfoil(&file)?.0),
        None => Err(Error::Nothing(format!(
            "APC airfoil {name:?}: no coordinates for it in {} (a file {k}.dat; APC12 and NACA 4-digit names are generated)",
            dir.display()
        ))),
    }
}

/// A PE0 file in memory for a prop whose sections are assumed: UIUC's chord and twist, one
/// airfoil from root to tip at one thickness ratio.
pub(super) fn assumed_pe0(table: &[propbet_measure::uiuc::GeometryRow], big_r: f64, airfoil: &str, tc: f64) -> Pe0 {
    let at = |f: &dyn Fn(&propbet_measure::uiuc::GeometryRow) -> f64| -> Vec<(f64, f64)> {
        table.iter().map(|row| (row.r_r * big_r, f(row))).collect()
    };
    let r0 = table.first().map_or(0.0, |row| row.r_r * big_r);
    Pe0 {
        thickness: at(&|_| tc),
        chord: at(&|row| row.c_r * big_r),
        twist: at(&|row| row.beta.to_degrees()),
        airfoils: [(r0, airfoil.to_string()), (r0, airfoil.to_string())],
    }
}

/// A prop's blade as validate predicts it: the table of stations, the PE0 file its sections
/// come from, and each station's row and section (Selig text).
pub(super) struct Blade {
    pub(super) big_r: f64,
    pub(super) table: Vec<propbet_measure::uiuc::GeometryRow>,
    pub(super) pe0: Pe0,
    /// The section assumed (with why), None for APC's own.
    pub(super) assumed: Option<String>,
    pub(super) uiuc_geometry: bool,
    pub(super) geometry_used: GeometrySource,
    pub(super) rows: Vec<PropRow>,
    pub(super) airfoils: Vec<(usize, String)>,
}

/// The blade (metres) and each station's section scaled to the PE0 thickness there.
pub(super) fn blade(spec: &ValidateSpec, prop: &str, sections: &Sections) -> Result<Blade> {
    let d = uiuc_diameter(prop).ok_or_else(|| Error::Nothing(format!("{prop}: no diameter in the name")))?;
    let big_r = 0.5 * d;
    let geom_path = spec.uiuc.join(format!("{prop}_geom.txt"));
    let uiuc_geometry = geom_path.exists();
    let uiuc_table = if uiuc_geometry {
        Some(stages::read_geometry_table(&geom_path)?)
    } else {
        None
    };
    let (pe0, assumed) = match sections {
        Sections::Apc(path) => (read_pe0(&read_text(path)?, &path.display().to_string())?, None),
        Sections::Assumed {
            airfoil,
            thickness,
            why,
        } => {
            let Some(table) = &uiuc_table else {
                return Err(Error::Nothing(format!(
                    "{why}, and no UIUC geometry file: no blade to predict"
                )));
            };
            let tc = match thickness {
                Some(t) => *t,
                None => apc_airfoil(airfoil, &spec.airfoils)?.max_thickness().0,
            };
            let text = format!("{airfoil} t/c {tc:.3} ({why})");
            (assumed_pe0(table, big_r, airfoil, tc), Some(text))
        }
    };
    // UIUC's measured blade, or APC's design where UIUC has no geometry file of the prop.
    let (table, geometry_used) = match uiuc_table {
        Some(table) => (table, spec.geometry),
        None => (pe0_table(&pe0, big_r), GeometrySource::Pe0),
    };
    if table.len() < 2 {
        return Err(Error::Nothing(format!(
            "{prop}: no UIUC geometry file, and APC's PE0 blade covers fewer than two of UIUC's stations (r/R 0.15 to 1)"
        )));
    }
    let (f1, f2) = (
        apc_airfoil(&pe0.airfoils[0].1, &spec.airfoils)?,
        apc_airfoil(&pe0.airfoils[1].1, &spec.airfoils)?,
    );
    let mut rows = Vec::new();
    let mut airfoils = Vec::new();
    for (i, row) in table.iter().enumerate() {
        let r = row.r_r * big_r;
        let (chord, beta) = match geometry_used {
            GeometrySource::Uiuc => (row.c_r * big_r, row.beta.to_degrees()),
            GeometrySource::Pe0 => (pe0.chord_at(r), pe0.twist_at(r)),
        };
        rows.push(PropRow {
            r,
            chord,
            beta,
            coeffs: Vec::new(),
        });
        let frac = pe0.blend_at(r);
        let base = if frac <= 0.0 {
            f1.clone()
        } else if frac >= 1.0 {
            f2.clone()
        } else {
            f1.blend(&f2, frac, 80)?
        };
        let tc = pe0.thickness_at(r);
        // APC scales its sections "based on thickness ratio" and defines pitch on a flat bottom
        // (`Airfoil::scale_as_apc`: thinned or flat-bottomed sections as a whole, thickened
        // cambered ones about their camber line; docs/studies/section-scaling.md).
        let scaled = base.scale_as_apc(tc);
        let mut foil = scaled?;
        foil.name = format!("{} t/c {:.3}", base.name, tc);
        airfoils.push((i, foil.to_selig()));
    }
    Ok(Blade {
        big_r,
        table,
        pe0,
        assumed,
        uiuc_geometry,
        geometry_used,
        rows,
        airfoils,
    })
}
