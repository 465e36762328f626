//! Point clouds: PLY (ASCII and binary, with vertex colours, as COLMAP's `fused.ply`), COLMAP
//! `points3D.txt`, plain XYZ / XYZRGB text; and the cleaning steps: colour filter (RGB distance
//! to given colours, histogram, Otsu threshold suggestion), region-of-interest crop, statistical
//! outlier removal (k nearest neighbours, kiddo's k-d tree).

use std::num::NonZero;

use kiddo::{ImmutableKdTree, SquaredEuclidean};
use nalgebra::Vector3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{Property, PropertyAccess, PropertyAccessResult};
use rayon::prelude::*;
use thiserror::Error;

/// Points with optional colours.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Cloud {
    /// Positions.
    pub points: Vec<Vector3<f64>>,
    /// RGB colours, one per point, when the file has them.
    pub colors: Option<Vec<[u8; 3]>>,
}

/// What is wrong with a cloud file.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum CloudError {
    /// No point.
    #[error("{0}: the file holds no point")]
    Empty(String),
    /// A syntax error at a line.
    #[error("{name}: line {line}: {message}")]
    Syntax {
        /// File name.
        name: String,
        /// 1-based line.
        line: usize,
        /// What was expected.
        message: String,
    },
    /// A PLY file the parser rejects (truncated binary data, unknown format).
    #[error("{name}: {message}")]
    Ply {
        /// File name.
        name: String,
        /// The parser's message.
        message: String,
    },
    /// A coordinate that is NaN or infinite.
    #[error("{name}: point {index}: a coordinate is not a finite number")]
    NotFinite {
        /// File name.
        name: String,
        /// 1-based point number.
        index: usize,
    },
}

#[derive(Default)]
struct PlyVertex {
    p: [f64; 3],
    c: [u8; 3],
    has_c: bool,
}

fn channel(v: &Property) -> Option<u8> {
    Some(match *v {
        Property::UChar(x) => x,
        Property::Char(x) => x.max(0) as u8,
        Property::UShort(x) => (x >> 8) as u8,
        Property::Float(x) => (x.clamp(0.0, 1.0) * 255.0).round() as u8,
        Property::Double(x) => (x.clamp(0.0, 1.0) * 255.0).round() as u8,
        _ => return None,
    })
}

fn number(v: &Property) -> Option<f64> {
    Some(match *v {
        Property::Float(x) => x as f64,
        Property::Double(x) => x,
        Property::Int(x) => x as f64,
        Property::UInt(x) => x as f64,
        Property::Short(x) => x as f64,
        Property::UShort(x) => x as f64,
        Property::Char(x) => x as f64,
        Property::UChar(x) => x as f64,
        _ => return None,
    })
}

impl PropertyAccess for PlyVertex {
    fn new() -> Self {
        Self::default()
    }
    fn set_property(&mut self, key: &str, v: Property) -> PropertyAccessResult {
        let slot = match key {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            "red" | "r" | "diffuse_red" => 3,
            "green" | "g" | "diffuse_green" => 4,
            "blue" | "b" | "diffuse_blue" => 5,
            _ => return PropertyAccessResult::Ignored,
        };
        if slot < 3 {
            match number(&v) {
                Some(x) => self.p[slot] = x,
                None => return PropertyAccessResult::UnsupportedType,
            }
        } else {
            match channel(&v) {
                Some(x) => {
                    self.c[slot - 3] = x;
                    self.has_c = true;
                }
                None => return PropertyAccessResult::UnsupportedType,
            }
        }
        PropertyAccessResult::Set
    }
}

/// Reads a PLY file's vertices (faces, if any, are ignored: a cloud is its points).
pub fn read_ply(bytes: &[u8], name: &str) -> Result<Cloud, CloudError> {
    let err = |m: String| CloudError::Ply {
        name: name.to_string(),
        message: m,
    };
    // The vertex element must name x, y and z once each: a missing one would read as 0 (a
    // flat cloud, blamed on its symmetry later) and a doubled one would overwrite itself.
    let head = String::from_utf8_lossy(&bytes[..bytes.len().min(1 << 16)]);
    let mut in_vertex = false;
    let mut names: Vec<&str> = Vec::new();
    for line in head.lines().take_while(|l| l.trim() != "end_header") {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.first() {
            Some(&"element") => in_vertex = words.get(1) == Some(&"vertex"),
            Some(&"property") if in_vertex => names.extend(words.last()),
            _ => {}
        }
    }
    if !names.is_empty() {
        for axis in ["x", "y", "z"] {
            let n = names.iter().filter(|&&p| p == axis).count();
            if n != 1 {
                return Err(err(format!(
                    "the vertex element names its '{axis}' coordinate {n} times (properties: {}): each of x, y, z once",
                    propbet_units::excerpt(&names.join(" "))
                )));
            }
        }
    }
    let parser = Parser::<PlyVertex>::new();
    let mut reader = ply_rs_bw::parser::Reader::new(std::io::BufReader::new(bytes));
    let header = parser
        .read_header(&mut reader)
        .map_err(|e| err(format!("header: {}", propbet_units::excerpt(&e.to_string()))))?;
    // PLY writers put the vertices first; anything before them would have to be skipped.
    let element = match header.elements.values().next() {
        Some(e) if e.name == "vertex" => e,
        Some(e) => {
            return Err(err(format!(
                "the first element is '{}', not 'vertex'",
                propbet_units::excerpt(&e.name)
            )))
        }
        None => return Err(CloudError::Empty(name.to_string())),
    };
    let verts = parser
        .read_payload_for_element(&mut reader, element, &header)
        .map_err(|e| {
            err(format!(
                "vertex data ({} announced): {}",
                element.count,
                propbet_units::excerpt(&e.to_string())
            ))
        })?;
    let has_c = verts.first().is_some_and(|v| v.has_c);
    let mut cloud = Cloud {
        points: Vec::with_capacity(verts.len()),
        colors: has_c.then(|| Vec::with_capacity(verts.len())),
    };
    for v in verts {
        cloud.points.push(Vector3::from(v.p));
        if let Some(c) = cloud.colors.as_mut() {
            c.push(v.c);
        }
    }
    check(cloud, name)
}

fn check(cloud: Cloud, name: &str) -> Result<Cloud, CloudError> {
    if cloud.points.is_empty() {
        return Err(CloudError::Empty(name.to_string()));
    }
    if let Some(i) = cloud.points.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
        return Err(CloudError::NotFinite {
            name: name.to_string(),
            index: i + 1,
        });
    }
    Ok(cloud)
}

/// Reads whitespace-separated text: COLMAP `points3D.txt` (`ID X Y Z R G B ERROR TRACK...`,
/// `#` comments) when `colmap`, else XYZ or XYZRGB rows (commas allowed, `#` comments).
pub fn read_text(text: &str, name: &str, colmap: bool) -> Result<Cloud, CloudError> {
    let mut cloud = Cloud::default();
    let mut colors = Vec::new();
    let mut width = None;
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') || line.starts_with("//") {
            continue;
        }
        let syntax = |m: String| CloudError::Syntax {
            name: name.to_string(),
            line: i + 1,
            message: m,
        };
        let f: Vec<&str> = line
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|s| !s.is_empty())
            .collect();
        let skip = usize::from(colmap);
        let need = if colmap { 7 } else { 3 };
        if f.len() < need {
            return Err(syntax(format!("expected at least {need} columns, found {}", f.len())));
        }
        let w = *width.get_or_insert(if colmap || f.len() >= 6 { 6 } else { 3 });
        let mut v = [0.0; 6];
        for (k, slot) in v.iter_mut().enumerate().take(w) {
            let s = f
                .get(skip + k)
                .ok_or_else(|| syntax(format!("column {} is missing", skip + k + 1)))?;
            *slot = s.parse::<f64>().map_err(|_| {
                syntax(format!(
                    "column {}: '{}' is not a number",
                    skip + k + 1,
                    propbet_units::excerpt(s)
                ))
            })?;
        }
        if !v[..3].iter().all(|x| x.is_finite()) {
            return Err(syntax("a coordinate is not a finite number".into()));
        }
        cloud.points.push(Vector3::new(v[0], v[1], v[2]));
        if w == 6 {
            let scale = if v[3..].iter().all(|&c| c <= 1.0) && !colmap {
                255.0
            } else {
                1.0
            };
            colors.push([3, 4, 5].map(|k| (v[k] * scale).round().clamp(0.0, 255.0) as u8));
        }
    }
    if width == Some(6) {
        cloud.colors = Some(colors);
    }
    check(cloud, name)
}

/// Reads a cloud by its name: `.ply`, `points3D.txt` (or any text starting with COLMAP's
/// header comment), else XYZ / XYZRGB text.
pub fn read_cloud(bytes: &[u8], name: &str) -> Result<Cloud, CloudError> {
    if bytes.starts_with(b"ply") {
        return read_ply(bytes, name);
    }
    let text = std::str::from_utf8(bytes).map_err(|e| CloudError::Ply {
        name: name.to_string(),
        message: format!("neither PLY nor text: {e}"),
    })?;
    let colmap = name.ends_with("points3D.txt") || text.starts_with("# 3D point list");
    read_text(text, name, colmap)
}

impl Cloud {
    /// Keeps the points where `keep` is true.
    pub fn retain(&mut self, keep: &[bool]) {
        let mut i = 0;
        self.points.retain(|_| {
            i += 1;
            keep[i - 1]
        });
        if let Some(c) = self.colors.as_mut() {
            let mut i = 0;
            c.retain(|_| {
                i += 1;
                keep[i - 1]
            });
        }
    }

    /// Scales every point.
    pub fn scale(&mut self, s: f64) {
        for p in &mut self.points {
            *p *= s;
        }
    }
}

/// RGB distance of each point's colour to the nearest of `colours` (infinite without colours).
pub fn colour_distances(cloud: &Cloud, colours: &[[u8; 3]]) -> Vec<f64> {
    match &cloud.colors {
        None => vec![f64::INFINITY; cloud.points.len()],
        Some(c) => c
            .iter()
            .map(|p| {
                colours
                    .iter()
                    .map(|q| (0..3).map(|k| (p[k] as f64 - q[k] as f64).powi(2)).sum::<f64>().sqrt())
                    .fold(f64::INFINITY, f64::min)
            })
            .collect(),
    }
}

/// A histogram of colour distances (bins of width 4 from 0 to 444, the RGB cube's diagonal).
#[derive(Debug, Clone, PartialEq)]
pub struct Histogram {
    /// Bin width.
    pub width: f64,
    /// Counts.
    pub counts: Vec<usize>,
}

impl Histogram {
    /// Bins the finite distances.
    pub fn of(d: &[f64]) -> Self {
        let width = 4.0;
        let mut counts = vec![0usize; 112];
        for &x in d.iter().filter(|x| x.is_finite()) {
            counts[((x / width) as usize).min(111)] += 1;
        }
        Self { width, counts }
    }

    /// Otsu's threshold: the split of the histogram with the largest between-class variance
    /// (the near colours from the rest).
    pub fn otsu(&self) -> f64 {
        let total: usize = self.counts.iter().sum();
        let sum: f64 = self.counts.iter().enumerate().map(|(i, &c)| i as f64 * c as f64).sum();
        let (mut w0, mut s0, mut best, mut last) = (0.0, 0.0, (f64::NEG_INFINITY, 0usize), 0usize);
        for (i, &c) in self.counts.iter().enumerate() {
            w0 += c as f64;
            s0 += i as f64 * c as f64;
            let w1 = total as f64 - w0;
            if w0 == 0.0 || w1 == 0.0 {
                continue;
            }
            let (m0, m1) = (s0 / w0, (sum - s0) / w1);
            let v = w0 * w1 * (m0 - m1).powi(2);
            if v > best.0 * (1.0 + 1e-9) {
                best = (v, i);
                last = i;
            } else if v >= best.0 * (1.0 - 1e-9) {
                last = i;
            }
        }
        // Between the two groups every split scores alike: take the middle of the gap.
        (0.5 * (best.1 + last) as f64 + 1.0) * self.width
    }
}

/// Keeps the points inside an axis-aligned box.
pub fn crop(cloud: &Cloud, lo: Vector3<f64>, hi: Vector3<f64>) -> Vec<bool> {
    cloud
        .points
        .iter()
        .map(|p| (0..3).all(|k| p[k] >= lo[k] && p[k] <= hi[k]))
        .collect()
}

/// Statistical outlier removal: the mean distance of each point to its `k` nearest neighbours;
/// points farther than the mean of those plus `sigmas` standard deviations are dropped.
pub fn outlier_mask(points: &[Vector3<f64>], k: usize, sigmas: f64) -> Vec<bool> {
    if points.len() <= k + 1 {
        return vec![true; points.len()];
    }
    let entries: Vec<[f64; 3]> = points.iter().map(|p| [p.x, p.y, p.z]).collect();
    let Ok(tree) = ImmutableKdTree::<f64, 3>::new_from_slice(&entries) else {
        return vec![true; points.len()];
    };
    let n = NonZero::new(k + 1).unwrap_or(NonZero::<usize>::MIN);
    let mean: Vec<f64> = entries
        .par_iter()
        .map(|q| {
            let res = tree.query(q).nearest_n::<SquaredEuclidean<f64>>(n).execute();
            res.iter().skip(1).map(|r| r.distance.sqrt()).sum::<f64>() / k as f64
        })
        .collect();
    let m = mean.iter().sum::<f64>() / mean.len() as f64;
    let sd = (mean.iter().map(|x| (x - m).powi(2)).sum::<f64>() / mean.len() as f64).sqrt();
    mean.iter().map(|&x| x <= m + sigmas * sd).collect()
}

/// A named or hex colour: `orange`, `black`, `#e66400`, `230,100,10`.
pub fn parse_colour(s: &str) -> Result<[u8; 3], String> {
    let named = [
        ("black", [0, 0, 0]),
        ("white", [255, 255, 255]),
        ("grey", [200, 200, 200]),
        ("gray", [200, 200, 200]),
        ("red", [220, 30, 30]),
        ("orange", [230, 100, 10]),
        ("yellow", [230, 220, 30]),
        ("green", [30, 150, 40]),
        ("blue", [20, 20, 200]),
    ];
    let t = s.trim().to_ascii_lowercase();
    if let Some((_, c)) = named.iter().find(|(n, _)| *n == t) {
        return Ok(*c);
    }
    if let Some(h) = t.strip_prefix('#') {
        if h.len() == 6 {
            let b = |i: usize| u8::from_str_radix(&h[i..i + 2], 16);
            if let (Ok(r), Ok(g), Ok(bl)) = (b(0), b(2), b(4)) {
                return Ok([r, g, bl]);
            }
        }
    }
    let parts: Vec<&str> = t.split(['/', ' ']).filter(|x| !x.is_empty()).collect();
    if parts.len() == 3 {
        if let (Ok(r), Ok(g), Ok(b)) = (parts[0].parse(), parts[1].parse(), parts[2].parse()) {
            return Ok([r, g, b]);
        }
    }
    Err(format!(
        "'{s}' is not a colour (a name: {}; #rrggbb; or r/g/b)",
        named.iter().map(|n| n.0).collect::<Vec<_>>().join(", ")
    ))
}

/// Writes a binary little-endian PLY with float coordinates, uchar colours when the cloud has
/// them, and, given `blade` labels, an int property `blade` per point (−1 for the hub).
pub fn to_ply(cloud: &Cloud, blade: Option<&[Option<u8>]>) -> Vec<u8> {
    let has_c = cloud.colors.is_some();
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\ncomment propbet\nelement vertex {}\n\
         property float x\nproperty float y\nproperty float z\n{}{}end_header\n",
        cloud.points.len(),
        if has_c {
            "property uchar red\nproperty uchar green\nproperty uchar blue\n"
        } else {
            ""
        },
        if blade.is_some() { "property int blade\n" } else { "" }
    )
    .into_bytes();
    for (i, p) in cloud.points.iter().enumerate() {
        for k in 0..3 {
            out.extend((p[k] as f32).to_le_bytes());
        }
        if let Some(c) = &cloud.colors {
            out.extend(c[i]);
        }
        if let Some(b) = blade {
            let v = b.get(i).copied().flatten().map_or(-1, i32::from);
            out.extend(v.to_le_bytes());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_formats_and_errors() {
        let c = read_text("# x y z r g b\n1 2 3 255 0 0\n4,5,6,0,0,255\n", "a.xyz", false).unwrap();
        assert_eq!(c.points.len(), 2);
        assert_eq!(c.colors.as_ref().unwrap()[1], [0, 0, 255]);
        let c = read_text(
            "# 3D point list with one line of data per point:\n1 0.5 0.25 2 10 20 30 0.1 3 4\n",
            "points3D.txt",
            true,
        )
        .unwrap();
        assert_eq!(c.points[0], Vector3::new(0.5, 0.25, 2.0));
        assert_eq!(c.colors.unwrap()[0], [10, 20, 30]);
        let e = read_text("1 2 3\n4 x 6\n", "b.xyz", false).unwrap_err().to_string();
        assert!(e.contains("b.xyz: line 2") && e.contains("'x'"), "{e}");
        let e = read_text("1 2 nan\n", "n.xyz", false).unwrap_err().to_string();
        assert!(e.contains("line 1") && e.contains("finite"), "{e}");
        assert!(matches!(
            read_text("# nothing\n", "e.xyz", false),
            Err(CloudError::Empty(_))
        ));
    }

    #[test]
    fn ply_ascii_and_truncated_binary() {
        let ascii = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n\
                     property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n1 2 3 4 5 6\n7 8 9 10 11 12\n";
        let c = read_cloud(ascii.as_bytes(), "a.ply").unwrap();
        assert_eq!(c.points.len(), 2);
        assert_eq!(c.colors.unwrap()[1], [10, 11, 12]);
        let mut bin = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n".to_vec();
        for v in [1.0f32, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0] {
            bin.extend(v.to_le_bytes());
        }
        let e = read_cloud(&bin, "t.ply").unwrap_err().to_string();
        assert!(e.starts_with("t.ply: vertex data (3 announced)"), "{e}");
    }

    #[test]
    fn otsu_splits_two_groups() {
        let d: Vec<f64> = (0..100)
            .map(|i| (i % 20) as f64)
            .chain((0..50).map(|i| 150.0 + i as f64))
            .collect();
        let t = Histogram::of(&d).otsu();
        assert!(t > 20.0 && t < 150.0, "{t}");
        assert_eq!(parse_colour("#E6640A").unwrap(), [230, 100, 10]);
        assert!(parse_colour("purple-ish").unwrap_err().contains("not a colour"));
    }
}
