//! Unit tests of `spec.rs`.

use super::*;

#[test]
fn trips_read_back_as_written() {
    use crate::{settings::trip_text, values::parse_trip};
    assert_eq!(parse_trip("free").unwrap(), None);
    assert_eq!(parse_trip("1").unwrap(), None);
    assert_eq!(parse_trip("0.5").unwrap(), Some(0.5));
    for t in [None, Some(0.05), Some(0.5), crate::settings::default_trip()] {
        assert_eq!(parse_trip(&trip_text(t)).unwrap(), t);
    }
    for bad in ["0", "-0.1", "1.5", "nan", "mid"] {
        let e = parse_trip(bad).unwrap_err().to_string();
        assert!(e.contains(&format!("--trip {bad}: ")), "{e}");
    }
}

#[test]
fn the_declared_stations_are_the_scans_default() {
    let stations = crate::values::parse_list("--stations", crate::settings::STATIONS.default).unwrap();
    assert_eq!(stations, default_stations());
}

#[test]
fn rotation_defaults_to_snel_with_tables_and_off_with_qprops_law() {
    assert_eq!(Rotation::or_default(None, true), crate::settings::ROTATION.default);
    assert_eq!(Rotation::or_default(None, false), Rotation::Off);
    assert_eq!(Rotation::or_default(Some(Rotation::Off), true), Rotation::Off);
    for r in Rotation::ALL {
        assert_eq!(Rotation::parse(r.name()).unwrap(), r);
    }
    assert_eq!(Rotation::Snel.coefficient(), 3.0);
    let e = Rotation::parse("snell").unwrap_err().to_string();
    assert!(e.contains("`snell`: expected off or snel"), "{e}");
    // The equivalent command names the setting only where it is not the default.
    let mut spec = ModelSpec::prop("p.qprop".into());
    spec.polars = Some("polars.json".into());
    spec.rotation = crate::settings::ROTATION.default;
    let mut v = Vec::new();
    spec.push_argv(&mut v);
    assert!(!v.iter().any(|a| a == "--rotation"), "{v:?}");
    spec.rotation = Rotation::Off;
    let mut v = Vec::new();
    spec.push_argv(&mut v);
    assert!(v.windows(2).any(|w| w[0] == "--rotation" && w[1] == "off"), "{v:?}");
}

#[test]
fn the_drag_factor_defaults_with_tables_only_and_is_named_where_not_default() {
    assert_eq!(drag_factor_or_default(None, true), crate::settings::DRAG_FACTOR.default);
    assert_eq!(drag_factor_or_default(None, false), 1.0);
    assert_eq!(drag_factor_or_default(Some(1.0), true), 1.0);
    let mut spec = ModelSpec::prop("p.qprop".into());
    spec.polars = Some("polars.json".into());
    spec.drag_factor = crate::settings::DRAG_FACTOR.default;
    let mut v = Vec::new();
    spec.push_argv(&mut v);
    assert!(!v.iter().any(|a| a.starts_with("--drag-factor")), "{v:?}");
    spec.drag_factor = 1.0;
    let mut v = Vec::new();
    spec.push_argv(&mut v);
    assert!(v.iter().any(|a| a == "--drag-factor=1"), "{v:?}");
}
