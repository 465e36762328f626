//! Writes a synthetic coloured cloud for the benchmark: `gencloud OUT.ply [BLADE_POINTS]`
//! (plus a quarter as many box points and 20 % background).
use nalgebra::{Rotation3, Vector3};
use propbet_geometry::cloud::to_ply;
use propbet_geometry::synth::{BladeDef, CloudSpec, StationDef};
fn main() {
    let out = std::env::args().nth(1).unwrap_or_else(|| "cloud.ply".into());
    let n: usize = std::env::args().nth(2).and_then(|s| s.parse().ok()).unwrap_or(400_000);
    let rows = [
        (0.15, 0.138, 37.9),
        (0.45, 0.190, 26.2),
        (0.75, 0.144, 17.6),
        (1.00, 0.050, 13.6),
    ];
    let def = BladeDef {
        blades: 2,
        pitch_axis: 0.3,
        hub: None,
        stations: rows
            .iter()
            .map(|&(x, c, b)| StationDef {
                r: x * 127.0,
                chord: c * 127.0,
                beta: b,
                t_c: 0.1,
                camber: 0.05,
                camber_pos: 0.45,
            })
            .collect(),
    };
    let axis = nalgebra::Unit::new_normalize(Vector3::new(0.2, -1.0, 0.7));
    let spec = CloudSpec {
        blade_points: n,
        noise: 0.05,
        background: 0.2,
        reference_box: Some(([50.8, 48.26, 50.8], [0.0, 0.0, -40.0], n / 4)),
        rotation: *Rotation3::from_axis_angle(&axis, 2.1).matrix(),
        translation: Vector3::new(-160.0, 190.0, 105.0),
        scale: 0.756,
        seed: 7,
    };
    std::fs::write(out, to_ply(&def.to_cloud(&spec), None)).unwrap();
}
