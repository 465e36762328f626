//! Time per NeuralFoil point of propbet's engine (benchsuite/neuralfoil.sh sets it beside the
//! Python package's): a 25-angle polar of NACA 4412 at Re 1e5 (batched: the whole polar; single:
//! one point), and the section's Kulfan fit. Prints one JSON line.

use std::time::Instant;

use propbet_neuralfoil::{cst, Condition, Network, DEFAULT_SIZE};
use propbet_units::stats::median;

fn main() {
    let path = std::env::args().nth(1).expect("an airfoil .dat file");
    let points = cst::selig_points(&std::fs::read_to_string(&path).expect("the airfoil file"));
    let net = Network::shipped(DEFAULT_SIZE).expect("the shipped weights");
    let alphas: Vec<f64> = (-8..=16).map(f64::from).collect();
    let c = Condition {
        alpha_deg: 0.0,
        re: 1e5,
        ncrit: 9.0,
        xtr_upper: 1.0,
        xtr_lower: 1.0,
    };
    let runs = 200;
    let time = |f: &mut dyn FnMut()| {
        let t = Instant::now();
        f();
        t.elapsed().as_secs_f64()
    };
    let mut fit_s = Vec::new();
    let mut batch_s = Vec::new();
    let mut single_s = Vec::new();
    let mut sink = 0.0;
    for _ in 0..runs {
        let mut k = None;
        fit_s.push(time(&mut || k = Some(cst::fit(&points).expect("a fit").kulfan)));
        let k = k.unwrap();
        batch_s.push(time(&mut || {
            sink += net.polar(&k, &alphas, &c).iter().map(|a| a.cl).sum::<f64>()
        }));
        single_s.push(time(&mut || sink += net.evaluate(&k, &c).cl));
    }
    println!(
        "{{\"fit_s\": {}, \"point_batched_s\": {}, \"point_single_s\": {}, \"check\": {}}}",
        median(fit_s),
        median(batch_s) / alphas.len() as f64,
        median(single_s),
        sink.is_finite()
    );
}
