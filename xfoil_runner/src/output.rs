//! Reading XFOIL's polar save file (`PACC`).

use serde::{Deserialize, Serialize};

use crate::XfoilError;

/// One converged operating point as XFOIL saved it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct XfoilPoint {
    /// Angle of attack [deg].
    pub alpha_deg: f64,
    /// Lift coefficient [-].
    pub cl: f64,
    /// Drag coefficient [-].
    pub cd: f64,
    /// Pressure drag coefficient [-].
    pub cdp: f64,
    /// Quarter-chord pitching moment coefficient [-].
    pub cm: f64,
    /// Transition point on the upper surface [x/c].
    pub xtr_top: f64,
    /// Transition point on the lower surface [x/c].
    pub xtr_bottom: f64,
}

impl XfoilPoint {
    /// A point with lift and drag only (pressure drag and moment 0, laminar to the trailing
    /// edge on both surfaces): synthetic polars and tests.
    pub fn lift_drag(alpha_deg: f64, cl: f64, cd: f64) -> Self {
        XfoilPoint {
            alpha_deg,
            cl,
            cd,
            cdp: 0.0,
            cm: 0.0,
            xtr_top: 1.0,
            xtr_bottom: 1.0,
        }
    }
}

/// Parses the text of an XFOIL polar save file: header lines up to the dashed rule, then one
/// row per point (`alpha CL CD CDp CM Top_Xtr Bot_Xtr [Top_Itr Bot_Itr]`). A file cut off after
/// the header has no points; a last row cut off before its line end is left out (XFOIL was
/// stopped writing it); any other row that is not seven numbers is an error naming the line.
pub fn parse_polar_file(text: &str, output_tail: &str) -> Result<Vec<XfoilPoint>, XfoilError> {
    let garbage = |detail: String| XfoilError::Garbage {
        detail,
        output_tail: output_tail.to_string(),
    };
    let mut lines = text.lines().enumerate();
    if !lines.by_ref().any(|(_, l)| l.trim_start().starts_with("------")) {
        return if text.trim().is_empty() {
            Ok(Vec::new())
        } else {
            Err(garbage("the polar file has no header rule (------)".into()))
        };
    }
    let mut points = Vec::new();
    for (i, line) in lines {
        if line.trim().is_empty() {
            continue;
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        let nums: Option<Vec<f64>> = fields.iter().take(7).map(|f| f.parse::<f64>().ok()).collect();
        match nums {
            Some(v) if v.len() == 7 && v.iter().all(|x| x.is_finite()) => points.push(XfoilPoint {
                alpha_deg: v[0],
                cl: v[1],
                cd: v[2],
                cdp: v[3],
                cm: v[4],
                xtr_top: v[5],
                xtr_bottom: v[6],
            }),
            // A last row without its line end was cut off as XFOIL was writing it (a crash,
            // a kill at the timeout): the rows before it stand, the angle counts as missed.
            _ if !text.ends_with('\n') && text.lines().count() == i + 1 => break,
            _ => {
                return Err(garbage(format!(
                    "polar file line {}: {:?} is not seven numbers",
                    i + 1,
                    line.trim()
                )))
            }
        }
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLE: &str = "\n       XFOIL         Version 6.99\n\n Calculated polar for: NACA 4412\n\n\
   alpha    CL        CD       CDp       CM     Top_Xtr  Bot_Xtr  Top_Itr  Bot_Itr\n\
  ------ -------- --------- --------- -------- -------- -------- -------- --------\n\
   0.000   0.4377   0.01791   0.00867  -0.1064   0.8207   1.0000  13.4713 160.0000\n\
   4.000   0.8880   0.01965   0.00855  -0.1026   0.6589   1.0000  23.4766 160.0000\n";

    #[test]
    fn reads_rows_after_the_rule() {
        let p = parse_polar_file(SAMPLE, "").unwrap();
        assert_eq!(p.len(), 2);
        assert_eq!(p[1].alpha_deg, 4.0);
        assert_eq!(p[1].cl, 0.8880);
        assert_eq!(p[1].cd, 0.01965);
        assert_eq!(p[0].xtr_top, 0.8207);
    }

    #[test]
    fn a_last_row_cut_off_is_left_out_and_a_bad_row_inside_is_an_error() {
        let cut = format!("{SAMPLE}   5.000   0.88");
        let p = parse_polar_file(&cut, "").unwrap();
        assert_eq!(p.len(), 2);
        let inside = format!("{SAMPLE}   5.000   0.88\n");
        let e = parse_polar_file(&inside, "").unwrap_err().to_string();
        assert!(e.contains("line 10") && e.contains("not seven numbers"), "{e}");
    }

    #[test]
    fn header_only_and_empty_have_no_points() {
        let header: String = SAMPLE.lines().take(7).collect::<Vec<_>>().join("\n");
        assert!(parse_polar_file(&header, "").unwrap().is_empty());
        assert!(parse_polar_file("", "").unwrap().is_empty());
    }

    #[test]
    fn garbage_names_the_line() {
        let bad = format!("{SAMPLE}   5.000   ******   0.02\n");
        let e = parse_polar_file(&bad, "tail").unwrap_err().to_string();
        assert!(e.contains("line 10"), "{e}");
        assert!(e.contains("tail"), "{e}");
        assert!(parse_polar_file("hello\nworld\n", "").is_err());
    }
}
