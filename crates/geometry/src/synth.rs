//! Blade definition → mesh: NACA 4-digit sections (closed trailing edge) on cylinders,
//! stacked at a pitch axis, for tests with exact truth.
//!
//! A section point at chord fraction `xs` (0 at the leading edge) and thickness coordinate
//! `ys` (towards the suction side) lands on the unrolled cylinder at
//! `u = d cos(beta) - ys c sin(beta)`, `w = d sin(beta) + ys c cos(beta)` with
//! `d = (pitch_axis - xs) c`, then at angle `theta = theta_blade + u/r`, height `z = w`: the
//! leading edge is at +theta and higher z, as in the propeller frame.

use std::f64::consts::PI;

use nalgebra::Vector3;

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
        m
    }
}
