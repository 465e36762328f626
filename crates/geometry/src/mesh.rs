//! Triangle meshes and STL files.

use nalgebra::Vector3;
use thiserror::Error;

/// A triangle soup with shared vertices.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub vertices: Vec<Vector3<f64>>,
    /// Triangles as vertex indices.
    pub triangles: Vec<[u32; 3]>,
}

/// What is wrong with a mesh file.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MeshError {
    /// No triangle.
    #[error("{0}: the file holds no triangle")]
    Empty(String),
    /// Binary STL shorter than its triangle count says.
    #[error("{name}: truncated binary STL: the header announces {announced} triangles ({need} bytes), the file has {have} bytes")]
    Truncated {
        /// File name.
        name: String,
        /// Triangles announced.
        announced: u32,
        /// Bytes needed.
        need: usize,
        /// Bytes present.
        have: usize,
    },
    /// A coordinate that is NaN or infinite.
    #[error("{name}: {location}: a vertex coordinate is not a finite number")]
    NotFinite {
        /// File name.
        name: String,
        /// "triangle 12" or "line 40".
        location: String,
    },
    /// ASCII syntax.
    #[error("{name}: line {line}: {message}")]
    Syntax {
        /// File name.
        name: String,
        /// 1-based line.
        line: usize,
        /// What was expected.
        message: String,
    },
}

impl Mesh {
    /// Adds a triangle by its corner positions (vertices are not shared).
    pub fn push_triangle(&mut self, a: Vector3<f64>, b: Vector3<f64>, c: Vector3<f64>) {
        let n = self.vertices.len() as u32;
        self.vertices.extend([a, b, c]);
        self.triangles.push([n, n + 1, n + 2]);
    }

    /// The corners of triangle `i`.
    pub fn corners(&self, i: usize) -> [Vector3<f64>; 3] {
        self.triangles[i].map(|k| self.vertices[k as usize])
    }

    /// The triangles where `keep(i)` holds, sharing the vertex list.
    pub fn subset(&self, keep: impl Fn(usize) -> bool) -> Mesh {
        Mesh {
            vertices: self.vertices.clone(),
            triangles: (0..self.triangles.len())
                .filter(|&i| keep(i))
                .map(|i| self.triangles[i])
                .collect(),
        }
    }

    /// Applies `x -> s (R x + t)`.
    pub fn transform(&mut self, rot: &nalgebra::Matrix3<f64>, t: &Vector3<f64>, s: f64) {
        for v in &mut self.vertices {
            *v = s * (rot * *v + t);
        }
    }

    /// Binary STL bytes (normals from the corners).
    pub fn to_stl(&self) -> Vec<u8> {
        let mut b = Vec::with_capacity(84 + 50 * self.triangles.len());
        let mut header = [0u8; 80];
        header[..16].copy_from_slice(b"propbet mesh STL");
        b.extend_from_slice(&header);
        b.extend_from_slice(&(self.triangles.len() as u32).to_le_bytes());
        for i in 0..self.triangles.len() {
            let [p, q, r] = self.corners(i);
            let n = (q - p)
                .cross(&(r - p))
                .try_normalize(0.0)
                .unwrap_or_else(Vector3::zeros);
            for v in [n, p, q, r] {
                for c in v.iter() {
                    b.extend_from_slice(&(*c as f32).to_le_bytes());
                }
            }
            b.extend_from_slice(&[0, 0]);
        }
        b
    }
}

/// Reads an STL file, binary or ASCII (`name` is used in messages).
pub fn read_stl(bytes: &[u8], name: &str) -> Result<Mesh, MeshError> {
    // ASCII: `solid`, then `facet` within the first 1000 bytes (or a short file). The `solid`
    // line is a free-text name that exporters write in any encoding (Latin-1 from older CAD
    // tools), so the test does not ask for UTF-8.
    let head = String::from_utf8_lossy(&bytes[..bytes.len().min(1000)]);
    let ascii = bytes.len() >= 5
        && bytes[..5].eq_ignore_ascii_case(b"solid")
        && (head.contains("facet") || head.trim().len() < 1000);
    let binary_consistent = bytes.len() >= 84 && {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        bytes.len() == 84 + 50 * n
    };
    if ascii && !binary_consistent {
        read_ascii(bytes, name)
    } else {
        read_binary(bytes, name)
    }
}

fn read_binary(bytes: &[u8], name: &str) -> Result<Mesh, MeshError> {
    if bytes.len() < 84 {
        return Err(if bytes.is_empty() {
            MeshError::Empty(name.to_string())
        } else {
            MeshError::Truncated {
                name: name.to_string(),
                announced: 0,
                need: 84,
                have: bytes.len(),
            }
        });
    }
    let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]);
    let need = 84 + 50 * n as usize;
    if bytes.len() < need {
        return Err(MeshError::Truncated {
            name: name.to_string(),
            announced: n,
            need,
            have: bytes.len(),
        });
    }
    if n == 0 {
        return Err(MeshError::Empty(name.to_string()));
    }
    let mut m = Mesh::default();
    for i in 0..n as usize {
        let base = 84 + 50 * i + 12;
        let f = |k: usize| {
            let o = base + 4 * k;
            f32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]) as f64
        };
        let v: Vec<Vector3<f64>> = (0..3)
            .map(|c| Vector3::new(f(3 * c), f(3 * c + 1), f(3 * c + 2)))
            .collect();
        if v.iter().any(|p| !p.iter().all(|x| x.is_finite())) {
            return Err(MeshError::NotFinite {
                name: name.to_string(),
                location: format!("triangle {}", i + 1),
            });
        }
        m.push_triangle(v[0], v[1], v[2]);
    }
    Ok(m)
}

fn read_ascii(bytes: &[u8], name: &str) -> Result<Mesh, MeshError> {
    let text = String::from_utf8_lossy(bytes);
    let mut m = Mesh::default();
    let mut corners: Vec<Vector3<f64>> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let mut w = line.split_whitespace();
        if w.next() != Some("vertex") {
            continue;
        }
        let vals: Vec<f64> = w
            .map(|x| x.parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| MeshError::Syntax {
                name: name.to_string(),
                line: i + 1,
                message: format!("`{}` is not `vertex x y z`", propbet_units::excerpt(line)),
            })?;
        if vals.len() != 3 {
            return Err(MeshError::Syntax {
                name: name.to_string(),
                line: i + 1,
                message: format!("`{}` is not `vertex x y z`", propbet_units::excerpt(line)),
            });
        }
        if !vals.iter().all(|x| x.is_finite()) {
            return Err(MeshError::NotFinite {
                name: name.to_string(),
                location: format!("line {}", i + 1),
            });
        }
        corners.push(Vector3::new(vals[0], vals[1], vals[2]));
        if corners.len() == 3 {
            m.push_triangle(corners[0], corners[1], corners[2]);
            corners.clear();
        }
    }
    if !corners.is_empty() {
        return Err(MeshError::Syntax {
            name: name.to_string(),
            line: text.lines().count(),
            message: "the file ends inside a facet (truncated?)".into(),
        });
    }
    if m.triangles.is_empty() {
        return Err(MeshError::Empty(name.to_string()));
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_stl_with_a_latin1_name_is_read_as_ascii() {
        let mut bytes = b"solid h\xe9lice \xb0 10x4.7\n".to_vec();
        bytes.extend_from_slice(
            b"facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n",
        );
        let m = read_stl(&bytes, "latin1.stl").unwrap();
        assert_eq!(m.triangles.len(), 1);
    }

    fn tri() -> Mesh {
        let mut m = Mesh::default();
        m.push_triangle(
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.0, 1.0, 0.5),
        );
        m
    }

    #[test]
    fn binary_round_trip_and_ascii() {
        let m = tri();
        let back = read_stl(&m.to_stl(), "t.stl").unwrap();
        assert_eq!(back.triangles.len(), 1);
        assert!((back.vertices[2].z - 0.5).abs() < 1e-7);
        let ascii = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0.5\nendloop\nendfacet\nendsolid t\n";
        assert_eq!(read_stl(ascii.as_bytes(), "a.stl").unwrap().triangles.len(), 1);
    }

    #[test]
    fn bad_files() {
        assert!(matches!(read_stl(b"", "e.stl"), Err(MeshError::Empty(_))));
        let mut b = tri().to_stl();
        b.truncate(100);
        let e = read_stl(&b, "t.stl").unwrap_err().to_string();
        assert!(
            e.contains("t.stl: truncated binary STL: the header announces 1 triangles"),
            "{e}"
        );
        let nan = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex nan 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n";
        let e = read_stl(nan.as_bytes(), "n.stl").unwrap_err().to_string();
        assert!(
            e.contains("n.stl: line 5: a vertex coordinate is not a finite number"),
            "{e}"
        );
        let cut = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n";
        let e = read_stl(cut.as_bytes(), "c.stl").unwrap_err().to_string();
        assert!(e.contains("ends inside a facet"), "{e}");
        assert!(matches!(
            read_stl(b"solid x\nendsolid x\n", "e.stl"),
            Err(MeshError::Empty(_))
        ));
    }
}
