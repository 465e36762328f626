//! Unit tests of `stages.rs`.

use super::*;

#[test]
fn a_station_without_its_section_takes_the_nearest_one() {
    let naca = |d: &str| {
        let f = propbet_polar::naca4_from_name(d).unwrap().unwrap();
        let mut t = format!("{d}\n");
        for p in &f.points {
            t.push_str(&format!("{} {}\n", p[0], p[1]));
        }
        t
    };
    let dir = Path::new("airfoils");
    let text = |i: usize, d: &str| Some((dir.join(format!("station_{i:02}.dat")), naca(d)));
    let texts = vec![None, text(1, "naca2412"), None, None, text(4, "naca4409"), None];
    let mut notes = Vec::new();
    let foils = station_foils(dir, texts.clone(), None, &mut notes).unwrap();
    let t_c: Vec<f64> = foils.iter().map(|f| (100.0 * f.max_thickness().0).round()).collect();
    // 0 from 1; 2 from 1; 3 from 4; 5 from 4.
    assert_eq!(t_c, [12.0, 12.0, 12.0, 9.0, 9.0, 9.0], "{notes:?}");
    assert!(
        notes
            .iter()
            .any(|n| n.contains("[0, 2, 3, 5]") && n.contains("0 from 1, 2 from 1, 3 from 4, 5 from 4")),
        "{notes:?}"
    );
    let none = vec![None, None];
    let e = station_foils(dir, none, None, &mut notes).err().unwrap().to_string();
    assert!(e.contains("no station has a section file"), "{e}");
}

#[test]
fn xfoil_has_a_total_budget_unless_one_is_given() {
    let dir = tempfile::tempdir().unwrap();
    let exe = xfoil_runner::fake::write_fake_xfoil(dir.path(), "").unwrap();
    let spec = |budget| XfoilProcessSpec {
        engine: Default::default(),
        neuralfoil_size: None,
        xfoil: Some(exe.clone()),
        cache: None,
        no_cache: true,
        quiet: true,
        budget,
    };
    let engine = polar_engine(&spec(None)).unwrap();
    assert_eq!(engine.budget(), Some(propbet_settings::XFOIL_BUDGET.default));
    assert_eq!(polar_engine(&spec(Some(20.0))).unwrap().budget(), Some(20.0));
    let e = polar_engine(&spec(Some(-1.0))).err().unwrap().to_string();
    assert!(e.contains("--xfoil-budget -1: a positive number"), "{e}");
}
