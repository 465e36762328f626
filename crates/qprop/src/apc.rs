//! APC's published design files (PE0: blade stations with thickness ratio and the airfoils with
//! their transition), and the mapping from UIUC propeller names to APC's file names.

use thiserror::Error;

/// A PE0 file that cannot be read.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ReadPe0Error {
    /// An AIRFOIL line is not `r, NAME`.
    #[error("{name}: line {line}: '{text}': expected 'r, NAME'")]
    AirfoilLine {
        /// File name.
        name: String,
        /// Line (1-based).
        line: usize,
        /// The line.
        text: String,
    },
    /// The file has no station table or not two AIRFOIL lines.
    #[error("{name}: not an APC PE0 file ({stations} station rows, {airfoils} AIRFOIL lines)")]
    NotPe0 {
        /// File name.
        name: String,
        /// Station rows found.
        stations: usize,
        /// AIRFOIL lines found.
        airfoils: usize,
    },
}

/// A UIUC name's PE0 file name: `apcsf_10x4.7` → `10x47SF-PERF.PE0`, `apce_10x5` → `10x5E`,
/// `apcsp_10x6` → `10x6`, `apcff_4.2x4` → `42x4`; None for other makers.
pub fn pe0_name(uiuc: &str) -> Option<String> {
    let (kind, size) = uiuc.split_once('_')?;
    let suffix = match kind {
        "apcsf" => "SF",
        "apce" => "E",
        "apcsp" | "apcff" => "",
        _ => return None,
    };
    Some(format!("{}{suffix}-PERF.PE0", size.replace('.', "")))
}

/// The diameter [m] from a UIUC size in inches (`apcsf_10x4.7` → 10 in).
pub fn uiuc_diameter(uiuc: &str) -> Option<f64> {
    let d_in: f64 = uiuc.split_once('_')?.1.split_once('x')?.0.parse().ok()?;
    (d_in.is_finite() && d_in > 0.0).then_some(d_in * 0.0254)
}

/// A PE0 file: stations with their thickness ratio, and the two airfoils with their transition.
#[derive(Debug, Clone, PartialEq)]
pub struct Pe0 {
    /// (station radius [m], thickness ratio [-]).
    pub thickness: Vec<(f64, f64)>,
    /// (radius [m], APC's airfoil name) at the start and end of the transition.
    pub airfoils: [(f64, String); 2],
}

impl Pe0 {
    /// Thickness ratio at radius `r` [m], linear between stations, held beyond them.
    pub fn thickness_at(&self, r: f64) -> f64 {
        let t = &self.thickness;
        if r <= t[0].0 {
            return t[0].1;
        }
        for w in t.windows(2) {
            if r <= w[1].0 {
                let f = (r - w[0].0) / (w[1].0 - w[0].0);
                return w[0].1 + f * (w[1].1 - w[0].1);
            }
        }
        t[t.len() - 1].1
    }

    /// How far `r` [m] is through the transition from the first airfoil (0) to the second (1).
    pub fn blend_at(&self, r: f64) -> f64 {
        let (r1, r2) = (self.airfoils[0].0, self.airfoils[1].0);
        if r2 > r1 {
            ((r - r1) / (r2 - r1)).clamp(0.0, 1.0)
        } else {
            f64::from(u8::from(r >= r2))
        }
    }
}

/// Reads a PE0 file (inches inside, metres out): the station table's first and seventh columns
/// (rows of 13 numbers before the AIRFOIL lines), and the AIRFOIL1/2 lines.
pub fn read_pe0(text: &str, name: &str) -> Result<Pe0, ReadPe0Error> {
    const IN: f64 = 0.0254;
    let mut thickness = Vec::new();
    let mut foils: Vec<(f64, String)> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if let Some(rest) = t.strip_prefix("AIRFOIL1:").or_else(|| t.strip_prefix("AIRFOIL2:")) {
            let bad = || ReadPe0Error::AirfoilLine {
                name: name.to_string(),
                line: i + 1,
                text: t.to_string(),
            };
            let (r, n) = rest.split_once(',').ok_or_else(bad)?;
            let r: f64 = r.trim().parse().map_err(|_| bad())?;
            let n = n.split_whitespace().next().unwrap_or_default().to_string();
            foils.push((r * IN, n));
            continue;
        }
        let v: Vec<f64> = t.split_whitespace().map_while(|s| s.parse().ok()).collect();
        // The station table comes before the AIRFOIL lines; the performance tables after them
        // have as many columns.
        if v.len() >= 13 && foils.is_empty() {
            thickness.push((v[0] * IN, v[6]));
        }
    }
    if thickness.len() < 2 || foils.len() != 2 {
        return Err(ReadPe0Error::NotPe0 {
            name: name.to_string(),
            stations: thickness.len(),
            airfoils: foils.len(),
        });
    }
    Ok(Pe0 {
        thickness,
        airfoils: [foils[0].clone(), foils[1].clone()],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pe0_names_follow_apc() {
        assert_eq!(pe0_name("apcsf_10x4.7").as_deref(), Some("10x47SF-PERF.PE0"));
        assert_eq!(pe0_name("apce_11x7").as_deref(), Some("11x7E-PERF.PE0"));
        assert_eq!(pe0_name("apcsp_10x6").as_deref(), Some("10x6-PERF.PE0"));
        assert_eq!(pe0_name("apcff_4.2x4").as_deref(), Some("42x4-PERF.PE0"));
        assert_eq!(pe0_name("gwsdd_9x5"), None);
        assert!((uiuc_diameter("apcff_4.2x4").unwrap() - 4.2 * 0.0254).abs() < 1e-15);
    }

    #[test]
    fn pe0_reading_and_bad_files() {
        let text = "  0.9567 0.7943 4.5 4.5 3.79 0.39 0.2086 36.8 0.16 0.08 0.21 0.10 0.02\n  \
                    1.0164 0.8324 4.5 4.5 3.92 0.39 0.1973 35.7 0.16 0.08 0.21 0.09 0.02\n \
                    AIRFOIL1:  0.95, E63         (Transition Start, Airfoil 1)\n AIRFOIL2:  3.66, APC12  (End)\n";
        let p = read_pe0(text, "x.PE0").unwrap();
        assert_eq!(p.thickness, vec![(0.9567 * 0.0254, 0.2086), (1.0164 * 0.0254, 0.1973)]);
        assert_eq!(p.airfoils[1], (3.66 * 0.0254, "APC12".to_string()));
        assert_eq!(p.thickness_at(0.0), 0.2086);
        assert!((p.thickness_at(0.5 * (0.9567 + 1.0164) * 0.0254) - 0.20295).abs() < 1e-12);
        assert_eq!(p.blend_at(0.0), 0.0);
        assert_eq!(p.blend_at(1.0), 1.0);
        let e = read_pe0("nothing here\n", "y.PE0").unwrap_err().to_string();
        assert!(e.contains("y.PE0") && e.contains("not an APC PE0 file"), "{e}");
        let e = read_pe0("AIRFOIL1: x, E63\n", "z.PE0").unwrap_err().to_string();
        assert!(e.contains("line 1"), "{e}");
    }
}
