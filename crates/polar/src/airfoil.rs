//! Airfoil contours: reading (Selig, Lednicer, plain), checking, writing (Selig), normalising,
//! repaneling, the NACA 4-digit generator, thickness scaling and blending.
//!
//! Internally a contour is always in Selig order: trailing edge, upper surface, leading edge,
//! lower surface, back to the trailing edge (counter-clockwise with x aft and y up).

use std::fmt::Write;

use propbet_bemt::spline::DrelaSpline;
use thiserror::Error;

/// A closed (or blunt-trailing-edge) airfoil contour in Selig order.
#[derive(Debug, Clone, PartialEq)]
pub struct Airfoil {
    /// Name from the file's first line (or given).
    pub name: String,
    /// Contour points, Selig order.
    pub points: Vec<[f64; 2]>,
}

/// What was repaired while reading a file, worth telling the user.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Repair(pub String);

/// A coordinate file or contour that cannot be used.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum AirfoilError {
    /// A line that is neither the name nor two numbers.
    #[error("{source_name}, line {line}: '{text}' is not an `x y` pair of numbers")]
    BadLine {
        /// File or origin.
        source_name: String,
        /// One-based line number.
        line: usize,
        /// The line, as an excerpt ([`propbet_bemt::units::excerpt`]).
        text: String,
    },
    /// A Lednicer file whose point counts do not match its data.
    #[error("{source_name}: Lednicer header announces {upper} + {lower} points, the file has {found}")]
    LednicerCounts {
        /// File or origin.
        source_name: String,
        /// Announced upper-surface points.
        upper: usize,
        /// Announced lower-surface points.
        lower: usize,
        /// Points found.
        found: usize,
    },
    /// The contour itself is unusable.
    #[error("{source_name}: {reason}")]
    BadContour {
        /// File or origin.
        source_name: String,
        /// Why.
        reason: String,
    },
    /// An argument out of range (thickness, NACA digits, point count, blend fraction).
    #[error("{0}")]
    BadArgument(String),
}

fn bad_contour(source_name: &str, reason: impl Into<String>) -> AirfoilError {
    AirfoilError::BadContour {
        source_name: source_name.to_string(),
        reason: reason.into(),
    }
}

/// Largest trailing-edge gap, as a fraction of the chord, taken for a blunt trailing edge; a
/// wider gap is an open contour.
const MAX_TE_GAP: f64 = 0.05;

impl Airfoil {
    /// Reads a coordinate file: Selig (name, then x y from the trailing edge round to the
    /// trailing edge), Lednicer (name, `NU NL`, upper surface leading to trailing edge, lower
    /// surface likewise) or plain pairs without a name. Blank lines and `#` comments are skipped,
    /// commas and tabs separate numbers. The result is checked ([`Airfoil::check`]) and repaired
    /// where the repair is unambiguous: duplicate consecutive points removed, clockwise order
    /// reversed, a missing closing trailing-edge point added (e63.dat).
    pub fn parse(text: &str, source_name: &str) -> Result<(Airfoil, Vec<Repair>), AirfoilError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut name = None;
        let mut pairs: Vec<(usize, [f64; 2])> = Vec::new();
        for (i, raw) in text.lines().enumerate() {
            let line = raw.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            let fields: Vec<&str> = line
                .split(|c: char| c.is_whitespace() || c == ',')
                .filter(|f| !f.is_empty())
                .collect();
            let nums: Option<Vec<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
            match nums {
                Some(v) if v.len() == 2 => pairs.push((i + 1, [v[0], v[1]])),
                _ if name.is_none() && pairs.is_empty() => name = Some(line.to_string()),
                _ => {
                    return Err(AirfoilError::BadLine {
                        source_name: source_name.to_string(),
                        line: i + 1,
                        text: propbet_bemt::units::excerpt(raw),
                    })
                }
            }
        }
        if let Some((line, p)) = pairs.iter().find(|(_, p)| !(p[0].is_finite() && p[1].is_finite())) {
            return Err(AirfoilError::BadLine {
                source_name: source_name.to_string(),
                line: *line,
                text: format!("{} {}", p[0], p[1]),
            });
        }
        let name = name.unwrap_or_else(|| source_name.to_string());
        let mut repairs = Vec::new();
        let points: Vec<[f64; 2]> = match pairs.first() {
            Some((_, [nu, nl])) if *nu >= 2.0 && *nl >= 2.0 && nu.fract() == 0.0 && nl.fract() == 0.0 => {
                let (nu, nl) = (*nu as usize, *nl as usize);
                let rest: Vec<[f64; 2]> = pairs[1..].iter().map(|(_, p)| *p).collect();
                // Counts as large as 1e20 saturate to usize::MAX: compared without overflow.
                if nu.checked_add(nl) != Some(rest.len()) {
                    return Err(AirfoilError::LednicerCounts {
                        source_name: source_name.to_string(),
                        upper: nu,
                        lower: nl,
                        found: rest.len(),
                    });
                }
                repairs.push(Repair(
                    "read as Lednicer format (upper and lower surface from the leading edge)".into(),
                ));
                let mut pts: Vec<[f64; 2]> = rest[..nu].iter().rev().copied().collect();
                let lower = &rest[nu..];
                let skip = usize::from(dist(lower[0], pts[pts.len() - 1]) < 1e-9);
                pts.extend_from_slice(&lower[skip..]);
                pts
            }
            _ => pairs.iter().map(|(_, p)| *p).collect(),
        };
        let mut foil = Airfoil { name, points };
        foil.repair(source_name, &mut repairs)?;
        foil.check(source_name)?;
        Ok((foil, repairs))
    }

    fn repair(&mut self, source_name: &str, repairs: &mut Vec<Repair>) -> Result<(), AirfoilError> {
        let before = self.points.len();
        self.points.dedup_by(|a, b| dist(*a, *b) < 1e-12);
        if self.points.len() != before {
            repairs.push(Repair(format!(
                "removed {} repeated point(s)",
                before - self.points.len()
            )));
        }
        if self.points.len() < 10 {
            return Err(bad_contour(
                source_name,
                format!("{} points; an airfoil needs at least 10", self.points.len()),
            ));
        }
        if signed_area(&self.points) < 0.0 {
            self.points.reverse();
            repairs.push(Repair("reversed clockwise point order to Selig order".into()));
        }
        // A missing closing point: the ends differ mostly along x, not across a blunt edge.
        let (first, last) = (self.points[0], self.points[self.points.len() - 1]);
        let gap = dist(first, last);
        let chord = self.chord_estimate();
        if gap > 1e-12 && gap < MAX_TE_GAP * chord && (first[0] - last[0]).abs() > 0.5 * gap {
            let te = if first[0] >= last[0] { first } else { last };
            if te == first {
                self.points.push(first);
            } else {
                self.points.insert(0, last);
            }
            repairs.push(Repair(format!("closed the trailing edge at ({}, {})", te[0], te[1])));
        }
        Ok(())
    }

    /// Checks the contour: at least 10 finite points, non-zero area, a trailing-edge gap of at
    /// most 5 % of the chord, a leading edge between the two surfaces, no self-intersection.
    pub fn check(&self, source_name: &str) -> Result<(), AirfoilError> {
        let p = &self.points;
        if p.len() < 10 {
            return Err(bad_contour(
                source_name,
                format!("{} points; an airfoil needs at least 10", p.len()),
            ));
        }
        if let Some(i) = p.iter().position(|q| !(q[0].is_finite() && q[1].is_finite())) {
            return Err(bad_contour(source_name, format!("point {} is not finite", i + 1)));
        }
        let chord = self.chord_estimate();
        if chord.is_nan() || chord <= 0.0 {
            return Err(bad_contour(source_name, "all points coincide"));
        }
        let area = signed_area(p);
        if area.abs() < 1e-5 * chord * chord {
            return Err(bad_contour(
                source_name,
                "the contour encloses no area (points on a line?)",
            ));
        }
        let gap = dist(p[0], p[p.len() - 1]);
        if gap > MAX_TE_GAP * chord {
            return Err(bad_contour(
                source_name,
                format!(
                    "open contour: the ends are {:.3} chords apart (more than {MAX_TE_GAP}); is a surface missing?",
                    gap / chord
                ),
            ));
        }
        let le = self.leading_edge_index();
        if le == 0 || le == p.len() - 1 {
            return Err(bad_contour(
                source_name,
                "no leading edge between the two surfaces (not in Selig order?)",
            ));
        }
        if let Some((i, j)) = first_self_intersection(p) {
            return Err(bad_contour(
                source_name,
                format!(
                    "the contour crosses itself: segment {}-{} ({:.4}, {:.4}) crosses segment {}-{} ({:.4}, {:.4})",
                    i + 1,
                    i + 2,
                    p[i][0],
                    p[i][1],
                    j + 1,
                    j + 2,
                    p[j][0],
                    p[j][1]
                ),
            ));
        }
        Ok(())
    }

    /// Distance from the trailing-edge midpoint to the farthest point.
    fn chord_estimate(&self) -> f64 {
        let te = self.te_mid();
        self.points.iter().map(|&q| dist(q, te)).fold(0.0, f64::max)
    }

    fn te_mid(&self) -> [f64; 2] {
        let (a, b) = (self.points[0], self.points[self.points.len() - 1]);
        [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0]
    }

    /// Index of the leading-edge point: the point farthest from the trailing-edge midpoint.
    pub fn leading_edge_index(&self) -> usize {
        let te = self.te_mid();
        (0..self.points.len())
            .max_by(|&i, &j| dist(self.points[i], te).total_cmp(&dist(self.points[j], te)))
            .unwrap_or(0)
    }

    /// Moves the leading edge to (0, 0) and the trailing-edge midpoint to (1, 0). Returns the
    /// original chord length and the angle the chord line made with the x axis [rad].
    pub fn normalise(&mut self) -> (f64, f64) {
        let le = self.points[self.leading_edge_index()];
        let te = self.te_mid();
        let (dx, dy) = (te[0] - le[0], te[1] - le[1]);
        let chord = dx.hypot(dy);
        let angle = dy.atan2(dx);
        let (s, c) = (-angle).sin_cos();
        for q in &mut self.points {
            let (x, y) = (q[0] - le[0], q[1] - le[1]);
            *q = [(c * x - s * y) / chord, (s * x + c * y) / chord];
        }
        (chord, angle)
    }

    /// The contour as a Selig file: name line, then `x y` per line.
    pub fn to_selig(&self) -> String {
        let mut out = String::with_capacity(32 + 24 * self.points.len());
        let _ = writeln!(out, "{}", self.name.lines().next().unwrap_or("airfoil"));
        for q in &self.points {
            let _ = writeln!(out, "{:.7} {:.7}", q[0], q[1]);
        }
        out
    }

    /// Upper surface from the leading edge to the trailing edge, and lower likewise.
    pub fn surfaces(&self) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
        let le = self.leading_edge_index();
        let upper: Vec<[f64; 2]> = self.points[..=le].iter().rev().copied().collect();
        let lower = self.points[le..].to_vec();
        (upper, lower)
    }

    /// Maximum thickness (perpendicular to the chord, at equal x on both surfaces) and its x,
    /// for a normalised contour.
    pub fn max_thickness(&self) -> (f64, f64) {
        let (upper, lower) = self.surfaces();
        upper
            .iter()
            .map(|q| (q[1] - interp_surface(&lower, q[0]), q[0]))
            .chain(lower.iter().map(|q| (interp_surface(&upper, q[0]) - q[1], q[0])))
            .fold((0.0, 0.0), |acc, t| if t.0 > acc.0 { t } else { acc })
    }

    /// The factor that takes this contour's thickness to `target` (t/c, in (0, 0.5)).
    fn thickness_factor(&self, target: f64) -> Result<f64, AirfoilError> {
        if !(target.is_finite() && target > 0.0 && target < 0.5) {
            return Err(AirfoilError::BadArgument(format!(
                "target thickness {} must be in (0, 0.5)",
                propbet_units::show(target)
            )));
        }
        let (t, _) = self.max_thickness();
        if t <= 0.0 {
            return Err(AirfoilError::BadArgument(format!(
                "{}: has no thickness to scale",
                self.name
            )));
        }
        Ok(target / t)
    }

    /// Scales the thickness of a normalised contour to `target` (t/c) about its camber line,
    /// keeping every point's x, so the leading edge keeps its own points (resampling y(x) there
    /// would make zero-length panels, on which XFOIL divides by zero).
    pub fn scale_thickness(&self, target: f64) -> Result<Airfoil, AirfoilError> {
        let k = self.thickness_factor(target)?;
        let (upper, lower) = self.surfaces();
        let le = self.leading_edge_index();
        let points = self
            .points
            .iter()
            .enumerate()
            .map(|(i, q)| {
                let other = if i <= le {
                    interp_surface(&lower, q[0])
                } else {
                    interp_surface(&upper, q[0])
                };
                let camber = (q[1] + other) / 2.0;
                [q[0], camber + (q[1] - camber) * k]
            })
            .collect();
        Ok(Airfoil {
            name: format!("{} t/c {:.2}%", self.name, target * 100.0),
            points,
        })
    }

    /// Whether the lower surface is flat from 30 % to 95 % of the chord (within 0.3 % of the
    /// chord of the straight line through its ends there), as a Clark-Y's is; for a
    /// normalised contour.
    pub fn has_flat_bottom(&self) -> bool {
        let (_, lower) = self.surfaces();
        let (x0, x1) = (0.3, 0.95);
        let (y0, y1) = (interp_surface(&lower, x0), interp_surface(&lower, x1));
        lower
            .iter()
            .filter(|q| (x0..=x1).contains(&q[0]))
            .all(|q| (q[1] - (y0 + (y1 - y0) * (q[0] - x0) / (x1 - x0))).abs() < 0.003)
    }

    /// Scales a normalised contour to thickness `target` (t/c) as a whole, every y by the same
    /// factor: camber grows with thickness and a flat bottom stays flat. How a family of
    /// flat-bottomed sections (APC's Clark-Y "scaled based on thickness ratio", its pitch
    /// "defined with a flat bottom surface", PE0 files) is thickened; [`Self::scale_thickness`]
    /// keeps the camber line instead.
    pub fn scale_whole(&self, target: f64) -> Result<Airfoil, AirfoilError> {
        let k = self.thickness_factor(target)?;
        Ok(Airfoil {
            name: format!("{} scaled to t/c {:.2}%", self.name, target * 100.0),
            points: self.points.iter().map(|q| [q[0], q[1] * k]).collect(),
        })
    }

    /// Scales a normalised contour to thickness `target` (t/c) as APC's PE0 files imply
    /// ("airfoils are scaled based on thickness ratio"): as a whole ([`Self::scale_whole`], every
    /// y by one factor) where the section is made thinner or has a flat bottom, so a thinned
    /// section's camber falls with its thickness (NACA 4412 at t/c 0.10: camber 3.3 %) and a
    /// flat bottom, on which APC defines pitch, stays flat; about the camber line
    /// ([`Self::scale_thickness`]) where a cambered section is thickened, so its camber never
    /// grows past its own (E63, 4.3 % thick, made 21 % thick at an electric prop's root would
    /// otherwise carry 27 % camber). docs/studies/section-scaling.md has the candidates on the
    /// shared props.
    pub fn scale_as_apc(&self, target: f64) -> Result<Airfoil, AirfoilError> {
        if self.has_flat_bottom() || target <= self.max_thickness().0 {
            self.scale_whole(target)
        } else {
            self.scale_thickness(target)
        }
    }

    /// Resamples the contour with `n` points (odd counts put a node exactly at the leading edge;
    /// even counts are rounded up), cosine-clustered towards both edges along the arc length on
    /// each surface. The leading edge and trailing-edge points are kept exactly.
    pub fn repanel(&self, n: usize) -> Result<Airfoil, AirfoilError> {
        if !(21..=999).contains(&n) {
            return Err(AirfoilError::BadArgument(format!(
                "point count {n} must be in 21..=999"
            )));
        }
        let per_side = n.div_ceil(2);
        let (upper, lower) = self.surfaces();
        let u = resample_surface(&upper, per_side);
        let l = resample_surface(&lower, per_side);
        let mut points: Vec<[f64; 2]> = u.iter().rev().copied().collect();
        points.extend_from_slice(&l[1..]);
        Ok(Airfoil {
            name: self.name.clone(),
            points,
        })
    }

    /// Blends two normalised airfoils: `(1 - fraction) * self + fraction * other`, surface by
    /// surface at equal arc-length fractions from the leading edge (APC's transition sections).
    pub fn blend(&self, other: &Airfoil, fraction: f64, per_side: usize) -> Result<Airfoil, AirfoilError> {
        if !(fraction.is_finite() && (0.0..=1.0).contains(&fraction)) {
            return Err(AirfoilError::BadArgument(format!(
                "blend fraction {fraction} must be in [0, 1]"
            )));
        }
        if !(11..=500).contains(&per_side) {
            return Err(AirfoilError::BadArgument(format!(
                "points per side {per_side} must be in 11..=500"
            )));
        }
        let (ua, la) = self.surfaces();
        let (ub, lb) = other.surfaces();
        let mix = |a: &[[f64; 2]], b: &[[f64; 2]]| -> Vec<[f64; 2]> {
            let (a, b) = (resample_surface(a, per_side), resample_surface(b, per_side));
            a.iter()
                .zip(&b)
                .map(|(p, q)| [p[0] + fraction * (q[0] - p[0]), p[1] + fraction * (q[1] - p[1])])
                .collect()
        };
        let (u, l) = (mix(&ua, &ub), mix(&la, &lb));
        let mut points: Vec<[f64; 2]> = u.iter().rev().copied().collect();
        points.extend_from_slice(&l[1..]);
        Ok(Airfoil {
            name: format!(
                "{} {:.0}% + {} {:.0}%",
                self.name,
                (1.0 - fraction) * 100.0,
                other.name,
                fraction * 100.0
            ),
            points,
        })
    }
}

/// How a NACA 4-digit section is laid out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NacaStyle {
    /// As XFOIL's own `NACA` command (naca.f): thickness added vertically to the camber line,
    /// the -0.1015 x^4 coefficient (trailing edge 0.25 % thick). Polars then match XFOIL's.
    Xfoil,
    /// NACA Report 824: thickness perpendicular to the camber line; `closed_te` uses -0.1036
    /// (sharp trailing edge) instead of -0.1015.
    Report824 {
        /// Sharp trailing edge.
        closed_te: bool,
    },
}

/// Thin-airfoil lift coefficient at zero angle of attack of a NACA 4-digit mean line with
/// maximum camber `camber` at `camber_pos` (fractions of the chord): CL0 = −2π α_L0 with
/// α_L0 = −(1/π) ∫₀^π dy_c/dx (cos θ − 1) dθ, x = (1 − cos θ)/2 (Abbott & von Doenhoff,
/// *Theory of Wing Sections*, eq. 4.31), by the midpoint rule on 400 intervals with the slope
/// from central differences of the mean line.
pub fn naca4_cl0(camber: f64, camber_pos: f64) -> f64 {
    let (m, p) = (camber, camber_pos);
    let yc = |x: f64| {
        if m <= 0.0 || p <= 0.0 {
            0.0
        } else if x < p {
            m / (p * p) * (2.0 * p * x - x * x)
        } else {
            m / ((1.0 - p) * (1.0 - p)) * (1.0 - 2.0 * p + 2.0 * p * x - x * x)
        }
    };
    let n = 400;
    let mut s = 0.0;
    for k in 0..n {
        let th = std::f64::consts::PI * (k as f64 + 0.5) / n as f64;
        let x = 0.5 * (1.0 - th.cos());
        let h = 1e-5;
        let (a, b) = ((x + h).min(1.0), (x - h).max(0.0));
        let dyc = (yc(a) - yc(b)) / (a - b);
        s += dyc * (th.cos() - 1.0) * std::f64::consts::PI / n as f64;
    }
    let alpha_l0 = -s / std::f64::consts::PI;
    -2.0 * std::f64::consts::PI * alpha_l0
}

/// A NACA 4-digit section `m p tt` (max camber m/100 at p/10 chord, thickness tt/100), with
/// `per_side` points per surface, cosine spaced.
pub fn naca4(
    camber: f64,
    camber_pos: f64,
    thickness: f64,
    per_side: usize,
    style: NacaStyle,
) -> Result<Airfoil, AirfoilError> {
    if !(camber.is_finite() && (0.0..0.2).contains(&camber)) {
        return Err(AirfoilError::BadArgument(format!(
            "NACA camber {camber} must be in [0, 0.2)"
        )));
    }
    if camber > 0.0 && !(camber_pos.is_finite() && camber_pos > 0.0 && camber_pos < 1.0) {
        return Err(AirfoilError::BadArgument(format!(
            "NACA camber position {camber_pos} must be in (0, 1)"
        )));
    }
    if !(thickness.is_finite() && thickness > 0.0 && thickness < 0.5) {
        return Err(AirfoilError::BadArgument(format!(
            "NACA thickness {thickness} must be in (0, 0.5)"
        )));
    }
    if !(11..=500).contains(&per_side) {
        return Err(AirfoilError::BadArgument(format!(
            "points per side {per_side} must be in 11..=500"
        )));
    }
    let (a4, perpendicular) = match style {
        NacaStyle::Xfoil => (-0.1015, false),
        NacaStyle::Report824 { closed_te } => (if closed_te { -0.1036 } else { -0.1015 }, true),
    };
    let (m, p, t) = (camber, camber_pos, thickness);
    let surface_point = |x: f64, sign: f64| -> [f64; 2] {
        let yt = 5.0 * t * (0.2969 * x.sqrt() - 0.1260 * x - 0.3516 * x * x + 0.2843 * x.powi(3) + a4 * x.powi(4));
        let (yc, dyc) = if m == 0.0 {
            (0.0, 0.0)
        } else if x < p {
            (m / (p * p) * (2.0 * p * x - x * x), 2.0 * m / (p * p) * (p - x))
        } else {
            let q = (1.0 - p) * (1.0 - p);
            (m / q * (1.0 - 2.0 * p + 2.0 * p * x - x * x), 2.0 * m / q * (p - x))
        };
        if !perpendicular {
            return [x, yc + sign * yt];
        }
        let th = dyc.atan();
        [x - sign * yt * th.sin(), yc + sign * yt * th.cos()]
    };
    let xs: Vec<f64> = (0..per_side)
        .map(|i| 0.5 * (1.0 - (std::f64::consts::PI * i as f64 / (per_side - 1) as f64).cos()))
        .collect();
    let mut points: Vec<[f64; 2]> = xs.iter().rev().map(|&x| surface_point(x, 1.0)).collect();
    points.extend(xs[1..].iter().map(|&x| surface_point(x, -1.0)));
    Ok(Airfoil {
        name: format!("NACA {:.0}{:.0}{:02.0}", m * 100.0, p * 10.0, t * 100.0),
        points,
    })
}

/// Parses `naca4412` / `NACA 4412` into a NACA 4-digit section laid out as XFOIL's `NACA`
/// command does ([`NacaStyle::Xfoil`]).
pub fn naca4_from_name(name: &str) -> Option<Result<Airfoil, AirfoilError>> {
    let lower = name.trim().to_ascii_lowercase();
    let digits = lower.strip_prefix("naca")?.trim();
    if digits.len() != 4 || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let d: Vec<f64> = digits.bytes().map(|b| f64::from(b - b'0')).collect();
    Some(naca4(
        d[0] / 100.0,
        d[1] / 10.0,
        (d[2] * 10.0 + d[3]) / 100.0,
        81,
        NacaStyle::Xfoil,
    ))
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

fn signed_area(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    0.5 * (0..n)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
}

/// y of a surface (leading edge to trailing edge) at `x`, linear between points, clamped at
/// the ends.
fn interp_surface(s: &[[f64; 2]], x: f64) -> f64 {
    if x <= s[0][0] {
        return s[0][1];
    }
    for w in s.windows(2) {
        let (a, b) = (w[0], w[1]);
        if (a[0] <= x && x <= b[0]) || (b[0] <= x && x <= a[0]) {
            let dx = b[0] - a[0];
            return if dx.abs() < 1e-15 {
                a[1]
            } else {
                a[1] + (x - a[0]) / dx * (b[1] - a[1])
            };
        }
    }
    s[s.len() - 1][1]
}

/// `n` points along a surface (leading edge first), spline through the points by arc length,
/// cosine-clustered towards both ends; the end points are kept exactly.
fn resample_surface(s: &[[f64; 2]], n: usize) -> Vec<[f64; 2]> {
    let mut arc = Vec::with_capacity(s.len());
    let mut acc = 0.0;
    for (i, q) in s.iter().enumerate() {
        if i > 0 {
            acc += dist(s[i - 1], *q);
        }
        arc.push(acc);
    }
    let xs: Vec<f64> = s.iter().map(|q| q[0]).collect();
    let ys: Vec<f64> = s.iter().map(|q| q[1]).collect();
    let (sx, sy) = (DrelaSpline::new(&arc, &xs), DrelaSpline::new(&arc, &ys));
    (0..n)
        .map(|i| {
            if i == 0 {
                return s[0];
            }
            if i == n - 1 {
                return s[s.len() - 1];
            }
            let t = 0.5 * (1.0 - (std::f64::consts::PI * i as f64 / (n - 1) as f64).cos());
            [sx.eval(t * acc), sy.eval(t * acc)]
        })
        .collect()
}

/// First pair of non-adjacent segments that cross (the closing segment included when the ends
/// differ).
fn first_self_intersection(p: &[[f64; 2]]) -> Option<(usize, usize)> {
    let n = p.len();
    let closed_gap = dist(p[0], p[n - 1]) > 0.0;
    let segs = if closed_gap { n } else { n - 1 };
    let seg = |i: usize| (p[i], p[(i + 1) % n]);
    for i in 0..segs {
        for j in i + 2..segs {
            if i == 0 && j == segs - 1 {
                continue; // neighbours through the closing point
            }
            let (a, b) = seg(i);
            let (c, d) = seg(j);
            if segments_cross(a, b, c, d) {
                return Some((i, j));
            }
        }
    }
    None
}

fn segments_cross(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let orient = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    o1 * o2 < 0.0 && o3 * o4 < 0.0
}

#[cfg(test)]
mod tests;
