//! Unit tests of `spec.rs`.

use super::*;
use propbet_geometry::scan::default_stations;

#[test]
fn trips_read_back_as_written() {
    use crate::{trip_text, values::parse_trip};
    assert_eq!(parse_trip("free").unwrap(), None);
    assert_eq!(parse_trip("1").unwrap(), None);
    assert_eq!(parse_trip("0.5").unwrap(), Some(0.5));
    for t in [None, Some(0.05), Some(0.5), crate::default_trip()] {
        assert_eq!(parse_trip(&trip_text(t)).unwrap(), t);
    }
    for bad in ["0", "-0.1", "1.5", "nan", "mid"] {
        let e = parse_trip(bad).unwrap_err().to_string();
        assert!(e.contains(&format!("--trip {bad}: ")), "{e}");
    }
}

#[test]
fn the_declared_stations_are_the_scans_default() {
    let stations = crate::values::parse_list("--stations", crate::STATIONS.default).unwrap();
    assert_eq!(stations, default_stations());
}

#[test]
fn rotation_defaults_to_snel_with_tables_and_off_with_qprops_law() {
    assert_eq!(Rotation::or_default(None, true), crate::ROTATION.default);
    assert_eq!(Rotation::or_default(None, false), Rotation::Off);
    assert_eq!(Rotation::or_default(Some(Rotation::Off), true), Rotation::Off);
    for r in Rotation::ALL {
        assert_eq!(Rotation::parse(r.name()).unwrap(), r);
    }
    assert_eq!(Rotation::Snel.coefficient(), 3.0);
    let e = Rotation::parse("snell").unwrap_err().to_string();
    assert!(e.contains("`snell`: expected off or snel"), "{e}");
}

#[test]
fn the_drag_factor_defaults_with_tables_only() {
    assert_eq!(crate::drag_factor_or_default(None, true), crate::DRAG_FACTOR.default);
    assert_eq!(crate::drag_factor_or_default(None, false), 1.0);
    assert_eq!(crate::drag_factor_or_default(Some(1.0), true), 1.0);
}
