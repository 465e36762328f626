//! Polars: XFOIL's converged points at one Reynolds number, Mach number and Ncrit, and
//! interpolation in alpha and Reynolds number.

use std::fmt::Write;

use serde::{Deserialize, Serialize};

use crate::engine::Engine;
pub use xfoil_runner::{Branches, Fault, XfoilPoint as PolarPoint};

/// Columns of a polar CSV: `engine` is the program that made the point (`xfoil` or
/// `neuralfoil`), `confidence` NeuralFoil's in its point (empty for XFOIL's).
pub const CSV_HEADER: &str = "re,mach,ncrit,alpha_deg,cl,cd,cdp,cm,xtr_top,xtr_bottom,engine,confidence";

/// NeuralFoil's confidence below which a point is said to be uncertain (its training data
/// are thin there: beyond stall, far outside its Reynolds numbers or shapes).
pub const LOW_CONFIDENCE: f64 = 0.5;

/// One polar: the points XFOIL converged, ascending in alpha, and what failed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Polar {
    /// Chord Reynolds number [-].
    pub re: f64,
    /// Mach number [-].
    pub mach: f64,
    /// Transition amplification ratio [-].
    pub ncrit: f64,
    /// Forced transition x/c on both surfaces (absent: free transition).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub trip: Option<f64>,
    /// Converged points, ascending in alpha.
    pub points: Vec<PolarPoint>,
    /// Angles requested that did not converge [deg].
    pub unconverged_deg: Vec<f64>,
    /// Angles with two solutions, one from each direction of approach (the lower-drag one is
    /// in `points`; `xfoil_runner::Xfoil::sweep`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hysteresis: Vec<Branches>,
    /// Crashes and hangs of XFOIL while computing this polar.
    pub faults: Vec<Fault>,
    /// The points NeuralFoil made (all of a NeuralFoil polar's; those `auto` filled in where
    /// XFOIL did not converge), each with the network's confidence; empty: XFOIL made them all.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub neuralfoil: Vec<Filled>,
    /// Why NeuralFoil could not fill the angles XFOIL left out (`auto` with a section the
    /// Kulfan fit cannot take): XFOIL's polar is kept with its gaps.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub not_filled: Option<String>,
}

/// A polar point NeuralFoil made.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Filled {
    /// Its angle [deg].
    pub alpha_deg: f64,
    /// The network's confidence in it, 0 to 1.
    pub confidence: f64,
}

impl Polar {
    /// NeuralFoil's confidence in the point at `alpha_deg` if NeuralFoil made it (`None`: XFOIL
    /// did).
    pub fn neuralfoil_at(&self, alpha_deg: f64) -> Option<f64> {
        self.neuralfoil
            .iter()
            .find(|f| f.alpha_deg == alpha_deg)
            .map(|f| f.confidence)
    }

    /// The angles with two solutions, in words (`None` without any): each angle with the lift
    /// kept and the other branch's.
    pub fn hysteresis_text(&self) -> Option<String> {
        if self.hysteresis.is_empty() {
            return None;
        }
        let list: Vec<String> = self
            .hysteresis
            .iter()
            .map(|b| format!("{} (cl {:.3}, other {:.3})", b.kept.alpha_deg, b.kept.cl, b.other.cl))
            .collect();
        Some(format!(
            "two solutions (hysteresis), the lower-drag one kept, at alpha [deg]: {}",
            list.join(", ")
        ))
    }

    /// The point at `alpha_deg`, linear between converged points; `None` outside their range.
    pub fn at_alpha(&self, alpha_deg: f64) -> Option<PolarPoint> {
        let p = &self.points;
        if p.is_empty() || alpha_deg < p[0].alpha_deg || alpha_deg > p[p.len() - 1].alpha_deg {
            return None;
        }
        if p.len() == 1 {
            return Some(p[0]);
        }
        let i = p.partition_point(|q| q.alpha_deg <= alpha_deg).clamp(1, p.len() - 1);
        let (a, b) = (p[i - 1], p[i]);
        let t = (alpha_deg - a.alpha_deg) / (b.alpha_deg - a.alpha_deg);
        let mix = |x: f64, y: f64| x + t * (y - x);
        Some(PolarPoint {
            alpha_deg,
            cl: mix(a.cl, b.cl),
            cd: mix(a.cd, b.cd),
            cdp: mix(a.cdp, b.cdp),
            cm: mix(a.cm, b.cm),
            xtr_top: mix(a.xtr_top, b.xtr_top),
            xtr_bottom: mix(a.xtr_bottom, b.xtr_bottom),
        })
    }

    /// Drag at lift coefficient `cl` on the attached branch (between the lowest and highest cl,
    /// where cl rises with alpha), linear between points; `None` outside.
    pub fn cd_at_cl(&self, cl: f64) -> Option<f64> {
        let (lo, hi) = self.attached_range()?;
        let p = &self.points[lo..=hi];
        p.windows(2).find_map(|w| {
            let (a, b) = (w[0], w[1]);
            let (c0, c1) = (a.cl.min(b.cl), a.cl.max(b.cl));
            (c0 <= cl && cl <= c1 && c1 > c0).then(|| a.cd + (cl - a.cl) / (b.cl - a.cl) * (b.cd - a.cd))
        })
    }

    /// Indices of the lowest-cl and highest-cl points: the attached range between the stalls
    /// (as far as XFOIL converged).
    pub fn attached_range(&self) -> Option<(usize, usize)> {
        let p = &self.points;
        if p.len() < 2 {
            return None;
        }
        let lo = (0..p.len()).min_by(|&i, &j| p[i].cl.total_cmp(&p[j].cl))?;
        let hi = (0..p.len()).max_by(|&i, &j| p[i].cl.total_cmp(&p[j].cl))?;
        (lo < hi).then_some((lo, hi))
    }

    /// A polar at Ncrit 9 and Mach 0 from a law `alpha [deg] -> (cl, cd)` at whole degrees
    /// `from..=to`, everything converged (for tests).
    pub fn from_law(re: f64, from: i32, to: i32, law: impl Fn(f64) -> (f64, f64)) -> Polar {
        let points = (from..=to)
            .map(|a| {
                let alpha_deg = f64::from(a);
                let (cl, cd) = law(alpha_deg);
                PolarPoint {
                    xtr_top: 0.5,
                    ..PolarPoint::lift_drag(alpha_deg, cl, cd)
                }
            })
            .collect();
        Polar {
            trip: None,
            re,
            mach: 0.0,
            ncrit: 9.0,
            points,
            unconverged_deg: vec![],
            hysteresis: vec![],
            faults: vec![],
            neuralfoil: Vec::new(),
            not_filled: None,
        }
    }

    /// CSV: a comment header with Re, Mach, Ncrit and the failed angles, then one row per point.
    pub fn to_csv(&self) -> String {
        let mut out = String::new();
        let _ = writeln!(out, "# Re = {}, Mach = {}, Ncrit = {}", self.re, self.mach, self.ncrit);
        if !self.unconverged_deg.is_empty() {
            let list: Vec<String> = self.unconverged_deg.iter().map(|a| a.to_string()).collect();
            let _ = writeln!(out, "# not converged at alpha [deg]: {}", list.join(" "));
        }
        if let Some(text) = self.hysteresis_text() {
            let _ = writeln!(out, "# {text}");
        }
        for f in &self.faults {
            let _ = writeln!(out, "# {f}");
        }
        let _ = writeln!(out, "{CSV_HEADER}");
        out.push_str(&self.csv_rows());
        out
    }

    /// The CSV rows alone (columns of [`CSV_HEADER`]), one per point.
    pub fn csv_rows(&self) -> String {
        let mut out = String::new();
        for p in &self.points {
            let (engine, confidence) = match self.neuralfoil_at(p.alpha_deg) {
                Some(c) => ("neuralfoil", c.to_string()),
                None => ("xfoil", String::new()),
            };
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{},{},{},{engine},{confidence}",
                self.re, self.mach, self.ncrit, p.alpha_deg, p.cl, p.cd, p.cdp, p.cm, p.xtr_top, p.xtr_bottom
            );
        }
        out
    }
}

/// Which program made a set of polars: XFOIL, NeuralFoil, or XFOIL with NeuralFoil filling
/// what it left out (the `auto` engine), and how sure NeuralFoil was.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct Makers {
    /// Polars in all.
    pub polars: usize,
    /// Polars NeuralFoil made in whole.
    pub neuralfoil: usize,
    /// Polars XFOIL made with some angles from NeuralFoil.
    pub filled: usize,
    /// Angles NeuralFoil made in the polars XFOIL made.
    pub filled_points: usize,
    /// Points NeuralFoil made in all.
    pub neuralfoil_points: usize,
    /// Of them, those below [`LOW_CONFIDENCE`].
    pub unsure: usize,
}

impl Makers {
    /// Counts `polars`.
    pub fn of<'a>(polars: impl IntoIterator<Item = &'a Polar>) -> Makers {
        let mut m = Makers::default();
        for p in polars {
            m.polars += 1;
            let made = p.neuralfoil.len();
            if made == 0 {
                continue;
            }
            if made >= p.points.len() {
                m.neuralfoil += 1;
            } else {
                m.filled += 1;
                m.filled_points += made;
            }
            m.neuralfoil_points += made;
            m.unsure += p.neuralfoil.iter().filter(|f| f.confidence < LOW_CONFIDENCE).count();
        }
        m
    }

    /// The engine that made these polars as they are: XFOIL, NeuralFoil, or both (`Auto`).
    pub fn engine(&self) -> Engine {
        match (self.neuralfoil, self.filled) {
            (0, 0) => Engine::Xfoil,
            (n, 0) if n == self.polars => Engine::NeuralFoil,
            _ => Engine::Auto,
        }
    }

    /// "97 XFOIL polars", "97 NeuralFoil polars", or "97 polars: XFOIL's, 31 angles in 12 of
    /// them and 3 in whole from NeuralFoil".
    pub fn words(&self) -> String {
        let n = self.polars;
        match self.engine() {
            Engine::Xfoil => format!("{n} XFOIL polars"),
            Engine::NeuralFoil => format!("{n} NeuralFoil polars"),
            Engine::Auto => {
                let mut parts = Vec::new();
                if self.filled > 0 {
                    parts.push(format!("{} angles in {} of them", self.filled_points, self.filled));
                }
                if self.neuralfoil > 0 {
                    parts.push(format!("{} in whole", self.neuralfoil));
                }
                format!("{n} polars: XFOIL's, {} from NeuralFoil", parts.join(" and "))
            }
        }
    }

    /// How many of NeuralFoil's points it is unsure of (`None`: none).
    pub fn doubts(&self) -> Option<String> {
        (self.unsure > 0).then(|| {
            format!(
                "NeuralFoil is unsure (confidence below {LOW_CONFIDENCE}) of {} of its {} points",
                self.unsure, self.neuralfoil_points
            )
        })
    }
}

/// Interpolation weights between the polars of a set (sorted by Re) at `re`: linear in ln Re,
/// clamped to the end polars. Returns `(lower index, upper index, fraction)`.
pub fn re_bracket(res: &[f64], re: f64) -> (usize, usize, f64) {
    let n = res.len();
    if n <= 1 || re <= res[0] {
        return (0, 0, 0.0);
    }
    if re >= res[n - 1] {
        return (n - 1, n - 1, 0.0);
    }
    let i = res.partition_point(|&r| r <= re).clamp(1, n - 1);
    let t = (re.ln() - res[i - 1].ln()) / (res[i].ln() - res[i - 1].ln());
    (i - 1, i, t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pt(alpha_deg: f64, cl: f64, cd: f64) -> PolarPoint {
        PolarPoint::lift_drag(alpha_deg, cl, cd)
    }

    fn polar() -> Polar {
        Polar {
            trip: None,
            re: 1e5,
            mach: 0.0,
            ncrit: 9.0,
            points: vec![
                pt(-6.0, -0.3, 0.03),
                pt(0.0, 0.4, 0.012),
                pt(4.0, 0.85, 0.015),
                pt(10.0, 1.3, 0.03),
                pt(14.0, 1.1, 0.08),
            ],
            unconverged_deg: vec![12.0],
            hysteresis: vec![],
            faults: vec![],
            neuralfoil: Vec::new(),
            not_filled: None,
        }
    }

    #[test]
    fn interpolates_in_alpha_inside_only() {
        let p = polar();
        let q = p.at_alpha(2.0).unwrap();
        assert!((q.cl - 0.625).abs() < 1e-12 && (q.cd - 0.0135).abs() < 1e-12);
        assert!(p.at_alpha(-7.0).is_none() && p.at_alpha(15.0).is_none());
        assert_eq!(p.at_alpha(14.0).unwrap().cl, 1.1);
    }

    #[test]
    fn drag_at_lift_stays_on_the_attached_branch() {
        let p = polar();
        assert_eq!(p.attached_range(), Some((0, 3)));
        assert!((p.cd_at_cl(0.4).unwrap() - 0.012).abs() < 1e-12);
        // cl = 1.2 occurs before and after stall; the attached branch is the one taken.
        let cd = p.cd_at_cl(1.2).unwrap();
        assert!(cd < 0.03, "{cd}");
        assert!(p.cd_at_cl(1.5).is_none());
    }

    #[test]
    fn re_bracket_is_log_linear_and_clamped() {
        let res = [5e4, 1e5, 2e5];
        assert_eq!(re_bracket(&res, 1e4), (0, 0, 0.0));
        assert_eq!(re_bracket(&res, 3e5), (2, 2, 0.0));
        let (i, j, t) = re_bracket(&res, 1e5 * 2f64.sqrt());
        assert_eq!((i, j), (1, 2));
        assert!((t - 0.5).abs() < 1e-12);
    }

    #[test]
    fn csv_names_failures() {
        let mut p = polar();
        p.hysteresis.push(crate::table::Branches {
            kept: pt(10.0, 1.3, 0.03),
            other: pt(10.0, 1.05, 0.06),
        });
        let csv = p.to_csv();
        assert!(csv.contains("not converged at alpha [deg]: 12"));
        assert!(
            csv.contains(
                "# two solutions (hysteresis), the lower-drag one kept, at alpha [deg]: 10 (cl 1.300, other 1.050)"
            ),
            "{csv}"
        );
        assert_eq!(csv.lines().filter(|l| l.starts_with("100000,")).count(), 5);
    }

    #[test]
    fn every_point_says_which_engine_made_it() {
        let xfoil = polar();
        let mut filled = polar();
        filled.neuralfoil.push(Filled {
            alpha_deg: 4.0,
            confidence: 0.3,
        });
        let mut whole = polar();
        whole.neuralfoil = whole
            .points
            .iter()
            .map(|p| Filled {
                alpha_deg: p.alpha_deg,
                confidence: 0.9,
            })
            .collect();
        let rows = filled.csv_rows();
        assert!(rows.lines().nth(2).unwrap().ends_with(",neuralfoil,0.3"), "{rows}");
        assert!(rows.lines().nth(1).unwrap().ends_with(",xfoil,"), "{rows}");
        assert_eq!(
            CSV_HEADER.split(',').count(),
            rows.lines().next().unwrap().split(',').count()
        );

        assert_eq!(Makers::of([&xfoil, &xfoil]).words(), "2 XFOIL polars");
        assert_eq!(Makers::of([&whole]).words(), "1 NeuralFoil polars");
        let m = Makers::of([&xfoil, &filled, &whole]);
        assert_eq!(m.engine(), Engine::Auto);
        assert_eq!(
            m.words(),
            "3 polars: XFOIL's, 1 angles in 1 of them and 1 in whole from NeuralFoil"
        );
        assert_eq!(
            m.doubts().unwrap(),
            "NeuralFoil is unsure (confidence below 0.5) of 1 of its 6 points"
        );
        assert_eq!(Makers::of([&xfoil]).doubts(), None);
    }
}
