//! Aligns an STL and prints chord and blade angle at r/R = 0.2..0.95:
//! `cargo run --release -p propbet-geometry --example probe -- FILE.stl`.

use propbet_geometry::align::{auto_align, to_frame};
use propbet_geometry::mesh::read_stl;
use propbet_geometry::section::{cut_points, measure, split_blades};

fn main() {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: probe FILE.stl");
        std::process::exit(2);
    };
    let bytes = std::fs::read(&path).unwrap_or_else(|e| {
        eprintln!("{path}: {e}");
        std::process::exit(2)
    });
    let mesh = match read_stl(&bytes, &path) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2)
        }
    };
    let frame = match auto_align(&mesh) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("{path}: {e}");
            std::process::exit(2)
        }
    };
    println!("{} triangles; {:?}", mesh.triangles.len(), frame.notes);
    let local = to_frame(&mesh, &frame);
    println!("r/R     r       chord   beta    t/c     camber");
    for k in 0..16 {
        let x = 0.2 + 0.05 * k as f64;
        let r = x * frame.tip_radius;
        let pts = cut_points(&local, r);
        match measure(&split_blades(&pts, frame.blades)[0], r) {
            Some(s) => println!(
                "{x:.2}  {r:7.2}  {:6.2}  {:6.2}  {:.4}  {:.4}",
                s.chord,
                s.beta.to_degrees(),
                s.t_c,
                s.camber
            ),
            None => println!("{x:.2}  {r:7.2}  (too few points)"),
        }
    }
}
