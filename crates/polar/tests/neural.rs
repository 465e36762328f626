//! The NeuralFoil engine behind the polar engine's interface: a whole polar from the network,
//! and an XFOIL polar's unconverged angles filled from it (`auto`), each NeuralFoil point listed
//! with its confidence.

use propbet_neuralfoil::{Network, DEFAULT_SIZE};
use propbet_polar::{naca4_from_name, neural, Engine, PolarEngine, PolarJob, Source};

fn job() -> PolarJob {
    let foil = naca4_from_name("naca4412").unwrap().unwrap();
    let alphas: Vec<f64> = (-4..=10).map(f64::from).collect();
    let mut j = PolarJob::new(foil, 2e5, 0.1, 9.0, alphas);
    j.section.trip = Some(0.5);
    j
}

/// The job's section and condition, as NeuralFoil takes them.
fn section_of(j: &PolarJob) -> neural::Section<'_> {
    neural::Section {
        airfoil: &j.airfoil,
        re: j.re,
        ncrit: j.section.ncrit,
        trip: j.section.trip,
    }
}

#[test]
fn a_neuralfoil_polar_has_every_angle_and_says_so() {
    let engine = PolarEngine::neuralfoil(Network::shipped(DEFAULT_SIZE).unwrap());
    assert_eq!(engine.engine(), Engine::NeuralFoil);
    let (p, source) = engine.compute(&job()).unwrap();
    assert_eq!(source, Source::NeuralFoil);
    assert_eq!(p.points.len(), 15);
    assert_eq!(p.neuralfoil.len(), 15, "every point is NeuralFoil's");
    assert_eq!(p.mach, 0.0, "incompressible: the tables apply Prandtl-Glauert");
    // NACA 4412 at Re 2e5: lift near 0.45 at zero incidence, a lift slope near 2 pi per rad,
    // drag around 0.01 (NeuralFoil is trained on XFOIL).
    let at = |a: f64| p.at_alpha(a).unwrap();
    assert!((0.35..0.6).contains(&at(0.0).cl), "{:?}", at(0.0));
    let slope = (at(4.0).cl - at(0.0).cl) / 4f64.to_radians();
    assert!((4.5..7.0).contains(&slope), "{slope}");
    assert!((0.005..0.02).contains(&at(0.0).cd), "{:?}", at(0.0));
    assert!(p.neuralfoil.iter().all(|f| f.confidence > 0.5), "{:?}", p.neuralfoil);
}

#[test]
fn auto_fills_only_what_xfoil_left_out() {
    let net = Network::shipped(DEFAULT_SIZE).unwrap();
    let j = job();
    let section = section_of(&j);
    let whole = neural::polar(&section, &j.section.alphas_deg, &net).unwrap();
    // An XFOIL polar with two angles unconverged.
    let mut xfoil = whole.clone();
    xfoil.neuralfoil.clear();
    xfoil.points.retain(|p| p.alpha_deg != 3.0 && p.alpha_deg != 9.0);
    xfoil.unconverged_deg = vec![3.0, 9.0];
    let filled = neural::fill(xfoil, &section, &net);
    assert!(filled.unconverged_deg.is_empty());
    assert_eq!(filled.points.len(), 15);
    let angles: Vec<f64> = filled.neuralfoil.iter().map(|f| f.alpha_deg).collect();
    assert_eq!(angles, [3.0, 9.0], "only the filled angles are NeuralFoil's");
    assert!(filled.points.windows(2).all(|w| w[0].alpha_deg < w[1].alpha_deg));
    // The same point as in the whole polar, to single precision (the network's: another batch
    // size sums its products in another order).
    assert!((filled.at_alpha(3.0).unwrap().cl - whole.at_alpha(3.0).unwrap().cl).abs() < 1e-5);
    for e in Engine::ALL {
        assert_eq!(Engine::parse(e.name()), Some(e));
    }
}

#[test]
fn auto_keeps_xfoils_polar_where_neuralfoil_cannot_take_the_section() {
    let net = Network::shipped(DEFAULT_SIZE).unwrap();
    let mut j = job();
    // The upper surface dips through the lower one between x/c 0.3 and 0.6: a contour that
    // crosses itself (a scan's broken section).
    let le = j.airfoil.leading_edge_index();
    for p in &mut j.airfoil.points[..le] {
        if (0.3..0.6).contains(&p[0]) {
            p[1] = -p[1] - 0.05;
        }
    }
    let section = section_of(&j);
    let err = neural::polar(&section, &j.section.alphas_deg, &net).unwrap_err();
    assert!(err.0.contains("crosses itself"), "{err}");
    let xfoil = propbet_polar::Polar {
        unconverged_deg: vec![3.0],
        ..propbet_polar::Polar::from_law(2e5, -4, 10, |a| (0.1 * a, 0.01))
    };
    let kept = neural::fill(xfoil.clone(), &section, &net);
    assert_eq!(kept.points, xfoil.points, "XFOIL's polar as it was");
    assert_eq!(kept.unconverged_deg, [3.0]);
    assert!(kept.neuralfoil.is_empty());
    let why = kept.not_filled.unwrap();
    assert!(
        why.starts_with("NeuralFoil cannot take this section: ") && why.contains("crosses itself"),
        "{why}"
    );
}

#[test]
fn outside_its_training_data_neuralfoil_says_it_is_unsure() {
    let net = Network::shipped(DEFAULT_SIZE).unwrap();
    let j = job();
    let confidence = |re: f64, alpha: f64, foil: &propbet_polar::Airfoil| {
        let section = neural::Section {
            airfoil: foil,
            re,
            ncrit: 9.0,
            trip: None,
        };
        neural::polar(&section, &[alpha], &net).unwrap().neuralfoil[0].confidence
    };
    let low = propbet_polar::table::LOW_CONFIDENCE;
    assert!(confidence(2e5, 2.0, &j.airfoil) > 0.9);
    for (re, alpha) in [(1e2, 2.0), (1e9, 2.0), (2e5, 60.0), (2e5, -60.0)] {
        let c = confidence(re, alpha, &j.airfoil);
        assert!(c < low, "Re {re}, alpha {alpha}: confidence {c}");
    }
    // A blunt trailing edge 4 % of the chord thick: beyond the sections it learned.
    let mut blunt = j.airfoil.clone();
    let n = blunt.points.len();
    for (i, p) in blunt.points.iter_mut().enumerate() {
        let side = if i < n / 2 { 1.0 } else { -1.0 };
        p[1] += side * 0.02 * p[0];
    }
    let section = neural::Section {
        airfoil: &blunt,
        re: 2e5,
        ncrit: 9.0,
        trip: None,
    };
    let err = neural::polar(&section, &[2.0], &net).unwrap_err();
    assert!(err.0.starts_with("a blunt trailing edge 0.04"), "{err}");
}
