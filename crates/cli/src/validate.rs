//! `propbet validate`: every UIUC propeller that has a geometry file and a matching APC PE0
//! file is predicted (UIUC's r/R, c/R, β; APC's airfoils scaled to the PE0 thickness ratio at
//! each station; XFOIL polars at each station's Re) and compared with every static and J-sweep
//! file, before and after the diagnosis' ladder. Each prop is run as the documented commands
//! (`polars`, `compare`, `diagnose`, `compare --effect ...`) in its own directory; the table of
//! relative CT and CP errors is written as Markdown and CSV.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use clap::Args;
use propbet_polar::{naca4_from_name, Airfoil};

use crate::output::{write_atomic, CsvTable};
use crate::polar::{read_airfoil, XfoilProcess};
use crate::run::stage;

/// Arguments of `propbet validate`.
#[derive(Debug, Args)]
pub struct ValidateArgs {
    /// UIUC directory: `<prop>_geom.txt` and the prop's static and J-sweep files.
    #[arg(long)]
    pub uiuc: PathBuf,
    /// APC PE0 directory (`<D><P><type>-PERF.PE0`).
    #[arg(long)]
    pub pe0: PathBuf,
    /// Airfoil coordinates: `e63.dat`, `clarky.dat` (APC12 is NACA 4412, generated).
    #[arg(long)]
    pub airfoils: PathBuf,
    /// Only the props whose name contains one of these (comma-separated).
    #[arg(long)]
    pub only: Option<String>,
    /// Operating point of the polars' Reynolds numbers [rpm].
    #[arg(long, default_value_t = 5000.0)]
    pub rpm: f64,
    /// Output directory.
    #[arg(long, short)]
    pub out: PathBuf,
    /// XFOIL executable, polar cache, progress bars (passed on to the polars stages).
    #[command(flatten)]
    pub xfoil: XfoilProcess,
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

/// The diameter [in] from a UIUC size `10x4.7`.
fn diameter_in(uiuc: &str) -> Option<f64> {
    uiuc.split_once('_')?.1.split_once('x')?.0.parse().ok()
}

/// A PE0 file: stations [in], thickness ratios, and the two airfoils with their transition.
#[derive(Debug, Clone, PartialEq)]
pub struct Pe0 {
    /// (station [in], thickness ratio).
    pub thickness: Vec<(f64, f64)>,
    /// (radius [in], APC's airfoil name) at the start and end of the transition.
    pub airfoils: [(f64, String); 2],
}

/// Reads a PE0 file: the station table's first and seventh columns (rows of 13 numbers before
/// the AIRFOIL lines), and the AIRFOIL1/2 lines.
pub fn read_pe0(text: &str, name: &str) -> Result<Pe0> {
    let mut thickness = Vec::new();
    let mut foils: Vec<(f64, String)> = Vec::new();
    for line in text.lines() {
        let t = line.trim();
        if let Some(rest) = t.strip_prefix("AIRFOIL1:").or_else(|| t.strip_prefix("AIRFOIL2:")) {
            let (r, n) = rest
                .split_once(',')
                .with_context(|| format!("{name}: '{t}': expected 'r, NAME'"))?;
            let r: f64 = r.trim().parse().with_context(|| format!("{name}: '{t}': bad radius"))?;
            let n = n.split_whitespace().next().unwrap_or_default().to_string();
            foils.push((r, n));
            continue;
        }
        let v: Vec<f64> = t.split_whitespace().map_while(|s| s.parse().ok()).collect();
        // The station table comes before the AIRFOIL lines; the performance tables after them
        // have as many columns.
        if v.len() >= 13 && foils.is_empty() {
            thickness.push((v[0], v[6]));
        }
    }
    if thickness.len() < 2 || foils.len() != 2 {
        bail!(
            "{name}: not an APC PE0 file ({} station rows, {} AIRFOIL lines)",
            thickness.len(),
            foils.len()
        );
    }
    Ok(Pe0 {
        thickness,
        airfoils: [foils[0].clone(), foils[1].clone()],
    })
}

fn interp(t: &[(f64, f64)], x: f64) -> f64 {
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

/// APC's airfoil name → a section: E63 and CLARK-Y from the directory, APC12 = NACA 4412.
fn apc_airfoil(name: &str, dir: &Path) -> Result<Airfoil> {
    let file = match name.to_ascii_uppercase().as_str() {
        "APC12" => return Ok(naca4_from_name("naca4412").expect("a NACA name")?),
        "E63" => "e63.dat",
        "CLARK-Y" | "CLARKY" => "clarky.dat",
        other => bail!("APC airfoil {other}: no coordinates known (E63, CLARK-Y, APC12)"),
    };
    Ok(read_airfoil(&dir.join(file))?.0)
}

/// One row of the table.
struct Row {
    prop: String,
    points: usize,
    ct: [(f64, f64); 2],
    cp: [(f64, f64); 2],
    ladder: String,
}

fn quantile(mut v: Vec<f64>, q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

/// |relative| CT and CP errors of the points of a `compare` points.csv that lie below 85 % of
/// their file's zero-thrust J (measured; every point when the sweep never reaches zero thrust).
fn errors(points_csv: &Path) -> Result<(Vec<f64>, Vec<f64>)> {
    let text = std::fs::read_to_string(points_csv).with_context(|| format!("{}: cannot read", points_csv.display()))?;
    let t = CsvTable::parse(&text, "points.csv");
    let (cf, cj, ct, ctp, cp, cpp) = (
        t.col("file")?,
        t.col("j")?,
        t.col("ct")?,
        t.col("ct_pred")?,
        t.col("cp")?,
        t.col("cp_pred")?,
    );
    let rows = &t.rows;
    let num = |r: &Vec<String>, k: usize| CsvTable::num(r, k);
    let mut files: Vec<&str> = rows.iter().map(|r| r[cf].as_str()).collect();
    files.dedup();
    let (mut ect, mut ecp) = (Vec::new(), Vec::new());
    for f in files {
        let mut pts: Vec<&Vec<String>> = rows.iter().filter(|r| r[cf] == f).collect();
        pts.sort_by(|a, b| num(a, cj).total_cmp(&num(b, cj)));
        let j0 = pts
            .windows(2)
            .find(|w| num(w[0], ct) > 0.0 && num(w[1], ct) <= 0.0)
            .map(|w| {
                let (a, b) = (num(w[0], ct), num(w[1], ct));
                num(w[0], cj) + a / (a - b) * (num(w[1], cj) - num(w[0], cj))
            });
        for r in pts {
            let j = num(r, cj);
            if j0.is_some_and(|j0| j >= 0.85 * j0) {
                continue;
            }
            let (m, p) = (num(r, ct), num(r, ctp));
            if m.is_finite() && p.is_finite() && m > 0.0 {
                ect.push((p / m - 1.0).abs());
            }
            let (m, p) = (num(r, cp), num(r, cpp));
            if m.is_finite() && p.is_finite() && m > 0.0 {
                ecp.push((p / m - 1.0).abs());
            }
        }
    }
    Ok((ect, ecp))
}

/// Runs `propbet validate`.
pub fn run(a: &ValidateArgs) -> Result<bool> {
    let mut geoms: Vec<String> = std::fs::read_dir(&a.uiuc)
        .with_context(|| format!("{}: cannot read the directory", a.uiuc.display()))?
        .filter_map(|e| {
            e.ok()?
                .file_name()
                .to_str()?
                .strip_suffix("_geom.txt")
                .map(String::from)
        })
        .collect();
    geoms.sort();
    if let Some(only) = &a.only {
        let keys: Vec<&str> = only.split(',').map(str::trim).collect();
        geoms.retain(|g| keys.iter().any(|k| g.contains(k)));
    }
    std::fs::create_dir_all(&a.out).with_context(|| format!("{}: cannot create", a.out.display()))?;
    let mut rows = Vec::new();
    let mut skipped = Vec::new();
    let mut all_clean = true;
    let total = geoms.len();
    for (k, prop) in geoms.iter().enumerate() {
        let pe0_path = match pe0_name(prop) {
            Some(n) if a.pe0.join(&n).is_file() => a.pe0.join(n),
            Some(n) => {
                skipped.push(format!("{prop}: no PE0 file {n}"));
                continue;
            }
            None => {
                skipped.push(format!("{prop}: not an APC propeller (no PE0 file)"));
                continue;
            }
        };
        eprintln!("propbet validate [{}/{total}] {prop}", k + 1);
        match validate_one(a, prop, &pe0_path) {
            Ok((row, clean)) => {
                all_clean &= clean;
                rows.push(row);
            }
            Err(e) => {
                all_clean = false;
                skipped.push(format!("{prop}: {e:#}"));
            }
        }
    }
    if rows.is_empty() {
        bail!(
            "{}: no propeller could be validated: {}",
            a.uiuc.display(),
            skipped.join("; ")
        );
    }
    let (md, csv) = table(&rows, &skipped, a);
    write_atomic(&a.out.join("validation.md"), &[md.as_bytes()], &[])?;
    write_atomic(&a.out.join("validation.csv"), &[csv.as_bytes()], &[])?;
    println!("{md}");
    Ok(all_clean)
}

fn validate_one(a: &ValidateArgs, prop: &str, pe0_path: &Path) -> Result<(Row, bool)> {
    let dir = a.out.join(prop);
    std::fs::create_dir_all(dir.join("airfoils"))?;
    let geom_path = a.uiuc.join(format!("{prop}_geom.txt"));
    let table = crate::scan::read_reference(&geom_path)?;
    let d_in = diameter_in(prop).with_context(|| format!("{prop}: no diameter in the name"))?;
    let big_r = 0.5 * d_in;
    let pe0_text = std::fs::read_to_string(pe0_path).with_context(|| format!("{}: cannot read", pe0_path.display()))?;
    let pe0 = read_pe0(&pe0_text, &pe0_path.display().to_string())?;
    let (f1, f2) = (
        apc_airfoil(&pe0.airfoils[0].1, &a.airfoils)?,
        apc_airfoil(&pe0.airfoils[1].1, &a.airfoils)?,
    );
    // The prop file (inches) and each station's section scaled to the PE0 thickness.
    let mut qp = format!(
        "{prop} (UIUC geometry, APC PE0 sections)\n\n 2  {big_r}  ! Nblades  R\n\n 0.50 5.8 ! CL0 CL_a\n -0.3 1.2 ! CLmin CLmax\n\n \
         0.028 0.050 0.050 0.5 ! CD0 CD2u CD2l CLCD0\n 70000 -0.5 ! REref REexp\n\n 0.0254 0.0254 1.0 ! Rfac Cfac Bfac\n 0 0 0 ! Radd Cadd Badd\n\n#  r [in]  chord [in]  beta [deg]\n"
    );
    let (r1, r2) = (pe0.airfoils[0].0, pe0.airfoils[1].0);
    for (i, row) in table.iter().enumerate() {
        let r = row[0] * big_r;
        let _ = writeln!(qp, " {:.4} {:.4} {:.2}", r, row[1] * big_r, row[2]);
        let frac = if r2 > r1 {
            ((r - r1) / (r2 - r1)).clamp(0.0, 1.0)
        } else {
            f64::from(u8::from(r >= r2))
        };
        let base = if frac <= 0.0 {
            f1.clone()
        } else if frac >= 1.0 {
            f2.clone()
        } else {
            f1.blend(&f2, frac, 80)?
        };
        let tc = interp(&pe0.thickness, r);
        let mut foil = base.scale_thickness(tc)?;
        foil.name = format!("{} t/c {:.3}", base.name, tc);
        write_atomic(
            &dir.join(format!("airfoils/station_{i:02}.dat")),
            &[foil.to_selig().as_bytes()],
            &[],
        )?;
    }
    let geometry = dir.join("geometry.qprop");
    write_atomic(&geometry, &[qp.as_bytes()], &[])?;
    let p = |x: &Path| x.display().to_string();
    let mut argv = vec![
        "polars".to_string(),
        "--geometry".into(),
        p(&geometry),
        "--airfoil".into(),
        p(&dir.join("airfoils/station_00.dat")),
        "--station-airfoils".into(),
        p(&dir.join("airfoils")),
        "--rpm".into(),
        a.rpm.to_string(),
    ];
    argv.extend(a.xfoil.flags());
    argv.extend([
        "--out-prop".into(),
        p(&dir.join("prop.qprop")),
        "--out-polars".into(),
        p(&dir.join("polars.json")),
    ]);
    let mut clean = stage("polars", argv, 1, 4)?.clean;
    // The measurements: every file of this prop but the geometry.
    let mut measured: Vec<String> = std::fs::read_dir(&a.uiuc)?
        .filter_map(|e| {
            let n = e.ok()?.file_name().to_str()?.to_string();
            (n.starts_with(&format!("{prop}_")) && n.ends_with(".txt") && !n.ends_with("_geom.txt")).then_some(n)
        })
        .map(|n| p(&a.uiuc.join(n)))
        .collect();
    measured.sort();
    if measured.is_empty() {
        bail!("no static or J-sweep file");
    }
    let model = ["--prop".to_string(), p(&dir.join("prop.qprop"))];
    let data: Vec<String> = std::iter::once("--measured".to_string()).chain(measured).collect();
    let compare = |name: &str, extra: &[String]| -> Result<bool> {
        let mut argv = vec!["compare".to_string()];
        argv.extend(model.iter().cloned());
        argv.extend(data.iter().cloned());
        argv.extend(extra.iter().cloned());
        argv.extend(["--out".into(), p(&dir.join(name))]);
        Ok(stage("compare", argv, 2, 4)?.clean)
    };
    clean &= compare("compare", &[])?;
    let mut argv = vec!["diagnose".to_string()];
    argv.extend(model.iter().cloned());
    argv.extend(data.iter().cloned());
    argv.extend(["--out".into(), p(&dir.join("diagnose"))]);
    clean &= stage("diagnose", argv, 3, 4)?.clean;
    let d: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.join("diagnose/diagnosis.json"))?)?;
    let effects: Vec<String> = d["final_effects"]
        .as_array()
        .map(|v| v.iter().filter_map(|e| e.as_str()).map(String::from).collect())
        .unwrap_or_default();
    let extra: Vec<String> = effects
        .iter()
        .flat_map(|e| ["--effect".to_string(), e.clone()])
        .collect();
    clean &= compare("calibrated", &extra)?;
    let (ct0, cp0) = errors(&dir.join("compare/points.csv"))?;
    let (ct1, cp1) = errors(&dir.join("calibrated/points.csv"))?;
    let q = |v: &Vec<f64>| (quantile(v.clone(), 0.5), quantile(v.clone(), 0.9));
    Ok((
        Row {
            prop: prop.to_string(),
            points: ct0.len(),
            ct: [q(&ct0), q(&ct1)],
            cp: [q(&cp0), q(&cp1)],
            ladder: if effects.is_empty() {
                "none".into()
            } else {
                effects.join(" + ")
            },
        },
        clean,
    ))
}

fn table(rows: &[Row], skipped: &[String], a: &ValidateArgs) -> (String, String) {
    let pct = |x: f64| format!("{:.1}", 100.0 * x);
    let mut md = format!(
        "Relative errors |pred/meas − 1| of CT and CP, points below 85 % of each sweep's zero-thrust J \
         (static points included); polars at {} rpm. Before: UIUC geometry + APC sections + XFOIL; \
         after: with the effects the diagnosis' ladder fitted to the same data (calibration).\n\n\
         | prop | points | CT median | CT p90 | CP median | CP p90 | CT median after | CT p90 after | CP median after | CP p90 after | ladder |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
        a.rpm
    );
    let mut csv = String::from("prop,points,ct_median,ct_p90,cp_median,cp_p90,ct_median_after,ct_p90_after,cp_median_after,cp_p90_after,ladder\n");
    for r in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {} % | {} % | {} % | {} % | {} % | {} % | {} % | {} % | {} |",
            r.prop,
            r.points,
            pct(r.ct[0].0),
            pct(r.ct[0].1),
            pct(r.cp[0].0),
            pct(r.cp[0].1),
            pct(r.ct[1].0),
            pct(r.ct[1].1),
            pct(r.cp[1].0),
            pct(r.cp[1].1),
            r.ladder
        );
        let _ = writeln!(
            csv,
            "{},{},{:.5},{:.5},{:.5},{:.5},{:.5},{:.5},{:.5},{:.5},{}",
            r.prop,
            r.points,
            r.ct[0].0,
            r.ct[0].1,
            r.cp[0].0,
            r.cp[0].1,
            r.ct[1].0,
            r.ct[1].1,
            r.cp[1].0,
            r.cp[1].1,
            r.ladder.replace(',', ";")
        );
    }
    // Overall: the medians and 90th percentiles of the per-prop medians would hide the sizes;
    // pool the points instead.
    let pooled = |f: &dyn Fn(&Row) -> (f64, f64)| -> (f64, f64) {
        let med: Vec<f64> = rows.iter().map(|r| f(r).0).collect();
        let p90: Vec<f64> = rows.iter().map(|r| f(r).1).collect();
        (quantile(med, 0.5), quantile(p90, 0.5))
    };
    let (a0, b0) = pooled(&|r| r.ct[0]);
    let (c0, d0) = pooled(&|r| r.cp[0]);
    let (a1, b1) = pooled(&|r| r.ct[1]);
    let (c1, d1) = pooled(&|r| r.cp[1]);
    let _ = writeln!(
        md,
        "| **all (median over props)** | {} | {} % | {} % | {} % | {} % | {} % | {} % | {} % | {} % | |",
        rows.iter().map(|r| r.points).sum::<usize>(),
        pct(a0),
        pct(b0),
        pct(c0),
        pct(d0),
        pct(a1),
        pct(b1),
        pct(c1),
        pct(d1)
    );
    if !skipped.is_empty() {
        md.push_str("\nNot validated:\n");
        for s in skipped {
            let _ = writeln!(md, "- {s}");
        }
    }
    (md, csv)
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
        assert_eq!(diameter_in("apcff_4.2x4"), Some(4.2));
    }

    #[test]
    fn pe0_reading_and_bad_files() {
        let text = "  0.9567 0.7943 4.5 4.5 3.79 0.39 0.2086 36.8 0.16 0.08 0.21 0.10 0.02\n  \
                    1.0164 0.8324 4.5 4.5 3.92 0.39 0.1973 35.7 0.16 0.08 0.21 0.09 0.02\n \
                    AIRFOIL1:  0.95, E63         (Transition Start, Airfoil 1)\n AIRFOIL2:  3.66, APC12  (End)\n";
        let p = read_pe0(text, "x.PE0").unwrap();
        assert_eq!(p.thickness, vec![(0.9567, 0.2086), (1.0164, 0.1973)]);
        assert_eq!(p.airfoils[1], (3.66, "APC12".to_string()));
        let e = read_pe0("nothing here\n", "y.PE0").unwrap_err().to_string();
        assert!(e.contains("y.PE0") && e.contains("not an APC PE0 file"), "{e}");
    }

    #[test]
    fn errors_stop_below_85_percent_of_the_zero_thrust_j() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("points.csv");
        // Measured CT crosses zero at J = 0.5: J 0.45 (>= 0.425) is left out.
        let csv = "file,j,ct,ct_pred,cp,cp_pred\na,0.0,0.1,0.11,0.05,0.05\na,0.2,0.08,0.08,0.04,0.044\n\
                   a,0.45,0.01,0.02,0.02,0.02\na,0.55,-0.01,0.0,0.01,0.01\n";
        std::fs::write(&p, csv).unwrap();
        let (ct, cp) = errors(&p).unwrap();
        assert_eq!(ct.len(), 2);
        assert!((ct[0] - 0.1).abs() < 1e-12 && ct[1].abs() < 1e-12, "{ct:?}");
        assert!((cp[1] - 0.1).abs() < 1e-12, "{cp:?}");
    }
}
