//! Runs the scan pipeline on a file and prints the stations:
//! `cargo run --release -p propbet-geometry --example probe -- FILE [box]`
//! (`box`: the synthetic scan's colours and 50.8 x 48.26 x 50.8 mm box at z = -40 mm).

use propbet_geometry::cloud::{parse_colour, read_cloud};
use propbet_geometry::mesh::read_stl;
use propbet_geometry::scan::{scan_cloud, scan_mesh, BoxSpec, ScanOptions};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(path) = args.first() else {
        eprintln!("usage: probe FILE [box]");
        std::process::exit(2);
    };
    let bytes = std::fs::read(path).unwrap_or_else(|e| {
        eprintln!("{path}: {e}");
        std::process::exit(2)
    });
    let mut opts = ScanOptions::default();
    let t0 = std::time::Instant::now();
    let geo = if path.ends_with(".stl") {
        read_stl(&bytes, path)
            .map_err(|e| e.to_string())
            .and_then(|m| scan_mesh(&m, &opts).map_err(|e| e.to_string()))
    } else {
        if args.iter().any(|a| a == "box") {
            let c = |s: &str| parse_colour(s).unwrap_or([0, 0, 0]);
            opts.blade_colours = vec![c("orange"), c("black")];
            opts.reference_box = Some(BoxSpec {
                dims: [50.8, 48.26, 50.8],
                offset: [0.0, 0.0, -40.0],
                colours: vec![c("grey"), c("blue")],
                seeds: Vec::new(),
            });
        }
        read_cloud(&bytes, path)
            .map_err(|e| e.to_string())
            .and_then(|m| scan_cloud(&m, &opts).map_err(|e| e.to_string()))
    };
    let geo = geo.unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(2)
    });
    println!(
        "{:.3} s; {} blades, tip {:.3} mm, hub {:?}, root {:.2}",
        t0.elapsed().as_secs_f64(),
        geo.blades,
        1000.0 * geo.tip_radius,
        geo.hub_radius.map(|h| 1000.0 * h),
        1000.0 * geo.root_radius
    );
    for n in &geo.notes {
        println!("  {n}");
    }
    println!("r/R     r       chord   beta    t/c  t_pos   camber c_pos naca  rms_naca rms_cst spread");
    for s in &geo.stations {
        println!(
            "{:.3}  {:7.2}  {:6.2}  {:6.2}  {:.4} {:.2} {:.4} {:.2} {}  {:.4}  {:.4}  {:.2}",
            s.r_r,
            1000.0 * s.r,
            1000.0 * s.chord,
            s.beta.to_degrees(),
            s.t_c,
            s.t_pos,
            s.camber,
            s.camber_pos,
            s.naca.designation(),
            1000.0 * s.naca.rms,
            s.cst.as_ref().map_or(f64::NAN, |c| 1000.0 * c.rms),
            s.blade_spread.to_degrees()
        );
    }
    for f in &geo.failed {
        println!("{:.3}  {}", f.r_r, f.reason);
    }
}
