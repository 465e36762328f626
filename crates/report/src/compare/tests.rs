//! Unit tests of `compare.rs`.

use super::*;

/// A point of file `file` at `rpm` and `j` with measured and predicted CT.
fn pt(file: usize, rpm: f64, j: f64, ct: [f64; 2]) -> ComparedPoint {
    let mut p = ComparedPoint {
        file,
        rpm,
        j,
        ..Default::default()
    };
    p.measured.ct = Some(ct[0]);
    p.predicted.ct = Some(ct[1]);
    p
}

#[test]
fn speed_trends_read_the_static_rise_and_the_zero_thrust_j() {
    // A static test rising 20 % measured, 8 % predicted; two J sweeps whose measured
    // zero-thrust J falls 0.65 → 0.62 and the model's rises 0.61 → 0.63.
    let mut pts = vec![pt(0, 2500.0, 0.0, [0.10, 0.10]), pt(0, 6500.0, 0.0, [0.12, 0.108])];
    for (f, rpm, jm, jp) in [(1, 4000.0, 0.65, 0.61), (2, 6800.0, 0.62, 0.63)] {
        for j in [0.5, 0.7] {
            pts.push(pt(f, rpm, j, [0.3 * (jm - j), 0.3 * (jp - j)]));
        }
    }
    let t = speed_trends(&pts);
    assert_eq!(t.len(), 2, "{t:?}");
    assert!(
        t[0].starts_with("Static CT grows by +20.0 % from 2500 to 6500 rpm, faster than the model's (+8.0 %;"),
        "{t:?}"
    );
    assert!(
            t[1].starts_with("The J sweeps' zero-thrust J moves from 0.650 at 4000 rpm to 0.620 at 6800 rpm (-4.6 %); the model's from 0.610 to 0.630 (+3.3 %)"),
            "{t:?}"
        );
    assert!(t[1].contains("twists nose-down"), "{t:?}");
    // Both rising (0.65 → 0.66, 0.60 → 0.62), the model's 0.045 lower: an offset, not a trend.
    let mut offset = pts.clone();
    for p in offset.iter_mut().filter(|p| p.file == 2) {
        p.measured.ct = p.measured.ct.map(|c| c + 0.3 * 0.04);
        p.predicted.ct = p.predicted.ct.map(|c| c - 0.3 * 0.01);
    }
    for p in offset.iter_mut().filter(|p| p.file == 1) {
        p.predicted.ct = p.predicted.ct.map(|c| c - 0.3 * 0.01);
    }
    let t = speed_trends(&offset);
    assert!(
        !t[1].contains("nose-down") && t[1].contains("The model's is lower by 0.045"),
        "{t:?}"
    );
    // A static test alone spanning little RPM, and no sweeps: nothing to say.
    assert!(speed_trends(&pts[..1]).is_empty());
}
