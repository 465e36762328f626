//! Blade definition → mesh: NACA 4-digit sections (closed trailing edge) on cylinders,
//! stacked at a pitch axis, for tests with exact truth.
//!
//! A section point at chord fraction `xs` (0 at the leading edge) and thickness coordinate
//! `ys` (towards the suction side) lands on the unrolled cylinder at
//! `u = d cos(beta) - ys c sin(beta)`, `w = d sin(beta) + ys c cos(beta)` with
//! `d = (pitch_axis - xs) c`, then at angle `theta = theta_blade + u/r`, height `z = w`: the
//! leading edge is at +theta and higher z, as in the propeller frame.

use std::f64::consts::PI;

use nalgebra::{Matrix3, Vector3};

use crate::mesh::Mesh;

/// One defining station.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StationDef {
    /// Radius [mm].
    pub r: f64,
    /// Chord [mm].
    pub chord: f64,
    /// Blade angle to the rotation plane [deg].
    pub beta: f64,
    /// Thickness ratio t/c.
    pub t_c: f64,
    /// Maximum camber / chord.
    pub camber: f64,
    /// Chord fraction of the maximum camber.
    pub camber_pos: f64,
}

/// A propeller to generate.
#[derive(Debug, Clone, PartialEq)]
pub struct BladeDef {
    /// Number of blades.
    pub blades: usize,
    /// Stations, radius increasing (root first, tip last).
    pub stations: Vec<StationDef>,
    /// Chord fraction of the stacking (pitch) axis.
    pub pitch_axis: f64,
    /// A hub cylinder (radius, length) [mm] about the axis, apart from the blades.
    pub hub: Option<(f64, f64)>,
}

/// NACA 4-digit upper and lower surface at chord fraction `x`: ((xu, yu), (xl, yl)).
pub fn naca4(x: f64, t: f64, m: f64, p: f64) -> ((f64, f64), (f64, f64)) {
    let yt = 5.0 * t * (0.2969 * x.sqrt() - 0.1260 * x - 0.3516 * x * x + 0.2843 * x.powi(3) - 0.1036 * x.powi(4));
    let (yc, dyc) = if m <= 0.0 || p <= 0.0 {
        (0.0, 0.0)
    } else if x < p {
        (m / (p * p) * (2.0 * p * x - x * x), 2.0 * m / (p * p) * (p - x))
    } else {
        (
            m / ((1.0 - p) * (1.0 - p)) * (1.0 - 2.0 * p + 2.0 * p * x - x * x),
            2.0 * m / ((1.0 - p) * (1.0 - p)) * (p - x),
        )
    };
    let th = dyc.atan();
    (
        (x - yt * th.sin(), yc + yt * th.cos()),
        (x + yt * th.sin(), yc - yt * th.cos()),
    )
}

impl BladeDef {
    /// The definition interpolated linearly at radius `r`.
    pub fn at(&self, r: f64) -> StationDef {
        let s = &self.stations;
        let i = s
            .iter()
            .position(|x| x.r >= r)
            .unwrap_or(s.len() - 1)
            .clamp(1, s.len() - 1);
        let (a, b) = (s[i - 1], s[i]);
        let f = ((r - a.r) / (b.r - a.r)).clamp(0.0, 1.0);
        let l = |x: f64, y: f64| x + f * (y - x);
        StationDef {
            r,
            chord: l(a.chord, b.chord),
            beta: l(a.beta, b.beta),
            t_c: l(a.t_c, b.t_c),
            camber: l(a.camber, b.camber),
            camber_pos: l(a.camber_pos, b.camber_pos),
        }
    }

    /// The closed loop of one section (TE, upper surface to the LE, lower surface back) on its
    /// cylinder, for blade `b`; `n` points per surface (cosine spacing).
    fn section_loop(&self, st: &StationDef, b: usize, n: usize) -> Vec<Vector3<f64>> {
        let theta_b = 2.0 * PI * b as f64 / self.blades as f64;
        let (sb, cb) = st.beta.to_radians().sin_cos();
        let place = |xs: f64, ys: f64| {
            let d = (self.pitch_axis - xs) * st.chord;
            let u = d * cb - ys * st.chord * sb;
            let w = d * sb + ys * st.chord * cb;
            let th = theta_b + u / st.r;
            Vector3::new(st.r * th.cos(), st.r * th.sin(), w)
        };
        let xs: Vec<f64> = (0..=n)
            .map(|k| 0.5 * (1.0 - (PI * k as f64 / n as f64).cos()))
            .collect();
        let mut pts = Vec::with_capacity(2 * n);
        for &x in xs.iter().rev() {
            let ((xu, yu), _) = naca4(x, st.t_c, st.camber, st.camber_pos);
            pts.push(place(xu, yu));
        }
        for &x in xs.iter().skip(1).take(n - 1) {
            let (_, (xl, yl)) = naca4(x, st.t_c, st.camber, st.camber_pos);
            pts.push(place(xl, yl));
        }
        pts
    }

    /// The mesh: `spans` sections from root to tip per blade, `n` points per surface, closed
    /// with flat caps at root and tip.
    pub fn to_mesh(&self, spans: usize, n: usize) -> Mesh {
        let mut m = Mesh::default();
        let (r0, r1) = (self.stations[0].r, self.stations[self.stations.len() - 1].r);
        for b in 0..self.blades {
            let loops: Vec<Vec<Vector3<f64>>> = (0..=spans)
                .map(|k| {
                    let r = r0 + (r1 - r0) * k as f64 / spans as f64;
                    self.section_loop(&self.at(r), b, n)
                })
                .collect();
            let len = loops[0].len();
            for w in loops.windows(2) {
                for i in 0..len {
                    let j = (i + 1) % len;
                    m.push_triangle(w[0][i], w[1][i], w[1][j]);
                    m.push_triangle(w[0][i], w[1][j], w[0][j]);
                }
            }
            for (l, flip) in [(&loops[0], true), (&loops[spans], false)] {
                let c = l.iter().sum::<Vector3<f64>>() / len as f64;
                for i in 0..len {
                    let j = (i + 1) % len;
                    if flip {
                        m.push_triangle(c, l[j], l[i]);
                    } else {
                        m.push_triangle(c, l[i], l[j]);
                    }
                }
            }
        }
        if let Some((r, len)) = self.hub {
            // A closed cylinder of 96 facets with fan caps.
            let n = 96;
            let at = |k: usize, z: f64| {
                let t = 2.0 * PI * k as f64 / n as f64;
                Vector3::new(r * t.cos(), r * t.sin(), z)
            };
            let (lo, hi) = (-0.5 * len, 0.5 * len);
            for k in 0..n {
                let (a0, a1, b0, b1) = (at(k, lo), at(k + 1, lo), at(k, hi), at(k + 1, hi));
                m.push_triangle(a0, a1, b1);
                m.push_triangle(a0, b1, b0);
                m.push_triangle(Vector3::new(0.0, 0.0, lo), a1, a0);
                m.push_triangle(Vector3::new(0.0, 0.0, hi), b0, b1);
            }
        }
        m
    }
}

/// How a synthetic coloured cloud is made from a blade definition.
#[derive(Debug, Clone, PartialEq)]
pub struct CloudSpec {
    /// Points on the propeller.
    pub blade_points: usize,
    /// Gaussian noise along each coordinate [mm].
    pub noise: f64,
    /// Fraction of all points that are background (green table plane and halo).
    pub background: f64,
    /// Reference box: edge lengths [mm], its centre in the propeller frame [mm], points on it.
    pub reference_box: Option<([f64; 3], [f64; 3], usize)>,
    /// Pose: rotation and translation [mm] (x_posed = R x + t).
    pub rotation: Matrix3<f64>,
    /// Translation [mm].
    pub translation: Vector3<f64>,
    /// Unknown scale applied last (x_cloud = s (R x + t)).
    pub scale: f64,
    /// Random seed.
    pub seed: u64,
}

/// Colours of the generated cloud: orange blade with black speckle, grey and blue box faces,
/// green background.
pub const SYNTH_COLOURS: [(&str, [u8; 3]); 5] = [
    ("orange", [230, 100, 10]),
    ("black", [0, 0, 0]),
    ("grey", [200, 200, 200]),
    ("blue", [20, 20, 200]),
    ("green", [30, 150, 40]),
];

impl BladeDef {
    /// A noisy coloured point cloud of the propeller (sampled on its mesh), with a reference
    /// box, background points, a pose and a scale.
    pub fn to_cloud(&self, spec: &CloudSpec) -> crate::cloud::Cloud {
        use rand::{RngExt, SeedableRng};
        use rand_distr::{Distribution, Normal};
        let mut rng = rand::rngs::StdRng::seed_from_u64(spec.seed);
        let noise = Normal::new(0.0, spec.noise.max(0.0)).unwrap_or_else(|_| Normal::new(0.0, 0.0).expect("zero sd"));
        let mesh = self.to_mesh(80, 60);
        let areas: Vec<f64> = (0..mesh.triangles.len())
            .map(|i| {
                let [a, b, c] = mesh.corners(i);
                0.5 * (b - a).cross(&(c - a)).norm()
            })
            .collect();
        let mut cum = Vec::with_capacity(areas.len());
        let mut acc = 0.0;
        for a in &areas {
            acc += a;
            cum.push(acc);
        }
        let jitter = |rng: &mut rand::rngs::StdRng, c: [u8; 3]| {
            c.map(|x| (x as f64 + rng.random_range(-12.0..12.0)).clamp(0.0, 255.0) as u8)
        };
        let (mut pts, mut cols) = (Vec::new(), Vec::new());
        for _ in 0..spec.blade_points {
            let pick = rng.random_range(0.0..acc);
            let k = cum.partition_point(|&c| c < pick).min(areas.len() - 1);
            let [a, b, c] = mesh.corners(k);
            let (mut u, mut v) = (rng.random_range(0.0..1.0), rng.random_range(0.0..1.0));
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            let p = a + u * (b - a) + v * (c - a);
            let p = p + Vector3::new(noise.sample(&mut rng), noise.sample(&mut rng), noise.sample(&mut rng));
            // Speckle: black dots on a 2 mm grid.
            let speck = ((p.x / 2.0).floor() as i64 + (p.y / 2.0).floor() as i64 + (p.z / 2.0).floor() as i64) % 3 == 0;
            pts.push(p);
            cols.push(jitter(
                &mut rng,
                if speck { SYNTH_COLOURS[1].1 } else { SYNTH_COLOURS[0].1 },
            ));
        }
        if let Some((dims, centre, n)) = spec.reference_box {
            let c = Vector3::from(centre);
            let d = Vector3::from(dims);
            for i in 0..n {
                let axis = i % 3;
                let side = if (i / 3) % 2 == 0 { -0.5 } else { 0.5 };
                let mut p = Vector3::new(
                    rng.random_range(-0.5..0.5),
                    rng.random_range(-0.5..0.5),
                    rng.random_range(-0.5..0.5),
                );
                p[axis] = side;
                let p = c
                    + p.component_mul(&d)
                    + Vector3::new(noise.sample(&mut rng), noise.sample(&mut rng), noise.sample(&mut rng));
                pts.push(p);
                cols.push(jitter(
                    &mut rng,
                    if axis == 2 {
                        SYNTH_COLOURS[3].1
                    } else {
                        SYNTH_COLOURS[2].1
                    },
                ));
            }
        }
        // Background: a table plane below the box and a halo near the blades.
        let fg = pts.len();
        let n_bg = (spec.background / (1.0 - spec.background).max(1e-9) * fg as f64) as usize;
        let tip = self.stations.last().map_or(100.0, |s| s.r);
        for i in 0..n_bg {
            let p = if i % 2 == 0 {
                Vector3::new(
                    rng.random_range(-1.2..1.2) * tip,
                    rng.random_range(-1.2..1.2) * tip,
                    -0.55 * tip,
                )
            } else {
                let q = pts[rng.random_range(0..fg)];
                q + Vector3::new(
                    rng.random_range(-5.0..5.0),
                    rng.random_range(-5.0..5.0),
                    rng.random_range(-5.0..5.0),
                )
            };
            pts.push(p);
            cols.push(jitter(&mut rng, SYNTH_COLOURS[4].1));
        }
        let points = pts
            .into_iter()
            .map(|p| spec.scale * (spec.rotation * p + spec.translation))
            .collect();
        crate::cloud::Cloud {
            points,
            colors: Some(cols),
        }
    }
}

/// An APC-E-10x5-like blade (R = 127 mm) for tests and examples: chord and angle of the UIUC style table, NACA
/// sections 10 % -> 7 % thick, 5 % -> 4 % camber at 45 %.
pub fn apce_like(blades: usize) -> BladeDef {
    let rows = [
        (0.15, 0.138, 37.9),
        (0.25, 0.167, 36.0),
        (0.35, 0.185, 30.6),
        (0.45, 0.190, 26.2),
        (0.55, 0.184, 22.6),
        (0.65, 0.168, 19.8),
        (0.75, 0.144, 17.6),
        (0.85, 0.112, 15.8),
        (0.95, 0.075, 14.3),
        (1.00, 0.050, 13.6),
    ];
    let big_r = 127.0;
    BladeDef {
        blades,
        pitch_axis: 0.3,
        hub: Some((7.0, 16.0)),
        stations: rows
            .iter()
            .map(|&(x, c, b)| StationDef {
                r: x * big_r,
                chord: c * big_r,
                beta: b,
                t_c: 0.10 - 0.03 * (x - 0.15) / 0.85,
                camber: 0.05 - 0.01 * (x - 0.15) / 0.85,
                camber_pos: 0.45,
            })
            .collect(),
    }
}
