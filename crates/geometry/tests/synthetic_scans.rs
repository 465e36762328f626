//! Generated propellers (meshes and noisy coloured clouds with a reference box, random pose
//! and scale): the pipeline recovers the geometry they were made with (the acceptance numbers of scanning).

use nalgebra::{Rotation3, Vector3};
use propbet_geometry::align::auto_align;
use propbet_geometry::cloud::read_cloud;
use propbet_geometry::cloud::to_ply;
use propbet_geometry::mesh::read_stl;
use propbet_geometry::scan::{scan_cloud, scan_mesh, BoxSpec, Geometry, Manual, ScanOptions, SectionKind};
use propbet_geometry::synth::{apce_like, BladeDef, CloudSpec, SYNTH_COLOURS};

fn rms(v: &[f64]) -> f64 {
    (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt()
}

/// Errors against the definition: (beta deg, chord relative, t/c absolute) per station.
fn errors(geo: &Geometry, def: &BladeDef) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let (mut b, mut c, mut t) = (Vec::new(), Vec::new(), Vec::new());
    for s in &geo.stations {
        // The definition is in mm and degrees.
        let truth = def.at(1000.0 * s.r);
        b.push(s.beta.to_degrees() - truth.beta);
        c.push(1000.0 * s.chord / truth.chord - 1.0);
        t.push(s.t_c - truth.t_c);
    }
    (b, c, t)
}

fn stations() -> Vec<f64> {
    (0..15).map(|k| 0.2 + 0.05 * k as f64).collect()
}

#[test]
fn posed_meshes_give_the_geometry_they_were_made_with() {
    for (blades, seed) in [(2usize, 1.0f64), (3, 2.0)] {
        let def = apce_like(blades);
        let mut mesh = def.to_mesh(60, 60);
        let axis = nalgebra::Unit::new_normalize(Vector3::new(0.3 * seed, 1.0, -0.4));
        let rot = Rotation3::from_axis_angle(&axis, 0.7 * seed);
        mesh.transform(rot.matrix(), &Vector3::new(12.0, -40.0, 7.5), 1.0);
        let mesh = read_stl(&mesh.to_stl(), "synthetic.stl").unwrap();
        let opts = ScanOptions {
            stations: stations(),
            ..ScanOptions::default()
        };
        let geo = scan_mesh(&mesh, &opts).unwrap();
        assert_eq!(geo.blades, blades);
        assert!(geo.failed.is_empty(), "{:?}", geo.failed);
        let (e_beta, e_chord, e_tc) = errors(&geo, &def);
        eprintln!(
            "{blades} blades: twist RMSE {:.4} deg, chord RMSE {:.4} %, t/c max error {:.5}, hub {:?} (7), tip {:.4} (127)",
            rms(&e_beta),
            100.0 * rms(&e_chord),
            e_tc.iter().map(|x| x.abs()).fold(0.0, f64::max),
            geo.hub_radius,
            geo.tip_radius
        );
        // The acceptance numbers.
        assert!(rms(&e_beta) <= 0.1, "twist RMSE {} deg: {e_beta:?}", rms(&e_beta));
        assert!(rms(&e_chord) <= 0.005, "chord RMSE {}: {e_chord:?}", rms(&e_chord));
        assert!(e_tc.iter().all(|x| x.abs() <= 0.002), "t/c errors {e_tc:?}");
        assert!(
            (geo.hub_radius.unwrap() - 7.0e-3).abs() <= 0.2e-3,
            "hub {:?}",
            geo.hub_radius
        );
        assert!((geo.tip_radius - 127.0e-3).abs() <= 0.2e-3, "tip {}", geo.tip_radius);
        blade_labels_match_the_construction(&geo, &mesh, blades);
    }
}

/// `to_mesh` writes the blades one after the other and the hub last: every blade's triangles
/// must share one label, distinct blades distinct labels, and the hub must be hub.
fn blade_labels_match_the_construction(geo: &Geometry, mesh: &propbet_geometry::Mesh, blades: usize) {
    let hub_triangles = 96 * 4;
    let per_blade = (mesh.triangles.len() - hub_triangles) / blades;
    let labels = &geo.labelled.blade;
    assert_eq!(labels.len(), mesh.triangles.len());
    let mut seen = Vec::new();
    for b in 0..blades {
        let part = &labels[b * per_blade..(b + 1) * per_blade];
        let mut count = vec![0usize; blades];
        for k in part.iter().flatten() {
            count[*k as usize] += 1;
        }
        let (best, n) = count.iter().enumerate().max_by_key(|c| c.1).unwrap();
        let wrong = part.iter().filter(|l| l.is_some_and(|k| k as usize != best)).count();
        eprintln!("  blade {b}: label {best} on {n} of {per_blade} triangles, {wrong} on other blades");
        assert_eq!(wrong, 0, "blade {b}: {wrong} triangles labelled as another blade");
        assert!(
            *n as f64 >= 0.97 * per_blade as f64,
            "blade {b}: only {n} of {per_blade} labelled"
        );
        seen.push(best);
    }
    seen.sort_unstable();
    seen.dedup();
    assert_eq!(seen.len(), blades, "two blades got the same label");
    let hub = &labels[blades * per_blade..];
    assert!(hub.iter().all(|l| l.is_none()), "hub triangles labelled as blade");
}

fn cloud_spec(points: usize, seed: u64) -> CloudSpec {
    let axis = nalgebra::Unit::new_normalize(Vector3::new(0.2, -1.0, 0.7));
    CloudSpec {
        blade_points: points,
        noise: 0.05,
        background: 0.2,
        reference_box: Some(([50.8, 48.26, 50.8], [0.0, 0.0, -40.0], points / 4)),
        rotation: *Rotation3::from_axis_angle(&axis, 2.1).matrix(),
        translation: Vector3::new(-160.0, 190.0, 105.0),
        scale: 0.756,
        seed,
    }
}

fn colour(name: &str) -> [u8; 3] {
    SYNTH_COLOURS.iter().find(|c| c.0 == name).unwrap().1
}

fn cloud_options() -> ScanOptions {
    ScanOptions {
        stations: stations(),
        blade_colours: vec![colour("orange"), colour("black")],
        reference_box: Some(BoxSpec {
            dims: [50.8e-3, 48.26e-3, 50.8e-3],
            offset: [0.0, 0.0, -40.0e-3],
            colours: vec![colour("grey"), colour("blue")],
            seeds: Vec::new(),
        }),
        ..ScanOptions::default()
    }
}

#[test]
fn noisy_cloud_with_a_reference_box_and_unknown_scale() {
    let def = apce_like(2);
    let cloud = def.to_cloud(&cloud_spec(400_000, 7));
    // Through the PLY writer and reader, as a user's file would come.
    let cloud = read_cloud(&to_ply(&cloud, None), "synthetic.ply").unwrap();
    let geo = scan_cloud(&cloud, &cloud_options()).unwrap();
    let scale = 1000.0 * geo.box_fit.as_ref().unwrap().scale;
    let (e_beta, e_chord, _) = errors(&geo, &def);
    eprintln!(
        "cloud: scale error {:.4} %, twist max {:.3} deg, chord max {:.3} %, notes {:?}",
        100.0 * (scale * 0.756 - 1.0),
        e_beta.iter().map(|x| x.abs()).fold(0.0, f64::max),
        100.0 * e_chord.iter().map(|x| x.abs()).fold(0.0, f64::max),
        geo.notes
    );
    assert!(geo.failed.is_empty(), "{:?}", geo.failed);
    assert!((scale * 0.756 - 1.0).abs() <= 0.002, "scale {scale}");
    assert!(e_beta.iter().all(|x| x.abs() <= 0.3), "twist errors {e_beta:?}");
    assert!(e_chord.iter().all(|x| x.abs() <= 0.01), "chord errors {e_chord:?}");
    // Points by blade: the two blades are alike, so their counts must be too.
    let (per_blade, hub) = geo.labelled.counts(2);
    eprintln!("cloud labels: {per_blade:?} per blade, {hub} hub");
    let ratio = per_blade[0] as f64 / per_blade[1] as f64;
    assert!((ratio - 1.0).abs() < 0.05, "blade point counts {per_blade:?}");
    // The hub (7 mm, 16 mm long: 1,010 mm^2 of surface against about 5,400 mm^2 a blade) holds
    // about a fifth of a blade's points; its radius is its wall's.
    assert!(hub < (2 * per_blade[0]) / 5, "hub {hub} of {per_blade:?}");
    let hub_mm = geo.hub_radius.unwrap() * 1000.0;
    assert!((hub_mm - 7.0).abs() <= 0.3, "hub radius {hub_mm} mm (truth 7)");
    let c = geo.colour.as_ref().unwrap();
    assert!(c.kept < c.total && c.threshold > 20.0 && c.threshold < 150.0, "{c:?}");
    // The same with the faces given by one seed point each (face centres, posed and scaled).
    let spec = cloud_spec(400_000, 7);
    let mut opts = cloud_options();
    let seeds: Vec<Vector3<f64>> = (0..6)
        .map(|k| {
            let mut p = Vector3::new(0.0, 0.0, -40.0);
            p[k % 3] += if k < 3 { 25.0 } else { -24.0 };
            spec.scale * (spec.rotation * p + spec.translation)
        })
        .collect();
    if let Some(b) = opts.reference_box.as_mut() {
        b.seeds = seeds;
    }
    let seeded = scan_cloud(&cloud, &opts).unwrap();
    let s2 = 1000.0 * seeded.box_fit.as_ref().unwrap().scale;
    assert!((s2 * 0.756 - 1.0).abs() <= 0.002, "seeded scale {s2}");
}

#[test]
fn a_sparse_station_is_reported_and_the_others_kept() {
    let def = apce_like(2);
    let cloud = def.to_cloud(&cloud_spec(40_000, 3));
    let mut opts = cloud_options();
    opts.stations = vec![0.3, 0.5, 0.7, 0.99];
    opts.slab_points = 0;
    let geo = scan_cloud(&cloud, &opts).unwrap();
    assert_eq!(geo.stations.len(), 3, "{:?}", geo.failed);
    assert_eq!(geo.failed.len(), 1);
    assert!(geo.failed[0].reason.contains("too sparse"), "{:?}", geo.failed);
}

#[test]
fn not_a_propeller_has_no_rotational_symmetry() {
    // One blade alone.
    let one = apce_like(1).to_mesh(20, 20);
    let e = auto_align(&one).unwrap_err().to_string();
    assert!(e.starts_with("no rotational symmetry"), "{e}");
    // A cube: no axis stands out.
    let mut cube = propbet_geometry::Mesh::default();
    let v = |x: f64, y: f64, z: f64| Vector3::new(x, y, z);
    for (a, b, c, d) in [
        (v(0., 0., 0.), v(1., 0., 0.), v(1., 1., 0.), v(0., 1., 0.)),
        (v(0., 0., 1.), v(1., 0., 1.), v(1., 1., 1.), v(0., 1., 1.)),
        (v(0., 0., 0.), v(1., 0., 0.), v(1., 0., 1.), v(0., 0., 1.)),
        (v(0., 1., 0.), v(1., 1., 0.), v(1., 1., 1.), v(0., 1., 1.)),
        (v(0., 0., 0.), v(0., 1., 0.), v(0., 1., 1.), v(0., 0., 1.)),
        (v(1., 0., 0.), v(1., 1., 0.), v(1., 1., 1.), v(1., 0., 1.)),
    ] {
        cube.push_triangle(a, b, c);
        cube.push_triangle(a, c, d);
    }
    let e = auto_align(&cube).unwrap_err().to_string();
    assert!(e.contains("no rotational symmetry") && e.contains("not flat"), "{e}");
}

#[test]
fn manual_alignment_and_planar_sections() {
    let def = apce_like(2);
    // In its own frame, then scaled to centimetres: the manual scale brings it back to mm.
    let mut mesh = def.to_mesh(60, 60);
    mesh.transform(&nalgebra::Matrix3::identity(), &Vector3::zeros(), 0.1);
    let opts = ScanOptions {
        stations: vec![0.4, 0.6, 0.8],
        manual: Some(Manual {
            root: Vector3::new(2.0, 0.0, 0.0),
            tip: Vector3::new(12.7, 0.0, 0.0),
            origin: Some(Vector3::zeros()),
            rotate: [0.0, 0.0, 0.0],
            scale: 0.01,
        }),
        ..ScanOptions::default()
    };
    let geo = scan_mesh(&mesh, &opts).unwrap();
    assert_eq!(geo.blades, 2);
    assert!((geo.tip_radius - 127.0e-3).abs() < 0.2e-3, "{}", geo.tip_radius);
    let (e_beta, e_chord, _) = errors(&geo, &def);
    assert!(
        e_beta.iter().all(|x| x.abs() < 0.1) && e_chord.iter().all(|x| x.abs() < 0.005),
        "{e_beta:?} {e_chord:?}"
    );
    // Planar sections (x = r) of the same blade: the chord line seen in the plane is longer
    // than on the cylinder and its angle smaller; both close where the blade is narrow
    // against the radius.
    let planar = scan_mesh(
        &mesh,
        &ScanOptions {
            kind: SectionKind::Planar,
            ..opts
        },
    )
    .unwrap();
    for (p, c) in planar.stations.iter().zip(&geo.stations) {
        assert!(
            p.chord >= c.chord * 0.99 && p.chord < c.chord * 1.1,
            "{} vs {}",
            p.chord,
            c.chord
        );
        assert!(
            (p.beta - c.beta).abs() < 3f64.to_radians(),
            "{} vs {}",
            p.beta.to_degrees(),
            c.beta.to_degrees()
        );
    }
}

#[test]
fn a_cloud_without_a_scale_says_the_millimetres_are_assumed() {
    let cloud = apce_like(2).to_cloud(&cloud_spec(200_000, 5));
    let opts = ScanOptions {
        reference_box: None,
        ..cloud_options()
    };
    let assumed = scan_cloud(&cloud, &opts).unwrap();
    assert!(
        assumed
            .notes
            .iter()
            .any(|n| n.starts_with("SCALE ASSUMED: 1 file unit = 1 mm")),
        "{:?}",
        assumed.notes
    );
    let given = scan_cloud(
        &cloud,
        &ScanOptions {
            scale_given: true,
            ..opts
        },
    )
    .unwrap();
    assert!(
        !given.notes.iter().any(|n| n.contains("SCALE ASSUMED")),
        "{:?}",
        given.notes
    );
}

/// On a sparse cloud the hub radius came out as 1.31 mm for a 6 mm hub. The hub's end
/// caps put few points in a thin cylinder cut at small radii, so a ring near the axis can look
/// closed and the next one open; the hub is the outermost closed ring, where its wall is.
#[test]
fn the_hub_radius_of_a_sparse_cloud_is_its_wall() {
    for (seed, points) in [(11, 60_000), (12, 90_000), (13, 120_000)] {
        let def = BladeDef {
            hub: Some((6.0, 10.0)),
            ..apce_like(2)
        };
        let cloud = def.to_cloud(&cloud_spec(points, seed));
        let geo = scan_cloud(&cloud, &cloud_options()).unwrap();
        let hub_mm = geo.hub_radius.unwrap() * 1000.0;
        assert!(
            (hub_mm - 6.0).abs() <= 0.3,
            "seed {seed}, {points} points: hub {hub_mm} mm (truth 6.0)"
        );
    }
}
