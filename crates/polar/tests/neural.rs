//! The NeuralFoil engine behind the polar engine's interface: a whole polar from the network,
//! and an XFOIL polar's unconverged angles filled from it (`auto`), each NeuralFoil point listed
//! with its confidence.

use propbet_neuralfoil::{Network, DEFAULT_SIZE};
use propbet_polar::{naca4_from_name, neural, Engine, PolarEngine, PolarJob, Source};

fn job() -> PolarJob {
    let foil = naca4_from_name("naca4412").unwrap().unwrap();
    let alphas: Vec<f64> = (-4..=10).map(f64::from).collect();
    let mut j = PolarJob::new(foil, 2e5, 0.1, 9.0, alphas);
    j.trip = Some(0.5);
    j
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
    let section = neural::Section {
        airfoil: &j.airfoil,
        re: j.re,
        ncrit: j.ncrit,
        trip: j.trip,
    };
    let whole = neural::polar(&section, &j.alphas_deg, &net).unwrap();
    // An XFOIL polar with two angles unconverged.
    let mut xfoil = whole.clone();
    xfoil.neuralfoil.clear();
    xfoil.points.retain(|p| p.alpha_deg != 3.0 && p.alpha_deg != 9.0);
    xfoil.unconverged_deg = vec![3.0, 9.0];
    let filled = neural::fill(xfoil, &section, &net).unwrap();
    assert!(filled.unconverged_deg.is_empty());
    assert_eq!(filled.points.len(), 15);
    let angles: Vec<f64> = filled.neuralfoil.iter().map(|f| f.alpha_deg).collect();
    assert_eq!(angles, [3.0, 9.0], "only the filled angles are NeuralFoil's");
    assert!(filled.points.windows(2).all(|w| w[0].alpha_deg < w[1].alpha_deg));
    assert!((filled.at_alpha(3.0).unwrap().cl - whole.at_alpha(3.0).unwrap().cl).abs() < 1e-12);
    for e in Engine::ALL {
        assert_eq!(Engine::parse(e.name()), Some(e));
    }
}
