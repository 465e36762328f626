//! The blade validate predicts: UIUC's measured stations or APC's design at them, and each
//! station's section from the PE0 file (blended across APC's transition, scaled to its
//! thickness ratio) or the one assumed for another maker's prop.

use std::path::Path;

use propbet_polar::Airfoil;
use propbet_qprop::apc::{read_pe0, uiuc_diameter, Pe0};
use propbet_qprop::PropRow;

use super::{GeometrySource, Sections, ValidateSpec};
use propbet_model::{read_text, Error, Result};
use propbet_pipeline::stages;

pub use propbet_model::design::pe0_table;

/// APC's airfoil name → a section ([`propbet_model::design::airfoil_by_name`], `dir` looked in first).
pub(super) fn apc_airfoil(name: &str, dir: &Path) -> Result<Airfoil> {
    propbet_model::design::airfoil_by_name(name, Some(dir))
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
        // APC scales its sections "based on thickness ratio" and defines pitch on a flat bottom
        // (docs/studies/section-scaling.md).
        let foil = propbet_model::design::pe0_section(&pe0, &f1, &f2, r)?;
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
