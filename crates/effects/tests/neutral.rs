//! Every built-in effect at its neutral values leaves the model as it is, and away from them
//! moves the loads the way its physics says.

use propbet_bemt::{Discretization, Fluid, OperatingPoint, Rotor, SolverOptions};
use propbet_effects::spec::Registry;
use propbet_effects::{builtin, parse_spec, Stack};
use propbet_qprop::RadiusReading;

/// QPROP's example propeller, read from the shipped prop file.
fn cam6x3() -> Rotor {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../props/cam6x3/cam6x3.qprop");
    let (file, _) = propbet_qprop::parse_prop(&std::fs::read_to_string(path).unwrap()).unwrap();
    file.to_blade(RadiusReading::Documented)
        .to_rotor(Discretization::default())
        .unwrap()
}

fn loads(stack: &Stack, op: OperatingPoint) -> (f64, f64) {
    let rotor = cam6x3();
    let p = stack
        .predict(
            &rotor,
            &SolverOptions::default(),
            &Fluid::QPROP_DEFAULT,
            6.0 * 0.0254,
            op,
        )
        .unwrap();
    (p.loads.thrust, p.loads.torque)
}

#[test]
fn neutral_values_change_nothing() {
    let r = Registry::default();
    for op in [
        OperatingPoint::from_rpm(0.0, 9000.0),
        OperatingPoint::from_rpm(6.0, 9000.0),
    ] {
        let base = loads(&Stack::baseline(), op);
        for id in builtin::ids() {
            let Ok(active) = r.resolve(&parse_spec(id).unwrap()) else {
                assert_eq!(id, "post-stall", "only post-stall has no neutral value");
                continue;
            };
            let l = loads(&Stack { active: vec![active] }, op);
            assert!(
                (l.0 - base.0).abs() <= 1e-9 * base.0.abs() && (l.1 - base.1).abs() <= 1e-9 * base.1.abs(),
                "{id}: {l:?} vs {base:?}"
            );
        }
    }
}

#[test]
fn effects_move_loads_the_physical_way() {
    let r = Registry::default();
    let at = |spec: &str, op| {
        let a = r.resolve(&parse_spec(spec).unwrap()).unwrap();
        loads(&Stack { active: vec![a] }, op)
    };
    let op = OperatingPoint::from_rpm(5.0, 9000.0);
    let (t0, q0) = loads(&Stack::baseline(), op);
    let more = |x: (f64, f64)| x.0 > t0 && x.1 > q0;
    assert!(more(at("pitch-offset:deg=1", op)));
    assert!(more(at("chord-scale:factor=1.1", op)));
    assert!(more(at("tip-loss:strength=0.3", op)));
    assert!(!more(at("hub-loss:strength=1", op)));
    // Density scales thrust and torque nearly together (Re changes a little).
    let (t, q) = at("density:ratio=0.9", op);
    assert!(
        (t / t0 - 0.9).abs() < 0.02 && (q / q0 - 0.9).abs() < 0.03,
        "{} {}",
        t / t0,
        q / q0
    );
    // True RPM 5 % low: loads fall by about 10 % (and J rises).
    let (t, _) = at("rpm-scale:factor=0.95", op);
    assert!(t < 0.92 * t0);
    // Elastic untwist grows with RPM^2: negligible at 1000 rpm.
    let slow = OperatingPoint::from_rpm(0.0, 1000.0);
    let (ts, _) = loads(&Stack::baseline(), slow);
    assert!((at("elastic-twist:k=2", slow).0 / ts - 1.0).abs() < 0.01);
    assert!(at("elastic-twist:k=2", op).0 < 0.95 * t0);
    // Tares: torque shifted exactly, thrust reduced.
    let (t, q) = at("torque-tare:q0=0.001,q1=1e-6", op);
    assert_eq!(t, t0);
    assert!((q - q0 - 0.001 - 1e-6 * op.omega).abs() < 1e-12);
    assert!(at("thrust-tare:k=0.05", op).0 < t0);
    // Lower drag-rise Mach: more torque once the tip is above it (20,000 rpm: tip M ~ 0.47).
    let fast = OperatingPoint::from_rpm(0.0, 20000.0);
    let (_, qf) = loads(&Stack::baseline(), fast);
    assert!(at("compressibility:mcrit=0.3", fast).1 > 1.02 * qf);
    assert!(
        (at("compressibility:mcrit=0.5", op).1 / q0 - 1.0).abs() < 1e-9,
        "below the drag-rise Mach"
    );
    // A more negative Reynolds exponent raises the drag where Re is below REref (70,000; at
    // 9000 rpm the sections of this 6" prop run at 30,000-60,000): more torque; and the other
    // way round for a positive change.
    assert!(at("re-scaling:dexp=-0.5", op).1 > q0);
    assert!(at("re-scaling:dexp=0.5", op).1 < q0);
}

#[test]
fn user_formulas_on_section_and_geometry_hooks() {
    let text = r#"
[[effect]]
id = "lift-gain"
hook = "cl"
formula = "cl * f"
[[effect.param]]
name = "f"
neutral = 1.0
lower = 0.5
upper = 1.5

[[effect]]
id = "twist-user"
hook = "beta"
formula = "beta + d * x"
[[effect.param]]
name = "d"
neutral = 0.0
lower = -5.0
upper = 5.0

[[effect]]
id = "drag-user"
hook = "cd"
formula = "cd + dc"
[[effect.param]]
name = "dc"
neutral = 0.0
lower = -0.01
upper = 0.05
"#;
    let user = propbet_effects::user::parse(text, "inline.toml").unwrap();
    let r = Registry::with_user(user).unwrap();
    let at = |spec: &str, op| {
        let a = r.resolve(&parse_spec(spec).unwrap()).unwrap();
        loads(&Stack { active: vec![a] }, op)
    };
    let op = OperatingPoint::from_rpm(5.0, 9000.0);
    let (t0, q0) = loads(&Stack::baseline(), op);
    for id in ["lift-gain", "twist-user", "drag-user"] {
        let (t, q) = at(id, op);
        assert!(
            (t / t0 - 1.0).abs() < 1e-9 && (q / q0 - 1.0).abs() < 1e-9,
            "{id} at neutral"
        );
    }
    assert!(at("lift-gain:f=1.1", op).0 > 1.03 * t0);
    // beta + d x with d = 1 deg is a twist change of up to 1 deg at the tip: between no change
    // and a 1 deg collective offset.
    let twist = at("twist-user:d=1", op).0;
    let collective = at("pitch-offset:deg=1", op).0;
    assert!(twist > t0 && twist < collective, "{t0} < {twist} < {collective}");
    let (t, q) = at("drag-user:dc=0.01", op);
    assert!(q > 1.05 * q0 && t < t0);
}
