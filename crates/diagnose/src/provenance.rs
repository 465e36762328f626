//! Where the measurements came from, as far as it bounds a candidate effect: an optical RPM
//! sensor has no pole count to get wrong, and coefficients a lab reduced with the air it
//! measured leave a density ratio only that measurement's error. The diagnosis's candidates are
//! narrowed to these bounds before they are fitted.

use std::sync::Arc;

use propbet_effects::{Effect, Narrowed};
use propbet_measure::{Format, MeasuredSet, RpmSource};

/// Bounds of the RPM scale when every file's RPM is optical (the wide bounds hold the
/// pole-count ratios of an electrical reading, 12/14 and 14/12). An optical tachometer times
/// pulses against a quartz clock: a handheld one is specified to ±0.02 % of the reading ± 1
/// count (Ono Sokki HT-5500's data sheet), so ±1 % is fifty times that and still not a
/// miscount, which would be a factor of 2 (two reflections a turn). The bounds were once ±3 %
/// with no source; validate's held-out columns with each are in `README.md` (Validation on
/// real propellers).
pub const OPTICAL_RPM_SCALE: (f64, f64) = (0.99, 1.01);

/// Bounds of the density ratio when every file gives coefficients (UIUC's CT and CP): the lab
/// reduced its loads with the density it measured, so the ratio is only that measurement's
/// error. Density from a barometer and a thermometer (ideal gas) is good to a few tenths of a
/// percent (1 hPa is 0.1 %, 1 K 0.35 %); humidity left out makes dry-air density up to about
/// 1 % high at 30 C and 60 % RH (moist air's gas constant): ±2 % holds both with room. The
/// wide bounds (0.75-1.2) are those of a stand log whose air nobody wrote down.
pub const LAB_DENSITY_RATIO: (f64, f64) = (0.98, 1.02);

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

    /// The bounds this provenance sets on a candidate: (parameter, bounds, why); None where it
    /// sets none.
    pub fn bounds(&self, effect: &dyn Effect) -> Option<(&'static str, (f64, f64), &'static str)> {
        match effect.id() {
            "rpm-scale" if self.optical_rpm => Some((
                "factor",
                OPTICAL_RPM_SCALE,
                "an optical RPM sensor: no pole count to get wrong",
            )),
            "density" if self.lab_air => Some((
                "ratio",
                LAB_DENSITY_RATIO,
                "coefficients the lab reduced with the density it measured",
            )),
            _ => None,
        }
    }

    /// `candidates` with the bounds this provenance sets.
    pub fn narrow(&self, candidates: &mut [Arc<dyn Effect>]) {
        for c in candidates {
            if let Some((param, (lo, hi), why)) = self.bounds(c.as_ref()) {
                *c = Arc::new(Narrowed::new(c.clone(), &[(param, lo, hi, why)]));
            }
        }
    }
}
