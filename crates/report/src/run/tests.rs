//! Unit tests of the run's page.
use super::*;
use propbet_polar::blade::StationPolars;
use propbet_polar::table::{Branches, Polar, PolarPoint};

use PolarPoint as P;

#[test]
fn a_stations_problems_count_unconverged_angles_and_hysteresis_and_group_alike() {
    let polar = |unconverged: Vec<f64>, loops: usize| Polar {
        re: 5e4,
        mach: 0.05,
        ncrit: 5.0,
        trip: Some(0.5),
        points: vec![P::lift_drag(0.0, 0.5, 0.02), P::lift_drag(12.0, 1.2, 0.1)],
        unconverged_deg: unconverged,
        hysteresis: (0..loops)
            .map(|_| Branches {
                kept: P::lift_drag(12.0, 1.2, 0.1),
                other: P::lift_drag(12.0, 1.0, 0.12),
            })
            .collect(),
        faults: vec![],
        neuralfoil: Vec::new(),
        not_filled: None,
    };
    let station = |polars: Vec<Polar>| StationPolars {
        r: 0.1,
        chord: 0.02,
        re: 5e4,
        re_range: [4e4, 6e4],
        mach: 0.05,
        alpha_deg: 4.0,
        alpha_range_deg: [0.0, 8.0],
        polars,
        other_ncrit: vec![],
        band: vec![],
        fit: None,
        problem: None,
    };
    let one = station_problem_list(&station(vec![polar(vec![14.0], 1), polar(vec![], 0)]));
    assert_eq!(
        one,
        vec![
            "XFOIL did not converge at 1 of the angles of 2 polars".to_string(),
            "two XFOIL solutions (hysteresis) at 1 of the angles of 2 polars: the lower-drag one kept".to_string(),
        ]
    );
    let more = station_problem_list(&station(vec![polar(vec![13.0, 14.0], 2), polar(vec![], 0)]));
    assert_eq!(more[0], "XFOIL did not converge at 2 of the angles of 2 polars");
    // One group in the report's list, however many angles.
    let grouped = crate::page::group_alike(vec![one[0].clone(), more[0].clone()]);
    assert_eq!(grouped.len(), 1, "{grouped:?}");
    assert!(station_problem_list(&station(vec![polar(vec![], 0)])).is_empty());

    // auto: NeuralFoil's angles and its doubts are listed; a section it could not take too.
    let mut filled = polar(vec![], 0);
    filled.neuralfoil = vec![propbet_polar::Filled {
        alpha_deg: 12.0,
        confidence: 0.3,
    }];
    let mut kept = polar(vec![14.0], 0);
    kept.not_filled = Some("NeuralFoil cannot take this section: the contour crosses itself".into());
    assert_eq!(
        station_problem_list(&station(vec![filled, kept])),
        vec![
            "XFOIL did not converge at 1 of the angles of 2 polars".to_string(),
            "NeuralFoil cannot take this section: the contour crosses itself: XFOIL's polars kept with their gaps"
                .to_string(),
            "NeuralFoil made 1 of the angles of 2 polars (where XFOIL did not converge)".to_string(),
            "NeuralFoil is unsure (confidence below 0.5) at 1 of the angles of 2 polars".to_string(),
        ]
    );
}
