//! Unit tests of the blade files' readers.
use super::table::read_table;
use super::*;

#[test]
fn formats_are_told_by_their_text() {
    let pe0 = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../props/apcsp_10x7/10x7-PERF.PE0"
    ))
    .unwrap();
    assert_eq!(BladeFormat::of(&pe0), BladeFormat::Pe0);
    assert_eq!(
        BladeFormat::of("r/R    c/R     beta\n0.15 0.1 30\n"),
        BladeFormat::UiucTable
    );
    assert_eq!(
        BladeFormat::of("# a blade\nr (mm),chord (mm),beta (deg)\n10,20,30\n"),
        BladeFormat::Table
    );
    assert_eq!(BladeFormat::of("cam 6x3\n\n2 0.0762\n"), BladeFormat::Qprop);
    assert_eq!(pe0_diameter(&pe0), Some(10.0 * 0.0254));
    assert_eq!(pe0_diameter("4.2x4   (42x4.dat)\n"), Some(4.2 * 0.0254));
    assert_eq!(pe0_diameter("no diameter\n"), None);
}

#[test]
fn section_plans_read_one_airfoil_or_a_blend_and_refuse_the_rest() {
    assert_eq!(
        SectionPlan::parse("e63", "--airfoil").unwrap().anchors,
        vec![(0.0, "e63".into())]
    );
    let p = SectionPlan::parse("E63@0.25, APC12@0.45", "--airfoil").unwrap();
    assert_eq!(p.anchors, vec![(0.25, "E63".into()), (0.45, "APC12".into())]);
    for (bad, says) in [
        ("E63@0.5,APC12@0.3", "must increase"),
        ("E63@1.5", "between 0 and 1"),
        ("E63,APC12@0.4", "no '@r/R'"),
        ("@0.3", "names no airfoil"),
        ("", "no airfoil"),
    ] {
        let e = SectionPlan::parse(bad, "--airfoil").unwrap_err().to_string();
        assert!(e.contains(says) && e.contains("--airfoil"), "{bad}: {e}");
    }
}

#[test]
fn a_blend_moves_from_one_airfoil_to_the_next_between_its_radii() {
    let plan = SectionPlan::parse("e63@0.3,naca4412@0.6", "x").unwrap();
    let radii = [0.1, 0.3, 0.45, 0.6, 0.9];
    let foils = plan_sections(&plan, &radii, 1.0, &[None; 5], None).unwrap();
    let t: Vec<f64> = foils.iter().map(|f| f.max_thickness().0).collect();
    assert!((t[0] - t[1]).abs() < 1e-9 && (t[3] - t[4]).abs() < 1e-9, "{t:?}");
    assert!(t[0] < 0.05 && t[4] > 0.11 && t[2] > t[0] && t[2] < t[4], "{t:?}");
    // A thickness ratio per station scales the section.
    let scaled = plan_sections(&plan, &radii, 1.0, &[Some(0.08); 5], None).unwrap();
    assert!(scaled.iter().all(|f| (f.max_thickness().0 - 0.08).abs() < 2e-3));
}

#[test]
fn names_propbet_knows_need_no_file() {
    for n in ["E63", "clark-y", "APC12", "naca 4412", "SD7037"] {
        assert!(is_known_name(n) && airfoil_by_name(n, None).is_ok(), "{n}");
    }
    let e = airfoil_by_name("nosuchfoil", None).unwrap_err().to_string();
    assert!(e.contains("nosuchfoil") && e.contains("clarky"), "{e}");
    let dir = Path::new("/case");
    assert_eq!(resolve_in("e63", dir), ("e63".to_string(), vec![]));
    let (t, files) = resolve_in("my.dat@0.2,APC12@0.5", dir);
    assert_eq!(t, "/case/my.dat@0.2,APC12@0.5");
    assert_eq!(files, vec![PathBuf::from("/case/my.dat")]);
}

#[test]
fn a_blade_table_reads_its_units_sections_and_refuses_bad_rows_by_line() {
    let t = read_table(
        "# stations\nr (mm),chord (mm),beta (deg),t/c,airfoil\n20,15,30,0.1,e63\n60,20,20,8%,clarky\n",
        None,
    )
    .unwrap();
    assert_eq!(t.rows.len(), 2);
    assert!((t.rows[1].0 - 0.06).abs() < 1e-12 && (t.rows[1].1 - 0.02).abs() < 1e-12);
    assert_eq!(t.thickness, vec![Some(0.1), Some(0.08)]);
    assert_eq!(t.airfoils[1].as_deref(), Some("clarky"));
    // Units from --units when the header gives none.
    assert!(read_table("r,chord,beta\n1,1,30\n2,1,20\n", Some(0.0254)).is_ok());
    for (text, says) in [
        ("r,chord,beta\n1,1,30\n2,1,20\n", "name no unit"),
        (
            "r (mm),chord (mm),beta (deg)\n20,15,30\n10,15,30\n",
            "line 3: the radius must increase",
        ),
        (
            "r (mm),chord (mm),beta (deg)\n20,15,30\n30,x,30\n",
            "line 3: chord 'x' is not a number",
        ),
        ("r (mm),chord (mm),beta (deg)\n20,15,95\n30,5,30\n", "line 2:"),
        ("r (mm),chord (in),beta (deg)\n20,15,30\n", "same unit"),
        ("r (mm),chord (mm),beta (rad)\n20,15,30\n", "degrees"),
        ("r (mm),chord (mm),beta (deg)\n20,15,30\n", "fewer than two"),
    ] {
        let e = read_table(text, None).err().unwrap();
        assert!(e.contains(says), "{text:?}: {e}");
    }
}

#[test]
fn a_pe0_blade_is_apcs_design_at_uiucs_stations_with_its_sections() {
    let path = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../props/apcsp_10x7/10x7-PERF.PE0"
    ));
    let d = read_design(path, &DesignOptions::default()).unwrap().unwrap();
    let rows = &d.geometry.file.rows;
    assert_eq!(rows.len(), 17, "r/R 0.20 to 1.00 (APC's first station is at r/R 0.24)");
    assert!((rows.last().unwrap().r - 0.127).abs() < 1e-12);
    let sections = d.sections.unwrap();
    assert_eq!(sections.len(), rows.len());
    assert!(
        sections[0].contains("t/c 0.2") && d.description.contains("CLARK-Y"),
        "{}",
        d.description
    );
    // A QPROP file is not a design file.
    let cam = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../props/cam6x3/cam6x3.qprop"));
    assert!(read_design(cam, &DesignOptions::default()).unwrap().is_none());
}
