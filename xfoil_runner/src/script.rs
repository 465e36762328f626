//! XFOIL command scripts. Every line is a fixed keyword or a number formatted here; no text
//! from the user (names, paths) ever reaches XFOIL's standard input. The coordinates go to a
//! file we write ([`AIRFOIL_FILE`]) under a fixed name, and the polar to [`POLAR_FILE`], both in
//! the run's own temporary directory.

use std::fmt::Write;

/// Name of the coordinate file in a run's directory.
pub const AIRFOIL_FILE: &str = "airfoil.dat";
/// Name of the polar save file in a run's directory.
pub const POLAR_FILE: &str = "polar.txt";
/// Name line written at the top of the coordinate file.
pub const AIRFOIL_NAME: &str = "propbet section";

/// One angle of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// Angle of attack [deg].
    pub alpha_deg: f64,
    /// Re-initialise the boundary layer before this angle.
    pub init: bool,
    /// A step of a return over angles already passed (hysteresis, [`crate::Xfoil::sweep`]).
    pub returning: bool,
}

impl Step {
    /// `alphas` in order, the first of them (or every one, with `init_each`) re-initialised.
    pub fn list(alphas: &[f64], init_first: bool, init_each: bool) -> Vec<Step> {
        alphas
            .iter()
            .enumerate()
            .map(|(k, &alpha_deg)| Step {
                alpha_deg,
                init: init_each || (init_first && k == 0),
                returning: false,
            })
            .collect()
    }
}

/// Settings of one viscous run: the flow, and the section's settings (its iteration limit
/// lowered for a retry pass).
#[derive(Debug, Clone, PartialEq)]
pub struct RunSettings {
    /// Chord Reynolds number [-].
    pub reynolds: f64,
    /// Mach number [-].
    pub mach: f64,
    /// Transition, panels, iterations (the angles are the run's steps).
    pub section: crate::SectionSettings,
}

/// The script for one run: plot window made tiny (graphics must stay on, see
/// [`crate::display`]), load, repanel, viscous settings, an optional warm-up angle that is
/// solved but not saved (continuation after a restart), then the angles in order, each saved to
/// the polar file as soon as it converges. A step with `init` re-initialises the boundary layer
/// first (the start of the downward branch, and every angle of the retry pass). XFOIL's `INIT`
/// is a toggle: after any `ALFA` it means "initialise on the next point", but in a fresh
/// process it would mean "assume initialised", and the first point dies in STFIND; hence never
/// before the first angle of a process.
pub fn sweep_script(s: &RunSettings, warm_up_deg: Option<f64>, steps: &[Step]) -> String {
    let mut out = String::with_capacity(256 + 16 * steps.len());
    // Writing to a String cannot fail.
    let _ = writeln!(out, "PLOP\nW 0.05\n");
    let _ = writeln!(out, "LOAD {AIRFOIL_FILE}");
    let _ = writeln!(out, "PPAR\nN {}\n\n", s.section.panel_count());
    let _ = writeln!(out, "OPER");
    let _ = writeln!(out, "VISC {:e}", s.reynolds);
    let _ = writeln!(out, "MACH {:.6}", s.mach);
    let _ = writeln!(out, "VPAR\nN {:.6}", s.section.ncrit);
    if let Some(x) = s.section.trip {
        let _ = writeln!(out, "XTR {x:.6} {x:.6}");
    }
    let _ = writeln!(out);
    let _ = writeln!(out, "ITER {}", s.section.max_iter);
    if let Some(a) = warm_up_deg {
        let _ = writeln!(out, "ALFA {a:.6}");
    }
    let _ = writeln!(out, "PACC\n{POLAR_FILE}\n");
    for (k, step) in steps.iter().enumerate() {
        if step.init && (k > 0 || warm_up_deg.is_some()) {
            let _ = writeln!(out, "INIT");
        }
        let _ = writeln!(out, "ALFA {:.6}", step.alpha_deg);
    }
    let _ = writeln!(out, "PACC\n\nQUIT");
    out
}

/// The coordinate file: a fixed name line, then one `x y` pair per line.
pub fn airfoil_file(points: &[[f64; 2]]) -> String {
    let mut out = String::with_capacity(32 + 28 * points.len());
    let _ = writeln!(out, "{AIRFOIL_NAME}");
    for p in points {
        let _ = writeln!(out, "{:.8} {:.8}", p[0], p[1]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn script_is_keywords_and_numbers_only() {
        let s = RunSettings {
            reynolds: 1e5,
            mach: 0.1,
            section: crate::SectionSettings {
                max_iter: 100,
                panels: Some(160),
                ..crate::SectionSettings::new(Vec::new())
            },
        };
        let text = sweep_script(&s, Some(3.0), &Step::list(&[4.0, 5.0], false, false));
        let retry = sweep_script(&s, None, &Step::list(&[4.0, 6.0], false, true));
        assert!(retry.contains("\n\nALFA 4.000000\nINIT\nALFA 6.000000\n"), "{retry}");
        // Free transition says nothing of XTR; a trip sets both surfaces, inside VPAR.
        assert!(!text.contains("XTR"));
        let tripped = sweep_script(
            &RunSettings {
                section: crate::SectionSettings {
                    trip: Some(0.05),
                    ..s.section.clone()
                },
                ..s.clone()
            },
            None,
            &Step::list(&[4.0], false, false),
        );
        assert!(
            tripped.contains("VPAR\nN 9.000000\nXTR 0.050000 0.050000\n\n"),
            "{tripped}"
        );
        let keywords = [
            "PLOP", "W", "LOAD", "PPAR", "N", "OPER", "VISC", "MACH", "VPAR", "XTR", "ITER", "INIT", "ALFA", "PACC",
            "QUIT",
        ];
        for line in text.lines() {
            for word in line.split_whitespace() {
                let ok = keywords.contains(&word)
                    || word == AIRFOIL_FILE
                    || word == POLAR_FILE
                    || word.parse::<f64>().is_ok();
                assert!(ok, "unexpected word {word:?} in {line:?}");
            }
        }
        assert!(text.contains("VISC 1e5\n"));
        assert!(text.contains("ALFA 3.000000\nPACC\npolar.txt\n\nALFA 4.000000\nALFA 5.000000\nPACC\n\nQUIT"));
    }
}
