//! Where the measurements came from, as far as it bounds a candidate effect: an optical RPM
//! sensor has no pole count to get wrong, and coefficients a lab reduced with the air it
//! measured leave a density ratio only that measurement's error. Each effect declares the
//! bounds such evidence sets on its parameters ([`propbet_effects::Param::known`]); the
//! diagnosis's candidates are narrowed to them before they are fitted.

use std::sync::Arc;

use propbet_effects::{Effect, Evidence, Narrowed};
use propbet_measure::{Format, MeasuredSet, RpmSource};

/// What the measured files say about their own errors.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Provenance {
    /// Every file's RPM is optical (a wind tunnel's, a thrust stand's optical probe).
    pub optical_rpm: bool,
    /// Every file gives coefficients a lab reduced with the air it measured (UIUC's).
    pub lab_air: bool,
}

impl Provenance {
    /// The provenance of a comparison's measured sets.
    pub fn of(sets: &[MeasuredSet]) -> Self {
        let uiuc = |s: &MeasuredSet| matches!(s.format, Format::UiucStatic | Format::UiucSweep);
        Provenance {
            optical_rpm: sets.iter().all(|s| uiuc(s) || s.rpm_source == Some(RpmSource::Optical)),
            lab_air: sets.iter().all(uiuc),
        }
    }

    /// Whether the files show `e`.
    pub fn shows(&self, e: Evidence) -> bool {
        match e {
            Evidence::OpticalRpm => self.optical_rpm,
            Evidence::LabAir => self.lab_air,
        }
    }

    /// The bounds this provenance sets on a candidate's parameters, as each parameter declares
    /// them: (parameter, lower, upper, why).
    pub fn bounds<'a>(&self, effect: &'a dyn Effect) -> Vec<(&'a str, f64, f64, &'static str)> {
        effect
            .params()
            .iter()
            .filter_map(|p| {
                let k = p.known.filter(|k| self.shows(k.given))?;
                Some((p.name.as_str(), k.bounds.0, k.bounds.1, k.why))
            })
            .collect()
    }

    /// `candidates` with the bounds this provenance sets.
    pub fn narrow(&self, candidates: &mut [Arc<dyn Effect>]) {
        for c in candidates {
            let bounds = self.bounds(c.as_ref());
            if !bounds.is_empty() {
                let narrowed = Narrowed::new(c.clone(), &bounds);
                *c = Arc::new(narrowed);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use propbet_effects::builtin;

    fn bounds_of(p: Provenance, id: &str) -> Vec<(String, f64, f64)> {
        let mut c = vec![builtin::get(id).unwrap()];
        p.narrow(&mut c);
        c[0].params()
            .iter()
            .map(|q| (q.name.clone(), q.lower, q.upper))
            .collect()
    }

    #[test]
    fn each_effect_is_narrowed_by_the_evidence_it_declares_and_no_other() {
        let none = Provenance {
            optical_rpm: false,
            lab_air: false,
        };
        let optical = Provenance {
            optical_rpm: true,
            lab_air: false,
        };
        let lab = Provenance {
            optical_rpm: true,
            lab_air: true,
        };
        assert_eq!(bounds_of(none, "rpm-scale"), [("factor".into(), 0.85, 1.2)]);
        assert_eq!(bounds_of(optical, "rpm-scale"), [("factor".into(), 0.99, 1.01)]);
        assert_eq!(bounds_of(optical, "density"), [("ratio".into(), 0.75, 1.2)]);
        assert_eq!(bounds_of(lab, "density"), [("ratio".into(), 0.98, 1.02)]);
        let pitch = bounds_of(lab, "pitch-offset");
        let plain: Vec<_> = builtin::get("pitch-offset")
            .unwrap()
            .params()
            .iter()
            .map(|q| (q.name.clone(), q.lower, q.upper))
            .collect();
        assert_eq!(pitch, plain, "an effect that declares no evidence keeps its bounds");
        // Only the declaring effects are narrowed by any evidence.
        let declaring: Vec<&str> = builtin::all()
            .iter()
            .filter(|e| e.params().iter().any(|p| p.known.is_some()))
            .map(|e| e.id())
            .collect();
        assert_eq!(declaring, ["density", "rpm-scale"]);
    }
}
