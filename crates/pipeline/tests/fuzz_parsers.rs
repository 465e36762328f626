//! Mutation fuzzing of every parser propbet feeds user files to, on stable Rust: each parser
//! gets seeds (shipped or small generated files) and mutated copies of them (bytes flipped,
//! inserted, deleted, chunks repeated, numbers replaced by extreme ones), and must return `Ok`
//! or `Err` for each: a panic, or a case slower than `PROPBET_FUZZ_HANG_SECONDS` (default 10),
//! fails the test and leaves the input in the system's temporary directory.
//!
//! Short run (CI, part of the test suite): `PROPBET_FUZZ_CASES` mutations per parser (default 200).
//! Long run, 10 minutes per parser, one parser after the other:
//!
//! ```sh
//! PROPBET_FUZZ_SECONDS=600 PROPBET_FUZZ_CASES=100000000 \
//!   cargo test --release -p propbet-pipeline --test fuzz_parsers -- --test-threads 1 --nocapture
//! ```
//!
//! A parser's output must also hold only finite numbers: each closure returns whether it does,
//! and a non-finite output fails the test like a panic.
//!
//! Each test prints its counts: runs, panics, hangs, non-finite outputs. The generator is a fixed-seed xorshift
//! (`PROPBET_FUZZ_SEED` to vary), so a failure replays.

use std::path::Path;
use std::time::{Duration, Instant};

fn repo() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

fn env_num(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// xorshift64*: enough randomness for mutations, no dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Numbers that break arithmetic and allocation.
const EXTREMES: [&str; 12] = [
    "1e308",
    "-1e308",
    "nan",
    "inf",
    "-inf",
    "0",
    "-0",
    "1e-320",
    "4294967296",
    "-1",
    "1e20",
    "99999999999999999999",
];

fn mutate(seed: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut v = seed.to_vec();
    for _ in 0..1 + rng.below(6) {
        let len = v.len().max(1);
        let at = rng.below(len).min(v.len());
        match rng.below(7) {
            0 if !v.is_empty() => {
                let k = at.min(v.len() - 1);
                v[k] ^= 1 << rng.below(8);
            }
            1 => v.insert(at, (rng.next() & 0xff) as u8),
            2 => {
                let end = (at + 1 + rng.below(64)).min(v.len());
                v.drain(at..end);
            }
            3 => {
                // Repeat a chunk (up to 4 kB, up to 8 times).
                let end = (at + 1 + rng.below(4096)).min(v.len());
                let chunk = v[at..end].to_vec();
                for _ in 0..1 + rng.below(8) {
                    v.splice(at..at, chunk.iter().copied());
                }
            }
            4 => {
                // Replace the number around `at` by an extreme one.
                let is_num = |b: u8| b.is_ascii_digit() || b == b'.' || b == b'-' || b == b'e' || b == b'+';
                let (mut s, mut e) = (at, at);
                while s > 0 && is_num(v[s - 1]) {
                    s -= 1;
                }
                while e < v.len() && is_num(v[e]) {
                    e += 1;
                }
                let x = EXTREMES[rng.below(EXTREMES.len())].as_bytes();
                v.splice(s..e, x.iter().copied());
            }
            5 => {
                let junk = [b'\n', b',', b'\t', b' ', b'"', 0, 0xff, b'[', b'='];
                v.insert(at, junk[rng.below(junk.len())]);
            }
            _ => v.truncate(at),
        }
    }
    v
}

/// Runs `parse` on every seed and on mutations of them until the case or time budget is spent;
/// panics (with the input saved) on a panic or a hang.
fn fuzz(name: &str, seeds: &[Vec<u8>], parse: impl Fn(&[u8]) -> bool + std::panic::RefUnwindSafe) {
    let cases = env_num("PROPBET_FUZZ_CASES", 200);
    let seconds = env_num("PROPBET_FUZZ_SECONDS", 0);
    let hang = Duration::from_secs(env_num("PROPBET_FUZZ_HANG_SECONDS", 10));
    let mut rng = Rng(env_num("PROPBET_FUZZ_SEED", 0x9E37_79B9_7F4A_7C15) | 1);
    let start = Instant::now();
    let (mut runs, mut panics, mut hangs, mut nonfinite) = (0u64, 0u64, 0u64, 0u64);
    let mut first_failure: Option<String> = None;
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut k = 0u64;
    loop {
        let input = if (k as usize) < seeds.len() {
            seeds[k as usize].clone()
        } else {
            mutate(&seeds[rng.below(seeds.len())], &mut rng)
        };
        k += 1;
        let t = Instant::now();
        let result = std::panic::catch_unwind(|| parse(&input));
        runs += 1;
        let ok = result.is_ok();
        let finite = result.unwrap_or(true);
        let slow = t.elapsed() > hang;
        if !ok || slow || !finite {
            if !ok {
                panics += 1;
            } else if !finite {
                nonfinite += 1;
            } else {
                hangs += 1;
            }
            if first_failure.is_none() {
                let path = std::env::temp_dir().join(format!("propbet_fuzz_{name}_{runs}.bin"));
                let _ = std::fs::write(&path, &input);
                first_failure = Some(format!(
                    "{} on case {runs} ({:.1} s), input in {}",
                    if !ok {
                        "panic"
                    } else if !finite {
                        "non-finite output"
                    } else {
                        "hang"
                    },
                    t.elapsed().as_secs_f64(),
                    path.display()
                ));
            }
        }
        let done = if seconds > 0 {
            start.elapsed() >= Duration::from_secs(seconds) || runs >= cases
        } else {
            runs >= cases
        };
        if done {
            break;
        }
    }
    std::panic::set_hook(hook);
    println!(
        "fuzz {name}: {runs} runs in {:.1} s, {panics} panics, {hangs} hangs, {nonfinite} non-finite outputs",
        start.elapsed().as_secs_f64()
    );
    assert!(
        first_failure.is_none(),
        "fuzz {name}: {}",
        first_failure.unwrap_or_default()
    );
}

fn finite(xs: &[f64]) -> bool {
    xs.iter().all(|x| x.is_finite())
}

/// Every number of a measured set that reads is finite.
fn measured_finite(set: Result<propbet_measure::MeasuredSet, propbet_measure::ReadError>) -> bool {
    use propbet_measure::{Loads, Speed};
    let Ok(set) = set else { return true };
    set.points.iter().all(|p| {
        let speed = match p.speed {
            Speed::Airspeed(v) => v.mean,
            Speed::AdvanceRatio(j) => j,
        };
        let loads = match p.loads {
            Loads::Forces { thrust, torque } => finite(&[thrust.mean, torque.map_or(0.0, |q| q.mean)]),
            Loads::Coefficients { ct, cp } => finite(&[ct, cp]),
        };
        finite(&[p.omega.mean, speed]) && loads
    })
}

fn file(rel: &str) -> Vec<u8> {
    std::fs::read(repo().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

fn head(rel: &str, bytes: usize) -> Vec<u8> {
    let mut v = file(rel);
    v.truncate(bytes);
    v
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

#[test]
fn prop_files() {
    let seeds = [
        file("props/cam6x3/cam6x3.qprop"),
        file("props/photofoil_8x4.5/QProp_8x4_5.txt"),
        file("tests/data/bad_inputs/prop_R_metres_stations_cm.qprop"),
    ];
    fuzz("prop", &seeds, |b| {
        if let Ok((f, _)) = propbet_qprop::parse_prop(&text(b)) {
            // A file that reads also discretises or says why, into finite stations.
            if let Ok(rotor) = f
                .to_blade(propbet_qprop::RadiusReading::Documented)
                .to_rotor(propbet_bemt::Discretization::default())
            {
                return rotor.tip_radius.is_finite()
                    && rotor.blades.is_finite()
                    && rotor.stations.iter().all(|s| finite(&[s.r, s.dr, s.chord, s.beta]));
            }
        }
        true
    });
}

#[test]
fn motor_files() {
    let seeds = [
        file("props/motors/s400-6v-dd.motor"),
        file("../shared/reference/qprop/runs/s280-6v-dd"),
    ];
    fuzz("motor", &seeds, |b| {
        if let Ok(f) = propbet_motor::parse_motor(&text(b)) {
            // A motor that reads turns at 12 V or says it cannot, and its torque is a number.
            let m = f.motor;
            return match m.free_speed(12.0) {
                Some(w) => w.is_finite() && m.at(0.5 * w, 12.0).torque.is_finite(),
                None => true,
            };
        }
        true
    });
}

#[test]
fn airfoils() {
    let seeds = [file("props/airfoils/e63.dat"), file("props/airfoils/clarky.dat")];
    fuzz("airfoil", &seeds, |b| {
        if let Ok((mut a, _)) = propbet_polar::Airfoil::parse(&text(b), "fuzz.dat") {
            a.normalise();
            let _ = a.scale_thickness(0.08);
            return a.points.iter().all(|p| finite(p));
        }
        true
    });
}

fn small_stl_ascii() -> Vec<u8> {
    let mut s = String::from("solid fuzz\n");
    for k in 0..12 {
        let z = f64::from(k);
        s.push_str(&format!(
            "facet normal 0 0 1\nouter loop\nvertex {z} 0 0\nvertex 1 {z} 0\nvertex 0 1 {z}\nendloop\nendfacet\n"
        ));
    }
    s.push_str("endsolid fuzz\n");
    s.into_bytes()
}

fn small_stl_binary() -> Vec<u8> {
    let mut v = vec![0u8; 80];
    v.extend_from_slice(&12u32.to_le_bytes());
    for k in 0..12u32 {
        let mut tri = [0f32; 12];
        tri[3] = k as f32;
        tri[7] = 1.0;
        tri[11] = 1.0;
        for x in tri {
            v.extend_from_slice(&x.to_le_bytes());
        }
        v.extend_from_slice(&[0, 0]);
    }
    v
}

#[test]
fn stl() {
    fuzz(
        "stl",
        &[small_stl_ascii(), small_stl_binary()],
        |b| match propbet_geometry::mesh::read_stl(b, "fuzz.stl") {
            Ok(m) => m.vertices.iter().all(|v| finite(v.as_slice())),
            Err(_) => true,
        },
    );
}

#[test]
fn clouds() {
    let mut ply = String::from(
        "ply\nformat ascii 1.0\nelement vertex 20\nproperty float x\nproperty float y\nproperty float z\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n",
    );
    let mut xyz = String::new();
    let mut colmap = String::from("# 3D point list\n");
    for k in 0..20 {
        let x = f64::from(k) * 0.5;
        ply.push_str(&format!("{x} {} {} 200 100 {k}\n", x * 2.0, -x));
        xyz.push_str(&format!("{x} {} {} 10 20 30\n", x + 1.0, x * 3.0));
        colmap.push_str(&format!("{k} {x} {} {} 255 0 0 0.5 1 2\n", x - 1.0, x));
    }
    let seeds = [ply.into_bytes(), xyz.into_bytes(), colmap.into_bytes()];
    fuzz("cloud", &seeds, |b| {
        ["fuzz.ply", "fuzz.xyz", "points3D.txt"]
            .iter()
            .all(|name| match propbet_geometry::cloud::read_cloud(b, name) {
                Ok(c) => c.points.iter().all(|v| finite(v.as_slice())),
                Err(_) => true,
            })
    });
}

#[test]
fn thrust_stand_csv_and_column_maps() {
    let seeds = [
        file("tests/data/thrust_stand/series1520_no_torque.csv"),
        file("tests/data/thrust_stand/series1580_gf_steps.csv"),
        head("tests/data/thrust_stand/series1585_newton_steps.csv", 8000),
        file("tests/data/bad_inputs/stand_duplicated_header.csv"),
    ];
    fuzz("stand_csv", &seeds, |b| {
        measured_finite(propbet_measure::read(
            &text(b),
            &propbet_measure::ReadOptions::default(),
        ))
    });
    // As bytes (any encoding, any line end), every series: the Flight Stand and database
    // samples among the seeds.
    let bytes_seeds = [
        file("tests/data/thrust_stand/flight_stand_two_powertrains.csv"),
        file("tests/data/thrust_stand/tyto_database.csv"),
        file("tests/data/thrust_stand/series1580_gf_steps.csv"),
    ];
    fuzz("stand_bytes", &bytes_seeds, |b| {
        match propbet_measure::read_file(b, &propbet_measure::ReadOptions::default()) {
            Ok(sets) => sets.into_iter().all(|s| measured_finite(Ok(s))),
            Err(_) => true,
        }
    });
    let csv = "time_s,speed,force\n0,5000,1.0\n1,5000,1.1\n2,6000,1.5\n".to_string();
    let map = b"rpm = { column = \"speed\", unit = \"rpm\" }\nthrust = { column = \"force\", unit = \"N\" }\n".to_vec();
    fuzz("column_map", &[map], |b| {
        let opts = propbet_measure::ReadOptions {
            column_map: Some(text(b)),
            ..Default::default()
        };
        measured_finite(propbet_measure::read(&csv, &opts))
    });
}

#[test]
fn uiuc_files() {
    let seeds = [
        file("props/apcsf_10x4.7/uiuc/apcsf_10x4.7_static_kt0835.txt"),
        file("props/apcsf_10x4.7/uiuc/apcsf_10x4.7_kt0836_4014.txt"),
        file("tests/data/bad_inputs/uiuc_static_inf_hang.txt"),
    ];
    fuzz("uiuc", &seeds, |b| {
        let opts = propbet_measure::ReadOptions {
            name: Some("apcsf_10x4.7_kt0836_4014.txt".into()),
            ..Default::default()
        };
        measured_finite(propbet_measure::read(&text(b), &opts))
    });
    fuzz(
        "uiuc_geometry",
        &[file("props/apcsf_10x4.7/apcsf_10x4.7_geom.txt")],
        |b| match propbet_measure::uiuc::read_geometry(&text(b)) {
            Ok(rows) => rows.iter().all(|r| finite(&[r.r_r, r.c_r, r.beta])),
            Err(_) => true,
        },
    );
}

#[test]
fn apc_files() {
    fuzz(
        "pe0",
        &[file("tests/data/validate/pe0/9x47SF-PERF.PE0")],
        |b| match propbet_qprop::apc::read_pe0(&text(b), "fuzz.PE0") {
            Ok(p) => p.thickness.iter().all(|&(r, t)| finite(&[r, t])),
            Err(_) => true,
        },
    );
    fuzz("per3", &[head("tests/data/per3/PER3_10x47SF.dat", 12_000)], |b| {
        if let Ok(p) = propbet_qprop::apc::read_per3(&text(b), "fuzz.dat") {
            let _ = p.at(1500.0, 0.1);
        }
        true
    });
}

#[test]
fn case_files() {
    let seeds = [
        file("props/apcsf_10x4.7/case.toml"),
        file("props/cam6x3/case.toml"),
        file("props/photofoil_8x4.5/case.toml"),
    ];
    fuzz("case", &seeds, |b| {
        if let Ok(case) = toml::from_str::<propbet_pipeline::case::Case>(&text(b)) {
            let _ = case.plan(
                Path::new("case"),
                Path::new("out"),
                &propbet_settings::spec::XfoilProcessSpec::default(),
            );
        }
        true
    });
}

#[test]
fn user_effects() {
    fuzz("user_effects", &[file("docs/user_effects.toml")], |b| {
        let _ = propbet_effects::user::parse(&text(b), "fuzz.toml");
        true
    });
}

#[test]
fn polar_json() {
    // A small blade-polars file: two stations, two polars each.
    let polar = |re: f64| {
        let pts: Vec<String> = (-4..=8)
            .map(|a| {
                format!(
                    "{{\"alpha_deg\":{a},\"cl\":{},\"cd\":{},\"cdp\":0.005,\"cm\":-0.1,\"xtr_top\":0.5,\"xtr_bottom\":1.0}}",
                    0.4 + 0.1 * f64::from(a),
                    0.012 + 0.0004 * f64::from(a * a)
                )
            })
            .collect();
        format!(
            "{{\"re\":{re},\"mach\":0.05,\"ncrit\":5,\"points\":[{}],\"unconverged_deg\":[],\"faults\":[]}}",
            pts.join(",")
        )
    };
    let station = |r: f64| {
        format!(
            "{{\"r\":{r},\"chord\":0.02,\"re\":50000,\"re_range\":[40000,60000],\"mach\":0.05,\"alpha_deg\":3,\"alpha_range_deg\":[1,5],\"polars\":[{},{}],\"fit\":null,\"problem\":null}}",
            polar(39810.717),
            polar(63095.734)
        )
    };
    let json = format!(
        "{{\"format\":\"propbet-blade-polars-2\",\"geometry\":\"g\",\"airfoil\":\"a\",\"rpm\":[5000,6000],\"v\":[0,5],\"air\":[1.225,1.78e-5,340],\"stations\":[{},{}]}}",
        station(0.05),
        station(0.1)
    );
    assert!(propbet_polar::BladePolars::from_json(&json).is_ok(), "the seed reads");
    fuzz("polar_json", &[json.into_bytes()], |b| {
        if let Ok(p) = propbet_polar::BladePolars::from_json(&text(b)) {
            if let Ok((_, models)) = p.models() {
                use propbet_bemt::SectionAero;
                return models.iter().all(|m| {
                    let l = m.lift(0.05, 50_000.0, 0.01);
                    let d = m.drag(&propbet_bemt::DragInput {
                        alpha: 0.05,
                        cl: l.cl,
                        stalled: l.stalled,
                        re: 50_000.0,
                        mach: 0.1,
                    });
                    finite(&[l.cl, l.dcl_dalpha, d])
                });
            }
        }
        true
    });
}
