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
        /// The line, as an excerpt.
        text: String,
    },
    /// A station row whose radius or thickness ratio is not a finite number in range.
    #[error("{name}: line {line}: '{text}': a station needs a finite radius >= 0 and a thickness ratio in (0, 1)")]
    StationRow {
        /// File name.
        name: String,
        /// Line (1-based).
        line: usize,
        /// The line, as an excerpt.
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
        "apcmr" => "MR",
        "apcsp" | "apcff" => "",
        // UIUC's other free-flight families (apc29ff): APC names its free-flight props by size
        // alone, as the apcff ones.
        k if k.starts_with("apc") && k.ends_with("ff") => "",
        _ => return None,
    };
    Some(format!("{}{suffix}-PERF.PE0", size.replace('.', "")))
}

/// Why a UIUC prop has no PE0 name: another maker, or an APC family whose file name is not known.
pub fn pe0_unknown(uiuc: &str) -> String {
    let family = uiuc.split('_').next().unwrap_or(uiuc);
    if family.starts_with("apc") {
        format!(
            "UIUC family {family}: APC's PE0 file name for it is not known (known: apce -> <D><P>E, \
             apcsf -> <D><P>SF, apcmr -> <D><P>MR, apcsp and apc*ff -> <D><P>); no APC sections to \
             predict it with"
        )
    } else {
        format!("UIUC family {family}: not an APC propeller, no PE0 file with its sections")
    }
}

/// Largest number a UIUC name's size gives in inches: UIUC's tunnel takes props up to about 22
/// inches, and volume 2 names its micro props in millimetres (`pl_57x20`: 57 mm, 2.2 in), so a
/// size of this or more is millimetres.
pub const UIUC_MM_ABOVE: f64 = 30.0;

/// The diameter [m] from a UIUC size: inches (`apcsf_10x4.7` → 10 in), or millimetres where
/// the number cannot be inches ([`UIUC_MM_ABOVE`]: `pl_57x20` → 57 mm).
pub fn uiuc_diameter(uiuc: &str) -> Option<f64> {
    let d = diameter_before_x(uiuc.split_once('_')?.1)?;
    Some(if d / 0.0254 >= UIUC_MM_ABOVE {
        d / 0.0254 * 1e-3
    } else {
        d
    })
}

/// The diameter a propeller's size names (`10x4.7SF`, `4.2x4`: inches before the `x`, as
/// UIUC and APC write it) [m].
pub fn diameter_before_x(size: &str) -> Option<f64> {
    let d_in: f64 = size.split_once('x')?.0.parse().ok()?;
    (d_in.is_finite() && d_in > 0.0).then_some(d_in * 0.0254)
}

/// A PE0 file: stations with their thickness ratio, and the two airfoils with their transition.
#[derive(Debug, Clone, PartialEq)]
pub struct Pe0 {
    /// (station radius [m], thickness ratio [-]).
    pub thickness: Vec<(f64, f64)>,
    /// (station radius [m], chord [m]): APC's design chord, between the mould's LE and TE parting lines.
    pub chord: Vec<(f64, f64)>,
    /// (station radius [m], twist [deg]): APC's design angle of the LE-TE line (the chord line).
    pub twist: Vec<(f64, f64)>,
    /// (radius [m], APC's airfoil name) at the start and end of the transition.
    pub airfoils: [(f64, String); 2],
}

impl Pe0 {
    /// Thickness ratio at radius `r` [m], linear between stations, held beyond them.
    pub fn thickness_at(&self, r: f64) -> f64 {
        linear_held(&self.thickness, r)
    }

    /// Design chord at radius `r` [m], linear between stations, held beyond them.
    pub fn chord_at(&self, r: f64) -> f64 {
        linear_held(&self.chord, r)
    }

    /// Design twist (chord-line angle) [deg] at radius `r` [m], linear between stations, held beyond them.
    pub fn twist_at(&self, r: f64) -> f64 {
        linear_held(&self.twist, r)
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

/// `t`'s value at `x`, linear between its (ascending) abscissas, held beyond them.
fn linear_held(t: &[(f64, f64)], x: f64) -> f64 {
    if x <= t[0].0 {
        return t[0].1;
    }
    for w in t.windows(2) {
        if x <= w[1].0 {
            let f = (x - w[0].0) / (w[1].0 - w[0].0);
            return w[0].1 + f * (w[1].1 - w[0].1);
        }
    }
    t[t.len() - 1].1
}

/// Reads a PE0 file (inches inside, metres out): the station table's first and seventh columns
/// (rows of 13 numbers before the AIRFOIL lines), and the AIRFOIL1/2 lines.
pub fn read_pe0(text: &str, name: &str) -> Result<Pe0, ReadPe0Error> {
    const IN: f64 = 0.0254;
    let mut thickness = Vec::new();
    let (mut chord, mut twist) = (Vec::new(), Vec::new());
    let mut foils: Vec<(f64, String)> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if let Some(rest) = t.strip_prefix("AIRFOIL1:").or_else(|| t.strip_prefix("AIRFOIL2:")) {
            let bad = || ReadPe0Error::AirfoilLine {
                name: name.to_string(),
                line: i + 1,
                text: propbet_bemt::units::excerpt(t),
            };
            let (r, n) = rest.split_once(',').ok_or_else(bad)?;
            let r: f64 = r.trim().parse().ok().filter(|r: &f64| r.is_finite()).ok_or_else(bad)?;
            // The name runs to APC's "(Transition ...)" note, and may have a space ("NACA 4412").
            let n = n.split('(').next().unwrap_or_default().trim().to_string();
            if n.is_empty() {
                return Err(bad());
            }
            foils.push((r * IN, n));
            continue;
        }
        let v: Vec<f64> = t.split_whitespace().map_while(|s| s.parse().ok()).collect();
        // The station table comes before the AIRFOIL lines; the performance tables after them
        // have as many columns.
        if v.len() >= 13 && foils.is_empty() {
            if !(v[0].is_finite() && v[0] >= 0.0 && v[6] > 0.0 && v[6] < 1.0 && v[1] >= 0.0 && v[7].abs() < 90.0) {
                return Err(ReadPe0Error::StationRow {
                    name: name.to_string(),
                    line: i + 1,
                    text: propbet_bemt::units::excerpt(t),
                });
            }
            thickness.push((v[0] * IN, v[6]));
            chord.push((v[0] * IN, v[1] * IN));
            twist.push((v[0] * IN, v[7]));
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
        chord,
        twist,
        airfoils: [foils[0].clone(), foils[1].clone()],
    })
}

/// APC's predicted performance (a PER3 file): for each RPM block, (J, CT, CP) rows ascending in J.
/// Predictions of APC's own code, a reference to compare with, never measurements.
#[derive(Debug, Clone, PartialEq)]
pub struct Per3 {
    /// (rpm, rows of (J, CT, CP)), ascending in rpm.
    pub blocks: Vec<(f64, Vec<[f64; 3]>)>,
    /// Rows of a block left out, each as "line N: what" (a CT of 1e308, `******`, NaN).
    pub skipped: Vec<String>,
}

/// A PER3 file that cannot be read.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ReadPer3Error {
    /// A `PROP RPM =` line without a number.
    #[error("{name}: line {line}: '{text}': expected 'PROP RPM = <number>'")]
    RpmLine {
        /// File name.
        name: String,
        /// Line (1-based).
        line: usize,
        /// The line, as an excerpt.
        text: String,
    },
    /// No block with at least two rows.
    #[error("{name}: not an APC PER3 file (no 'PROP RPM =' block with two or more data rows)")]
    NotPer3 {
        /// File name.
        name: String,
    },
}

/// The PER3 file name of a UIUC prop (`apcsf_10x4.7` → `PER3_10x47SF.dat`).
pub fn per3_name(uiuc: &str) -> Option<String> {
    let pe0 = pe0_name(uiuc)?;
    Some(format!("PER3_{}.dat", pe0.strip_suffix("-PERF.PE0")?))
}

/// Reads a PER3 file: blocks `PROP RPM = N` followed by rows of 15 numbers (V [mph], J, Pe,
/// Ct, Cp, ...); rows with non-finite or negative J are skipped.
pub fn read_per3(text: &str, name: &str) -> Result<Per3, ReadPer3Error> {
    let mut blocks: Vec<(f64, Vec<[f64; 3]>)> = Vec::new();
    let mut skipped = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if let Some(rest) = t.strip_prefix("PROP RPM =") {
            let rpm: f64 = rest.trim().parse().map_err(|_| ReadPer3Error::RpmLine {
                name: name.to_string(),
                line: i + 1,
                text: propbet_bemt::units::excerpt(t),
            })?;
            blocks.push((rpm, Vec::new()));
            continue;
        }
        let v: Vec<f64> = t.split_whitespace().map_while(|s| s.parse().ok()).collect();
        // Beyond these no propeller's coefficients or advance ratio lie (the limits the
        // measurement readers drop rows at).
        let plausible = |v: &[f64]| v[1].abs() <= 20.0 && v[3].abs() <= 10.0 && v[4].abs() <= 10.0;
        if v.len() >= 5 && v[1].is_finite() && v[1] >= 0.0 && v[3].is_finite() && v[4].is_finite() && plausible(&v) {
            if let Some((_, rows)) = blocks.last_mut() {
                rows.push([v[1], v[3], v[4]]);
            }
        } else if !blocks.is_empty() && t.split_whitespace().count() >= 5 && v.len() >= 2 {
            // A row of the table (its first values are numbers) that cannot be used.
            skipped.push(format!("line {}: {}", i + 1, propbet_bemt::units::excerpt(t)));
        }
    }
    blocks.retain(|(rpm, rows)| rpm.is_finite() && *rpm > 0.0 && rows.len() >= 2);
    for (_, rows) in &mut blocks {
        rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
    }
    blocks.sort_by(|a, b| a.0.total_cmp(&b.0));
    if blocks.is_empty() {
        return Err(ReadPer3Error::NotPer3 { name: name.to_string() });
    }
    Ok(Per3 { blocks, skipped })
}

impl Per3 {
    /// (CT, CP) at `rpm` and `j`: linear in J within the two blocks around `rpm`, linear in rpm
    /// between them; None outside the blocks' J range or RPM range.
    pub fn at(&self, rpm: f64, j: f64) -> Option<(f64, f64)> {
        let in_block = |rows: &[[f64; 3]]| -> Option<(f64, f64)> {
            let k = rows.partition_point(|r| r[0] <= j);
            if k == 0 || (k == rows.len() && j > rows[rows.len() - 1][0]) {
                return None;
            }
            let k = k.min(rows.len() - 1).max(1);
            let (a, b) = (rows[k - 1], rows[k]);
            let t = if b[0] > a[0] { (j - a[0]) / (b[0] - a[0]) } else { 0.0 };
            Some((a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])))
        };
        let b = &self.blocks;
        let k = b.partition_point(|x| x.0 <= rpm);
        if k == 0 || (k == b.len() && rpm > b[b.len() - 1].0) {
            return None;
        }
        let k = k.min(b.len() - 1).max(1);
        let (lo, hi) = (&b[k - 1], &b[k]);
        let (p, q) = (in_block(&lo.1)?, in_block(&hi.1)?);
        let t = if hi.0 > lo.0 { (rpm - lo.0) / (hi.0 - lo.0) } else { 0.0 };
        Some((p.0 + t * (q.0 - p.0), p.1 + t * (q.1 - p.1)))
    }
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
        // Volume 2's micro props are named in millimetres.
        assert!((uiuc_diameter("pl_57x20").unwrap() - 0.057).abs() < 1e-15);
        assert!((uiuc_diameter("pl_57x20_geom.txt").unwrap() - 0.057).abs() < 1e-15);
        assert!((uiuc_diameter("apce_21x14").unwrap() - 21.0 * 0.0254).abs() < 1e-15);
        assert_eq!(per3_name("apcsf_10x4.7").as_deref(), Some("PER3_10x47SF.dat"));
        assert_eq!(pe0_name("apc29ff_9x5").as_deref(), Some("9x5-PERF.PE0"));
        assert_eq!(pe0_name("apcmr_10x4.5").as_deref(), Some("10x45MR-PERF.PE0"));
        assert_eq!(pe0_name("apcc_7.4x8.25"), None);
        assert!(pe0_unknown("apcc_7.4x8.25").contains("apcc: APC's PE0 file name for it is not known"));
        assert!(pe0_unknown("gwsdd_9x5").contains("not an APC propeller"));
    }

    #[test]
    fn per3_blocks_interpolate_in_j_and_rpm() {
        let text = "  PROP RPM =  1000\n  V J Pe Ct Cp\n (mph) - - - -\n\
                    0.00 0.0000 0.0 0.1342 0.0549 0 0 0 0 0 0 0 0 0 0\n\
                    0.21 0.1000 0.05 0.1242 0.0550 0 0 0 0 0 0 0 0 0 0\n\
                    PROP RPM = 2000\n\
                    0.00 0.0000 0.0 0.1442 0.0649 0 0 0 0 0 0 0 0 0 0\n\
                    0.21 0.1000 0.05 0.1342 0.0650 0 0 0 0 0 0 0 0 0 0\n";
        let p = read_per3(text, "x.dat").unwrap();
        assert_eq!(p.blocks.len(), 2);
        let (ct, cp) = p.at(1500.0, 0.05).unwrap();
        assert!((ct - 0.1342).abs() < 1e-12 && (cp - 0.05995).abs() < 1e-12, "{ct} {cp}");
        assert_eq!(p.at(1000.0, 0.0), Some((0.1342, 0.0549)));
        assert_eq!(p.at(2000.0, 0.1), Some((0.1342, 0.065)));
        assert_eq!(p.at(2500.0, 0.05), None, "beyond the RPM blocks");
        assert_eq!(p.at(1500.0, 0.2), None, "beyond the J range");
        let e = read_per3("PROP RPM = lots\n", "y.dat").unwrap_err().to_string();
        assert!(e.contains("y.dat: line 1"), "{e}");
        assert!(read_per3("hello\n", "z.dat")
            .unwrap_err()
            .to_string()
            .contains("not an APC PER3"));
    }

    #[test]
    fn the_shared_per3_files_read() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/per3");
        let text = std::fs::read_to_string(dir.join("PER3_10x47SF.dat")).unwrap();
        let p = read_per3(&text, "PER3_10x47SF.dat").unwrap();
        assert!(p.blocks.len() >= 10 && p.blocks[0].0 == 1000.0, "{}", p.blocks.len());
        // The file's first row at 1000 rpm: J 0, Ct 0.1342, Cp 0.0549.
        assert_eq!(p.at(1000.0, 0.0), Some((0.1342, 0.0549)));
    }

    #[test]
    fn pe0_reading_and_bad_files() {
        let text = "  0.9567 0.7943 4.5 4.5 3.79 0.39 0.2086 36.8 0.16 0.08 0.21 0.10 0.02\n  \
                    1.0164 0.8324 4.5 4.5 3.92 0.39 0.1973 35.7 0.16 0.08 0.21 0.09 0.02\n \
                    AIRFOIL1:  0.95, E63         (Transition Start, Airfoil 1)\n AIRFOIL2:  3.66, APC12  (End)\n";
        let p = read_pe0(text, "x.PE0").unwrap();
        assert_eq!(p.thickness, vec![(0.9567 * 0.0254, 0.2086), (1.0164 * 0.0254, 0.1973)]);
        assert_eq!(p.airfoils[1], (3.66 * 0.0254, "APC12".to_string()));
        // A name with a space runs to APC's "(Transition ...)" note; a line with no name is bad.
        let spaced = read_pe0(&text.replacen("APC12  (End)", "NACA 4412  (End)", 1), "x.PE0").unwrap();
        assert_eq!(spaced.airfoils[1].1, "NACA 4412");
        let e = read_pe0(&text.replacen(", E63 ", ",  ", 1), "u.PE0")
            .unwrap_err()
            .to_string();
        assert!(e.contains("u.PE0") && e.contains("line 3"), "{e}");
        assert_eq!(p.thickness_at(0.0), 0.2086);
        assert!((p.thickness_at(0.5 * (0.9567 + 1.0164) * 0.0254) - 0.20295).abs() < 1e-12);
        assert_eq!(p.blend_at(0.0), 0.0);
        assert_eq!(p.blend_at(1.0), 1.0);
        // Chord (second column, inches) and twist (eighth, degrees), linear between stations.
        assert_eq!(
            p.chord,
            vec![(0.9567 * 0.0254, 0.7943 * 0.0254), (1.0164 * 0.0254, 0.8324 * 0.0254)]
        );
        assert!((p.twist_at(0.5 * (0.9567 + 1.0164) * 0.0254) - 36.25).abs() < 1e-12);
        assert_eq!(p.twist_at(1.0), 35.7);
        assert!((p.chord_at(0.0) - 0.7943 * 0.0254).abs() < 1e-15);
        let e = read_pe0("nothing here\n", "y.PE0").unwrap_err().to_string();
        assert!(e.contains("y.PE0") && e.contains("not an APC PE0 file"), "{e}");
        let e = read_pe0("AIRFOIL1: x, E63\n", "z.PE0").unwrap_err().to_string();
        assert!(e.contains("line 1"), "{e}");
        // Found by the fuzz harness: an infinite radius or thickness passed through.
        for bad in ["inf", "nan"] {
            let t = text.replacen("0.9567", bad, 1);
            let e = read_pe0(&t, "w.PE0").unwrap_err().to_string();
            assert!(e.contains("w.PE0: line 1") && e.contains("finite radius"), "{e}");
        }
        let e = read_pe0(
            &text.replacen(", E63", ", inf", 1).replacen("0.95,", "inf,", 1),
            "v.PE0",
        )
        .unwrap_err();
        assert!(e.to_string().contains("line 3"), "{e}");
    }
}
