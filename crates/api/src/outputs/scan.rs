//! `propbet scan`'s outputs: geometry.csv, geom.txt, prop.qprop, airfoils/, plots/, blades/
//! and scan.json.

use crate::CommandResult as Result;
use propbet_pipeline::stages::Scanned;
use propbet_settings::spec::ScanSpec;
use serde_json::json;

use crate::files::Outputs;
use crate::geometry::cloud::to_ply;
use crate::geometry::scan::{Aligned, Geometry};
use crate::measure::uiuc::{geometry_at, GeometryRow};
use crate::qprop::write_prop;
use propbet_report::table::{csv_rows, Num};

/// A row of geometry.csv (the reference table's columns empty without one).
#[derive(serde::Serialize)]
struct GeometryCsvRow {
    r_mm: Num,
    #[serde(rename = "r_R")]
    r_r: Num,
    chord_mm: Num,
    #[serde(rename = "c_R")]
    c_r: Num,
    beta_deg: Num,
    t_c: Num,
    t_pos: Num,
    camber: Num,
    camber_pos: Num,
    le_offset_mm: Num,
    skew_deg: Num,
    rake_mm: Num,
    naca: String,
    naca_t_c: Num,
    naca_camber: Num,
    naca_camber_pos: Num,
    rms_naca_mm: Num,
    rms_cst_mm: Num,
    points: usize,
    blade_spread_deg: Num,
    #[serde(rename = "ref_c_R")]
    ref_c_r: Num,
    ref_beta_deg: Num,
}

/// Linear interpolation in a reference table at r/R `x`: column 1 c/R, 2 β [deg] (None outside).
fn interp(table: &[GeometryRow], x: f64, k: usize) -> Option<f64> {
    geometry_at(table, x).map(|(c, b)| if k == 1 { c } else { b.to_degrees() })
}

/// geometry.csv: one row per station, with the reference table's c/R and beta where given.
fn geometry_csv(g: &Geometry, reference: Option<&[GeometryRow]>) -> Result<Vec<u8>> {
    let big_r = g.tip_radius;
    let rows = g.stations.iter().map(|s| {
        let reference = |k| reference.and_then(|t| interp(t, s.r_r, k));
        GeometryCsvRow {
            r_mm: (1000.0 * s.r).into(),
            r_r: s.r_r.into(),
            chord_mm: (1000.0 * s.chord).into(),
            c_r: (s.chord / big_r).into(),
            beta_deg: s.beta.to_degrees().into(),
            t_c: s.t_c.into(),
            t_pos: s.t_pos.into(),
            camber: s.camber.into(),
            camber_pos: s.camber_pos.into(),
            le_offset_mm: (1000.0 * s.le_offset).into(),
            skew_deg: s.skew.to_degrees().into(),
            rake_mm: (1000.0 * s.rake).into(),
            naca: s.naca.designation(),
            naca_t_c: s.naca.t_c.into(),
            naca_camber: s.naca.camber.into(),
            naca_camber_pos: s.naca.camber_pos.into(),
            rms_naca_mm: (1000.0 * s.naca.rms).into(),
            rms_cst_mm: s.cst.as_ref().map(|c| 1000.0 * c.rms).into(),
            points: s.points,
            blade_spread_deg: s.blade_spread.to_degrees().into(),
            ref_c_r: reference(1).into(),
            ref_beta_deg: reference(2).into(),
        }
    });
    Ok(csv_rows(rows, true)?)
}

/// The cleaned surface in the propeller frame, by blade: one STL per blade and the hub's, or
/// the labelled cloud.
fn blades(files: &mut Outputs, g: &Geometry) {
    files.dir("blades");
    let lab = &g.labelled;
    match &lab.surface {
        Aligned::Mesh(m) => {
            for k in 0..g.blades {
                let part = m.subset(|i| lab.blade[i] == Some(k as u8));
                files.add(format!("blades/blade_{k}.stl"), part.to_stl());
            }
            let hub = m.subset(|i| lab.blade[i].is_none());
            if !hub.triangles.is_empty() {
                files.add("blades/hub.stl", hub.to_stl());
            }
        }
        Aligned::Cloud(c) => {
            files.add("blades/labelled.ply", to_ply(c, Some(&lab.blade)));
        }
    }
}

/// The scan stage's outputs.
pub fn outputs(a: &ScanSpec, sc: &Scanned) -> Result<Outputs> {
    let g = &sc.geometry;
    let mut files = Outputs::default();
    files.dir("airfoils");
    files.dir("plots");
    let reference = sc.reference.as_deref();
    let big_r = g.tip_radius;
    // Geometry CSV.
    files.add("geometry.csv", geometry_csv(g, reference)?);
    // UIUC-style table.
    let mut geom = String::from("r/R    c/R     beta\n");
    for s in &g.stations {
        geom.push_str(&format!(
            "{:.4} {:.4} {:.2}\n",
            s.r_r,
            s.chord / big_r,
            s.beta.to_degrees()
        ));
    }
    files.add("geom.txt", geom);
    // QPROP prop file.
    files.add("prop.qprop", write_prop(&sc.prop.file));
    // Airfoils, Selig order.
    for (i, t) in &sc.airfoils {
        files.add(format!("airfoils/station_{i:02}.dat"), t.as_bytes());
    }
    // Plots.
    files.svg("plots/sections", &propbet_report::scan::sections_figure(g))?;
    files.svg(
        "plots/distributions",
        &propbet_report::scan::distributions_figure(g, reference),
    )?;
    if let Some(c) = &g.colour {
        let fig = propbet_report::scan::colour_figure(c);
        files.svg("plots/colour_histogram", &fig)?;
    }
    blades(&mut files, g);
    let lab = &g.labelled;
    let (per_blade, hub_elements) = lab.counts(g.blades);
    // Summary.
    let summary = json!({
        "labels": {
            "elements": if matches!(lab.surface, Aligned::Mesh(_)) { "triangles" } else { "points" },
            "per_blade": per_blade,
            "hub": hub_elements,
        },
        "input": a.input.display().to_string(),
        "blades": g.blades,
        "tip_radius_mm": 1000.0 * g.tip_radius,
        "hub_radius_mm": g.hub_radius.map(|h| 1000.0 * h),
        "root_radius_mm": 1000.0 * g.root_radius,
        "section_kind": g.kind,
        "samples": g.samples,
        // Millimetres per input unit, as the box's known size says.
        "box": g.box_fit.as_ref().map(|b| json!({"scale": 1000.0 * b.scale, "rms_mm": 1000.0 * b.rms, "faces": b.faces})),
        "notes": g.notes,
        "stations": g.stations,
        "failed": g.failed,
    });
    files.add("scan.json", serde_json::to_string_pretty(&summary)?);
    Ok(files)
}
