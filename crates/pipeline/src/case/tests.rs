//! Unit tests of `case.rs`.

use super::*;
use propbet_bemt::units::rpm_to_omega;
use propbet_geometry::scan::SectionKind;

use propbet_settings::spec::{SweepAxis, XfoilProcessSpec};

fn plan(polars: &str) -> RunPlan {
    let text = format!(
        "name = \"x\"\n[geometry]\nscan = \"x.stl\"\n[sweep]\nrpm = \"4000,6000\"\nj = \"0:0.5:0.1\"\n\
         [polars]\nairfoil = \"naca4412\"\nrpm = 5000\n{polars}\n[measured]\nfiles = [\"m.txt\"]\n"
    );
    let case: Case = toml::from_str(&text).unwrap();
    case.plan(Path::new("case"), Path::new("out"), &XfoilProcessSpec::default())
        .unwrap()
}

#[test]
fn the_section_model_decides_what_the_stages_solve_with() {
    let q = plan("model = \"qprop\"");
    assert_eq!(q.predict.model.polars, None, "QPROP's law when asked");
    let t = plan("");
    let polars = Some(Path::new("out").join("polars/polars.json"));
    assert_eq!(t.predict.model.polars, polars);
    let (c, d) = t.compare.unwrap();
    assert_eq!(
        (c.model.polars.clone(), d.model.polars.clone()),
        (polars.clone(), polars)
    );
}

fn scan_plan(geometry: &str) -> Result<RunPlan> {
    let text = format!("name = \"x\"\n[geometry]\n{geometry}\n[sweep]\nrpm = \"4000\"\nj = \"0\"\n");
    let case: Case = toml::from_str(&text).map_err(|e| Error::input("case.toml", e))?;
    case.plan(Path::new("case"), Path::new("out"), &XfoilProcessSpec::default())
}

#[test]
fn the_scans_settings_are_keys_and_scan_args_is_refused() {
    let keys = scan_plan("scan = \"x.ply\"\noutliers = \"8,3\"\nplanar = true\nslab = 0.5").unwrap();
    let o = &keys.scan.as_ref().unwrap().options;
    assert_eq!(
        (o.outliers, o.kind, o.slab),
        (Some((8, 3.0)), SectionKind::Planar, 0.0005)
    );
    let e = scan_plan("scan = \"x.ply\"\nscan_args = [\"--outliers\", \"8,3\"]")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("[geometry] scan_args: removed in 0.2.0") && e.contains("outliers = \"8,3\""),
        "{e}"
    );
    // Unknown keys, wrong values and a scan's settings without a scan are refused, named.
    let e = scan_plan("scan = \"x.ply\"\nslabb = 3").unwrap_err().to_string();
    assert!(e.contains("unknown field `slabb`"), "{e}");
    let e = scan_plan("scan = \"x.ply\"\nslab = \"thick\"").unwrap_err().to_string();
    assert!(e.contains("[geometry] slab: invalid type"), "{e}");
    let e = scan_plan("prop = \"p.qprop\"\ncrop = \"0,0,0,1,1,1\"")
        .unwrap_err()
        .to_string();
    assert!(e.contains("the case has no scan"), "{e}");
    let e = scan_plan("scan = \"x.ply\"\nroot_point = \"0,0,0\"")
        .unwrap_err()
        .to_string();
    assert!(e.contains("needs both"), "{e}");
    assert!(
        scan_plan("prop = \"p.qprop\"\nunits = \"in\"").is_ok(),
        "a prop file's unit"
    );
}

#[test]
fn the_polars_cover_the_sweep_unless_the_case_says() {
    let sweep = plan("");
    let (p, _) = sweep.polars.unwrap();
    assert_eq!(p.omegas, vec![rpm_to_omega(5000.0)], "rpm = 5000 as given");
    assert_eq!(p.axis, sweep.predict.axis, "the sweep's J");
    let text = "name = \"x\"\n[geometry]\nscan = \"x.stl\"\n[sweep]\nrpm = \"4000,6000\"\nj = \"0:0.5:0.1\"\n\
         [polars]\nairfoil = \"naca4412\"\nv = \"0,5\"\n";
    let case: Case = toml::from_str(text).unwrap();
    let plan = case
        .plan(Path::new("case"), Path::new("out"), &XfoilProcessSpec::default())
        .unwrap();
    let (p, _) = plan.polars.unwrap();
    assert_eq!(p.omegas, vec![rpm_to_omega(4000.0), rpm_to_omega(6000.0)]);
    assert_eq!(p.axis, SweepAxis::V(vec![0.0, 5.0]));
}
